//! Solves with the free block `H_ff` of a mesh's Hessian: preconditioned conjugate gradients
//! with the exact Hessian, and a preconditioner that may come from a nearby state (Newton's
//! iterations and path following reuse it until it stops paying). The preconditioner is faer's
//! sparse Cholesky factor where that factor is small (2D meshes, small 3D ones) — then a solve
//! with the Hessian it was made from takes one iteration — and a block-Jacobi one otherwise (a
//! 3D mesh of 10⁵ nodes would need a factor of 10⁹ values). A factor is modified where the
//! matrix is not positive definite.

use std::sync::Arc;

use rayon::ThreadPool;

use super::amg::Amg;
use super::blocks::{memory_probe, BlockLayout, BlockMatrix};
use super::cg::{conjugate_gradients, SolveStats, Stop};
use super::small_matrix::{inverse, mul_vec, Matrix, Vector};
use super::sparse::{Factor, FreeHessian};
use crate::error::Result;

/// Largest factor (stored values) the direct solver is used for: 3·10⁷ values, 360 MB while
/// it is computed and rounded to single precision, 120 MB kept.
const DIRECT_FACTOR_LIMIT: usize = 30_000_000;

/// Largest number of free coordinates of a 3D mesh whose factor is tried at all (the analysis of
/// a larger one costs seconds and its factor would not fit the limit anyway).
const DIRECT_3D_COORDINATES: usize = 60_000;

/// Largest Hessian (stored values) of a 3D mesh too large to factor for which the Newton method
/// is the default: its multigrid-preconditioned steps keep one Hessian and the hierarchy (the
/// start state keeps only its preconditioner), about 17 bytes per value at the peak (the wing's
/// 33.6 million values: 0.59 GB, where its sweeps take 0.16 GB). 10⁸ values are about 310,000
/// H27 nodes (320 values per node).
const MULTIGRID_NEWTON_VALUES: usize = 100_000_000;

/// The structure a solver needs for one mesh and one set of free coordinates, to be kept and
/// reused across states of the same mesh.
pub struct SolverSetup {
    /// Per node, the bits of its free coordinates (nodes without cells have none).
    pub free: Vec<u8>,
    layout: Arc<BlockLayout>,
    direct: Option<FreeHessian>,
    /// Stored values of the Hessian (blocks of d × d).
    hessian_values: usize,
}

impl std::fmt::Debug for SolverSetup {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SolverSetup")
            .field("direct", &self.direct.is_some())
            .finish()
    }
}

impl SolverSetup {
    /// Prepares solves with `problem`'s free coordinates; the direct solver's symbolic
    /// factorisation is computed here when it applies.
    pub fn new<const D: usize>(
        problem: &super::Problem<D>,
        layout: Arc<BlockLayout>,
    ) -> Result<Self> {
        let free = Self::free_mask(problem);
        let coordinates: usize = free.iter().map(|m| m.count_ones() as usize).sum();
        let direct = if D == 2 || coordinates <= DIRECT_3D_COORDINATES {
            let analysis = FreeHessian::new(problem, &layout, &free)?;
            (analysis.factor_size() <= DIRECT_FACTOR_LIMIT).then_some(analysis)
        } else {
            None
        };
        Ok(SolverSetup {
            free,
            hessian_values: layout.block_count() * D * D,
            layout,
            direct,
        })
    }

    /// Per node, the bits of its free coordinates: those of its free mask, none for a node in no
    /// cell.
    pub fn free_mask<const D: usize>(problem: &super::Problem<D>) -> Vec<u8> {
        (0..problem.node_count())
            .map(|v| match problem.incident_cells(v).is_empty() {
                true => 0,
                false => problem.free_mask(v) & ((1 << D) - 1),
            })
            .collect()
    }

    /// The layout of the Hessian.
    pub fn layout(&self) -> &Arc<BlockLayout> {
        &self.layout
    }

    /// Whether the Newton method is the default ([`Method::Auto`](crate::Method::Auto)): where
    /// solves are direct, or where the Hessian is at most 10⁸ values
    /// (multigrid-preconditioned CG). On the wing (105,060 H27 nodes, 2 threads) Newton's method
    /// relocates in 8.9 s to min quality 0.974, the sweeps in 20.5 s to 0.954 (same run).
    pub fn newton_by_default(&self) -> bool {
        self.is_direct() || self.hessian_values <= MULTIGRID_NEWTON_VALUES
    }

