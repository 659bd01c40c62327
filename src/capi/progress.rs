//! Progress reporting of long calls: the stages, the callback type, and how a call asks the
//! callback (and the handle's release request) whether to go on.

use std::ffi::{c_int, c_void};

use super::handle::ReleaseWatch;

/// A stage of long work, passed to the progress callback.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum igaparam_stage {
    /// First placement of the free nodes.
    IGAPARAM_STAGE_PLACEMENT = 0,
    /// Optimization sweeps: `done` sweeps so far over all steps; `total` is 0 (not known in
    /// advance, as large motions may be split into more steps).
    IGAPARAM_STAGE_OPTIMIZATION = 1,
    /// Adaptive refinement of a domain's T-mesh from the quality of its spline map: `done`
    /// rounds of `total` at most.
    IGAPARAM_STAGE_ADAPTATION = 2,
    /// Newton iterations on the global objective (`stationarity_tolerance`): `done` so far,
    /// `total` 0.
    IGAPARAM_STAGE_STATIONARITY = 3,
    /// The fits and certifications of `igaparam_spline_fit_domain_with`: `done` of `total`.
    IGAPARAM_STAGE_FIT = 4,
    /// Untangling rounds of a fitted map that is not certified: `done` of at most `total`.
    IGAPARAM_STAGE_UNTANGLING = 5,
    /// Smoothing sweeps of a certified map: `done` of at most `total`.
    IGAPARAM_STAGE_SMOOTHING = 6,
}

/// Progress callback: `user` is the options' `progress_user`; `done` of `total` steps of `stage`
/// are complete. Return 0 to go on, non-zero to cancel (the call then returns
/// `IGAPARAM_STATUS_CANCELLED` and leaves the mesh unchanged). Called on the calling thread.
pub type igaparam_progress_fn = Option<
    unsafe extern "C" fn(
        user: *mut c_void,
        stage: igaparam_stage,
        done: usize,
        total: usize,
    ) -> c_int,
>;

/// Calls the progress callback `f` (none: go on) with `user`; true to go on.
pub(crate) fn call_progress(
    f: igaparam_progress_fn,
    user: *mut c_void,
    stage: igaparam_stage,
    done: usize,
    total: usize,
) -> bool {
    match f {
        None => true,
        // SAFETY: the caller supplied a valid callback and its user pointer.
        Some(f) => unsafe { f(user, stage, done, total) == 0 },
    }
}

/// The progress of the optimization of a T-mesh as the C callback `progress` sees it
/// (`IGAPARAM_STAGE_OPTIMIZATION`, sweeps done, total 0): false when it asks to cancel or the
/// handle's release was requested (`watch`).
pub(super) fn optimization_progress(
    progress: igaparam_progress_fn,
    user: *mut c_void,
    watch: ReleaseWatch<'_>,
) -> impl FnMut(usize, usize) -> bool + '_ {
    move |done, total| {
        call_progress(
            progress,
            user,
            igaparam_stage::IGAPARAM_STAGE_OPTIMIZATION,
            done,
            total,
        ) && !watch.requested()
    }
}
