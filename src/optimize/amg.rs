//! Smoothed-aggregation algebraic multigrid (Vaněk, Mandel and Brezina) for the free block of a
//! mesh's Hessian: the preconditioner of conjugate gradients on 3D meshes too large to factor.
//!
//! The Hessian of the mean-ratio objective behaves like an elasticity operator: its softest modes
//! are the rigid motions, which the objective does not see. On quadratic cells (Q8, Q9, H20,
//! H27) the first coarsening is the p-coarsening to the cells' corners (the coarse functions are
//! the bi-/trilinear interpolants of the corner values): smoothed aggregation applied directly to
//! their dense stencils gives coarse operators of over a thousand values per row (measured on the
//! wing: 63 million values at the second level). Aggregates of strongly coupled nodes
//! carry the rigid motions restricted to them (translations and rotations, orthonormalised per
//! aggregate) as their coarse functions; the tentative prolongator is smoothed by one damped
//! Jacobi step where the level is sparse enough for that to keep the coarse operator sparse;
//! coarse operators are Galerkin products; each level is smoothed by a Chebyshev polynomial in
//! the Jacobi-scaled operator (symmetric, so the V-cycle preconditions CG; the smoothers keep
//! their operators in single precision, the finest one of quadratic cells in bfloat16, and
//! multiply in single precision, operands scaled to stay normal numbers: `single.rs`), and the
//! coarsest level (below 5,000 unknowns unless coarsening stalls first) is solved by a sparse
//! Cholesky factorisation. Every step is sequential or row-parallel with a fixed summation
//! order, so the result does not depend on the thread count.
//!
//! Hand-written: no maintained Rust crate provides aggregation with a rigid-motion near-null
//! space; faer's sparse Cholesky factorises the coarsest level.

use rayon::ThreadPool;

use super::aggregation::{aggregate, node_grouping, tentative_prolongator, Grouping};
use super::block_rows::BlockRows;
use super::blocks::{BlockLayout, BlockMatrix};
use super::csr::Csr;
use super::lattice;
use super::problem::Problem;
use super::small_matrix::Vector;
use super::sparse::{CholeskyPattern, Coordinates, Factor};
use super::spectrum::largest_eigenvalue;

/// Stop coarsening below this many unknowns (then factor the level, sparse).
const COARSEST: usize = 5_000;

/// Smooth the prolongator only on levels with at most this many values per row: on denser
/// ones the smoothed prolongator's coarse operator becomes dense.
const SMOOTHING_DENSITY: usize = 40;

/// Degree of the Chebyshev smoother.
const CHEBYSHEV_DEGREE: usize = 3;

/// The smoother damps the upper part `[λ_max/45, λ_max]` of the Jacobi-scaled spectrum
/// (`λ_max` with its margin, `spectrum.rs`). Against 30 (15, 60 and 100 were slower still),
/// runs alternated: the wing 4.1–4.5 s against 4.2–4.6, the 812,040-node wing 46.4–48.6 s
/// against 48.9–52.0, the 1,214,040-node one 67.4–73.2 s against 69.3–71.7 (the last Newton
/// step's iterations 13 → 12 on the wing).
const CHEBYSHEV_RATIO: f64 = 45.0;

/// A level's operator in single precision, for the smoother's products.
enum Operator {
    /// In compressed rows, scaled by a power of two ([`Csr::single`]).
    Rows(Csr<f32>, f64),
    /// By node blocks (the finest level of quadratic cells: half the memory traffic).
    Blocks(BlockRows),
}

impl Operator {
    /// The operator in compressed rows, its values scaled and rounded to single precision.
    fn rows(a: Csr) -> Self {
        let (a, scale) = a.single();
        Operator::Rows(a, scale)
    }

    /// `y = A x`.
    fn apply(&self, pool: &ThreadPool, x: &[f64], y: &mut [f64]) {
        match self {
            Operator::Rows(a, scale) => a.apply_single(pool, *scale, x, y),
            Operator::Blocks(a) => a.apply(pool, x, y),
        }
    }

    /// Number of rows.
    fn size(&self) -> usize {
        match self {
            Operator::Rows(a, _) => a.rows(),
            Operator::Blocks(a) => a.rows(),
        }
    }
}

/// One level of the hierarchy.
struct Level {
    /// The operator (in single precision: the smoother's products).
    a: Operator,
    /// `1/diag(A)`.
    inverse_diagonal: Vec<f64>,
    /// Estimate of the largest eigenvalue of `D⁻¹A`.
    lambda: f64,
    /// Prolongation from the next level, and its transpose.
    p: Csr,
    r: Csr,
}

