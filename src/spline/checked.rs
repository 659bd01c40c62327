//! The checked fit of a T-mesh's map: fit, certify, quasi-interpolate where the fit is not
//! certified, keep the better map, untangle it where it folds.

use std::time::Instant;

use super::fit::{FitReport, FitStages};
use super::map::SplineMap;
use super::thb::ThbSpace;
use super::untangle::UntangleOptions;
use super::validity::{ValidityOptions, ValidityReport};
use crate::error::Result;

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
    ) -> Result<(Self, FitReport, ValidityReport)> {
        let source = super::quadratic::QuadraticMap::new(mesh, positions)?;
        let space = ThbSpace::new(mesh.tree().clone())?;
        Self::fit_checked(space, |x| source.eval(x), options, untangle)
    }

    /// Fits `f` by [`SplineMap::fit`] (Greville interpolation, or least squares) and, unless
    /// that map is certified valid, also by [`SplineMap::fit_quasi_interpolation`], and keeps
    /// the better: certified valid first, then fewer uncertified elements, then the higher
    /// smallest mean ratio, the interpolation on ties. Interpolation follows the data more
    /// closely; the local quasi-interpolant does not overshoot where the collocation is badly
    /// conditioned. When the map kept is not certified valid, it is untangled
    /// ([`SplineMap::untangle`] with `untangle`). Returns the map, its fit report and its
    /// validity (certified with `options`).
    pub fn fit_checked(
        space: ThbSpace<D>,
        f: impl Fn([f64; D]) -> Option<[f64; D]> + Sync,
        options: &ValidityOptions,
        untangle: &UntangleOptions,
    ) -> Result<(Self, FitReport, ValidityReport)> {
        let start = Instant::now();
        let mut stages = FitStages::default();
        let mut lap = Instant::now();
        let mut split = |slot: &mut f64| {
            *slot += lap.elapsed().as_secs_f64();
            lap = Instant::now();
        };
        let (map, mut report) = SplineMap::fit(space.clone(), &f)?;
        split(&mut stages.fit);
        let validity = map.validity(options);
        split(&mut stages.certify);
        if validity.certified_positive {
            let mut map = map;
            let validity = map.smooth_into(validity, options, untangle, &mut report);
            split(&mut stages.smooth);
            report.seconds = start.elapsed().as_secs_f64();
            report.stages = stages;
            return Ok((map, report, validity));
        }
        let (quasi, quasi_report) = SplineMap::fit_quasi_interpolation(space, &f)?;
        split(&mut stages.fit);
        let quasi_validity = quasi.validity(options);
        split(&mut stages.certify);
        let (mut map, mut report, validity) = if quasi_validity.is_better_than(&validity) {
            (quasi, quasi_report, quasi_validity)
        } else {
            (map, report, validity)
        };
        let (validity, untangled) = map.untangle(validity, options, untangle);
        split(&mut stages.untangle);
        let validity = map.smooth_into(validity, options, untangle, &mut report);
        split(&mut stages.smooth);
        report.untangled = untangled.moved;
        report.boundary_offset = untangled.boundary_offset;
        report.seconds = start.elapsed().as_secs_f64();
        report.stages = stages;
        Ok((map, report, validity))
    }

    /// [`SplineMap::smooth`] with the sweeps and samples of `untangle`, the control points
    /// moved written to `report`; returns the validity of the map kept.
    fn smooth_into(
        &mut self,
        validity: ValidityReport,
        options: &ValidityOptions,
        untangle: &UntangleOptions,
        report: &mut FitReport,
    ) -> ValidityReport {
        let (validity, smoothed) = self.smooth(
            validity,
            options,
            untangle.smoothing_sweeps,
            untangle.samples,
        );
        report.smoothed = smoothed.moved;
        validity
    }
}
