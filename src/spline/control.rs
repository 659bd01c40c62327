//! Optimization of a spline map's control points on the quality of its own Jacobian: the
//! elements and sample points an objective looks at, and coloured Gauss–Seidel sweeps of the
//! T-mesh optimizer's per-node Newton solver over the free control points.
//!
//! `J_S` at a point is affine in each control point (`J_S = A + P_i ∇N_iᵀ`), exactly the form of
//! a T-mesh node's terms, so the kernel's objective (the regularised mean-ratio distortion), its
//! δ rule and its solver apply unchanged; the terms are stored by their invariants
//! ([`AffineTerms`]), a control point's objective looking at a thousand samples or more.
//! Control points whose supports share no element do not interact: they are coloured so, each
//! colour is solved in parallel and its moves applied in order, so the result does not depend
//! on the number of threads.

use std::collections::{BTreeSet, HashMap};

use rayon::prelude::*;

use super::bernstein::GridTables;
use super::map::SplineMap;
use super::space::SplineSpace;
use super::thb::ThbSpace;
use crate::optimize::affine::AffineTerms;
use crate::optimize::metric::mean_ratio;
use crate::optimize::node::minimise;
use crate::optimize::small_matrix::{add_outer, det, Matrix, Vector};
use crate::optimize::NodeSolverOptions;

/// One element of a [`Region`]: its functions and their gradients at its samples, sample by
/// sample (`gradients[s * functions.len() + i]` for function `i` at sample `s`).
struct SampledElement<const D: usize> {
    functions: Vec<usize>,
    gradients: Vec<[f64; D]>,
}

impl<const D: usize> SampledElement<D> {
    /// Per sample, the gradients of the element's functions.
    fn samples(&self) -> std::slice::ChunksExact<'_, [f64; D]> {
        self.gradients.chunks_exact(self.functions.len().max(1))
    }

    /// The number of samples.
    fn sample_count(&self) -> usize {
        self.gradients.len() / self.functions.len().max(1)
    }
}

/// The elements and samples the objective of some free control points looks at.
pub(super) struct Region<const D: usize> {
    /// The elements, in increasing order.
    pub(super) order: Vec<usize>,
    /// Per element: its functions and, per sample, their gradients.
    elements: Vec<SampledElement<D>>,
    /// Per element and sample, `J_S` in the coordinates of the control points given.
    jacobians: Vec<Vec<Matrix<D>>>,
    /// Per free function: its (element, position in the element's functions) pairs.
    touches: Vec<(usize, Vec<(usize, usize)>)>,
    /// Per free function: a length of its support (parametric).
    lengths: Vec<f64>,
    /// The free functions (positions in `touches`) by colour: no two of a colour share an
    /// element.
    colours: Vec<Vec<usize>>,
}

impl<const D: usize> SplineMap<D, ThbSpace<D>> {
    /// Per function, the elements it is non-zero on.
    pub(super) fn function_elements(&self) -> Vec<Vec<usize>> {
        let mut support = vec![Vec::new(); self.basis_count()];
        for e in 0..self.element_count() {
            for &f in self.space.extraction(e).0 {
                support[f].push(e);
            }
        }
        support
    }

    /// The region of the free `functions` (increasing): the elements of their supports with
    /// `samples^d` points each, the Jacobians there for the control points `y`.
    pub(super) fn region(
        &self,
        functions: &BTreeSet<usize>,
        support: &[Vec<usize>],
        samples: usize,
        y: &[Vector<D>],
    ) -> Region<D> {
        let mut objective_elements = BTreeSet::new();
        for &f in functions {
            objective_elements.extend(support[f].iter().copied());
        }
        let order: Vec<usize> = objective_elements.into_iter().collect();
        let elements = self.sampled_elements(&order, samples);
        let position: HashMap<usize, usize> =
            order.iter().enumerate().map(|(i, &e)| (e, i)).collect();
        let mut touches = Vec::with_capacity(functions.len());
        let mut lengths = Vec::with_capacity(functions.len());
        for &f in functions {
            let list: Vec<(usize, usize)> = support[f]
                .iter()
                .map(|e| {
                    let r = position[e];
                    let at = elements[r]
                        .functions
                        .binary_search(&f)
                        .expect("a function of its support's elements");
                    (r, at)
                })
                .collect();
            let side: f64 = support[f]
                .iter()
                .map(|&e| {
                    let (lo, hi) = self.space.element_bounds(e);
                    hi[0] - lo[0]
                })
                .sum::<f64>()
                / support[f].len().max(1) as f64;
            lengths.push(side);
            touches.push((f, list));
        }
        let jacobians = sample_jacobians(&elements, y);
        let colours = colour(&touches, order.len());
        Region {
            order,
            elements,
            jacobians,
            touches,
            lengths,
            colours,
        }
    }