    /// Whether solves are direct (exact to round-off) rather than iterative.
    pub fn is_direct(&self) -> bool {
        self.direct.is_some()
    }
}

/// A preconditioner of `H_ff`: a Cholesky factor (of this Hessian or a nearby one), an algebraic
/// multigrid V-cycle, or the inverses of the diagonal blocks.
pub enum Preconditioner<const D: usize> {
    /// A sparse Cholesky factor.
    Direct(Factor),
    /// Smoothed-aggregation multigrid.
    Multigrid(Box<Amg>),
    /// Inverses of the nodes' diagonal blocks.
    BlockJacobi(Vec<Matrix<D>>),
}

impl<const D: usize> Preconditioner<D> {
    /// The preconditioner made from `hessian` at positions `x`: its factor (modified where
    /// needed, the shifts tried from level `first`: see [`Preconditioner::next_shift`]) when the
    /// setup is direct, else multigrid (block Jacobi where the multigrid's coarsest level is not
    /// positive definite). `None` when the factorisation fails (a non-finite or non-positive
    /// diagonal); refused ([`crate::ErrorKind::LimitExceeded`]) where the multigrid's memory
    /// cannot be reserved (probed before its setup).
    pub fn new(
        pool: &ThreadPool,
        problem: &super::Problem<D>,
        setup: &SolverSetup,
        hessian: &BlockMatrix<D>,
        (x, first): (&[Vector<D>], usize),
    ) -> Result<Option<Self>> {
        let layout = &setup.layout;
        let made = match &setup.direct {
            Some(analysis) => analysis
                .factorize(hessian, first)?
                .map(Preconditioner::Direct),
            None => {
                // The hierarchy's arrays, made while the Hessian is kept, add about a quarter
                // of its size at their peak (measured on the 812,040-node wing);
                // a third is probed first, so that a setup past the machine's memory is refused
                // rather than aborted midway.
                let bytes = std::mem::size_of_val(&hessian.blocks[..]) / 3;
                memory_probe(bytes, "the multigrid preconditioner")?;
                Some(
                    match Amg::new(pool, problem, layout, hessian, &setup.free, x) {
                        Some(amg) => Preconditioner::Multigrid(Box::new(amg)),
                        None => Preconditioner::BlockJacobi(block_jacobi(setup, layout, hessian)),
                    },
                )
            }
        };
        crate::diagnostics::note(|| match &made {
            Some(Preconditioner::Direct(f)) => format!(
                "preconditioner: Cholesky factor, shift level {}, {} values",
                f.level,
                setup.direct.as_ref().map_or(0, |a| a.factor_size())
            ),
            Some(Preconditioner::Multigrid(amg)) => {
                format!("preconditioner: multigrid, {} levels", amg.level_count())
            }
            Some(Preconditioner::BlockJacobi(_)) => "preconditioner: block Jacobi".into(),
            None => "preconditioner: none (the factorisation failed)".into(),
        });
        Ok(made)
    }

    /// CG iterations this preconditioner gets, made at an earlier state, before a fresh one is
    /// made: a fresh Cholesky factor of the bundled airfoil costs about 15 solves with a lagged
    /// one and makes the next solve exact, so a lagged factor gets 8; a fresh multigrid
    /// hierarchy of the wing (105,060 H27 nodes) costs about 7 CG iterations and converges no
    /// faster than one made a Newton step earlier (6–10 iterations either way), so a lagged
    /// one gets 40.
    pub fn lagged_iterations(&self) -> usize {
        match self {
            Preconditioner::Multigrid(_) => 40,
            Preconditioner::Direct(_) | Preconditioner::BlockJacobi(_) => 8,
        }
    }

    /// The shift level a factor of a nearby state's indefinite Hessian starts from: one below
    /// this factor's (the shift that state's matrix needed; the smallest shift that works
    /// matters: starting from this factor's level itself, the 96,740-node refined airfoil took
    /// 187 Newton iterations instead of 40), at least the smallest shift — but this factor's
    /// own level where the one below was just too small for it: the level below is tried every
    /// other factorisation, not at each (a failed factorisation costs about a successful one).
    pub fn next_shift(&self) -> usize {
        match self {
            Preconditioner::Direct(f) if f.first < f.level => f.level,
            Preconditioner::Direct(f) => f.level.saturating_sub(1).max(1),
            _ => 0,
        }
    }

