//! Seam relief: boundary vertices leave the boundary, by at most a given offset, where cells
//! stay folded with every boundary vertex on it.
//!
//! The Jacobian of a cell at a Gauss–Lobatto point on an edge of the cube depends on boundary
//! vertices only (its three columns follow the edge and the two faces). Where the two faces meet
//! at a reflex dihedral angle — a jittered triangulation, a jagged seam — no placement of those
//! vertices on the surfaces gives a positive Jacobian there, and refining only shortens the
//! chords across the same fold. The relief moves each boundary vertex of a folded cell by the
//! shortest displacement that lifts `det S` (the Jacobian normalized by the cell's target) to
//! [`MARGIN`] at every Gauss–Lobatto point it influences, the displacement from its point on the
//! boundary being clipped to the allowed offset; the inner vertices are then optimized again.
//!
//! With the other nodes fixed, `det S` is affine in one node's position `y`: `S = A + y gᵀ` is a
//! rank-one update, so `det S(y + d) = det S(y) + (cof(S) g)·d`. The displacement is found by
//! cyclic projections onto these half-spaces from `d = 0`.

use rayon::ThreadPool;

use super::budget::Sweeps;
use super::build::Domain;
use super::cube_map::CubeMap;
use super::options::{sweep_options, DomainOptions};
use crate::error::Result;
use crate::optimize::metric::Term;
use crate::optimize::motion::optimize_in_place;
use crate::optimize::small_matrix::{clip_to_ball, cofactor, det, dot, mul_vec, Vector};
use crate::optimize::{invalid_cells, Problem, QualitySummary};

/// The value of `det S` (1 for a cell of its target shape) the relief asks for at the points a
/// moved vertex influences.
pub(crate) const MARGIN: f64 = 0.05;

/// Rounds of projections per vertex.
const PROJECTION_ROUNDS: usize = 64;

/// Largest number of rounds of relief (move the boundary vertices of folded cells, optimize the
/// inner ones).
const RELIEF_ROUNDS: u32 = 16;

/// Rounds in a row without fewer folded cells after which the relief stops (a round may open
/// nothing yet move vertices that the next rounds need).
const PATIENCE: u32 = 3;

/// The shortest displacement `d` (approximately: cyclic projections from 0) of a node at `y`
/// such that `det S ≥ margin` for every term, or the best found after the projection rounds.
pub fn lifting_displacement<const D: usize>(
    terms: &[Term<D>],
    y: Vector<D>,
    margin: f64,
) -> Vector<D> {
    // det S(y + d) = σ + c·d for each term.
    let planes: Vec<(f64, Vector<D>)> = terms
        .iter()
        .map(|t| {
            let s = t.jacobian(&y);
            (det(&s), mul_vec(&cofactor(&s), &t.g))
        })
        .filter(|(_, c)| dot(c, c) > 0.0)
        .collect();
    let mut d = [0.0; D];
    for _ in 0..PROJECTION_ROUNDS {
        let mut moved = false;
        for (sigma, c) in &planes {
            let gap = margin - sigma - dot(c, &d);
            if gap > 0.0 {
                let step = gap / dot(c, c);
                for k in 0..D {
                    d[k] += step * c[k];
                }
                moved = true;
            }
        }
        if !moved {
            break;
        }
    }
    d
}

impl<const D: usize, B: CubeMap<D>> Domain<D, B> {
    /// The point on the boundary (in frame coordinates) of every boundary vertex; `None` for the
    /// inner ones.
    pub(super) fn boundary_anchors(&self) -> Vec<Option<[f64; D]>> {
        let framed = self.framed_boundary();
        self.mesh
            .parametric()
            .into_iter()
            .enumerate()
            .map(|(v, p)| self.mesh.on_boundary(v).then(|| framed.boundary_point(p)))
            .collect()
    }

