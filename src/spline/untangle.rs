//! Untangling of a fitted spline map: where `det J_S` is not proven positive, the control points
//! around those elements are moved, one at a time, to minimise the regularised mean-ratio
//! distortion of `J_S` at sample points of the elements they touch — the T-mesh optimizer's
//! objective and per-node Newton solver, applied to control points. `J_S` at a point is affine
//! in each control point (`J_S = A + P_i ∇N_iᵀ`), exactly the form of a T-mesh node's terms.
//!
//! First only the control points of functions that vanish on the boundary of \[0,1\]^d move: the
//! boundary of the map does not change. If elements stay uncertified and `boundary_offset` is
//! positive, those of the boundary functions move too, each at most `boundary_offset` (in
//! coordinates that map the control points' bounding box onto a unit box) from where it was:
//! where two boundary surfaces meet almost tangentially, `det J_S` on their common edge depends
//! on the surfaces alone, and at a corner of the cube on its three edge curves alone. The map is
//! kept only if fewer elements stay uncertified.

use std::collections::BTreeSet;

use rayon::prelude::*;

use super::control::Region;
use super::map::SplineMap;
use super::space::SplineSpace;
use super::thb::ThbSpace;
use super::validity::{ValidityOptions, ValidityReport};
use crate::optimize::small_matrix::{bounding_box, clip_to_ball, det, Vector};
use crate::optimize::NodeSolverOptions;

/// Options of [`SplineMap::untangle`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UntangleOptions {
    /// Largest number of untangling rounds (mark the uncertified elements, optimize the control
    /// points around them, certify again) per stage for a map that is not certified (default
    /// 4); a round that leaves as many elements uncertified as it found ends the stage. In a
    /// checked fit 0 turns the untangling off: such a map is returned as fitted, with its
    /// uncertified elements in its validity report (`igaparam_spline_check_validity` in C).
    pub rounds: u32,
    /// Sweeps over the free control points per untangling round (default 20).
    pub sweeps: u32,
    /// Sample points per direction and element (the element's corners included).
    pub samples: usize,
    /// Rings of elements around the uncertified ones whose control points move too.
    pub rings: u32,
    /// Largest move of a control point of a function non-zero on the boundary of \[0,1\]^d, in
    /// coordinates that map the control points' bounding box onto a unit box; 0 keeps the
    /// boundary of the map. The boundary moves only when moving the inner control points alone
    /// leaves elements uncertified. Default 1e-2, as
    /// [`DomainOptions::boundary_offset`](crate::domain::DomainOptions::boundary_offset).
    pub boundary_offset: f64,
    /// Largest number of smoothing sweeps over the inner control points of a certified map
    /// ([`SplineMap::smooth`], the stage that follows the untangling, or a fit certified as it
    /// is, in a checked fit; default 8); 0 turns the smoothing off.
    pub smoothing_sweeps: u32,
    /// Exponent `p` of the smoothing's objective, the sum of the distortions `η*^p` at the
    /// samples: 0 (default) chooses 4 for planar maps and 1 for solids; else at least 1, at most
    /// 16. Above 1 the worst samples weigh most, which lifts the smallest q_S where the mean
    /// distortion (`p = 1`) would not move it. Such a smoothing samples two points more per
    /// direction than `samples` (with four, `p = 4` folded Gran Canaria's map between samples;
    /// with five, its certified bound fell while the sampled minimum rose), and where it cannot
    /// lift the map the `p = 1` smoothing runs instead. On the 3D duck it lifted nothing (the
    /// smallest q_S is held at the boundary) and doubled the smoothing's time, hence 1 for
    /// solids by default.
    pub smoothing_power: f64,
}

impl Default for UntangleOptions {
    fn default() -> Self {
        UntangleOptions {
            rounds: 4,
            sweeps: 20,
            samples: 4,
            rings: 1,
            boundary_offset: 1e-2,
            smoothing_sweeps: 8,
            smoothing_power: 0.0,
        }
    }
}

/// What [`SplineMap::untangle`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UntangleReport {
    /// Elements not certified before.
    pub uncertified_before: usize,
    /// Elements not certified after (equal to before when the map was kept unchanged).
    pub uncertified_after: usize,
    /// Control points moved (0 when the map was kept unchanged).
    pub moved: usize,
    /// Largest move of a control point of a boundary function, in the unit-box coordinates of
    /// [`UntangleOptions::boundary_offset`].
    pub boundary_offset: f64,
    /// Whether the progress callback of [`SplineMap::untangle_with`] stopped it (the map is
    /// then left as it was).
    pub cancelled: bool,
}

