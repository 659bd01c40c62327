//! Cubic truncated hierarchical B-splines over the levels of a quadtree or octree.
//!
//! Level `l` has the clamped uniform cubic knots with `2^l` spans per direction and their tensor
//! B-splines; `Ω_l` is the union of the leaves of level ≥ `l`, i.e. of the tree cells of level
//! `l`. A level-`l` function is active when its support lies in `Ω_l` but not in `Ω_{l+1}`
//! (Kraft's selection). A coarse function is truncated level by level: expressed in the next
//! level's B-splines (two-scale relation), it loses the coefficients of the functions whose
//! support lies in that level's subdomain. The element (leaf) extraction operators are built by
//! following this through the leaf's ancestors with 4×4 one-direction matrices.

use std::collections::HashMap;

use rayon::prelude::*;

use super::bernstein::{extraction, function_count, greville, support_spans, two_scale, Matrix4};
use super::space::SplineSpace;
use crate::error::{Error, Result};
use crate::tmesh::{Cell, Tree, MAX_LEVEL, UNIT};

/// Per function of one level: how many level cells of its support exist in the tree, and how
/// many of those are refined.
type Counts<const D: usize> = HashMap<[u32; D], (u32, u32)>;

/// A cubic THB-spline space over a quadtree (d = 2) or octree (d = 3) — a T-mesh's tree is
/// strongly balanced, a tree read from a G+Smo file need not be; its
/// elements are the tree's leaves, in the order of [`Tree::leaves`] (that of the T-mesh cells).
#[derive(Clone, Debug)]
pub struct ThbSpace<const D: usize> {
    tree: Tree<D>,
    leaves: Vec<usize>,
    leaf_of_cell: Vec<usize>,
    /// Active functions: level and multi-index, in global order.
    functions: Vec<(u8, [u32; D])>,
    element_functions: Vec<Vec<usize>>,
    element_matrices: Vec<Vec<f64>>,
}

fn support_size<const D: usize>(level: u8, f: &[u32; D]) -> u32 {
    support_span_indices(level, f).len() as u32
}

/// The multi-indices of the level-`level` knot spans in the support of the B-spline `f` of that
/// level (per direction, the spans of [`support_spans`]), the first direction varying fastest.
pub(crate) fn support_span_indices<const D: usize>(
    level: u8,
    f: &[u32; D],
) -> impl ExactSizeIterator<Item = [usize; D]> {
    let spans: [(usize, usize); D] = std::array::from_fn(|k| support_spans(level, f[k] as usize));
    let count: usize = spans.iter().map(|(a, b)| b - a).product();
    (0..count).map(move |flat| {
        let mut rest = flat;
        std::array::from_fn(|k| {
            let n = spans[k].1 - spans[k].0;
            let v = spans[k].0 + rest % n;
            rest /= n;
            v
        })
    })
}

/// Applies a 4×4 matrix per direction to a tensor of `4^d` values:
/// `out[q] = Σ_j Π_k m_k[j_k][q_k] v[j]`.
pub(super) fn tensor_apply<const D: usize>(m: &[Matrix4; D], v: &[f64]) -> Vec<f64> {
    let mut cur = v.to_vec();
    for (k, mk) in m.iter().enumerate() {
        let stride = 4usize.pow(k as u32);
        let mut next = vec![0.0; cur.len()];
        for (flat, out) in next.iter_mut().enumerate() {
            let q = flat / stride % 4;
            let base = flat - q * stride;
            *out = (0..4).map(|j| mk[j][q] * cur[base + j * stride]).sum();
        }
        cur = next;
    }
    cur
}

/// Per level, the [`Counts`] of the functions whose support meets a tree cell of that level.
fn level_counts<const D: usize>(cells: &[Cell<D>]) -> Vec<Counts<D>> {
    let max_level = cells.iter().map(|c| c.level).max().unwrap_or(0);
    let mut counts: Vec<Counts<D>> = vec![HashMap::new(); max_level as usize + 2];
    for cell in cells {
        let side = cell.side();
        let span = cell.lower.map(|v| v / side);
        let refined = cell.first_child.is_some() as u32;
        for q in 0..4usize.pow(D as u32) {
            let f: [u32; D] = std::array::from_fn(|k| span[k] + (q >> (2 * k) & 3) as u32);
            let e = counts[cell.level as usize].entry(f).or_insert((0, 0));
            e.0 += 1;
            e.1 += refined;
        }
    }
    counts
}

/// Whether the support of the level-`level` function `f` lies in `Ω_level`.
fn inside<const D: usize>(counts: &[Counts<D>], level: u8, f: &[u32; D]) -> bool {
    counts[level as usize]
        .get(f)
        .is_some_and(|&(n, _)| n == support_size(level, f))
}