    /// The `elements` (in this order) with their functions and, at `samples^d` points each,
    /// the functions' gradients.
    fn sampled_elements(&self, elements: &[usize], samples: usize) -> Vec<SampledElement<D>> {
        let local = 4usize.pow(D as u32);
        let tables = GridTables::new(samples);
        let count = tables.points().pow(D as u32);
        elements
            .par_iter()
            .map_init(
                || [Vec::new(), Vec::new()],
                |scratch, &e| {
                    let (lo, hi) = self.space.element_bounds(e);
                    let h = std::array::from_fn(|k| hi[k] - lo[k]);
                    let (functions, c) = self.space.extraction(e);
                    let stride = functions.len();
                    let mut gradients = vec![[0.0; D]; count * stride];
                    for (at, row) in c.chunks_exact(local).enumerate() {
                        tables.gradients(row, h, scratch, &mut gradients, (stride, at));
                    }
                    SampledElement {
                        functions: functions.to_vec(),
                        gradients,
                    }
                },
            )
            .collect()
    }
}

/// Per element and sample, `J_S = Σ_h y_h ∇N_hᵀ` for the control points `y`.
fn sample_jacobians<const D: usize>(
    elements: &[SampledElement<D>],
    y: &[Vector<D>],
) -> Vec<Vec<Matrix<D>>> {
    elements
        .par_iter()
        .map(|element| {
            element
                .samples()
                .map(|gradients| {
                    let mut j = [[0.0; D]; D];
                    for (&h, g) in element.functions.iter().zip(gradients) {
                        j = add_outer(&j, &y[h], g);
                    }
                    j
                })
                .collect()
        })
        .collect()
}

/// Greedy colouring of the free functions in their order: the smallest colour not used by a
/// function sharing an element.
fn colour(touches: &[(usize, Vec<(usize, usize)>)], elements: usize) -> Vec<Vec<usize>> {
    let mut used: Vec<Vec<usize>> = vec![Vec::new(); elements];
    let mut colours: Vec<Vec<usize>> = Vec::new();
    for (i, (_, list)) in touches.iter().enumerate() {
        let mut taken: Vec<usize> = list
            .iter()
            .flat_map(|&(r, _)| used[r].iter().copied())
            .collect();
        taken.sort_unstable();
        taken.dedup();
        let c = (0..).find(|c| taken.binary_search(c).is_err()).unwrap_or(0);
        if c == colours.len() {
            colours.push(Vec::new());
        }
        colours[c].push(i);
        for &(r, _) in list {
            used[r].push(c);
        }
    }
    colours
}

impl<const D: usize> Region<D> {
    /// The number of elements with a sample where `det J_S ≤ 0`, the smallest `det J_S` and
    /// the smallest mean ratio at the samples (in the coordinates of the control points).
    pub(super) fn folded(&self) -> (usize, f64, f64) {
        let mut count = 0;
        let mut smallest = f64::INFINITY;
        let mut quality = f64::INFINITY;
        for samples in &self.jacobians {
            let least = samples.iter().map(det).fold(f64::INFINITY, f64::min);
            count += (least <= 0.0) as usize;
            smallest = smallest.min(least);
            quality = samples.iter().map(mean_ratio).fold(quality, f64::min);
        }
        (count, smallest, quality)
    }