/// The multigrid hierarchy of `H_ff`.
pub struct Amg {
    levels: Vec<Level>,
    coarsest: (CholeskyPattern, Factor),
    coarsest_size: usize,
    /// The free coordinates (the finest level's rows).
    coordinates: Coordinates,
}

impl Level {
    /// The level of the operator `a()` (and `ap = A P`, the operator times the prolongator `p`
    /// from the next level; the smoother's `inverse_diagonal` and `lambda`), and the next
    /// level's operator `PᵀAP`. The operator is made once `A P` is dropped: at the finest level
    /// `A P` and the smoother's copy of `A` are each hundreds of megabytes, and together they
    /// were the peak of a relocation.
    fn new(
        pool: &ThreadPool,
        a: impl FnOnce() -> Operator,
        (ap, p): (Csr, Csr),
        (inverse_diagonal, lambda): (Vec<f64>, f64),
    ) -> (Level, Csr) {
        let r = p.transpose();
        let coarse = r.product(pool, &ap);
        drop(ap);
        let level = Level {
            a: a(),
            inverse_diagonal,
            lambda,
            p,
            r,
        };
        (level, coarse)
    }
}

/// The finest level of quadratic cells, its rows `fine` of `hessian`, `p` the prolongator from
/// their corners, and the next level's operator. The finest operator is read from the block
/// Hessian (no copy in compressed rows: on the wing, 720 MB); its smoother's operator is by node
/// blocks in bfloat16, the largest eigenvalue estimated with it. The corner prolongator is not
/// smoothed.
fn corner_level<const D: usize>(
    pool: &ThreadPool,
    (layout, hessian): (&BlockLayout, &BlockMatrix<D>),
    fine: &FineRows<'_, D>,
    p: Csr,
) -> (Level, Csr) {
    let inverse_diagonal = inverses(fine.diagonal());
    let (sizes, nodes) = fine.nodes();
    let entries = |g: usize| fine.node_entries(nodes[g]);
    let ap = Csr::grouped_product_of::<D, _>(pool, &sizes, entries, &p);
    crate::diagnostics::note(|| format!("multigrid: A P, {} stored", ap.stored()));
    let coordinates = &fine.coordinates;
    let blocks = || Operator::Blocks(BlockRows::new(pool, layout, hessian, coordinates));
    let (mut level, coarse) = Level::new(pool, blocks, (ap, p), (inverse_diagonal, 0.0));
    crate::diagnostics::note(|| {
        let stored = coarse.stored();
        format!("multigrid: P^T A P, {stored} stored, and the smoother's node blocks")
    });
    let apply = |x: &[f64], y: &mut [f64]| level.a.apply(pool, x, y);
    level.lambda = largest_eigenvalue(level.a.size(), apply, &level.inverse_diagonal);
    crate::diagnostics::note(|| format!("multigrid: smoother's bound {:e}", level.lambda));
    (level, coarse)
}

/// The sparse Cholesky factor of the coarsest operator `a`; `None` where it is not positive
/// definite.
fn coarsest_factor(a: &Csr) -> Option<(CholeskyPattern, Factor)> {
    let (pattern, positions) = CholeskyPattern::of_csr(a).ok()?;
    crate::diagnostics::note(|| {
        format!(
            "multigrid: coarsest level, {} unknowns, {} stored, factor {}",
            a.rows(),
            a.stored(),
            pattern.factor_size()
        )
    });
    let factor = pattern
        .factorize(positions.iter().map(|&p| a.value[p]).collect(), 0)
        .ok()??;
    if factor.modified() {
        return None;
    }
    Some((pattern, factor))
}

