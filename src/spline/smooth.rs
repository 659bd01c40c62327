//! Smoothing of a certified spline map: every inner control point (of a function vanishing on
//! the boundary of \[0,1\]^d, so the map's boundary is kept) moves to the minimum of the sum of
//! the regularised mean-ratio distortions of `J_S` at the sample points of its support, each
//! raised to a power `p`, in coloured Gauss–Seidel sweeps
//! ([`Region::sweep`](super::control::Region)). The distortion grows without bound as
//! `det J_S → 0`, so its minimisation keeps the map away from folds; with `p = 1` (the mean
//! distortion) it raises the mean ratio on the whole, with `p > 1` the worst samples weigh most
//! and it raises the smallest mean ratio (measured on the G+Smo comparison domains: `p = 4`
//! lifts the certified min q_S of the rotor from 0.16 to 0.33, the 2D duck's from 0.24 to 0.36,
//! where `p = 1` left the duck as fitted). Coordinates are scaled by one factor for all axes, so
//! the objective's mean ratio is the reported `q_S`. The new map is kept only when it is certified
//! valid and its smallest sampled mean ratio (or, that equal, its mean) is higher.

use std::collections::BTreeSet;

use super::fit_options::{MAX_SAMPLES, MAX_SMOOTHING_POWER};
use super::map::SplineMap;
use super::thb::ThbSpace;
use super::validity::{ValidityOptions, ValidityReport};
use crate::optimize::small_matrix::{bounding_box, Vector};
use crate::optimize::NodeSolverOptions;

/// What [`SplineMap::smooth`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SmoothReport {
    /// Sweeps made.
    pub sweeps: u32,
    /// Control points moved (0 when the map was kept as it was).
    pub moved: usize,
    /// Smallest sampled mean ratio before.
    pub min_quality_before: f64,
    /// Smallest sampled mean ratio of the map kept.
    pub min_quality_after: f64,
    /// Whether the progress callback of [`SplineMap::smooth_with`] stopped it (the map is then
    /// left as it was).
    pub cancelled: bool,
}

/// The power of [`SplineMap::smooth`]'s automatic choice (`power = 0`) for planar maps and for
/// solids: on the 3D duck the power 4 lifted nothing and doubled the smoothing's time.
const AUTOMATIC_POWER: [f64; 2] = [4.0, 1.0];

/// The least relative lift of the smallest sampled mean ratio (or, that not lower, of the mean)
/// that a smoothing sweep must bring for the sweeps to go on.
const MIN_LIFT: f64 = 0.01;

/// The relative lift from `before` to `now` (smallest and mean sampled mean ratio): that of the
/// smallest, or when it is not lower the larger of that and the mean's.
fn lift(now: (f64, f64), before: (f64, f64)) -> f64 {
    let smallest = now.0 / before.0 - 1.0;
    match now.0 >= before.0 {
        true => smallest.max(now.1 / before.1 - 1.0),
        false => smallest,
    }
}

/// The options of one smoothing.
#[derive(Clone, Copy)]
struct Stage<'a> {
    certify: &'a ValidityOptions,
    sweeps: u32,
    samples: usize,
    power: f64,
}

impl<const D: usize> SplineMap<D, ThbSpace<D>> {
    /// Smooths a certified map (see the module documentation) with at most `sweeps` sweeps
    /// over its inner control points on the distortions to the power `power` (in [1, 16]; 0: 4
    /// for planar maps, 1 for solids) at `samples` points per direction and element (two more
    /// when `power > 1`); the sweeps stop when one no longer lifts the smallest sampled mean
    /// ratio by 1% of itself or the mean by 1%, or when the next lift, extrapolated
    /// geometrically from the last two, would be under 1%. Where a `power > 1` smoothing keeps
    /// nothing, the `power = 1` one runs. `validity` is the map's validity with the options
    /// `certify`; returns the validity of the map kept. A map that is not certified is left as
    /// it is.
    pub fn smooth(
        &mut self,
        validity: ValidityReport,
        certify: &ValidityOptions,
        sweeps: u32,
        samples: usize,
        power: f64,
    ) -> (ValidityReport, SmoothReport) {
        self.smooth_with(validity, certify, sweeps, samples, power, &mut |_, _| true)
    }

