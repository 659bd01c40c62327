//! Point queries of a spline map from C: values and Jacobians, mean ratio, inverse, and the
//! basis functions non-zero at a point.

use super::{dim, igaparam_spline, map};
use crate::capi::ffi::{
    check_capacity, non_null_mut, optional_out, run, slice, slice_mut, Failure,
};
use crate::capi::igaparam_status;
use crate::error::{check_finite, Error, Result};
use crate::spline::SplineMap;

/// `n × width` doubles at `ptr`, with an overflow check.
fn points_in<'a>(
    ptr: *const f64,
    n: usize,
    width: usize,
    name: &'static str,
) -> std::result::Result<&'a [f64], Failure> {
    let len = n
        .checked_mul(width)
        .ok_or_else(|| Error::invalid(format!("`{name}`: count {n} is too large")))?;
    let values = slice(ptr, len, name)?;
    check_finite(name, values)?;
    Ok(values)
}

/// A writable buffer of `n × width` doubles, or `None` when `ptr` is NULL.
fn points_out<'a>(
    ptr: *mut f64,
    n: usize,
    width: usize,
    name: &'static str,
) -> std::result::Result<Option<&'a mut [f64]>, Failure> {
    if ptr.is_null() {
        return Ok(None);
    }
    let len = n
        .checked_mul(width)
        .ok_or_else(|| Error::invalid(format!("`{name}`: count {n} is too large")))?;
    Ok(Some(slice_mut(ptr, len, name)?))
}

/// Checks that `x` lies in the parametric domain [0,1]^d.
fn check_parameter<const D: usize>(x: [f64; D], i: usize) -> Result<()> {
    if x.iter().all(|v| (0.0..=1.0).contains(v)) {
        Ok(())
    } else {
        Err(Error::invalid(format!(
            "parametric point {i} {x:?} is outside [0,1]^{D}"
        )))
    }
}

fn point<const D: usize>(values: &[f64], i: usize) -> [f64; D] {
    std::array::from_fn(|k| values[D * i + k])
}

/// Evaluates the map at `n` parametric points `params` (`n × d` doubles in [0,1]^d): `points`
/// receives `S(params)` (`n × d` doubles) and `jacobians` the Jacobian matrices `dS/du`
/// (`n × d × d` doubles, row-major: entry (i, j) = ∂S_i/∂u_j). Either may be NULL to skip it.
/// Fails with `IGAPARAM_STATUS_INVALID_ARGUMENT` when a point is outside [0,1]^d.
#[allow(rustdoc::broken_intra_doc_links)]
#[no_mangle]
pub extern "C" fn igaparam_spline_evaluate(
    spline: *const igaparam_spline,
    n: usize,
    params: *const f64,
    points: *mut f64,
    jacobians: *mut f64,
) -> igaparam_status {
    run("igaparam_spline_evaluate", || {
        let m = map(spline)?;
        let d = dim(&m);
        let input = points_in(params, n, d, "params")?;
        let values = with_map!(m, m => evaluate(m, input)?);
        if let Some(out) = points_out(points, n, d, "points")? {
            for (o, (y, _)) in out.chunks_mut(d).zip(&values) {
                o.copy_from_slice(y);
            }
        }
        if let Some(out) = points_out(jacobians, n, d * d, "jacobians")? {
            for (o, (_, j)) in out.chunks_mut(d * d).zip(&values) {
                o.copy_from_slice(j);
            }
        }
        Ok(())
    })
}

/// Values and row-major Jacobians of `m` at the flat parametric points `input`.
fn evaluate<const D: usize>(m: &SplineMap<D>, input: &[f64]) -> Result<Vec<(Vec<f64>, Vec<f64>)>> {
    let xs: Vec<[f64; D]> = (0..input.len() / D).map(|i| point(input, i)).collect();
    for (i, &x) in xs.iter().enumerate() {
        check_parameter(x, i)?;
    }
    m.eval_many(&xs)
        .into_iter()
        .enumerate()
        .map(|(i, r)| {
            let (y, j) =
                r.ok_or_else(|| Error::invalid(format!("point {i} cannot be evaluated")))?;
            Ok((y.to_vec(), j.iter().flatten().copied().collect()))
        })
        .collect()
}

/// Writes the mean ratio of the Jacobian, `q_S = d·det(J)^(2/d)/‖J‖²_F` in [0, 1] (1 for a
/// conformal map, 0 where det J ≤ 0), at `n` parametric points `params` (`n × d` doubles) into
/// `quality` (`n` doubles).
#[no_mangle]
pub extern "C" fn igaparam_spline_mean_ratio(
    spline: *const igaparam_spline,
    n: usize,
    params: *const f64,
    quality: *mut f64,
) -> igaparam_status {
    run("igaparam_spline_mean_ratio", || {
        let m = map(spline)?;
        let d = dim(&m);
        let input = points_in(params, n, d, "params")?;
        let q = with_map!(m, m => mean_ratios(m, input)?);
        slice_mut(quality, n, "quality")?.copy_from_slice(&q);
        Ok(())
    })
}

