//! Relocation of a mesh's nodes: `igaparam_mesh_relocate`, its default options (the struct is
//! generated from the core's in `options_gen.rs`) and report, and the sensitivities of the result
//! (`igaparam_mesh_adjoint`, `igaparam_mesh_tangent`).

use std::ffi::c_int;

use super::ffi::{options_or, run, slice, slice_mut, write_optional};
use super::mesh::{igaparam_mesh, with_mesh};
use super::options_gen::igaparam_relocate_options;
use super::progress::call_progress;
use super::{igaparam_stage, igaparam_status};
use crate::fe_mesh::{RelocateOptions, Stage};

/// What `igaparam_mesh_relocate` did. Quality is the inverse mean distortion of a cell against its
/// target over its Gauss–Lobatto points: 1 is the target shape, 0 an inverted cell.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct igaparam_relocate_report {
    /// Number of cells.
    pub cells: usize,
    /// Number of nodes.
    pub nodes: usize,
    /// Nodes with at least one free coordinate.
    pub free_nodes: usize,
    /// Cells with det J <= 0 at a Gauss–Lobatto point when the call started.
    pub invalid_before: usize,
    /// Invalid cells after the first placement.
    pub invalid_after_placement: usize,
    /// Invalid cells at the end.
    pub invalid_after: usize,
    /// Smallest cell quality at the end.
    pub min_quality: f64,
    /// Mean cell quality at the end.
    pub mean_quality: f64,
    /// Optimization sweeps performed (over all steps).
    pub sweeps: u32,
    /// Steps the prescribed motion was applied in (large motions are split so that no prescribed
    /// node moves more than about one cell size per step).
    pub steps: u32,
    /// 1 when the sweeps met their stopping rule (valid mesh, small moves) and, when asked for,
    /// the Newton stage its `stationarity_tolerance`; else 0.
    pub converged: c_int,
    /// Scaled max-norm of the gradient of F at the end: over the free coordinates,
    /// |dF/dx| times the node's local cell size divided by its number of cells (the gradient of
    /// the node's own objective times its size; dimensionless). Infinite for an invalid mesh.
    pub gradient_norm: f64,
    /// Newton iterations of the stationarity stage.
    pub newton_iterations: u32,
    /// Wall-clock seconds of the call.
    pub seconds: f64,
}

/// The default relocation options.
#[no_mangle]
pub extern "C" fn igaparam_relocate_options_default() -> igaparam_relocate_options {
    igaparam_relocate_options::from(&RelocateOptions::default())
}

/// Relocates the free coordinates of the nodes so that every cell is valid and close to its
/// target shape, keeping the connectivity. `options` may be NULL for the defaults; `report` may
/// be NULL. On any error or cancellation the mesh is unchanged and `*report` is not written.
///
/// Units: the result does not depend on them. The mesh is optimized in coordinates scaled by
/// the power of two `2^-k` with `2^k <= L < 2^(k+1)`, L the largest side of the bounding box of
/// the reference shape's cell nodes, so every tolerance inside (and every option's tolerance,
/// given relative to a local cell size) is relative to the mesh's size; a mesh scaled by a
/// power of two relocates to the same result scaled bit for bit, by any other factor to the
/// same result to round-off. Prescribed coordinates are returned with the bits they were
/// given.
#[no_mangle]
pub extern "C" fn igaparam_mesh_relocate(
    mesh: *mut igaparam_mesh,
    options: *const igaparam_relocate_options,
    report: *mut igaparam_relocate_report,
) -> igaparam_status {
    run("igaparam_mesh_relocate", || {
        let mut handle = with_mesh(mesh)?;
        let raw = options_or(options, igaparam_relocate_options_default());
        let opts = raw.to_core()?;
        let (handle, watch) = handle.split();
        let mut relocation = relocation_progress(&raw);
        let mut progress = |stage: Stage, done: usize, total: usize| {
            relocation(stage, done, total) && !watch.requested()
        };
        // Mesh::relocate changes nothing on error or cancellation.
        let r = handle
            .relocate(&opts, &mut progress)
            .map_err(|e| watch.explain(e))?;
        write_optional(report, report_of(&r));
        Ok(())
    })
}