impl Amg {
    /// The hierarchy of the free block of `hessian` (free coordinates per node given by `free`);
    /// `x` are the node positions (for the rigid motions). `None` where the coarsest level is not
    /// positive definite.
    pub fn new<const D: usize>(
        pool: &ThreadPool,
        problem: &Problem<D>,
        layout: &BlockLayout,
        hessian: &BlockMatrix<D>,
        free: &[u8],
        x: &[Vector<D>],
    ) -> Option<Amg> {
        let fine = FineRows::new(layout, hessian, Coordinates::of_mask(free, D).ok()?);
        let modes = D * (D + 1) / 2;
        let mut levels = Vec::new();
        let (mut a, mut grouping, mut null_space) =
            match corner_prolongator(pool, problem, &fine, x) {
                Some((p, grouping, null_space)) => {
                    crate::diagnostics::note(|| {
                        format!(
                            "multigrid: corner prolongator, {} unknowns -> {}",
                            p.rows(),
                            p.columns
                        )
                    });
                    let (level, coarse) = corner_level(pool, (layout, hessian), &fine, p);
                    levels.push(level);
                    (coarse, grouping, null_space)
                }
                None => {
                    let (grouping, null_space) = node_grouping(&fine.coordinates, x);
                    (fine.csr(pool), grouping, null_space)
                }
            };
        while a.rows() > COARSEST && levels.len() < 12 {
            let clock = std::time::Instant::now();
            let aggregates = aggregate(&a, &grouping);
            let (tentative, coarse_grouping, coarse_null) =
                tentative_prolongator(&grouping, &aggregates, &null_space, modes);
            crate::diagnostics::note(|| {
                format!(
                    "multigrid: level {}, {} unknowns, {} stored, {} groups -> {} coarse \
                     (aggregated in {:?})",
                    levels.len(),
                    a.rows(),
                    a.stored(),
                    grouping.count(),
                    tentative.columns,
                    clock.elapsed()
                )
            });
            if tentative.columns as f64 > 0.8 * a.rows() as f64 {
                break;
            }
            let inverse_diagonal = inverses(a.diagonal());
            let apply = |x: &[f64], y: &mut [f64]| a.apply(pool, x, y);
            let lambda = largest_eigenvalue(a.rows(), apply, &inverse_diagonal);
            let p = match a.stored() <= SMOOTHING_DENSITY * a.rows() {
                true => smooth_prolongator(pool, &a, &inverse_diagonal, lambda, &tentative),
                false => tentative,
            };
            let ap = a.product(pool, &p);
            let rows = || Operator::rows(a);
            let (level, coarse) = Level::new(pool, rows, (ap, p), (inverse_diagonal, lambda));
            levels.push(level);
            a = coarse;
            grouping = coarse_grouping;
            null_space = coarse_null;
        }
        Some(Amg {
            levels,
            coarsest: coarsest_factor(&a)?,
            coarsest_size: a.rows(),
            coordinates: fine.coordinates,
        })
    }

    /// Number of levels (the coarsest included).
    pub fn level_count(&self) -> usize {
        self.levels.len() + 1
    }

    /// One V-cycle applied to a residual given per node.
    pub fn apply<const D: usize>(&self, pool: &ThreadPool, r: &[Vector<D>]) -> Vec<Vector<D>> {
        let n = self
            .levels
            .first()
            .map_or(self.coarsest_size, |l| l.a.size());
        let mut b = vec![0.0; n];
        for (v, k, d) in self.coordinates.free() {
            b[d] = r[v][k];
        }
        let x = self.cycle(pool, 0, &b);
        let mut out = vec![[0.0; D]; r.len()];
        for (v, k, d) in self.coordinates.free() {
            out[v][k] = x[d];
        }
        out
    }

    fn cycle(&self, pool: &ThreadPool, level: usize, b: &[f64]) -> Vec<f64> {
        let Some(l) = self.levels.get(level) else {
            let mut x = b.to_vec();
            self.coarsest.0.solve(pool, &self.coarsest.1, &mut x);
            return x;
        };
        // Pre-smoothing from zero keeps the residual up to date, post-smoothing starts from the
        // residual after the coarse correction: six products with the level's operator.
        let mut x = vec![0.0; b.len()];
        let mut residual = b.to_vec();
        chebyshev(pool, l, &mut x, &mut residual, false);
        let mut coarse_b = vec![0.0; l.r.rows()];
        l.r.apply(pool, &residual, &mut coarse_b);
        let coarse_x = self.cycle(pool, level + 1, &coarse_b);
        let mut correction = vec![0.0; b.len()];
        l.p.apply(pool, &coarse_x, &mut correction);
        let mut a_correction = vec![0.0; b.len()];
        l.a.apply(pool, &correction, &mut a_correction);
        for i in 0..b.len() {
            x[i] += correction[i];
            residual[i] -= a_correction[i];
        }
        chebyshev(pool, l, &mut x, &mut residual, true);
        x
    }
}

/// The finest level, `H_ff` read from the block Hessian: a row `(v, k)` for every free
/// component `k` of a node `v`, numbered as [`Coordinates`] number them.
struct FineRows<'a, const D: usize> {
    layout: &'a BlockLayout,
    hessian: &'a BlockMatrix<D>,
    coordinates: Coordinates,
    /// `(v, k)` per row.
    rows: Vec<(usize, usize)>,
}