/// One stage of the untangling, in unit-box coordinates (each axis scaled by the extent of the
/// control points where it started).
struct Stage<const D: usize> {
    /// Per axis, the factor into unit-box coordinates.
    scale: [f64; D],
    /// The control points where the stage started.
    start: Vec<Vector<D>>,
    /// The control points now.
    y: Vec<Vector<D>>,
    /// The control points moved so far.
    moved: BTreeSet<usize>,
}

impl<const D: usize> SplineMap<D, ThbSpace<D>> {
    /// Moves control points around the elements `validity` does not certify so that `det J_S`
    /// becomes positive there (see the module documentation): first the inner control points,
    /// then, while elements stay uncertified and `options.boundary_offset` is positive, those of
    /// the boundary too. Keeps the new control points only when fewer elements stay uncertified
    /// (or as many, with a higher smallest mean ratio) and returns the validity of the map kept,
    /// certified with `certify`.
    pub fn untangle(
        &mut self,
        validity: ValidityReport,
        certify: &ValidityOptions,
        options: &UntangleOptions,
    ) -> (ValidityReport, UntangleReport) {
        self.untangle_with(validity, certify, options, &mut |_, _| true)
    }

    /// [`SplineMap::untangle`], calling `progress(done, total)` before each round (`total`:
    /// the rounds of every stage); when it returns false the untangling stops, the map is left
    /// as it was and the report says `cancelled`.
    pub fn untangle_with(
        &mut self,
        validity: ValidityReport,
        certify: &ValidityOptions,
        options: &UntangleOptions,
        progress: &mut dyn FnMut(usize, usize) -> bool,
    ) -> (ValidityReport, UntangleReport) {
        let mut report = UntangleReport {
            uncertified_before: validity.uncertified,
            uncertified_after: validity.uncertified,
            ..Default::default()
        };
        let mut validity = validity;
        // Stage 1: the inner control points, and the boundary ones of the elements folded where
        // det J_S depends on the boundary alone; stage 2: every boundary one too.
        let pinned = self.pinned_boundary(&validity, certify);
        let cap = options.boundary_offset;
        let stages: Vec<BTreeSet<usize>> = if cap > 0.0 {
            vec![pinned, (0..self.basis_count()).collect()]
        } else {
            vec![BTreeSet::new()]
        };
        let rounds = options.rounds as usize;
        let total = rounds * stages.len();
        for (stage, boundary) in stages.iter().enumerate() {
            if validity.certified_positive || options.rounds == 0 {
                break;
            }
            let mut round = |r: usize| progress(stage * rounds + r, total);
            let Some((after, moved, offset)) =
                self.untangle_within(validity.clone(), certify, options, boundary, &mut round)
            else {
                report.cancelled = true;
                return (validity, report);
            };
            validity = after;
            report.moved += moved;
            report.boundary_offset = report.boundary_offset.max(offset);
        }
        report.uncertified_after = validity.uncertified;
        (validity, report)
    }

    /// The boundary functions non-zero on an uncertified element whose `det J_S` is not
    /// positive at a sample on two or more sides of \[0,1\]^d (a corner of the square, an edge of
    /// the cube), in 3D also on an element in the support of one of those: at such a sample every
    /// column of `J_S` is a tangent of the boundary, so `det J_S` depends on the boundary
    /// control points alone and no inner one can lift it.
    fn pinned_boundary(
        &self,
        validity: &ValidityReport,
        certify: &ValidityOptions,
    ) -> BTreeSet<usize> {
        let n = certify.samples.max(2);
        let pinned: Vec<usize> = marked(validity)
            .into_par_iter()
            .filter(|&e| {
                let (lo, hi) = self.space.element_bounds(e);
                let jacobians = self.piece(e).grid_jacobians(n);
                jacobians.iter().enumerate().any(|(s, j)| {
                    let sides = (0..D)
                        .filter(|&k| {
                            let i = s / n.pow(k as u32) % n;
                            (i == 0 && lo[k] == 0.0) || (i == n - 1 && hi[k] == 1.0)
                        })
                        .count();
                    sides >= 2 && det(j) <= 0.0
                })
            })
            .collect();
        let boundary_of = |e: usize| {
            self.space
                .extraction(e)
                .0
                .iter()
                .copied()
                .filter(|&f| self.boundary_sides(f) > 0)
        };
        let own: BTreeSet<usize> = pinned.iter().flat_map(|&e| boundary_of(e)).collect();
        if D < 3 {
            // A corner of the square: its element's own boundary functions, so that no more
            // of the boundary moves than there (the squeeze below was seen on the cube's
            // edges only).
            return own;
        }
        // An edge of the cube: with the boundary functions of the pinned elements alone the
        // untangling squeezes their neighbours along the edge (the duck B-rep's min q_S fell
        // from 0.077 to 0.006 so); those of every element in their supports move too.
        let support = self.function_elements();
        own.iter()
            .flat_map(|&f| support[f].iter().flat_map(|&e| boundary_of(e)))
            .collect()
    }