/// The active functions (support in `Ω_l`, not in `Ω_{l+1}`), level by level, each level's
/// by multi-index with the last direction slowest.
fn active_functions<const D: usize>(counts: &[Counts<D>]) -> Vec<(u8, [u32; D])> {
    let active = |level: u8, f: &[u32; D]| -> bool {
        counts[level as usize]
            .get(f)
            .is_some_and(|&(n, r)| n == support_size(level, f) && r < n)
    };
    let mut functions: Vec<(u8, [u32; D])> = Vec::new();
    for (level, map) in counts.iter().enumerate() {
        let level = level as u8;
        let mut here: Vec<[u32; D]> = map.keys().filter(|f| active(level, f)).copied().collect();
        here.sort_by(|a, b| a.iter().rev().cmp(b.iter().rev()));
        functions.extend(here.into_iter().map(|f| (level, f)));
    }
    functions
}

/// The active functions non-zero on the leaf `cell` (ascending, by their `index`) and its
/// extraction matrix (a row of `4^d` Bernstein coefficients per function): each function
/// followed from its level down the leaf's ancestors by the two-scale relation, truncated on the
/// way.
fn leaf_extraction<const D: usize>(
    cell: &Cell<D>,
    counts: &[Counts<D>],
    index: &HashMap<(u8, [u32; D]), usize>,
) -> (Vec<usize>, Vec<f64>) {
    let local = 4usize.pow(D as u32);
    let span = cell.lower.map(|v| v / cell.side());
    let ancestor = |k: u8| -> [usize; D] { span.map(|s| (s >> (cell.level - k)) as usize) };
    let mut rows: Vec<(usize, Vec<f64>)> = Vec::new();
    for k in 0..=cell.level {
        let a = ancestor(k);
        if k > 0 {
            let parent = ancestor(k - 1);
            let m: [Matrix4; D] = std::array::from_fn(|d| two_scale(k - 1, parent[d], a[d]));
            // The level-k functions on the ancestor whose support lies in Ω_k, looked up once
            // for all rows.
            let truncated: Vec<bool> = (0..local)
                .map(|q| {
                    let f = std::array::from_fn(|d| (a[d] + (q >> (2 * d) & 3)) as u32);
                    inside(counts, k, &f)
                })
                .collect();
            for (_, coef) in rows.iter_mut() {
                *coef = tensor_apply(&m, coef);
                for (v, &cut) in coef.iter_mut().zip(&truncated) {
                    if cut {
                        *v = 0.0;
                    }
                }
            }
            rows.retain(|(_, coef)| coef.iter().any(|&v| v != 0.0));
        }
        for q in 0..local {
            let f = std::array::from_fn(|d| (a[d] + (q >> (2 * d) & 3)) as u32);
            if let Some(&g) = index.get(&(k, f)) {
                let mut coef = vec![0.0; local];
                coef[q] = 1.0;
                rows.push((g, coef));
            }
        }
    }
    let a = ancestor(cell.level);
    let m: [Matrix4; D] = std::array::from_fn(|d| extraction(cell.level, a[d]));
    rows.sort_by_key(|r| r.0);
    let functions = rows.iter().map(|r| r.0).collect();
    let matrix = rows
        .iter()
        .flat_map(|(_, coef)| tensor_apply(&m, coef))
        .collect();
    (functions, matrix)
}

impl<const D: usize> ThbSpace<D> {
    /// The THB space of a tree (balanced or not: Kraft's selection and the truncation need no
    /// grading; a balanced tree bounds the functions per element).
    pub fn new(tree: Tree<D>) -> Result<Self> {
        let cells = tree.cells();
        let counts = level_counts(cells);
        let functions = active_functions(&counts);
        let index: HashMap<(u8, [u32; D]), usize> =
            functions.iter().enumerate().map(|(i, &f)| (f, i)).collect();
        let leaves = tree.leaves();
        let mut leaf_of_cell = vec![usize::MAX; cells.len()];
        for (e, &c) in leaves.iter().enumerate() {
            leaf_of_cell[c] = e;
        }
        // Each leaf's operator is its own: built in parallel, collected in leaf order.
        let (element_functions, element_matrices) = leaves
            .par_iter()
            .map(|&c| leaf_extraction(&cells[c], &counts, &index))
            .unzip();
        Ok(ThbSpace {
            tree,
            leaves,
            leaf_of_cell,
            functions,
            element_functions,
            element_matrices,
        })
    }

    /// The tree of the space.
    pub fn tree(&self) -> &Tree<D> {
        &self.tree
    }

    /// Level and multi-index (per direction, among the level's `2^level + 3` B-splines) of every
    /// function, in global order: by level, then with the last direction slowest (G+Smo's order).
    pub fn functions(&self) -> &[(u8, [u32; D])] {
        &self.functions
    }