/// Mean ratios of `m` at the flat parametric points `input`.
fn mean_ratios<const D: usize>(m: &SplineMap<D>, input: &[f64]) -> Result<Vec<f64>> {
    Ok(evaluate(m, input)?
        .iter()
        .map(|(_, j)| {
            let jacobian: [[f64; D]; D] = std::array::from_fn(|a| point(j, a));
            crate::optimize::metric::mean_ratio(&jacobian)
        })
        .collect())
}

/// Inverts the map at `n` physical points `points` (`n × d` doubles): `params` receives the
/// parametric points whose images they are (`n × d` doubles), `found` (`n` ints) 1 where the
/// point was located and 0 where it is outside the domain (or Newton's method did not converge;
/// `params` is NaN there). `found` may be NULL. Newton's method starts from the nearest of
/// `samples^d` samples per element (`samples` from 2 to 32; 4 is a good choice).
#[no_mangle]
pub extern "C" fn igaparam_spline_invert(
    spline: *const igaparam_spline,
    n: usize,
    points: *const f64,
    samples: u32,
    params: *mut f64,
    found: *mut i32,
) -> igaparam_status {
    run("igaparam_spline_invert", || {
        let m = map(spline)?;
        let d = dim(&m);
        if !(2..=32).contains(&samples) {
            return Err(Error::invalid(format!("samples = {samples} is not in 2..=32")).into());
        }
        let input = points_in(points, n, d, "points")?;
        let located: Vec<Option<Vec<f64>>> = with_map!(m, m => {
            let inverse = m.inverse_map(samples as usize);
            (0..n).map(|i| inverse.locate(point(input, i)).map(|x| x.to_vec())).collect()
        });
        let out =
            points_out(params, n, d, "params")?.ok_or(crate::capi::ffi::NullArgument("params"))?;
        let flags = if found.is_null() {
            None
        } else {
            Some(slice_mut(found, n, "found")?)
        };
        for (o, x) in out.chunks_mut(d).zip(&located) {
            match x {
                Some(x) => o.copy_from_slice(x),
                None => o.fill(f64::NAN),
            }
        }
        if let Some(flags) = flags {
            for (f, x) in flags.iter_mut().zip(&located) {
                *f = x.is_some() as i32;
            }
        }
        Ok(())
    })
}

/// Writes to `*count` the number of basis functions non-zero on the element holding the
/// parametric point `param` (`d` doubles in [0,1]^d): the size of the buffers of
/// `igaparam_spline_basis_at`.
#[allow(rustdoc::broken_intra_doc_links)]
#[no_mangle]
pub extern "C" fn igaparam_spline_basis_count_at(
    spline: *const igaparam_spline,
    param: *const f64,
    count: *mut usize,
) -> igaparam_status {
    run("igaparam_spline_basis_count_at", || {
        let (f, _, _) = basis_at(spline, param)?;
        *non_null_mut(count, "count")? = f.len();
        Ok(())
    })
}

/// The basis functions non-zero on the element holding the parametric point `param` (`d`
/// doubles in [0,1]^d; on an element boundary the element on the upper side): `*count` receives
/// their number `m`, `functions` their global indices (`m` values), `values` their values (`m`
/// doubles) and `gradients` their gradients with respect to the parametric coordinates
/// (`m × d` doubles). The buffers hold `len` functions (`len ≥ m`, see
/// `igaparam_spline_basis_count_at`); any of them may be NULL to skip it. The values sum to 1,
/// and `Σ values[i] × control_point[functions[i]]` is the map's value at `param`. When the
/// buffers are too small (`IGAPARAM_STATUS_BUFFER_TOO_SMALL`) `*count` still receives `m` and
/// nothing else is written.
#[allow(rustdoc::broken_intra_doc_links)]
#[no_mangle]
pub extern "C" fn igaparam_spline_basis_at(
    spline: *const igaparam_spline,
    param: *const f64,
    count: *mut usize,
    functions: *mut usize,
    values: *mut f64,
    gradients: *mut f64,
    len: usize,
) -> igaparam_status {
    run("igaparam_spline_basis_at", || {
        let (f, v, g) = basis_at(spline, param)?;
        let count = non_null_mut(count, "count")?;
        let m = f.len();
        *count = m;
        if !functions.is_null() || !values.is_null() || !gradients.is_null() {
            check_capacity("functions/values/gradients (functions)", len, m)?;
        }
        for (out, from) in [
            (optional_out(values, m), &v),
            (optional_out(gradients, g.len()), &g),
        ] {
            if let Some(out) = out {
                out.copy_from_slice(from);
            }
        }
        if let Some(out) = optional_out(functions, m) {
            out.copy_from_slice(&f);
        }
        Ok(())
    })
}

/// Functions, values and gradients (`d` per function) of the basis at a point.
type BasisAt = (Vec<usize>, Vec<f64>, Vec<f64>);

/// The functions non-zero at `param`, their values and their gradients.
fn basis_at(
    spline: *const igaparam_spline,
    param: *const f64,
) -> std::result::Result<BasisAt, Failure> {
    let m = map(spline)?;
    let d = dim(&m);
    let x = points_in(param, 1, d, "param")?;
    Ok(with_map!(m, m => {
        let p = point(x, 0);
        check_parameter(p, 0)?;
        let b = m.basis_at(p)
            .ok_or_else(|| Error::invalid("the point is outside the parametric domain"))?;
        (b.functions, b.values, b.gradients.iter().flatten().copied().collect())
    }))
}