    /// [`SplineMap::smooth`], calling `progress(done, sweeps)` before each sweep; when it
    /// returns false the smoothing stops, the map is left as it was and the report says
    /// `cancelled`.
    pub fn smooth_with(
        &mut self,
        validity: ValidityReport,
        certify: &ValidityOptions,
        sweeps: u32,
        samples: usize,
        power: f64,
        progress: &mut dyn FnMut(usize, usize) -> bool,
    ) -> (ValidityReport, SmoothReport) {
        let power = if power == 0.0 {
            AUTOMATIC_POWER[D - 2]
        } else if power.is_finite() {
            power.clamp(1.0, MAX_SMOOTHING_POWER)
        } else {
            1.0
        };
        let mean = Stage {
            certify,
            sweeps,
            samples,
            power: 1.0,
        };
        if power <= 1.0 {
            return self.smooth_stage(validity, &mean, progress);
        }
        let weighted = Stage {
            samples: (samples + 2).min(MAX_SAMPLES),
            power,
            ..mean
        };
        let (kept, report) = self.smooth_stage(validity.clone(), &weighted, progress);
        if report.moved > 0 || report.cancelled {
            return (kept, report);
        }
        let (kept, mut second) = self.smooth_stage(validity, &mean, progress);
        second.sweeps += report.sweeps;
        (kept, second)
    }

    /// One smoothing with the options of `stage` (see [`SplineMap::smooth`]).
    fn smooth_stage(
        &mut self,
        validity: ValidityReport,
        stage: &Stage<'_>,
        progress: &mut dyn FnMut(usize, usize) -> bool,
    ) -> (ValidityReport, SmoothReport) {
        let mut report = SmoothReport {
            min_quality_before: validity.min_quality,
            min_quality_after: validity.min_quality,
            ..Default::default()
        };
        let sweeps = stage.sweeps;
        if !validity.certified_positive || sweeps == 0 {
            return (validity, report);
        }
        let (lo, hi) = bounding_box(self.control.iter().copied());
        let extent = (0..D).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        let scale = if extent > 0.0 && extent.is_finite() {
            1.0 / extent
        } else {
            1.0
        };
        let mut y: Vec<Vector<D>> = self.control.iter().map(|p| p.map(|v| v * scale)).collect();
        let functions: BTreeSet<usize> = (0..self.basis_count())
            .filter(|&f| self.boundary_sides(f) == 0)
            .collect();
        if functions.is_empty() {
            return (validity, report);
        }
        let support = self.function_elements();
        let mut region = self.region(&functions, &support, stage.samples, &y);
        let solver = NodeSolverOptions {
            gradient_tolerance: 1e-4,
            max_iterations: 20,
            relaxation: 1.0,
            power: stage.power,
        };
        let mut moved = BTreeSet::new();
        let start = region.quality();
        let mut best = start;
        let mut last_lift: Option<f64> = None;
        let mut states: Vec<(Vec<Vector<D>>, BTreeSet<usize>)> = Vec::new();
        for done in 0..sweeps as usize {
            if !progress(done, sweeps as usize) {
                report.cancelled = true;
                return (validity, report);
            }
            region.sweep(&mut y, &solver, &|_, next| next, &mut moved);
            report.sweeps += 1;
            let now = region.quality();
            if now.0 <= 0.0 {
                break;
            }
            // Only a state better than the start at the samples is worth certifying.
            if now.0 > start.0 || (now.0 >= start.0 && now.1 > start.1) {
                states.push((y.clone(), moved.clone()));
            }
            let lifted = lift(now, best);
            if lifted <= MIN_LIFT {
                break;
            }
            best = now;
            // The lifts of the sweeps fall about geometrically: the next one is not made when,
            // extrapolated from the last two, it would be under the least lift.
            if last_lift.is_some_and(|previous| lifted * lifted / previous <= MIN_LIFT) {
                break;
            }
            last_lift = Some(lifted);
        }
        let kept = self.keep_best(states, scale, validity, stage.certify, &mut report);
        (kept, report)
    }

    /// Keeps the last of the sweeps' `states` (control points in coordinates scaled by `scale`,
    /// and those moved) that is certified and better than the map given, whose validity is
    /// `validity`; returns the validity of the map kept.
    fn keep_best(
        &mut self,
        states: Vec<(Vec<Vector<D>>, BTreeSet<usize>)>,
        scale: f64,
        validity: ValidityReport,
        certify: &ValidityOptions,
        report: &mut SmoothReport,
    ) -> ValidityReport {
        // The last state that is certified and better than the map given, latest first.
        for (y, moved) in states.into_iter().rev() {
            let mut control = self.control.clone();
            for &f in &moved {
                control[f] = y[f].map(|v| v / scale);
            }
            let trial = SplineMap {
                space: self.space.clone(),
                control,
            };
            let after = trial.validity(certify);
            let higher = after.min_quality > validity.min_quality
                || (after.min_quality >= validity.min_quality
                    && after.mean_quality > validity.mean_quality);
            if after.certified_positive && higher {
                report.moved = moved.len();
                report.min_quality_after = after.min_quality;
                *self = trial;
                return after;
            }
        }
        validity
    }
}
