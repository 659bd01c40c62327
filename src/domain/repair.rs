//! The repair of a T-mesh whose optimization leaves folded cells: seam relief first (boundary
//! vertices leave the boundary, see [`relief`](super::relief)), then rounds that refine the
//! cells still folded and optimize again. [`Domain::build`] ends with it, and so does
//! [`Domain::update`] when asked to refine.

use rayon::ThreadPool;

use super::budget::Sweeps;
use super::build::Domain;
use super::cube_map::CubeMap;
use super::options::{DomainOptions, MAX_REPAIR_LEVEL};
use crate::error::Result;
use crate::tmesh::TMesh;

/// A saved T-mesh with its positions.
struct MeshState<const D: usize> {
    mesh: TMesh<D>,
    framed: Vec<[f64; D]>,
    positions: Vec<[f64; D]>,
    quality: Vec<f64>,
}

impl<const D: usize, B: CubeMap<D>> Domain<D, B> {
    /// The T-mesh and its positions, to be restored by [`Domain::restore`].
    fn state(&self) -> MeshState<D> {
        MeshState {
            mesh: self.mesh.clone(),
            framed: self.framed.clone(),
            positions: self.positions.clone(),
            quality: self.quality.clone(),
        }
    }

    fn restore(&mut self, state: MeshState<D>) {
        self.mesh = state.mesh;
        self.framed = state.framed;
        self.positions = state.positions;
        self.quality = state.quality;
    }

    /// Relieves the folds the boundary vertices alone cause, then, while cells stay invalid,
    /// refines them (up to level 16) and optimizes and relieves again, for at most
    /// `options.repair_rounds` rounds. Keeps the state with the fewest invalid cells, and stops
    /// once two rounds in a row have increased their number: where the boundary itself folds at
    /// every scale (a seam of two triangulated faces meeting at a reflex angle), refining only
    /// multiplies the folds. Stops too where the sweep budget runs out. Returns the rounds that
    /// refined cells.
    pub(super) fn relieve_and_repair(
        &mut self,
        options: &DomainOptions,
        pool: &ThreadPool,
        sweeps: &mut Sweeps<'_>,
    ) -> Result<u32> {
        // Folds that the boundary vertices alone cause where two faces meet at a reflex angle
        // (a jittered or jagged seam) are relieved before, and after, every refinement.
        let mut invalid = self.relieve(options, pool, sweeps)?;
        let mut repair_rounds = 0;
        let mut best = (invalid.len(), self.state());
        let mut growing = 0;
        while !invalid.is_empty() && repair_rounds < options.repair_rounds && growing < 2 {
            let refinable: Vec<usize> = invalid
                .iter()
                .copied()
                .filter(|&c| self.mesh.cell_level(c) < MAX_REPAIR_LEVEL)
                .collect();
            if refinable.is_empty() || sweeps.exhausted() {
                break;
            }
            let refined = self.refine_in_place(&refinable, options, pool, &mut sweeps.stage());
            if sweeps.absorb(refined)?.is_none() {
                break;
            }
            let still_invalid = self.relieve(options, pool, sweeps)?;
            // Folds on the cube's edges may open only once their chords are a few levels
            // shorter, so a round or two with more invalid cells is no failure; a count that
            // keeps growing is.
            growing = if still_invalid.len() > invalid.len() {
                growing + 1
            } else {
                0
            };
            invalid = still_invalid;
            repair_rounds += 1;
            if invalid.len() < best.0 {
                best = (invalid.len(), self.state());
            }
        }
        if invalid.len() > best.0 {
            self.restore(best.1);
        }
        Ok(repair_rounds)
    }
}
