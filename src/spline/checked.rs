//! The checked fit of a T-mesh's map: fit, certify, quasi-interpolate where the fit is not
//! certified, keep the better map, untangle it where it folds, smooth it.

use std::time::Instant;

use super::fit::{FitReport, FitStages};
use super::fit_options::{install_with_progress, FitChoice, FitOptions, FitProgress, FitStage};
use super::map::SplineMap;
use super::thb::ThbSpace;
use super::untangle::UntangleOptions;
use super::validity::{ValidityOptions, ValidityReport};
use crate::error::{Error, Result};

/// A fitted map, its fit report and its validity.
type Checked<const D: usize> = (SplineMap<D, ThbSpace<D>>, FitReport, ValidityReport);

/// Wall-clock laps of the stages of a checked fit.
struct Laps {
    start: Instant,
    lap: Instant,
    stages: FitStages,
}

impl Laps {
    fn new() -> Self {
        Laps {
            start: Instant::now(),
            lap: Instant::now(),
            stages: FitStages::default(),
        }
    }

    /// Adds the time since the last lap to the stage `pick` selects.
    fn split(&mut self, pick: fn(&mut FitStages) -> &mut f64) {
        *pick(&mut self.stages) += self.lap.elapsed().as_secs_f64();
        self.lap = Instant::now();
    }

    /// Writes the times to `report`.
    fn finish(self, report: &mut FitReport) {
        report.seconds = self.start.elapsed().as_secs_f64();
        report.stages = self.stages;
    }
}

/// Calls `progress` for the fit stage; an error when it cancels.
fn fit_step(progress: &mut FitProgress, done: usize, total: usize) -> Result<()> {
    match progress(FitStage::Fit, done, total) {
        true => Ok(()),
        false => Err(Error::cancelled()),
    }
}

impl<const D: usize> SplineMap<D, ThbSpace<D>> {
    /// Fits the THB space of the T-mesh's tree to its piecewise quadratic map (see
    /// [`SplineMap::fit_tmesh_checked`]).
    pub fn fit_tmesh(
        mesh: &crate::tmesh::TMesh<D>,
        positions: &[[f64; D]],
    ) -> Result<(Self, FitReport)> {
        let (map, report, _) = Self::fit_tmesh_checked(
            mesh,
            positions,
            &ValidityOptions::default(),
            &UntangleOptions::default(),
        )?;
        Ok((map, report))
    }

    /// Fits the THB space of the T-mesh's tree to its piecewise quadratic map with
    /// [`SplineMap::fit_checked`]. Returns the map, its fit report and its validity.
    pub fn fit_tmesh_checked(
        mesh: &crate::tmesh::TMesh<D>,
        positions: &[[f64; D]],
        options: &ValidityOptions,
        untangle: &UntangleOptions,
    ) -> Result<Checked<D>> {
        let options = FitOptions::of(options, untangle);
        Self::fit_tmesh_with(mesh, positions, &options, &mut |_, _, _| true)
    }

    /// Fits the THB space of the T-mesh's tree to its piecewise quadratic map with
    /// [`SplineMap::fit_checked_with`].
    pub fn fit_tmesh_with(
        mesh: &crate::tmesh::TMesh<D>,
        positions: &[[f64; D]],
        options: &FitOptions,
        progress: &mut FitProgress,
    ) -> Result<Checked<D>> {
        let source = super::tmesh_map::QuadraticMap::new(mesh, positions)?;
        let space = ThbSpace::new(mesh.tree().clone())?;
        Self::fit_checked_with(space, |x| source.eval(x), options, progress)
    }

    /// [`SplineMap::fit_checked_with`] with the default rule ([`FitChoice::Best`]), the
    /// certification `options`, the untangling and smoothing `untangle`, no progress.
    pub fn fit_checked(
        space: ThbSpace<D>,
        f: impl Fn([f64; D]) -> Option<[f64; D]> + Sync,
        options: &ValidityOptions,
        untangle: &UntangleOptions,
    ) -> Result<Checked<D>> {
        let options = FitOptions::of(options, untangle);
        Self::fit_checked_with(space, f, &options, &mut |_, _, _| true)
    }

