//! The domain handle: a planar domain bounded by four curves or a solid bounded by six surfaces,
//! and once built its T-mesh parameterization; the one check that a domain has been built.
//! Building is in `domain_build.rs`, read-back in `domain_query.rs`, boundary input in
//! `domain_input.rs`, moving the boundary in `domain_update.rs`.

use std::ffi::c_int;

use super::ffi::{non_null_mut, run, Failure};
use super::handle::{acquire, handle_type, release, Guarded, Held};
use super::igaparam_status;
use crate::boundary::{BoundaryLoop2, SolidBoundary};
use crate::domain::{CubeMap, Domain, PlanarDomain, SolidDomain};
use crate::error::{Error, Result};
use crate::spline::UntangleOptions;

/// A planar domain bounded by four curves or a solid bounded by six surfaces, and once built
/// its T-mesh parameterization (opaque). Create a planar one with
/// `igaparam_domain_new_from_file` or `igaparam_domain_new_from_polylines`, a solid with
/// `igaparam_domain_new_solid_from_file`, `igaparam_domain_new_solid_from_file_scaled` or
/// `igaparam_domain_new_solid_from_triangulations`; build with `igaparam_domain_build`,
/// release with `igaparam_domain_free`. One call at a time (see `IGAPARAM_STATUS_BUSY`).
pub struct igaparam_domain(Guarded<DomainData>);
handle_type!(igaparam_domain, DomainData, "domain");

/// What a domain handle holds: its boundary and, once built, its T-mesh parameterization.
// The handle itself lives on the heap behind the C pointer; the variants' sizes do not matter.
#[allow(clippy::large_enum_variant)]
pub(crate) enum DomainData {
    /// Bounded by four curves.
    Planar(BoundaryLoop2, Option<PlanarDomain>),
    /// Bounded by six surfaces.
    Solid(Box<SolidBoundary>, Option<Box<SolidDomain>>),
}

/// A built domain's boundary and T-mesh parameterization, of either dimension, borrowed from a
/// [`DomainData`]: `P` is what a planar one lends, `S` what a solid lends.
pub(crate) enum Built<P, S> {
    /// A planar domain.
    Planar(P),
    /// A solid.
    Solid(S),
}

/// A built domain, read only.
pub(crate) type BuiltRef<'a> =
    Built<(&'a BoundaryLoop2, &'a PlanarDomain), (&'a SolidBoundary, &'a SolidDomain)>;

/// A built domain, its parameterization writable.
pub(crate) type BuiltMut<'a> =
    Built<(&'a BoundaryLoop2, &'a mut PlanarDomain), (&'a SolidBoundary, &'a mut SolidDomain)>;

/// Runs `$body` with `$d` bound to the parameterization of a [`BuiltRef`] of either dimension
/// (the body is compiled for both).
macro_rules! with_built {
    ($built:expr, $d:ident => $body:expr) => {
        match $built {
            $crate::capi::domain::Built::Planar((_, $d)) => $body,
            $crate::capi::domain::Built::Solid((_, $d)) => $body,
        }
    };
}
pub(crate) use with_built;

/// The error of a call that needs a built domain on one that is not.
fn not_built() -> Error {
    Error::invalid("the domain has not been built: call igaparam_domain_build first")
}

impl DomainData {
    pub(super) fn dim(&self) -> usize {
        match self {
            DomainData::Planar(..) => 2,
            DomainData::Solid(..) => 3,
        }
    }

    /// The built domain, or the error that it has not been built.
    pub(super) fn built(&self) -> Result<BuiltRef<'_>> {
        match self {
            DomainData::Planar(boundary, Some(d)) => Ok(Built::Planar((boundary, d))),
            DomainData::Solid(boundary, Some(d)) => Ok(Built::Solid((boundary, d))),
            _ => Err(not_built()),
        }
    }

    /// The built domain with its parameterization writable, or the error that it has not been
    /// built.
    pub(super) fn built_mut(&mut self) -> Result<BuiltMut<'_>> {
        match self {
            DomainData::Planar(boundary, Some(d)) => Ok(Built::Planar((boundary, d))),
            DomainData::Solid(boundary, Some(d)) => Ok(Built::Solid((boundary, d))),
            _ => Err(not_built()),
        }
    }

    /// Whether the boundary was replaced (`igaparam_domain_set_boundary_*`) since the T-mesh
    /// was built or updated (false for a domain not built).
    fn pending(&self) -> bool {
        match self.built() {
            Ok(Built::Planar((boundary, d))) => d.boundary() != boundary,
            Ok(Built::Solid((boundary, d))) => d.boundary() != boundary,
            Err(_) => false,
        }
    }
}

/// Releases a domain. NULL is a no-op. Called on a domain in use (from the progress callback of
/// `igaparam_domain_build`, `igaparam_domain_update` or `igaparam_domain_fit_adaptive`, or from
/// another thread), the release waits for that call: the call stops at its next progress point
/// with `IGAPARAM_STATUS_CANCELLED` and the domain is released as it returns; the handle must
/// not be used after this call in either case.
#[no_mangle]
pub extern "C" fn igaparam_domain_free(domain: *mut igaparam_domain) {
    release(domain);
}

/// The domain of handle `domain`, held for the call.
pub(super) fn held<'a>(
    domain: *const igaparam_domain,
) -> std::result::Result<Held<'a, igaparam_domain>, Failure> {
    acquire(domain, "domain")
}

/// The built domain whose T-mesh is on its current boundary, or an error if it has not been
/// built or its boundary was replaced since (fits need the T-mesh moved first).
pub(super) fn current<'a>(
    domain: *const igaparam_domain,
) -> std::result::Result<Held<'a, igaparam_domain>, Failure> {
    let d = held(domain)?;
    d.built()?;
    if d.pending() {
        return Err(Error::invalid(
            "the boundary was replaced (igaparam_domain_set_boundary_*) since the T-mesh was \
             built: call igaparam_domain_update (or igaparam_domain_build) first",
        )
        .into());
    }
    Ok(d)
}

/// The untangling options of a built domain's fits: the defaults except the boundary offset,
/// which is the domain's own (a domain built to keep its boundary keeps it in the spline map
/// too).
pub(super) fn untangle_options<const D: usize, B: CubeMap<D>>(
    domain: &Domain<D, B>,
) -> UntangleOptions {
    UntangleOptions {
        boundary_offset: domain.options().boundary_offset,
        ..Default::default()
    }
}

/// Writes to `*out` the dimension of the domain: 2 for a planar domain, 3 for a solid.
#[no_mangle]
pub extern "C" fn igaparam_domain_dimension(
    domain: *const igaparam_domain,
    out: *mut usize,
) -> igaparam_status {
    run("igaparam_domain_dimension", || {
        let d = held(domain)?.dim();
        *non_null_mut(out, "out")? = d;
        Ok(())
    })
}

/// Writes to `*out` 1 if the domain has been built (by a successful `igaparam_domain_build`),
/// else 0.
#[no_mangle]
pub extern "C" fn igaparam_domain_is_built(
    domain: *const igaparam_domain,
    out: *mut c_int,
) -> igaparam_status {
    run("igaparam_domain_is_built", || {
        let b = held(domain)?.built().is_ok();
        *non_null_mut(out, "out")? = b as c_int;
        Ok(())
    })
}
