//! Moving the boundary of a built domain: `igaparam_domain_set_boundary_*` replace the boundary
//! (by one of the same kind and orientation, from the same inputs as the constructors) and
//! `igaparam_domain_update` moves the T-mesh onto it, keeping its tree (its options and report
//! structs are generated from the core's in `options_gen.rs` and `reports_gen.rs`).

use std::ffi::c_char;

use super::domain::{held, igaparam_domain, Built, DomainData};
use super::domain_input::{
    curves_boundary, igaparam_curve, igaparam_surface, planar_file_boundary, polylines_boundary,
    solid_file_boundary, surfaces_boundary, triangulations_boundary,
};
use super::ffi::{c_path, options_or, run, write_optional, Failure};
use super::igaparam_status;
use super::options_gen::igaparam_domain_update_options;
use super::progress::optimization_progress;
use super::reports_gen::igaparam_domain_update_report;
use crate::boundary::{BoundaryLoop2, SolidBoundary};
use crate::domain::UpdateOptions;
use crate::error::Error;

/// The default update options.
#[no_mangle]
pub extern "C" fn igaparam_domain_update_options_default() -> igaparam_domain_update_options {
    igaparam_domain_update_options::from(&UpdateOptions::default())
}

/// A new boundary of either kind.
// Made once per call and moved into the handle at once; the variants' sizes do not matter.
#[allow(clippy::large_enum_variant)]
enum NewBoundary {
    Planar(BoundaryLoop2),
    Solid(SolidBoundary),
}

/// The body of the `igaparam_domain_set_boundary_*` functions: checks that the domain is of
/// dimension `dim` (when given), makes the boundary, checks it against the built T-mesh (same
/// orientation) and puts it in the handle.
fn set_boundary(
    function: &str,
    domain: *mut igaparam_domain,
    dim: Option<usize>,
    make: impl FnOnce(usize) -> std::result::Result<NewBoundary, Failure>,
) -> igaparam_status {
    run(function, || {
        let mut held = held(domain)?;
        let own = held.dim();
        if let Some(dim) = dim.filter(|&dim| dim != own) {
            let (has, given) = match dim {
                2 => ("a solid, bounded by six surfaces", "four curves"),
                _ => ("planar, bounded by four curves", "six faces"),
            };
            return Err(Error::invalid(format!(
                "the domain is {has}; a boundary of {given} cannot replace its boundary"
            ))
            .into());
        }
        let new = make(own)?;
        match (&mut *held, new) {
            (DomainData::Planar(boundary, built), NewBoundary::Planar(new)) => {
                if let Some(b) = built {
                    b.check_boundary(&new)?;
                }
                *boundary = new;
            }
            (DomainData::Solid(boundary, built), NewBoundary::Solid(new)) => {
                if let Some(b) = built {
                    b.check_boundary(&new)?;
                }
                **boundary = new;
            }
            _ => return Err(Error::invalid("the boundary is not of the domain's kind").into()),
        }
        Ok(())
    })
}

/// Replaces the boundary of a domain by four B-spline or NURBS curves given as arrays (`count`
/// = 4 entries of `curves`, read as by `igaparam_domain_new_from_curves`: give them in the order
/// and direction of the first ones, so that each lands on the same side). The T-mesh of a built
/// domain stays where it is until `igaparam_domain_update` moves it onto the new boundary (or
/// `igaparam_domain_build` builds anew); fits need that first. Errors: those of
/// `igaparam_domain_new_from_curves`, `IGAPARAM_STATUS_INVALID_ARGUMENT` for a solid or, once
/// built, a boundary oriented the other way round (its parameterization mirrored relative to
/// the domain's). On error the domain is unchanged. The arrays are copied.
#[no_mangle]
pub extern "C" fn igaparam_domain_set_boundary_curves(
    domain: *mut igaparam_domain,
    count: usize,
    curves: *const igaparam_curve,
) -> igaparam_status {
    set_boundary(
        "igaparam_domain_set_boundary_curves",
        domain,
        Some(2),
        |_| Ok(NewBoundary::Planar(curves_boundary(count, curves)?)),
    )
}

/// Replaces the boundary of a planar domain by four polylines (the arrays of
/// `igaparam_domain_new_from_polylines`), as `igaparam_domain_set_boundary_curves` does.
#[no_mangle]
pub extern "C" fn igaparam_domain_set_boundary_polylines(
    domain: *mut igaparam_domain,
    counts: *const usize,
    points: *const *const f64,
) -> igaparam_status {
    set_boundary(
        "igaparam_domain_set_boundary_polylines",
        domain,
        Some(2),
        |_| Ok(NewBoundary::Planar(polylines_boundary(counts, points)?)),
    )
}

/// Replaces the boundary of a solid by six B-spline or NURBS surfaces given as arrays (`count`
/// = 6 entries of `surfaces`, read as by `igaparam_domain_new_solid_from_surfaces`: give them in
/// the order and with the parameterizations of the first ones), as
/// `igaparam_domain_set_boundary_curves` does for planar domains. Errors: those of
/// `igaparam_domain_new_solid_from_surfaces`, `IGAPARAM_STATUS_INVALID_ARGUMENT` for a planar
/// domain or a boundary oriented the other way round. On error the domain is unchanged.
#[no_mangle]
pub extern "C" fn igaparam_domain_set_boundary_surfaces(
    domain: *mut igaparam_domain,
    count: usize,
    surfaces: *const igaparam_surface,
) -> igaparam_status {
    set_boundary(
        "igaparam_domain_set_boundary_surfaces",
        domain,
        Some(3),
        |_| Ok(NewBoundary::Solid(surfaces_boundary(count, surfaces)?)),
    )
}