impl<'a, const D: usize> FineRows<'a, D> {
    /// The rows of the free `coordinates`.
    fn new(layout: &'a BlockLayout, hessian: &'a BlockMatrix<D>, coordinates: Coordinates) -> Self {
        let mut rows = vec![(0, 0); coordinates.count()];
        for (v, k, d) in coordinates.free() {
            rows[d] = (v, k);
        }
        FineRows {
            layout,
            hessian,
            coordinates,
            rows,
        }
    }

    /// Row `i`: the free coordinates of its node's neighbours, in column order, with their
    /// values (its node's rows taken together, [`FineRows::node_entries`], the one of its
    /// component picked).
    fn entries(&self, i: usize) -> impl Iterator<Item = (u32, f64)> + '_ {
        let (v, k) = self.rows[i];
        let position = (0..k)
            .filter(|&m| self.coordinates.of(v, m).is_some())
            .count();
        self.node_entries(v)
            .map(move |(d, values)| (d, values[position]))
    }

    /// The rows' counts of the nodes with a free component, and those nodes, in the order of
    /// their rows.
    fn nodes(&self) -> (Vec<usize>, Vec<usize>) {
        let runs = self.rows.chunk_by(|a, b| a.0 == b.0);
        runs.map(|run| (run.len(), run[0].0)).unzip()
    }

    /// The rows of node `v` together: per free coordinate of its neighbours, in column order,
    /// its value in each of the node's rows.
    fn node_entries(&self, v: usize) -> impl Iterator<Item = (u32, [f64; D])> + '_ {
        let mask = self.coordinates.mask(v);
        let (blocks, neighbours) = self.layout.row(v);
        blocks.zip(neighbours).flat_map(move |(b, &w)| {
            (0..D).filter_map(move |l| {
                let d = self.coordinates.of(w as usize, l)?;
                let block = &self.hessian.blocks[b];
                let mut values = [0.0; D];
                let rows = (0..D).filter(|&k| mask & (1 << k) != 0);
                for (value, k) in values.iter_mut().zip(rows) {
                    *value = block[k][l];
                }
                Some((d as u32, values))
            })
        })
    }

    /// The diagonal.
    fn diagonal(&self) -> Vec<f64> {
        (0..self.rows.len())
            .map(|i| {
                let (v, k) = self.rows[i];
                let own = self.layout.find(v, v);
                own.map_or(0.0, |b| self.hessian.blocks[b][k][k])
            })
            .collect()
    }

    /// The rows in compressed form (the next levels of linear cells aggregate them), written in
    /// parallel, each into its own slice of the arrays (on the wing, 315,000 rows of 190 values
    /// each, row by row in one thread took 0.65 s).
    fn csr(&self, pool: &ThreadPool) -> Csr {
        // Lengths first, then every row written in place (collecting the rows' entries into new
        // arrays in parallel took 0.83 s on the wing, of its 2.4 s multigrid setup; this 0.05 s).
        Csr::collected(pool, self.rows.len(), self.rows.len(), |i| self.entries(i))
    }
}

/// The p-coarsening of quadratic cells: the corners of the cells carry the coarse unknowns (their
/// free components), every free unknown interpolates them bi-/trilinearly over one of its cells.
/// Returns the prolongator, the coarse grouping and near-null space; `None` when every node is a
/// corner (linear cells, T-meshes).
fn corner_prolongator<const D: usize>(
    pool: &ThreadPool,
    problem: &Problem<D>,
    fine: &FineRows<'_, D>,
    x: &[Vector<D>],
) -> Option<(Csr, Grouping, Vec<f64>)> {
    let n = problem.node_count();
    let mut corner = vec![false; n];
    let mut all_corners = true;
    for c in 0..problem.cell_count() {
        let pattern = problem.pattern(c);
        for (&l, &v) in pattern.real.iter().zip(problem.cell_nodes(c)) {
            let is_corner = lattice::coords::<D>(l).iter().all(|&ck| ck != 1);
            corner[v as usize] |= is_corner;
            all_corners &= is_corner;
        }
    }
    if all_corners {
        return None;
    }
    // The corners' free components.
    let corner_mask: Vec<u8> = (0..n)
        .map(|v| {
            if corner[v] {
                fine.coordinates.mask(v)
            } else {
                0
            }
        })
        .collect();
    let coarse = Coordinates::of_mask(&corner_mask, D).ok()?;
    // Row `(v, k)`: the coarse coordinates `k` of the corners, sorted, with their weights.
    let row = |i: usize| {
        let (v, k) = fine.rows[i];
        let weights = corner_weights(problem, v).into_iter();
        let mut row: Vec<(u32, f64)> = weights
            .filter_map(|(w, weight)| Some((coarse.of(w, k)? as u32, weight)))
            .collect();
        row.sort_unstable_by_key(|e| e.0);
        row.into_iter()
    };
    let p = Csr::collected(pool, coarse.count(), fine.rows.len(), row);
    let (grouping, null_space) = node_grouping(&coarse, x);
    Some((p, grouping, null_space))
}

