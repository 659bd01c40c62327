//! Sensitivities of a spline's control points to its domain's boundary, with respect to the
//! T-mesh's boundary vertices (`igaparam_spline_tangent`, `igaparam_spline_adjoint`) or to the
//! boundary's own control points (`igaparam_spline_tangent_controls`,
//! `igaparam_spline_adjoint_controls`), and the count of those (`igaparam_domain_control_count`).

use super::{igaparam_spline, AnyMap};
use crate::capi::domain::{current, igaparam_domain, Built};
use crate::capi::ffi::{non_null_mut, run, slice, slice_mut, Failure};
use crate::capi::igaparam_status;
use crate::domain::{BoundaryControls, Domain};
use crate::error::{Error, Result};
use crate::spline::{FitRecord, SplineMap};

/// Which product to take.
#[derive(Clone, Copy)]
enum Product {
    /// Boundary-vertex motion in, control-point motion out.
    Tangent,
    /// Control-point derivatives in, boundary-vertex derivatives out.
    Adjoint,
    /// Boundary control-point motion in, control-point motion out.
    ControlTangent,
    /// Control-point derivatives in, boundary control-point derivatives out.
    ControlAdjoint,
}

/// What the arrays of a product hold: one point per T-mesh vertex, per control point of the
/// spline, or per control point of the boundary.
#[derive(Clone, Copy, PartialEq)]
enum Points {
    Vertices,
    Spline,
    Boundary,
}

impl Points {
    /// The points of a product's input and output.
    fn of(product: Product) -> (Points, Points) {
        match product {
            Product::Tangent => (Points::Vertices, Points::Spline),
            Product::Adjoint => (Points::Spline, Points::Vertices),
            Product::ControlTangent => (Points::Boundary, Points::Spline),
            Product::ControlAdjoint => (Points::Spline, Points::Boundary),
        }
    }

    /// How many points of this kind `map` and `domain` have, and what they are called.
    fn count<const D: usize, B: BoundaryControls<D>>(
        self,
        map: &SplineMap<D>,
        domain: &Domain<D, B>,
    ) -> Result<(usize, &'static str)> {
        Ok(match self {
            Points::Vertices => (
                domain.mesh().vertex_count(),
                "vertex of the domain's T-mesh",
            ),
            Points::Spline => (map.basis_count(), "control point of the spline"),
            Points::Boundary => (
                domain.boundary().control_count()?,
                "control point of the boundary",
            ),
        })
    }
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
fn apply<const D: usize, B: BoundaryControls<D>>(
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
    let (from, to) = Points::of(product);
    for (what, len, points) in [(input.1, input.0.len(), from), (out_len.1, out_len.0, to)] {
        let (count, name) = points.count(map, domain)?;
        if len != D * count {
            return Err(Error::invalid(format!(
                "{what} has {len} doubles, expected {} ({D} per {name})",
                D * count
            )));
        }
    }
    let threads = domain.options().threads;
    let input = points::<D>(input.0);
    let result = match product {
        Product::Tangent => map.boundary_tangent(domain, record, threads, &input)?,
        Product::Adjoint => map.boundary_adjoint(domain, record, threads, &input)?,
        Product::ControlTangent => map.control_tangent(domain, record, threads, &input)?,
        Product::ControlAdjoint => map.control_adjoint(domain, record, threads, &input)?,
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

/// The tangent product with respect to the boundary's own control points: for a motion `dc`
/// of the control points of the domain's boundary curves or surfaces (`control_size` = d ×
/// `igaparam_domain_control_count` doubles, the curves' or surfaces' control points one after
/// the other in the order the domain was made from, each in its own order), writes to `dp`
/// (`size` = d × basis_count doubles) the first-order motion of the control points of a refit
/// of `spline` after `igaparam_domain_update` to the boundary so moved (weights and knots
/// fixed). Each boundary vertex moves by the basis values at its parameters; then as
/// `igaparam_spline_tangent`, with its conditions. A corner of two curves, or an edge row of two
/// surfaces, is in two lists: a boundary vertex there follows one of them, so move both copies
/// alike. Fails with `IGAPARAM_STATUS_INVALID_ARGUMENT` for a boundary of polylines or
/// triangulated faces (use `igaparam_spline_tangent`).
#[no_mangle]
pub extern "C" fn igaparam_spline_tangent_controls(
    spline: *const igaparam_spline,
    domain: *const igaparam_domain,
    control_size: usize,
    dc: *const f64,
    size: usize,
    dp: *mut f64,
) -> igaparam_status {
    run_product(
        "igaparam_spline_tangent_controls",
        spline,
        domain,
        Product::ControlTangent,
        (dc, control_size, "dc"),
        (dp, size, "dp"),
    )
}

/// The adjoint product with respect to the boundary's own control points, the transpose of
/// `igaparam_spline_tangent_controls`: given `dj_dp`, the partial derivatives of a scalar J of
/// the spline's control points (`size` = d × basis_count doubles), writes to `dj_dc`
/// (`control_size` = d × `igaparam_domain_control_count` doubles) the total derivative of J
/// with respect to every control point of the boundary's curves or surfaces. Same conditions
/// as `igaparam_spline_tangent_controls`; not for a quasi-interpolation fit.
#[no_mangle]
pub extern "C" fn igaparam_spline_adjoint_controls(
    spline: *const igaparam_spline,
    domain: *const igaparam_domain,
    size: usize,
    dj_dp: *const f64,
    control_size: usize,
    dj_dc: *mut f64,
) -> igaparam_status {
    run_product(
        "igaparam_spline_adjoint_controls",
        spline,
        domain,
        Product::ControlAdjoint,
        (dj_dp, size, "dj_dp"),
        (dj_dc, control_size, "dj_dc"),
    )
}

/// Writes to `*out` the number of control points of the built domain's boundary: those of its
/// curves (planar) or surfaces (solid) together, in the order of the sensitivities with respect
/// to them (`igaparam_spline_tangent_controls`). Fails with
/// `IGAPARAM_STATUS_INVALID_ARGUMENT` for a domain not built or a boundary of polylines or
/// triangulated faces.
#[no_mangle]
pub extern "C" fn igaparam_domain_control_count(
    domain: *const igaparam_domain,
    out: *mut usize,
) -> igaparam_status {
    run("igaparam_domain_control_count", || {
        let d = current(domain)?;
        let n = match d.built()? {
            Built::Planar((_, b)) => b.boundary().control_count()?,
            Built::Solid((_, b)) => b.boundary().control_count()?,
        };
        *non_null_mut(out, "out")? = n;
        Ok(())
    })
}