/// The relocation's progress as the options' callback sees it.
pub(super) fn relocation_progress(
    raw: &igaparam_relocate_options,
) -> impl FnMut(Stage, usize, usize) -> bool + '_ {
    |stage: Stage, done: usize, total: usize| {
        let stage = match stage {
            Stage::Placement => igaparam_stage::IGAPARAM_STAGE_PLACEMENT,
            Stage::Optimization => igaparam_stage::IGAPARAM_STAGE_OPTIMIZATION,
            Stage::Stationarity => igaparam_stage::IGAPARAM_STAGE_STATIONARITY,
        };
        call_progress(raw.progress, raw.progress_user, stage, done, total)
    }
}

/// The C form of a relocation's report.
pub(super) fn report_of(r: &crate::fe_mesh::RelocateReport) -> igaparam_relocate_report {
    igaparam_relocate_report {
        cells: r.cells,
        nodes: r.nodes,
        free_nodes: r.free_nodes,
        invalid_before: r.invalid_before,
        invalid_after_placement: r.invalid_after_placement,
        invalid_after: r.invalid_after,
        min_quality: r.min_quality,
        mean_quality: r.mean_quality,
        sweeps: r.sweeps,
        steps: r.steps,
        converged: r.converged as c_int,
        gradient_norm: r.gradient_norm,
        newton_iterations: r.newton_iterations,
        seconds: r.seconds,
    }
}

/// The adjoint product of the last relocation: `dj_dx` holds the partial derivatives dJ/dx of a
/// scalar J of the node positions (`size` = 3 × num_nodes doubles, x0 y0 z0 x1 ...);
/// `dj_dprescribed` (`size` doubles) receives the total derivative of J with respect to every
/// prescribed coordinate, dJ/dx_p = dJ/dx_p (partial) − H_pf H_ff⁻¹ dJ/dx_f, through the
/// relocation's dependence of the free coordinates on the prescribed ones (implicit function
/// theorem at the stationary point; H the Hessian of F), and 0 at the free coordinates.
///
/// Free coordinates: those whose constraint bit is clear, of nodes that belong to a cell
/// (sliding nodes have both kinds); all others are prescribed, and z of every node of a 2D mesh.
/// Needs a last relocation with `stationarity_tolerance > 0` that reached it on a valid mesh;
/// `igaparam_mesh_move_nodes`, `igaparam_mesh_set_fixed`, `igaparam_mesh_reset_reference` and
/// a new relocation invalidate the state (the call then fails and says why). The factorisation
/// of H_ff (2D meshes and small 3D ones) is kept on the handle, so further products at one
/// state cost a solve each; larger 3D meshes solve by preconditioned conjugate gradients.
/// Uses the thread count of the last relocation.
#[no_mangle]
pub extern "C" fn igaparam_mesh_adjoint(
    mesh: *const igaparam_mesh,
    size: usize,
    dj_dx: *const f64,
    dj_dprescribed: *mut f64,
) -> igaparam_status {
    run("igaparam_mesh_adjoint", || {
        let handle = with_mesh(mesh)?;
        // The input is read before the output is written, so the two may be one array.
        let threads = handle.last_threads();
        let result = handle.adjoint(threads, slice(dj_dx, size, "dj_dx")?)?;
        slice_mut(dj_dprescribed, size, "dj_dprescribed")?.copy_from_slice(&result);
        Ok(())
    })
}

/// The tangent product of the last relocation (the transpose of `igaparam_mesh_adjoint`):
/// `dx_prescribed` (`size` = 3 × num_nodes doubles) is a motion of the prescribed coordinates
/// (its entries at free coordinates are ignored); `dx` (`size` doubles) receives the first-order
/// motion of every node: the given motion at prescribed coordinates, −H_ff⁻¹ H_fp dx_p at free
/// ones. Same conditions as `igaparam_mesh_adjoint`.
#[no_mangle]
pub extern "C" fn igaparam_mesh_tangent(
    mesh: *const igaparam_mesh,
    size: usize,
    dx_prescribed: *const f64,
    dx: *mut f64,
) -> igaparam_status {
    run("igaparam_mesh_tangent", || {
        let handle = with_mesh(mesh)?;
        // The input is read before the output is written, so the two may be one array.
        let threads = handle.last_threads();
        let result = handle.tangent(threads, slice(dx_prescribed, size, "dx_prescribed")?)?;
        slice_mut(dx, size, "dx")?.copy_from_slice(&result);
        Ok(())
    })
}