    /// Relieves the folds the boundary vertices alone cause (see the module documentation), with
    /// offsets up to `options.boundary_offset`: in each round the boundary vertices of the
    /// folded cells move, then the inner vertices are optimized. Keeps the positions only if
    /// they leave fewer folded cells. Stops where the sweep budget runs out. Returns the folded
    /// cells left.
    pub(super) fn relieve(
        &mut self,
        options: &DomainOptions,
        pool: &ThreadPool,
        sweeps: &mut Sweeps<'_>,
    ) -> Result<Vec<usize>> {
        let problem: Problem<D> = self.mesh.problem()?;
        let initial = invalid_cells(pool, &problem, &self.framed);
        let radius = options.boundary_offset;
        if initial.is_empty() || radius <= 0.0 || sweeps.exhausted() {
            return Ok(initial);
        }
        let mut invalid = initial.clone();
        let anchors = self.boundary_anchors();
        let mut x = self.framed.clone();
        let mut terms = Vec::new();
        let mut stalled = 0;
        for _ in 0..RELIEF_ROUNDS {
            let mut nodes: Vec<usize> = invalid
                .iter()
                .flat_map(|&c| problem.cell_nodes(c).iter().map(|&v| v as usize))
                .filter(|&v| anchors[v].is_some())
                .collect();
            nodes.sort_unstable();
            nodes.dedup();
            for &v in &nodes {
                let anchor = anchors[v].expect("a boundary vertex");
                problem.node_terms(v, &x, &mut terms);
                let d = lifting_displacement(&terms, x[v], MARGIN);
                x[v] = clip_to_ball(std::array::from_fn(|k| x[v][k] + d[k]), anchor, radius);
            }
            let optimized = optimize_in_place(
                pool,
                &problem,
                &mut x,
                &sweep_options(options),
                &mut sweeps.stage(),
            );
            // Stopped by the budget, the sweeps so far are kept.
            sweeps.absorb(optimized)?;
            let still = invalid_cells(pool, &problem, &x);
            stalled = if still.len() < invalid.len() {
                0
            } else {
                stalled + 1
            };
            invalid = still;
            if invalid.is_empty() || stalled == PATIENCE || sweeps.exhausted() {
                break;
            }
        }
        if invalid.len() < initial.len() {
            self.quality = QualitySummary::of(pool, &problem, &x).quality;
            self.set_framed(x);
            Ok(invalid)
        } else {
            Ok(initial)
        }
    }

    /// Largest distance, in frame coordinates (the bounding box mapped onto a unit box), of a
    /// boundary vertex from its point on the boundary.
    pub fn boundary_offset(&self) -> f64 {
        self.boundary_anchors()
            .iter()
            .zip(&self.framed)
            .filter_map(|(a, x)| {
                a.map(|a| (0..D).map(|k| (x[k] - a[k]).powi(2)).sum::<f64>().sqrt())
            })
            .fold(0.0, f64::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A node whose terms fold: the displacement lifts every determinant to the margin, and a
    /// node already clear of it does not move.
    #[test]
    fn lifting_displacement_reaches_the_margin() {
        // S = A + y gᵀ for three terms with different g.
        let terms: Vec<Term<3>> = [[1.0, 0.2, 0.0], [0.0, 1.0, -0.3], [0.5, 0.5, 1.0]]
            .into_iter()
            .map(|g| Term {
                a: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.1]],
                g,
                w: 1.0,
            })
            .collect();
        let y = [0.0, 0.0, -0.4];
        assert!(terms.iter().any(|t| det(&t.jacobian(&y)) <= 0.0));
        let d = lifting_displacement(&terms, y, MARGIN);
        let moved = [y[0] + d[0], y[1] + d[1], y[2] + d[2]];
        for t in &terms {
            assert!(det(&t.jacobian(&moved)) >= MARGIN * (1.0 - 1e-9));
        }
        let clear = [0.0, 0.0, 0.1];
        assert_eq!(lifting_displacement(&terms, clear, MARGIN), [0.0; 3]);
    }

    #[test]
    fn clip_keeps_points_within_the_radius() {
        assert_eq!(clip_to_ball([0.3, 0.4], [0.0, 0.0], 1.0), [0.3, 0.4]);
        let p = clip_to_ball([3.0, 4.0], [0.0, 0.0], 1.0);
        assert!((p[0] - 0.6).abs() < 1e-15 && (p[1] - 0.8).abs() < 1e-15);
    }
}