/// The corner nodes of the first cell around node `v`, with their bi-/trilinear weights at the
/// node's lattice point in it (none for a node in no cell).
fn corner_weights<const D: usize>(problem: &Problem<D>, v: usize) -> Vec<(usize, f64)> {
    let Some(&(c, r)) = problem.incident_cells(v).first() else {
        return Vec::new();
    };
    let pattern = problem.pattern(c as usize);
    let at = lattice::coords::<D>(pattern.real[r as usize]);
    pattern
        .real
        .iter()
        .zip(problem.cell_nodes(c as usize))
        .filter_map(|(&l, &w)| {
            let cc = lattice::coords::<D>(l);
            let weight: f64 = (0..D)
                .map(|k| match (cc[k], at[k]) {
                    (1, _) => 0.0,
                    (_, 1) => 0.5,
                    (a, b) if a == b => 1.0,
                    _ => 0.0,
                })
                .product();
            (weight != 0.0).then_some((w as usize, weight))
        })
        .collect()
}

/// The inverses of a diagonal's positive values (0 elsewhere).
fn inverses(diagonal: Vec<f64>) -> Vec<f64> {
    diagonal
        .iter()
        .map(|&d| if d > 0.0 { 1.0 / d } else { 0.0 })
        .collect()
}

/// `P = (I − ω D⁻¹A) P_tent` with `ω = 4/(3λ)`.
fn smooth_prolongator(
    pool: &ThreadPool,
    a: &Csr,
    inverse_diagonal: &[f64],
    lambda: f64,
    tentative: &Csr,
) -> Csr {
    let omega = 4.0 / (3.0 * lambda);
    let ap = a.product(pool, tentative);
    let rows: Vec<Vec<(u32, f64)>> = (0..a.rows())
        .map(|i| {
            let (tc, tv) = tentative.row(i);
            let (ac, av) = ap.row(i);
            let scale = omega * inverse_diagonal[i];
            let mut row: Vec<(u32, f64)> =
                ac.iter().zip(av).map(|(&c, &v)| (c, -scale * v)).collect();
            for (&c, &v) in tc.iter().zip(tv) {
                match row.binary_search_by_key(&c, |e| e.0) {
                    Ok(p) => row[p].1 += v,
                    Err(p) => row.insert(p, (c, v)),
                }
            }
            row
        })
        .collect();
    Csr::from_rows(tentative.columns, rows)
}

/// Chebyshev smoothing of `A x = b` in the Jacobi-scaled operator, from `x` in place, given and
/// updating the residual `r = b − A x` (`CHEBYSHEV_DEGREE` products with `A`; one fewer when
/// this is the `last` smoothing and the residual is not needed after it).
fn chebyshev(pool: &ThreadPool, level: &Level, x: &mut [f64], residual: &mut [f64], last: bool) {
    let (upper, lower) = (level.lambda, level.lambda / CHEBYSHEV_RATIO);
    let theta = 0.5 * (upper + lower);
    let delta = 0.5 * (upper - lower);
    let sigma = theta / delta;
    let mut rho = 1.0 / sigma;
    let n = x.len();
    let mut d: Vec<f64> = residual
        .iter()
        .zip(&level.inverse_diagonal)
        .map(|(r, w)| r * w / theta)
        .collect();
    let mut ad = vec![0.0; n];
    for k in 0..CHEBYSHEV_DEGREE {
        for (xi, di) in x.iter_mut().zip(&d) {
            *xi += di;
        }
        if last && k + 1 == CHEBYSHEV_DEGREE {
            break;
        }
        level.a.apply(pool, &d, &mut ad);
        for (r, a) in residual.iter_mut().zip(&ad) {
            *r -= a;
        }
        if k + 1 == CHEBYSHEV_DEGREE {
            break;
        }
        let rho_next = 1.0 / (2.0 * sigma - rho);
        for ((di, r), w) in d
            .iter_mut()
            .zip(residual.iter())
            .zip(&level.inverse_diagonal)
        {
            *di = rho_next * rho * *di + 2.0 * rho_next / delta * r * w;
        }
        rho = rho_next;
    }
}