    /// Whether the factor is that of a modified matrix (the Hessian was not positive definite).
    pub fn modified(&self) -> bool {
        match self {
            Preconditioner::Direct(f) => f.modified(),
            _ => false,
        }
    }

    fn apply(&self, pool: &ThreadPool, setup: &SolverSetup, r: &[Vector<D>]) -> Vec<Vector<D>> {
        match self {
            Preconditioner::Direct(factor) => {
                let analysis = setup.direct.as_ref().expect("direct setup");
                let coordinates = analysis.coordinates();
                let mut flat = vec![0.0; coordinates.count()];
                for (v, rv) in r.iter().enumerate() {
                    for (k, &value) in rv.iter().enumerate() {
                        if let Some(i) = coordinates.of(v, k) {
                            flat[i] = value;
                        }
                    }
                }
                analysis.solve(pool, factor, &mut flat);
                let mut z = vec![[0.0; D]; r.len()];
                for (v, zv) in z.iter_mut().enumerate() {
                    for (k, value) in zv.iter_mut().enumerate() {
                        if let Some(i) = coordinates.of(v, k) {
                            *value = flat[i];
                        }
                    }
                }
                z
            }
            Preconditioner::Multigrid(amg) => amg.apply(pool, r),
            Preconditioner::BlockJacobi(inverses) => {
                r.iter().zip(inverses).map(|(r, m)| mul_vec(m, r)).collect()
            }
        }
    }
}

/// A solver for `H_ff` at one state: the Hessian there and a preconditioner. It owns what it
/// needs, so it can be kept for later solves (sensitivities, path following).
pub struct HessianSolver<const D: usize> {
    setup: Arc<SolverSetup>,
    hessian: BlockMatrix<D>,
    preconditioner: Arc<Preconditioner<D>>,
}

impl<const D: usize> HessianSolver<D> {
    /// A solver of `hessian` with `preconditioner`.
    pub fn new(
        setup: Arc<SolverSetup>,
        hessian: BlockMatrix<D>,
        preconditioner: Arc<Preconditioner<D>>,
    ) -> Self {
        HessianSolver {
            setup,
            hessian,
            preconditioner,
        }
    }

    /// A solver of `hessian` (at positions `x` of `problem`) with a preconditioner made from
    /// it ([`Preconditioner::new`], a factor's shifts tried from level `first`); `None` where
    /// none can be made.
    pub fn fresh(
        pool: &ThreadPool,
        problem: &super::Problem<D>,
        setup: &Arc<SolverSetup>,
        hessian: BlockMatrix<D>,
        (x, first): (&[Vector<D>], usize),
    ) -> Result<Option<Self>> {
        let Some(p) = Preconditioner::new(pool, problem, setup, &hessian, (x, first))? else {
            return Ok(None);
        };
        Ok(Some(Self::new(setup.clone(), hessian, Arc::new(p))))
    }

    /// Replaces the preconditioner with one made from this solver's own Hessian (at positions
    /// `x` of `problem`, a factor's shifts tried from level `first`), in place: no copy of the
    /// Hessian (2.1 GB at 812,040 H27 nodes). `false`, the solver unchanged, where none can be
    /// made.
    pub fn refresh(
        &mut self,
        pool: &ThreadPool,
        problem: &super::Problem<D>,
        (x, first): (&[Vector<D>], usize),
    ) -> Result<bool> {
        let made = Preconditioner::new(pool, problem, &self.setup, &self.hessian, (x, first))?;
        Ok(made.map(|p| self.preconditioner = Arc::new(p)).is_some())
    }

    /// The Hessian this solver is for.
    pub fn hessian(&self) -> &BlockMatrix<D> {
        &self.hessian
    }

    /// The Hessian's storage and the preconditioner, the solver done with (the storage for the
    /// next evaluation to write into, the preconditioner for the next solves).
    pub fn into_parts(self) -> (BlockMatrix<D>, Arc<Preconditioner<D>>) {
        (self.hessian, self.preconditioner)
    }

    /// The layout of the Hessian.
    pub fn layout(&self) -> &BlockLayout {
        &self.setup.layout
    }