    /// Fits `f` by the rule of `options.choice`: with [`FitChoice::Best`] by [`SplineMap::fit`]
    /// (Greville interpolation, or least squares) and, unless that map is certified valid, also
    /// by [`SplineMap::fit_quasi_interpolation`], keeping the better: certified valid first,
    /// then fewer uncertified elements, then the higher smallest mean ratio, the interpolation
    /// on ties. Interpolation follows the data more closely; the local quasi-interpolant does
    /// not overshoot where the collocation is badly conditioned. When the map kept is not
    /// certified valid, it is untangled ([`SplineMap::untangle`] with `options.untangle`);
    /// a certified map is then smoothed ([`SplineMap::smooth`]). Returns the map, its fit
    /// report and its validity (certified with `options.validity`). `progress` is called
    /// before and after each stage, between untangling rounds and smoothing sweeps (always on
    /// the calling thread, also when `options.threads` gives the fit a pool of its own);
    /// returning false cancels
    /// ([`ErrorKind::Cancelled`](crate::error::ErrorKind::Cancelled)).
    pub fn fit_checked_with(
        space: ThbSpace<D>,
        f: impl Fn([f64; D]) -> Option<[f64; D]> + Sync,
        options: &FitOptions,
        progress: &mut FitProgress,
    ) -> Result<Checked<D>> {
        options.validate()?;
        match options.pool()? {
            Some(pool) => install_with_progress(&pool, progress, |progress| {
                Self::checked_stages(space, &f, options, progress)
            }),
            None => Self::checked_stages(space, &f, options, progress),
        }
    }

    /// The stages of [`SplineMap::fit_checked_with`].
    fn checked_stages(
        space: ThbSpace<D>,
        f: &(impl Fn([f64; D]) -> Option<[f64; D]> + Sync),
        options: &FitOptions,
        progress: &mut FitProgress,
    ) -> Result<Checked<D>> {
        let mut laps = Laps::new();
        let (map, mut report, validity) = Self::fitted(space, f, options, progress, &mut laps)?;
        let mut map = map;
        let validity = if validity.certified_positive {
            validity
        } else {
            let (validity, untangled) = map.untangle_with(
                validity,
                &options.validity,
                &options.untangle,
                &mut |d, t| progress(FitStage::Untangling, d, t),
            );
            laps.split(|s| &mut s.untangle);
            report.untangled = untangled.moved;
            report.boundary_offset = untangled.boundary_offset;
            if untangled.cancelled {
                return Err(Error::cancelled());
            }
            validity
        };
        let (validity, smoothed) = map.smooth_with(
            validity,
            &options.validity,
            options.untangle.smoothing_sweeps,
            options.untangle.samples,
            options.untangle.smoothing_power,
            &mut |d, t| progress(FitStage::Smoothing, d, t),
        );
        laps.split(|s| &mut s.smooth);
        if smoothed.cancelled {
            return Err(Error::cancelled());
        }
        report.smoothed = smoothed.moved;
        laps.finish(&mut report);
        Ok((map, report, validity))
    }

    /// The fitted map of `options.choice` with its report and validity, before untangling.
    fn fitted(
        space: ThbSpace<D>,
        f: &(impl Fn([f64; D]) -> Option<[f64; D]> + Sync),
        options: &FitOptions,
        progress: &mut FitProgress,
        laps: &mut Laps,
    ) -> Result<Checked<D>> {
        let total = if options.choice == FitChoice::Best {
            4
        } else {
            2
        };
        fit_step(progress, 0, total)?;
        let (map, report) = match options.choice {
            FitChoice::QuasiInterpolation => SplineMap::fit_quasi_interpolation(space.clone(), f)?,
            _ => SplineMap::fit(space.clone(), f)?,
        };
        laps.split(|s| &mut s.fit);
        fit_step(progress, 1, total)?;
        let validity = map.validity(&options.validity);
        laps.split(|s| &mut s.certify);
        if validity.certified_positive || options.choice != FitChoice::Best {
            fit_step(progress, total, total)?;
            return Ok((map, report, validity));
        }
        fit_step(progress, 2, total)?;
        let (quasi, quasi_report) = SplineMap::fit_quasi_interpolation(space, f)?;
        laps.split(|s| &mut s.fit);
        fit_step(progress, 3, total)?;
        let quasi_validity = quasi.validity(&options.validity);
        laps.split(|s| &mut s.certify);
        fit_step(progress, 4, total)?;
        Ok(if quasi_validity.is_better_than(&validity) {
            (quasi, quasi_report, quasi_validity)
        } else {
            (map, report, validity)
        })
    }
}