    /// The smallest and the mean mean ratio at the samples.
    pub(super) fn quality(&self) -> (f64, f64) {
        let (mut smallest, mut sum, mut count) = (f64::INFINITY, 0.0, 0usize);
        for samples in &self.jacobians {
            for j in samples {
                let q = mean_ratio(j);
                smallest = smallest.min(q);
                sum += q;
                count += 1;
            }
        }
        (smallest, sum / count.max(1) as f64)
    }

    /// Updates the Jacobians of the elements with a `pending` move (of the function at that
    /// position in the element's functions), elements in parallel, and clears them. A colour's
    /// functions share no element, so each element has one move at most: the same sums as one
    /// function after the other.
    fn shift(&mut self, pending: &mut [Option<(usize, Vector<D>)>]) {
        let elements = &self.elements;
        self.jacobians
            .par_iter_mut()
            .zip(pending.par_iter_mut())
            .enumerate()
            .for_each(|(r, (jacobians, pending))| {
                if let Some((at, delta)) = pending.take() {
                    for (j, gradients) in jacobians.iter_mut().zip(elements[r].samples()) {
                        *j = add_outer(j, &delta, &gradients[at]);
                    }
                }
            });
    }

    /// The objective terms of free function `i` (of `touches`), its control point at `y[f]`:
    /// one per sample of each element it touches, weighted equally per element.
    fn terms(&self, i: usize, y: &[Vector<D>]) -> AffineTerms<D> {
        let (f, touches) = &self.touches[i];
        let count = touches
            .iter()
            .map(|&(r, _)| self.elements[r].sample_count())
            .sum();
        let mut out = AffineTerms::new(y[*f], count);
        for &(r, at) in touches {
            let element = &self.elements[r];
            let w = 1.0 / element.sample_count() as f64;
            for (gradients, j) in element.samples().zip(&self.jacobians[r]) {
                let g = gradients[at];
                if g.iter().all(|&v| v == 0.0) {
                    continue;
                }
                out.push(j, g, w);
            }
        }
        out
    }

    /// One coloured Gauss–Seidel sweep over the free functions: each moves its control point
    /// (in `y`) to the minimum of the regularised mean-ratio distortion at the samples of its
    /// support, then `constrain(f, next)` bounds the move. Returns the largest move relative
    /// to the function's support length, and adds the functions moved to `moved`.
    pub(super) fn sweep(
        &mut self,
        y: &mut [Vector<D>],
        solver: &NodeSolverOptions,
        constrain: &(impl Fn(usize, Vector<D>) -> Vector<D> + Sync),
        moved: &mut BTreeSet<usize>,
    ) -> f64 {
        let mut largest = 0.0f64;
        let mut pending = vec![None; self.elements.len()];
        for c in 0..self.colours.len() {
            let this = &*self;
            let y_now = &*y;
            let moves: Vec<(usize, Vector<D>)> = this.colours[c]
                .par_iter()
                .filter_map(|&i| {
                    let f = this.touches[i].0;
                    let terms = this.terms(i, y_now);
                    let weight_sum = terms.weight_sum();
                    let next = minimise(
                        &terms,
                        y_now[f],
                        (1 << D) - 1,
                        weight_sum,
                        this.lengths[i],
                        solver,
                    )?;
                    Some((i, constrain(f, next)))
                })
                .collect();
            for (i, next) in moves {
                let f = self.touches[i].0;
                let delta: Vector<D> = std::array::from_fn(|k| next[k] - y[f][k]);
                let step = delta.iter().map(|v| v * v).sum::<f64>().sqrt();
                largest = largest.max(step / self.lengths[i]);
                if step > 0.0 {
                    for &(r, at) in &self.touches[i].1 {
                        pending[r] = Some((at, delta));
                    }
                    y[f] = next;
                    moved.insert(f);
                }
            }
            self.shift(&mut pending);
        }
        largest
    }
}