    /// Tree-cell index of each element.
    pub fn leaves(&self) -> &[usize] {
        &self.leaves
    }

    /// Number of B-splines of one direction at `level` (`2^level + 3`).
    pub fn level_size(level: u8) -> usize {
        function_count(level)
    }
}

impl<const D: usize> SplineSpace<D> for ThbSpace<D> {
    fn basis_count(&self) -> usize {
        self.functions.len()
    }

    fn element_count(&self) -> usize {
        self.leaves.len()
    }

    fn element_bounds(&self, e: usize) -> ([f64; D], [f64; D]) {
        let cell = self.tree.cells()[self.leaves[e]];
        let lo = cell.lower.map(|v| v as f64 / UNIT as f64);
        let hi = std::array::from_fn(|k| (cell.lower[k] + cell.side()) as f64 / UNIT as f64);
        (lo, hi)
    }

    fn element_level(&self, e: usize) -> u8 {
        self.tree.cells()[self.leaves[e]].level
    }

    fn element_at(&self, x: [f64; D]) -> Option<usize> {
        self.tree.leaf_at_point(&x).map(|c| self.leaf_of_cell[c])
    }

    fn extraction(&self, e: usize) -> (&[usize], &[f64]) {
        (&self.element_functions[e], &self.element_matrices[e])
    }

    fn greville_points(&self) -> Vec<[f64; D]> {
        self.functions
            .iter()
            .map(|&(level, f)| std::array::from_fn(|k| greville(level, f[k] as usize)))
            .collect()
    }

    /// The Greville points, except where those of functions of different levels coincide (near
    /// a level change; the collocation matrix would be singular): the finest function keeps the
    /// point, each coarser one (level `l`) takes, among the points `{¼, ½, ¾}^d` of the level-`l`
    /// leaves in its support (a coordinate on the boundary of \[0,1\]^d stays there), the free one
    /// where it is largest.
    fn interpolation_points(&self) -> Vec<[f64; D]> {
        let cells = self.tree.cells();
        let level_at = |x: &[f64; D]| self.tree.leaf_at_point(x).map(|c| cells[c].level);
        let mut points = self.greville_points();
        let key = |p: &[f64; D]| p.map(f64::to_bits);
        // Where Greville points of several functions coincide, the finest function keeps it.
        let mut owner: std::collections::HashMap<[u64; D], usize> = Default::default();
        let mut moved = Vec::new();
        for i in (0..points.len()).rev() {
            if owner.insert(key(&points[i]), i).is_some() {
                moved.push(i);
            }
        }
        moved.sort_unstable();
        let mut taken: std::collections::HashSet<[u64; D]> = points
            .iter()
            .enumerate()
            .filter(|(i, _)| moved.binary_search(i).is_err())
            .map(|(_, p)| key(p))
            .collect();
        for i in moved {
            let (level, f) = self.functions[i];
            let g = points[i];
            let h = 1.0 / (1u64 << level) as f64;
            let mut best: Option<(f64, [f64; D])> = None;
            for span in support_span_indices(level, &f) {
                let centre: [f64; D] = std::array::from_fn(|k| (span[k] as f64 + 0.5) * h);
                if level_at(&centre) != Some(level) {
                    continue;
                }
                for digits in 0..3usize.pow(D as u32) {
                    let mut rest = digits;
                    let fraction: [f64; D] = std::array::from_fn(|_| {
                        let v = 0.25 * (rest % 3 + 1) as f64;
                        rest /= 3;
                        v
                    });
                    let p: [f64; D] = std::array::from_fn(|k| {
                        if g[k] == 0.0 || g[k] == 1.0 {
                            g[k]
                        } else {
                            (span[k] as f64 + fraction[k]) * h
                        }
                    });
                    if taken.contains(&key(&p)) {
                        continue;
                    }
                    let value = self.basis_at(p).and_then(|b| {
                        b.functions
                            .iter()
                            .position(|&j| j == i)
                            .map(|q| b.values[q])
                    });
                    if let Some(v) = value {
                        if best.is_none_or(|(bv, _)| v > bv) {
                            best = Some((v, p));
                        }
                    }
                }
            }
            if let Some((_, p)) = best {
                taken.insert(key(&p));
                points[i] = p;
            }
        }
        points
    }

    fn refine(&self, marked: &[usize]) -> Result<Self> {
        let mut tree = self.tree.clone();
        for &e in marked {
            let c = *self
                .leaves
                .get(e)
                .ok_or_else(|| Error::invalid(format!("element {e} does not exist")))?;
            if tree.cells()[c].level < MAX_LEVEL {
                tree.refine(c)?;
            }
        }
        tree.balance()?;
        ThbSpace::new(tree)
    }
}