    /// The free coordinates: per node, their bits.
    pub fn free(&self) -> &[u8] {
        &self.setup.free
    }

    /// The preconditioner.
    pub fn preconditioner(&self) -> &Arc<Preconditioner<D>> {
        &self.preconditioner
    }

    /// Solves `H_ff y = b` over the free coordinates (entries of `b` elsewhere are ignored,
    /// those of `y` are 0) by preconditioned CG until `stop`, in at most `max_iterations`; CG
    /// stops early at negative curvature (the stats say so) and where its rate so far shows
    /// `stop` out of reach within `max_iterations`.
    pub fn solve_with(
        &self,
        pool: &ThreadPool,
        b: &[Vector<D>],
        stop: Stop<'_>,
        max_iterations: usize,
    ) -> (Vec<Vector<D>>, SolveStats) {
        let free = &self.setup.free;
        let b: Vec<Vector<D>> = mask(free, b);
        let apply = |x: &[Vector<D>], y: &mut [Vector<D>]| {
            self.hessian
                .product(pool, &self.setup.layout, free, free, x, y)
        };
        let precondition = |r: &[Vector<D>]| self.preconditioner.apply(pool, &self.setup, r);
        conjugate_gradients(&apply, &precondition, &b, stop, max_iterations)
    }

    /// The preconditioner applied to `r`.
    pub fn precondition(&self, pool: &ThreadPool, r: &[Vector<D>]) -> Vec<Vector<D>> {
        self.preconditioner
            .apply(pool, &self.setup, &mask(&self.setup.free, r))
    }

    /// [`HessianSolver::solve_with`] with an iteration limit that only a failing solve meets.
    pub fn solve(
        &self,
        pool: &ThreadPool,
        b: &[Vector<D>],
        stop: Stop<'_>,
    ) -> (Vec<Vector<D>>, SolveStats) {
        self.solve_with(pool, b, stop, 20 * b.len() + 100)
    }
}

/// `x` with the entries outside `free` set to 0.
pub fn mask<const D: usize>(free: &[u8], x: &[Vector<D>]) -> Vec<Vector<D>> {
    x.iter()
        .zip(free)
        .map(|(x, &m)| std::array::from_fn(|k| if m & (1 << k) != 0 { x[k] } else { 0.0 }))
        .collect()
}

/// Inverse of every node's diagonal block restricted to its free coordinates (identity rows for
/// the others); a block that is not invertible is replaced by the inverse of its diagonal.
fn block_jacobi<const D: usize>(
    setup: &SolverSetup,
    layout: &BlockLayout,
    hessian: &BlockMatrix<D>,
) -> Vec<Matrix<D>> {
    (0..layout.node_count())
        .map(|v| {
            let free = setup.free[v];
            let on = |k: usize| free & (1 << k) != 0;
            let block = layout
                .find(v, v)
                .map_or([[0.0; D]; D], |b| hessian.blocks[b]);
            let m: Matrix<D> = std::array::from_fn(|k| {
                std::array::from_fn(|l| match (on(k), on(l)) {
                    (true, true) => block[k][l],
                    _ => f64::from(u8::from(k == l)),
                })
            });
            inverse(&m).unwrap_or_else(|| {
                std::array::from_fn(|k| {
                    std::array::from_fn(|l| match k == l && m[k][k] != 0.0 {
                        true => 1.0 / m[k][k].abs(),
                        false => 0.0,
                    })
                })
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optimize::sparse::CholeskyPattern;

    /// The level below a factor's shift is tried every other factorisation: not right after it
    /// was too small, again after a factorisation that started at its own level.
    #[test]
    fn the_level_below_is_tried_every_other_time() {
        // [[1, 3], [3, 1]] (eigenvalues 4 and −2): positive definite from a shift of 10 only.
        let pattern = CholeskyPattern::new(2, vec![0, 2, 3], vec![0, 1, 1]).unwrap();
        let factor = |first| {
            pattern
                .factorize(vec![1.0, 3.0, 1.0], first)
                .unwrap()
                .unwrap()
        };
        let below_failed = Preconditioner::<2>::Direct(factor(3));
        assert_eq!(below_failed.next_shift(), 4);
        let started_there = Preconditioner::<2>::Direct(factor(4));
        assert!(started_there.modified());
        assert_eq!(started_there.next_shift(), 3);
    }
}
