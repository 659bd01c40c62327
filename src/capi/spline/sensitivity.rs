//! Sensitivities of a spline's control points to its domain's boundary:
//! `igaparam_spline_tangent` and `igaparam_spline_adjoint`.

use super::{igaparam_spline, AnyMap};
use crate::capi::domain::{current, igaparam_domain, Built};
use crate::capi::ffi::{run, slice, slice_mut, Failure};
use crate::capi::igaparam_status;
use crate::domain::{CubeMap, Domain};
use crate::error::{Error, Result};
use crate::spline::{FitRecord, SplineMap};

/// Which product to take.
#[derive(Clone, Copy)]
enum Product {
    /// Boundary-vertex motion in, control-point motion out.
    Tangent,
    /// Control-point derivatives in, boundary-vertex derivatives out.
    Adjoint,
}

/// `flat` (`n × D` doubles) as points.
fn points<const D: usize>(flat: &[f64]) -> Vec<[f64; D]> {
    flat.chunks_exact(D)
        .map(|p| std::array::from_fn(|k| p[k]))
        .collect()
}

/// What a product call is given: the spline's fit record, the product, the input (flat) and the
/// output's length, with their names.
#[derive(Clone, Copy)]
struct Call<'a> {
    record: &'a FitRecord,
    product: Product,
    input: (&'a [f64], &'a str),
    output: (usize, &'a str),
}

/// The product of `map` with `input` (flat), checked against the sizes it needs; the result
/// flat, `out_len` doubles.
fn apply<const D: usize, B: CubeMap<D>>(
    map: &SplineMap<D>,
    domain: &Domain<D, B>,
    call: &Call<'_>,
) -> Result<Vec<f64>> {
    let Call {
        record,
        product,
        input,
        output: out_len,
    } = *call;
    let vertices = D * domain.mesh().vertex_count();
    let controls = D * map.basis_count();
    let (needed_in, needed_out) = match product {
        Product::Tangent => (vertices, controls),
        Product::Adjoint => (controls, vertices),
    };
    for (what, len, needed) in [
        (input.1, input.0.len(), needed_in),
        (out_len.1, out_len.0, needed_out),
    ] {
        if len != needed {
            return Err(Error::invalid(format!(
                "{what} has {len} doubles, expected {needed} ({D} per {})",
                if needed == vertices {
                    "vertex of the domain's T-mesh"
                } else {
                    "control point"
                }
            )));
        }
    }
    let threads = domain.options().threads;
    let input = points::<D>(input.0);
    let result = match product {
        Product::Tangent => map.boundary_tangent(domain, record, threads, &input)?,
        Product::Adjoint => map.boundary_adjoint(domain, record, threads, &input)?,
    };
    Ok(result.into_iter().flatten().collect())
}

/// Runs `product` of `spline` and `domain`: `input` (`in_len` doubles) read before `output`
/// (`out_len` doubles) is written, so the two may overlap.
fn run_product(
    name: &'static str,
    spline: *const igaparam_spline,
    domain: *const igaparam_domain,
    product: Product,
    input: (*const f64, usize, &'static str),
    output: (*mut f64, usize, &'static str),
) -> igaparam_status {
    run(name, || {
        let d = current(domain)?;
        let s = super::held(spline)?;
        let record = s.fit.as_ref().ok_or_else(|| {
            Failure::from(Error::invalid(
                "the spline was read from a file: its fit rule is unknown until \
                 igaparam_spline_refit fits it to the domain",
            ))
        })?;
        let values = slice(input.0, input.1, input.2)?;
        let call = Call {
            record,
            product,
            input: (values, input.2),
            output: (output.1, output.2),
        };
        let result = match (&s.map, d.built()?) {
            (AnyMap::Two(m), Built::Planar((_, b))) => apply(m, b, &call)?,
            (AnyMap::Three(m), Built::Solid((_, b))) => apply(m, b, &call)?,
            (map, _) => return Err(super::dimension_mismatch(map)),
        };
        slice_mut(output.0, output.1, output.2)?.copy_from_slice(&result);
        Ok(())
    })
}

/// The tangent product of the control points: for a motion `dx_boundary` of the domain's
/// boundary vertices (`vertex_size` = d × num_vertices doubles, in the order of
/// `igaparam_domain_copy_vertices`; entries of inner vertices are ignored), writes to `dp`
/// (`size` = d × basis_count doubles) the first-order motion of the control points of a refit
/// of `spline` to the domain so moved. The T-mesh follows its boundary vertices as the
/// stationary point of its optimization (implicit function theorem), and the control points
/// follow the T-mesh by the spline's fit rule, a linear map.
///
/// A boundary vertex is one with a parametric coordinate 0 or 1 (see
/// `igaparam_domain_copy_vertices`); it sits at its parameters' point on the boundary, so a
/// host derives `dx_boundary` from its own change of the boundary curves or surfaces (for a
/// B-spline boundary, the basis functions at the vertex's parameter times the change of the
/// control points).
///
/// Needs: a domain built (or updated) with `stationarity_tolerance > 0` that converged and with
/// no boundary vertex moved off the boundary by the seam relief (`boundary_offset` 0 is the
/// sure way), and a spline in the T-mesh's own space whose last fit or refit did not untangle
/// (after one that did, `igaparam_spline_refit` once more carries the untangling's correction
/// as a constant). Otherwise `IGAPARAM_STATUS_INVALID_ARGUMENT` says which. The domain's
/// thread count is used; the result does not depend on it.
#[no_mangle]
pub extern "C" fn igaparam_spline_tangent(
    spline: *const igaparam_spline,
    domain: *const igaparam_domain,
    vertex_size: usize,
    dx_boundary: *const f64,
    size: usize,
    dp: *mut f64,
) -> igaparam_status {
    run_product(
        "igaparam_spline_tangent",
        spline,
        domain,
        Product::Tangent,
        (dx_boundary, vertex_size, "dx_boundary"),
        (dp, size, "dp"),
    )
}

/// The adjoint product of the control points, the transpose of `igaparam_spline_tangent`:
/// given `dj_dp`, the partial derivatives of a scalar J of the control points (`size` = d ×
/// basis_count doubles, in the order of `igaparam_spline_copy_control_points`), writes to
/// `dj_dboundary` (`vertex_size` = d × num_vertices doubles) the total derivative of J with
/// respect to every boundary vertex of the domain's T-mesh, through the fit and the T-mesh's
/// optimum (0 at inner vertices). For a B-spline boundary, the derivative with respect to a
/// boundary control point is the sum over boundary vertices of their derivative times the
/// control point's basis function at the vertex's parameter. Same conditions as
/// `igaparam_spline_tangent`; a spline fitted by quasi-interpolation is refused (its
/// transpose is not provided).
#[no_mangle]
pub extern "C" fn igaparam_spline_adjoint(
    spline: *const igaparam_spline,
    domain: *const igaparam_domain,
    size: usize,
    dj_dp: *const f64,
    vertex_size: usize,
    dj_dboundary: *mut f64,
) -> igaparam_status {
    run_product(
        "igaparam_spline_adjoint",
        spline,
        domain,
        Product::Adjoint,
        (dj_dp, size, "dj_dp"),
        (dj_dboundary, vertex_size, "dj_dboundary"),
    )
}