    /// One stage of [`SplineMap::untangle`]: the `boundary` functions (of those of the
    /// boundary) may move too, at most `cap`. Returns the validity of the map kept, the control
    /// points moved and the largest move of a boundary one; `None`, the map unchanged, when
    /// `round(r)`, called before round `r`, returns false.
    fn untangle_within(
        &mut self,
        validity: ValidityReport,
        certify: &ValidityOptions,
        options: &UntangleOptions,
        boundary: &BTreeSet<usize>,
        round: &mut dyn FnMut(usize) -> bool,
    ) -> Option<(ValidityReport, usize, f64)> {
        let mut stage = self.unit_box();
        let mut uncertified: Vec<usize> = marked(&validity);
        let support = self.function_elements();
        for r in 0..options.rounds as usize {
            if !round(r) {
                return None;
            }
            if uncertified.is_empty() {
                break;
            }
            let functions = self.free_functions(&uncertified, &support, options.rings, boundary);
            let mut region = self.region(&functions, &support, options.samples, &stage.y);
            self.sweep_round(&mut stage, &mut region, &uncertified, certify, options);
            let control = self.unscaled(&stage.y, &stage.scale, &stage.moved);
            let elements: Vec<usize> = region
                .order
                .par_iter()
                .copied()
                .filter(|&e| !self.certified_with(e, &control, certify))
                .collect();
            // A round that leaves as many elements uncertified as it started with stops the
            // stage: more of the same sweeps would not open them.
            let stalled = elements.len() >= uncertified.len();
            uncertified = elements;
            if stalled {
                break;
            }
        }
        Some(self.keep_if_better(stage, validity, certify))
    }

    /// The start of a stage: the control points in unit-box coordinates, each axis scaled by
    /// the extent of the control points, none moved yet.
    fn unit_box(&self) -> Stage<D> {
        let (lo, hi) = bounding_box(self.control.iter().copied());
        let scale: [f64; D] = std::array::from_fn(|k| {
            let e = hi[k] - lo[k];
            if e > 0.0 && e.is_finite() {
                1.0 / e
            } else {
                1.0
            }
        });
        let start: Vec<Vector<D>> = self
            .control
            .iter()
            .map(|p| std::array::from_fn(|k| p[k] * scale[k]))
            .collect();
        Stage {
            scale,
            y: start.clone(),
            start,
            moved: BTreeSet::new(),
        }
    }

    /// One round's sweeps over the free control points of `region`, while they improve the
    /// `uncertified` elements (the round's) or, once those are open, the sampled mean ratio.
    fn sweep_round(
        &self,
        stage: &mut Stage<D>,
        region: &mut Region<D>,
        uncertified: &[usize],
        certify: &ValidityOptions,
        options: &UntangleOptions,
    ) {
        let cap = options.boundary_offset;
        // Newton iterations per control point and sweep, as measured: in 3D 20 lift the duck
        // B-rep's min q_S from 0.076 (8) to 0.082; in 2D 8 untangle Gran Canaria with its
        // boundary kept, where 20 leave an element for the boundary stage (1% moves).
        let solver = NodeSolverOptions {
            gradient_tolerance: 1e-4,
            max_iterations: if D == 3 { 20 } else { 8 },
            relaxation: 1.0,
            power: 1.0,
        };
        let start = &stage.start;
        let constrain = |f: usize, next: Vector<D>| {
            if self.boundary_sides(f) > 0 {
                clip_to_ball(next, start[f], cap)
            } else {
                next
            }
        };
        let scale = &stage.scale;
        let progress = |region: &Region<D>, y: &[Vector<D>], moved: &BTreeSet<usize>| {
            let (folded, smallest, quality) = region.folded();
            let control = self.unscaled(y, scale, moved);
            let open = self.uncertified_count(uncertified, &control, certify);
            (folded + open, smallest, quality)
        };
        let (y, moved) = (&mut stage.y, &mut stage.moved);
        let mut best = progress(region, y, moved);
        for _ in 0..options.sweeps {
            let previous = (y.to_vec(), moved.clone());
            let largest = region.sweep(y, &solver, &constrain, moved);
            let now = progress(region, y, moved);
            // While samples fold or the round's elements are not certified, a sweep must
            // lower their count or lift the smallest sampled det J; after, it must lift
            // the smallest sampled mean ratio by 1%. Otherwise, or when it barely moves,
            // the round ends.
            let improved = if now.0 == 0 {
                best.0 > 0 || now.2 > 1.01 * best.2
            } else {
                now.0 < best.0 || (now.0 == best.0 && now.1 > best.1)
            };
            if !improved {
                // The sweep made the round's measure worse: the state goes back to the one
                // before it (the duck B-rep's last sweep lowered its min q_S from 0.16 to 0.11).
                (*y, *moved) = previous;
                break;
            }
            if largest < 1e-3 {
                break;
            }
            best = now;
        }
    }

