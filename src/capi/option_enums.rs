//! The integer types and `IGAPARAM_*` constants of the enums the option structs hold (the
//! conversions to and from the core's enums are generated in `options_gen.rs`): a new variant of
//! one of the core's enums needs its constant here, or the generated conversions do not compile.
//! Also the C names of the array lengths of the generated reports.

use std::ffi::c_int;

use crate::error::Error;
use crate::spline::HISTOGRAM_BINS;

/// Number of bins of the quality histogram of `igaparam_validity_report`.
pub const IGAPARAM_HISTOGRAM_BINS: usize = 10;
const _: () = assert!(IGAPARAM_HISTOGRAM_BINS == HISTOGRAM_BINS);

/// Where free nodes start: one of the `IGAPARAM_PLACEMENT_*` values.
pub type igaparam_placement = c_int;
/// Harmonic extension of the prescribed displacements (a discrete Laplace equation): every free
/// coordinate starts from its reference position plus that extension, whatever position
/// `igaparam_mesh_move_nodes` gave it.
pub const IGAPARAM_PLACEMENT_LAPLACIAN: igaparam_placement = 0;
/// The current positions, as they are.
pub const IGAPARAM_PLACEMENT_CURRENT: igaparam_placement = 1;
/// Warm start for loops: the positions of the last successful relocation plus the harmonic
/// extension of the prescribed motion since then (the first relocation of a mesh starts as
/// `IGAPARAM_PLACEMENT_LAPLACIAN`); the targets stay the reference shapes. Use it when the
/// boundary moves a little at every call, as in a shape-optimization loop.
pub const IGAPARAM_PLACEMENT_INCREMENTAL: igaparam_placement = 2;

/// How the free nodes are carried to the optimum: one of the `IGAPARAM_METHOD_*` values.
pub type igaparam_method = c_int;
/// `IGAPARAM_METHOD_NEWTON` where the Hessian's Cholesky factor is small (2D meshes, 3D meshes
/// up to about 20,000 nodes) or, beyond, where the Hessian has at most 10⁸ values (about
/// 310,000 H27 nodes; multigrid-preconditioned steps, about 17 bytes per value at the peak),
/// else `IGAPARAM_METHOD_SWEEPS` (default). Where memory is short, `IGAPARAM_METHOD_SWEEPS`
/// needs about a quarter (the bundled wing: 0.16 GB against 0.59 GB).
pub const IGAPARAM_METHOD_AUTO: igaparam_method = 0;
/// The per-node optimizer's coloured Gauss–Seidel sweeps, large motions in steps placed
/// harmonically; with `stationarity_tolerance > 0`, followed by the Newton stage.
pub const IGAPARAM_METHOD_SWEEPS: igaparam_method = 1;
/// Path following of the optimum of the global objective: each step predicted by the tangent of
/// the optimum (the linearised response of the mesh to the motion) and corrected by Newton's
/// method; the sweeps are the fallback where a step cannot be made (e.g. a tangled start). With
/// `IGAPARAM_PLACEMENT_CURRENT` (untangling in place): 3 sweeps (more while cells stay invalid),
/// then Newton's method to the stationarity tolerance (1e-8 when none is asked for). A Hessian,
/// or a multigrid preconditioner beside it, whose storage cannot be reserved (past an
/// address-space limit, strict overcommit's commit limit, or the machine's memory and swap) is
/// refused with `IGAPARAM_STATUS_LIMIT_EXCEEDED`.
pub const IGAPARAM_METHOD_NEWTON: igaparam_method = 2;

/// Which fit rule `igaparam_spline_fit_domain_with` uses: one of the `IGAPARAM_FIT_CHOICE_*`
/// values.
pub type igaparam_fit_choice = c_int;
/// Interpolation at the Greville points (least squares when that system is singular or badly
/// conditioned) and, unless that map is certified valid, the local quasi-interpolant too; the
/// better of the two is kept (what `igaparam_spline_fit_domain` does).
pub const IGAPARAM_FIT_CHOICE_BEST: igaparam_fit_choice = 0;
/// Interpolation at the Greville points only (least squares when singular).
pub const IGAPARAM_FIT_CHOICE_INTERPOLATION: igaparam_fit_choice = 1;
/// The local quasi-interpolant only.
pub const IGAPARAM_FIT_CHOICE_QUASI_INTERPOLATION: igaparam_fit_choice = 2;

/// The error of a value `code` of an enum called `what` that is none of the `allowed` constants
/// (name, value): "placement 7 is not IGAPARAM_PLACEMENT_LAPLACIAN (0), ... or ... (2)".
pub(crate) fn not_one_of(what: &str, code: c_int, allowed: &[(&str, c_int)]) -> Error {
    let named: Vec<String> = allowed.iter().map(|(n, v)| format!("{n} ({v})")).collect();
    let sentence = match named.split_last() {
        Some((last, [only])) => format!("is neither {only} nor {last}"),
        Some((last, first)) if !first.is_empty() => {
            format!("is not {} or {last}", first.join(", "))
        }
        _ => format!("is not {}", named.join("")),
    };
    Error::invalid(format!("{what} {code} {sentence}"))
}