/// Replaces the boundary of a solid by six triangulated faces (the arrays of
/// `igaparam_domain_new_solid_from_triangulations`, each face parameterized anew by Floater's
/// map), as `igaparam_domain_set_boundary_surfaces` does.
#[no_mangle]
pub extern "C" fn igaparam_domain_set_boundary_triangulations(
    domain: *mut igaparam_domain,
    vertex_counts: *const usize,
    xyz: *const *const f64,
    triangle_counts: *const usize,
    triangles: *const *const u32,
) -> igaparam_status {
    set_boundary(
        "igaparam_domain_set_boundary_triangulations",
        domain,
        Some(3),
        |_| {
            let b = triangulations_boundary(vertex_counts, xyz, triangle_counts, triangles)?;
            Ok(NewBoundary::Solid(b))
        },
    )
}

/// Replaces the boundary of a domain by the one of a file: for a planar domain a `.xml` G+Smo
/// B-rep of four curves or a `.txt` coastline (as `igaparam_domain_new_from_file`), for a solid a
/// `.xml` B-rep of six surfaces or a folder of six `.obj` faces (as
/// `igaparam_domain_new_solid_from_file`); otherwise as `igaparam_domain_set_boundary_curves`.
#[no_mangle]
pub extern "C" fn igaparam_domain_set_boundary_from_file(
    domain: *mut igaparam_domain,
    path: *const c_char,
) -> igaparam_status {
    set_boundary(
        "igaparam_domain_set_boundary_from_file",
        domain,
        None,
        |dim| {
            let path = c_path(path, "path")?;
            Ok(match dim {
                2 => NewBoundary::Planar(planar_file_boundary(path)?),
                _ => NewBoundary::Solid(solid_file_boundary(path, std::ptr::null())?),
            })
        },
    )
}

/// Replaces the boundary of a solid by the one of a file or folder, its coordinates scaled
/// first (`scale`: NULL or 3 finite positive factors, as
/// `igaparam_domain_new_solid_from_file_scaled`); otherwise as
/// `igaparam_domain_set_boundary_from_file`.
#[no_mangle]
pub extern "C" fn igaparam_domain_set_boundary_from_file_scaled(
    domain: *mut igaparam_domain,
    path: *const c_char,
    scale: *const f64,
) -> igaparam_status {
    set_boundary(
        "igaparam_domain_set_boundary_from_file_scaled",
        domain,
        Some(3),
        |_| {
            let path = c_path(path, "path")?;
            Ok(NewBoundary::Solid(solid_file_boundary(path, scale)?))
        },
    )
}

/// Moves the built T-mesh onto the domain's current boundary (the one given by the last
/// `igaparam_domain_set_boundary_*`), keeping its tree: every boundary vertex goes to the point
/// of its parameters on the new boundary (keeping the offset the seam relief gave it, if any),
/// the inner vertices to their current positions plus the harmonic extension of that motion
/// (a motion of more than about four cell sizes in steps), and all are optimized again (with
/// the seam relief of the build where cells stay folded). The targets of the cells stay those
/// of the build (its bounding box), as for relocated meshes. The report says whether the
/// tree's tolerance still holds; the tree changes only when `options->refine` is set. A spline
/// fitted to the domain is refitted in its own space with `igaparam_spline_refit`.
///
/// `options` may be NULL for the defaults (`igaparam_domain_update_options_default`); `report`
/// may be NULL. Errors: `IGAPARAM_STATUS_INVALID_ARGUMENT` when the domain has not been built
/// (call `igaparam_domain_build` first) or for threads above 4096, `IGAPARAM_STATUS_CANCELLED`,
/// `IGAPARAM_STATUS_LIMIT_EXCEEDED` when the build's `max_total_sweeps` runs out while the
/// vertices follow the boundary (later stages stop there and succeed, setting the report's
/// `sweep_budget_exhausted`), `IGAPARAM_STATUS_INVALID_ARGUMENT` also when cells stay invalid
/// on a planar T-mesh whose boundary facets cut across the new boundary (the message says
/// where). On any error the domain is unchanged and `*report` is not written.
#[no_mangle]
pub extern "C" fn igaparam_domain_update(
    domain: *mut igaparam_domain,
    options: *const igaparam_domain_update_options,
    report: *mut igaparam_domain_update_report,
) -> igaparam_status {
    run("igaparam_domain_update", || {
        let mut held = held(domain)?;
        let (d, watch) = held.split();
        let raw = options_or(options, igaparam_domain_update_options_default());
        let opts = raw.to_core()?;
        let mut progress = optimization_progress(raw.progress, raw.progress_user, watch);
        let r = match d.built_mut()? {
            Built::Planar((boundary, built)) => {
                built.update(boundary.clone(), &opts, &mut progress)
            }
            Built::Solid((boundary, built)) => built.update(boundary.clone(), &opts, &mut progress),
        }
        .map_err(|e| watch.explain(e))?;
        write_optional(report, igaparam_domain_update_report::from(&r));
        Ok(())
    })
}
