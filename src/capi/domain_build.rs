//! Building a domain: `igaparam_domain_build` and its default options (the options and report
//! structs are generated from the core's in `options_gen.rs` and `reports_gen.rs`).

use super::domain::{held, igaparam_domain, DomainData};
use super::ffi::{options_or, run, write_optional};
use super::igaparam_status;
use super::options_gen::igaparam_domain_options;
use super::progress::optimization_progress;
use super::reports_gen::igaparam_domain_report;
use crate::domain::{PlanarDomain, PlanarOptions, SolidDomain, SolidOptions};

/// The default options of a planar domain (tolerance 1e-5).
#[no_mangle]
pub extern "C" fn igaparam_domain_options_default() -> igaparam_domain_options {
    igaparam_domain_options::from(&PlanarOptions::default())
}

/// The default options of a solid: those of `igaparam_domain_options_default` with a
/// tolerance of 1e-3 (a tolerance bounds a volume in 3D; 1e-5 refines for many minutes).
/// `igaparam_domain_build` with NULL options uses these for a solid.
#[no_mangle]
pub extern "C" fn igaparam_domain_options_default_solid() -> igaparam_domain_options {
    igaparam_domain_options::from(&SolidOptions::solid())
}

/// Adapts a T-mesh to the boundary (refining boundary cells until `options.tolerance` or
/// `options.max_level` is met), places its vertices (boundary ones on the curves, inner ones by
/// the Coons patch) and optimizes them; the result is kept in the handle, replacing that of an
/// earlier build. `options` may be NULL for the defaults (`igaparam_domain_options_default`, or
/// `igaparam_domain_options_default_solid` for a solid); `report` may be NULL. On any error or
/// cancellation the handle is unchanged (an earlier build stays) and `*report` is not written.
/// A planar build fails with `IGAPARAM_STATUS_INVALID_ARGUMENT` when cells stay invalid because
/// the T-mesh's boundary facets cut across the boundary (it comes closer to itself than the
/// cells resolve); the message says where.
#[no_mangle]
pub extern "C" fn igaparam_domain_build(
    domain: *mut igaparam_domain,
    options: *const igaparam_domain_options,
    report: *mut igaparam_domain_report,
) -> igaparam_status {
    run("igaparam_domain_build", || {
        let mut held = held(domain)?;
        let (d, watch) = held.split();
        let defaults = match d {
            DomainData::Planar(..) => igaparam_domain_options_default(),
            DomainData::Solid(..) => igaparam_domain_options_default_solid(),
        };
        let raw = options_or(options, defaults);
        let opts = raw.to_core()?;
        opts.validate()?;
        let mut progress = optimization_progress(raw.progress, raw.progress_user, watch);
        let r = match d {
            DomainData::Planar(boundary, built) => {
                let (planar, r) = PlanarDomain::build(boundary.clone(), &opts, &mut progress)
                    .map_err(|e| watch.explain(e))?;
                *built = Some(planar);
                r
            }
            DomainData::Solid(boundary, built) => {
                let (solid, r) =
                    SolidDomain::build(boundary.as_ref().clone(), &opts, &mut progress)
                        .map_err(|e| watch.explain(e))?;
                *built = Some(Box::new(solid));
                r
            }
        };
        write_optional(report, igaparam_domain_report::from(&r));
        Ok(())
    })
}
