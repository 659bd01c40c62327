//! Relocation of a mesh's nodes: `igaparam_mesh_relocate` and its default options (the options
//! and report structs are generated from the core's in `options_gen.rs` and `reports_gen.rs`),
//! and the sensitivities of the result (`igaparam_mesh_adjoint`, `igaparam_mesh_tangent`).

use super::ffi::{options_or, run, slice, slice_mut, write_optional};
use super::mesh::{igaparam_mesh, with_mesh};
use super::options_gen::igaparam_relocate_options;
use super::progress::call_progress;
use super::reports_gen::igaparam_relocate_report;
use super::{igaparam_stage, igaparam_status};
use crate::fe_mesh::{RelocateOptions, Stage};

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
        write_optional(report, igaparam_relocate_report::from(&r));
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
