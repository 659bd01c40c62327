//! Options of a checked fit ([`SplineMap::fit_checked_with`](super::SplineMap::fit_checked_with)):
//! which fit rule to use, how to certify, untangle and smooth, the worker threads, and the
//! stages its progress callback is told about.

use std::sync::mpsc;

use super::untangle::UntangleOptions;
use super::validity::ValidityOptions;
use crate::error::{Error, Result};

/// Largest number of sample points per direction and element of a certification or an
/// untangling/smoothing objective: `64^3` samples per element already cost seconds per element.
pub(crate) const MAX_SAMPLES: usize = 64;

/// Largest exponent of the smoothing objective (`UntangleOptions::smoothing_power`): η*^16
/// of a distortion of 10³ is 10⁴⁸, far from overflow.
pub(crate) const MAX_SMOOTHING_POWER: f64 = 16.0;

/// Largest number of subdivisions of an element's determinant in a certification.
pub(crate) const MAX_DEPTH: u32 = 12;

/// Which fit rule a checked fit uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FitChoice {
    /// Interpolation at the Greville points (least squares when that system is singular or
    /// badly conditioned) and, unless that map is certified valid, the local quasi-interpolant
    /// too; the better of the two is kept.
    #[default]
    Best,
    /// Interpolation at the Greville points only (least squares when singular).
    Interpolation,
    /// The local quasi-interpolant only.
    QuasiInterpolation,
}

/// A stage of a checked fit, as told to its progress callback.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FitStage {
    /// The fits and their certifications: `done` of `total` (2 for one rule, 4 when the
    /// quasi-interpolant may be made too; `done` jumps to `total` when it is not needed).
    Fit,
    /// Untangling rounds: `done` of at most `total`.
    Untangling,
    /// Smoothing sweeps: `done` of at most `total`.
    Smoothing,
}

/// The progress callback of a checked fit: `(stage, done, total)`; returning false cancels.
/// It is always called on the thread that started the fit, one call at a time.
pub type FitProgress<'a> = dyn FnMut(FitStage, usize, usize) -> bool + 'a;

/// Options of a checked fit.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FitOptions {
    /// The fit rule.
    pub choice: FitChoice,
    /// The certification of the fitted maps and of the untangled and smoothed ones (default:
    /// the defaults of [`ValidityOptions`]); a spline handle of the C API keeps its result for
    /// `igaparam_spline_check_validity` with equal options.
    pub validity: ValidityOptions,
    /// The untangling (`rounds = 0` turns it off: a map that is not certified is returned as
    /// fitted) and the smoothing (`smoothing_sweeps = 0` turns it off).
    pub untangle: UntangleOptions,
    /// Worker threads, at most 4096, capped to the machine's cores; 0 (default) runs on the
    /// caller's thread pool: one thread per core, unless a Rust caller installed another. The
    /// result does not depend on it.
    pub threads: usize,
}

impl ValidityOptions {
    /// Checks the ranges: `samples` from 2 to 64, `max_depth` at most 12.
    pub fn validate(&self) -> Result<()> {
        if !(2..=MAX_SAMPLES).contains(&self.samples) || self.max_depth > MAX_DEPTH {
            return Err(Error::invalid(format!(
                "validity: samples = {} must be in [2, {MAX_SAMPLES}] and max_depth = {} at \
                 most {MAX_DEPTH}",
                self.samples, self.max_depth
            )));
        }
        Ok(())
    }
}

impl FitOptions {
    /// The default rule and threads with the certification `validity` and the untangling and
    /// smoothing `untangle`.
    pub fn of(validity: &ValidityOptions, untangle: &UntangleOptions) -> Self {
        FitOptions {
            validity: *validity,
            untangle: *untangle,
            ..Default::default()
        }
    }

    /// Checks the ranges of every field.
    pub fn validate(&self) -> Result<()> {
        self.validity.validate()?;
        crate::threads::check(self.threads)?;
        let u = &self.untangle;
        if !(2..=MAX_SAMPLES).contains(&u.samples) {
            return Err(Error::invalid(format!(
                "untangling samples = {} must be in [2, {MAX_SAMPLES}]",
                u.samples
            )));
        }
        if !(u.smoothing_power == 0.0 || (1.0..=MAX_SMOOTHING_POWER).contains(&u.smoothing_power)) {
            return Err(Error::invalid(format!(
                "smoothing_power = {} must be 0 (automatic) or in [1, {MAX_SMOOTHING_POWER}]",
                u.smoothing_power
            )));
        }
        if !(u.boundary_offset.is_finite() && u.boundary_offset >= 0.0) {
            return Err(Error::invalid(format!(
                "boundary_offset = {} must be finite and at least 0",
                u.boundary_offset
            )));
        }
        Ok(())
    }

    /// A pool of [`FitOptions::threads`] workers, or `None` for the caller's pool.
    pub(super) fn pool(&self) -> Result<Option<rayon::ThreadPool>> {
        if self.threads == 0 {
            return Ok(None);
        }
        crate::threads::pool(self.threads).map(Some)
    }
}

/// Runs `job` on `pool` while the calling thread answers the job's progress calls with
/// `progress`: the callback stays on the calling thread (a C or Python host may rely on it), one
/// call at a time, and the job waits for each answer. A job's panic is passed on; a panic of
/// the callback cancels the job (its answers stop) before it is passed on.
pub(super) fn install_with_progress<R: Send>(
    pool: &rayon::ThreadPool,
    progress: &mut FitProgress,
    job: impl FnOnce(&mut FitProgress) -> R + Send,
) -> R {
    let (ask, asked) = mpsc::channel::<(FitStage, usize, usize)>();
    let (answer, answered) = mpsc::channel::<bool>();
    std::thread::scope(|s| {
        let (asked, answer) = (asked, answer);
        let worker = s.spawn(move || {
            let mut relay = move |stage, done, total| {
                ask.send((stage, done, total)).is_ok() && answered.recv().unwrap_or(false)
            };
            pool.install(|| job(&mut relay))
        });
        // The questions end when the job returns and drops its relay.
        for (stage, done, total) in asked {
            if answer.send(progress(stage, done, total)).is_err() {
                break;
            }
        }
        match worker.join() {
            Ok(result) => result,
            Err(panic) => std::panic::resume_unwind(panic),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_ranges_are_checked() {
        assert!(FitOptions::default().validate().is_ok());
        let mut o = FitOptions::default();
        o.validity.samples = MAX_SAMPLES + 1;
        assert!(o.validate().is_err());
        let mut o = FitOptions::default();
        o.untangle.boundary_offset = f64::NAN;
        assert!(o.validate().is_err());
        let mut o = FitOptions::default();
        o.untangle.samples = 1;
        assert!(o.validate().is_err());
        let o = FitOptions {
            threads: crate::threads::MAX_THREADS + 1,
            ..Default::default()
        };
        assert!(o.validate().is_err());
    }

    #[test]
    fn progress_stays_on_the_calling_thread_and_cancels_the_job() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let caller = std::thread::current().id();
        let mut calls = Vec::new();
        let mut progress = |stage, done, _total| {
            assert_eq!(std::thread::current().id(), caller);
            calls.push((stage, done));
            done < 2
        };
        let steps = install_with_progress(&pool, &mut progress, |p| {
            (0..10)
                .take_while(|&i| p(FitStage::Smoothing, i, 10))
                .count()
        });
        assert_eq!(steps, 2);
        assert_eq!(calls.len(), 3);
    }
}