    /// The end of a stage: the map with the stage's control points if it is better than the
    /// one whose validity is `validity`, else the map unchanged. Returns the validity of the map
    /// kept, the control points moved and the largest move of a boundary one.
    fn keep_if_better(
        &mut self,
        stage: Stage<D>,
        validity: ValidityReport,
        certify: &ValidityOptions,
    ) -> (ValidityReport, usize, f64) {
        let Stage {
            scale,
            start,
            y,
            moved,
        } = stage;
        let trial = SplineMap {
            space: self.space.clone(),
            control: self.unscaled(&y, &scale, &moved),
        };
        let after = trial.validity(certify);
        if !after.is_better_than(&validity) {
            return (validity, 0, 0.0);
        }
        let offset = moved
            .iter()
            .filter(|&&f| self.boundary_sides(f) > 0)
            .map(|&f| {
                (0..D)
                    .map(|k| (y[f][k] - start[f][k]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .fold(0.0, f64::max);
        *self = trial;
        (after, moved.len(), offset)
    }

    /// How many of the `elements` are not certified for the control points `control` (in
    /// parallel).
    fn uncertified_count(
        &self,
        elements: &[usize],
        control: &[[f64; D]],
        certify: &ValidityOptions,
    ) -> usize {
        elements
            .par_iter()
            .filter(|&&e| !self.certified_with(e, control, certify))
            .count()
    }

    /// The number of sides of \[0,1\]^d function `f` is non-zero on.
    pub(super) fn boundary_sides(&self, f: usize) -> usize {
        let (level, index) = self.space.functions()[f];
        let last = super::bernstein::function_count(level) as u32 - 1;
        index.iter().filter(|&&i| i == 0 || i == last).count()
    }

    /// The control points with the `moved` ones at `y` (unit-box coordinates, `scale` per
    /// axis); the others keep their values bit for bit.
    fn unscaled(
        &self,
        y: &[Vector<D>],
        scale: &[f64; D],
        moved: &BTreeSet<usize>,
    ) -> Vec<[f64; D]> {
        let mut control = self.control.clone();
        for &f in moved {
            control[f] = std::array::from_fn(|k| y[f][k] / scale[k]);
        }
        control
    }

    /// The functions that move around the `uncertified` elements: theirs, and `rings` times
    /// those of the elements in the supports of the functions found (of the boundary ones,
    /// only those in `boundary`); `support` lists each function's elements.
    fn free_functions(
        &self,
        uncertified: &[usize],
        support: &[Vec<usize>],
        rings: u32,
        boundary: &BTreeSet<usize>,
    ) -> BTreeSet<usize> {
        let mut element_set: BTreeSet<usize> = uncertified.iter().copied().collect();
        let mut functions = BTreeSet::new();
        let movable = |f: usize| self.boundary_sides(f) == 0 || boundary.contains(&f);
        for ring in 0..=rings {
            let current: Vec<usize> = element_set.iter().copied().collect();
            for e in current {
                for &f in self.space.extraction(e).0 {
                    if movable(f) && functions.insert(f) && ring < rings {
                        element_set.extend(support[f].iter().copied());
                    }
                }
            }
        }
        functions
    }
}

/// The uncertified elements of a report.
fn marked(validity: &ValidityReport) -> Vec<usize> {
    validity
        .elements
        .iter()
        .enumerate()
        .filter(|(_, v)| !v.certified_positive)
        .map(|(e, _)| e)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tmesh::Tree;

    /// The identity of \[0,1\]^d on the uniform space of `level` (control points at the Greville
    /// points), with the inner control point `moved` displaced by `by`.
    fn folded<const D: usize>(level: u8, moved: usize, by: [f64; D]) -> SplineMap<D> {
        let mut tree = Tree::<D>::new();
        tree.refine_uniformly(level).unwrap();
        let space = ThbSpace::new(tree).unwrap();
        let mut control = space.greville_points();
        for k in 0..D {
            control[moved][k] += by[k];
        }
        SplineMap::new(space, control).unwrap()
    }

    /// The index of the function of multi-index `index` (one level).
    fn function<const D: usize>(map: &SplineMap<D>, index: [u32; D]) -> usize {
        map.space()
            .functions()
            .iter()
            .position(|&(_, i)| i == index)
            .unwrap()
    }

    fn untangles<const D: usize>(level: u8, index: [u32; D], by: [f64; D]) {
        let probe = folded::<D>(level, 0, [0.0; D]);
        let f = function(&probe, index);
        let mut map = folded::<D>(level, f, by);
        let certify = ValidityOptions::default();
        let before = map.validity(&certify);
        assert!(
            before.uncertified > 0,
            "the displaced point folds the map: {f} {:?} {:?}",
            map.control_points()[f],
            before.det_lower_bound
        );
        assert!(before.elements.iter().any(|v| v.sampled_min_det < 0.0));
        let original = map.control_points().to_vec();
        let options = UntangleOptions {
            boundary_offset: 0.0,
            ..Default::default()
        };
        let (after, report) = map.untangle(before.clone(), &certify, &options);
        assert!(after.certified_positive, "{report:?}");
        assert_eq!(after, map.validity(&certify));
        assert_eq!(report.uncertified_before, before.uncertified);
        assert_eq!(report.uncertified_after, 0);
        assert!(report.moved > 0 && report.boundary_offset == 0.0);
        // The boundary of the map is that of the identity: its control points did not move.
        for (g, (p, q)) in original.iter().zip(map.control_points()).enumerate() {
            if map.boundary_sides(g) > 0 {
                assert_eq!(p, q, "boundary control point {g} moved");
            }
        }
    }

    #[test]
    fn a_folded_square_is_untangled_with_its_boundary_kept() {
        untangles::<2>(2, [2, 2], [0.8, 0.0]);
    }

    #[test]
    fn a_folded_cube_is_untangled_with_its_boundary_kept() {
        untangles::<3>(2, [3, 2, 3], [0.0, 1.2, 0.0]);
    }

    #[test]
    fn a_certified_map_is_left_as_it_is() {
        let mut map = folded::<2>(2, 0, [0.0; 2]);
        let certify = ValidityOptions::default();
        let validity = map.validity(&certify);
        let control = map.control_points().to_vec();
        let (after, report) = map.untangle(validity.clone(), &certify, &UntangleOptions::default());
        assert_eq!(after, validity);
        assert_eq!(report.moved, 0);
        assert_eq!(map.control_points(), &control[..]);
    }

    #[test]
    fn boundary_control_points_move_within_the_offset() {
        // A boundary control point pushed across the domain folds the map whatever the inner
        // points do; with an offset the boundary may move, at most that far.
        let probe = folded::<2>(2, 0, [0.0; 2]);
        let f = function(&probe, [2, 0]);
        let mut map = folded::<2>(2, f, [0.0, 0.3]);
        let certify = ValidityOptions::default();
        let before = map.validity(&certify);
        assert!(before.uncertified > 0);
        let original = map.control_points().to_vec();
        let options = UntangleOptions {
            boundary_offset: 0.05,
            ..Default::default()
        };
        let (after, report) = map.untangle(before.clone(), &certify, &options);
        assert!(after.uncertified <= before.uncertified);
        assert!(report.boundary_offset <= 0.05 * (1.0 + 1e-12), "{report:?}");
        // Moves are measured in the unit box of the control points, here the unit square.
        let extent = [1.0, 1.0];
        for (g, (p, q)) in original.iter().zip(map.control_points()).enumerate() {
            if map.boundary_sides(g) > 0 {
                let d: f64 = (0..2)
                    .map(|k| ((p[k] - q[k]) / extent[k]).powi(2))
                    .sum::<f64>();
                assert!(
                    d.sqrt() <= 0.05 * (1.0 + 1e-9) + 1e-12,
                    "{g}: {p:?} → {q:?}"
                );
            }
        }
    }
}
