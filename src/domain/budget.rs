//! The total sweep budget of a build or an update ([`DomainOptions::max_total_sweeps`]).
//!
//! A build optimizes in several stages — the first sweeps, the growth from the bounding box
//! (several steps), the seam relief (several rounds) and the repair (several rounds of
//! refinement, each optimized and relieved again) — and each stage's sweeps are bounded by
//! `max_sweeps`, not their sum: inputs that fold at every level (a coastline with one point
//! far away) ran to 19,000 sweeps and 20 s with `max_sweeps` at 200. [`Sweeps`] counts the
//! sweeps of all stages: every stage's progress goes through it, and once the budget is spent
//! the running stage stops after its current sweep, keeping what it did, and no later stage
//! starts. The report then says so (`sweep_budget_exhausted`).
//!
//! [`DomainOptions::max_total_sweeps`]: super::DomainOptions::max_total_sweeps

use crate::error::{ErrorKind, Result};

/// The sweeps of a build's stages, counted against a budget, and the caller's progress.
pub(super) struct Sweeps<'a> {
    limit: usize,
    spent: usize,
    exhausted: bool,
    progress: &'a mut dyn FnMut(usize) -> bool,
}

impl<'a> Sweeps<'a> {
    /// A budget of `limit` sweeps; `progress(sweeps so far)` is the caller's callback (false
    /// cancels).
    pub(super) fn new(limit: u32, progress: &'a mut dyn FnMut(usize) -> bool) -> Self {
        Sweeps {
            limit: limit as usize,
            spent: 0,
            exhausted: false,
            progress,
        }
    }

    /// The progress callback of the next stage, which counts its sweeps from 0: it adds them to
    /// the sweeps of the stages before, reports the total to the caller, and stops the stage
    /// (returns false) once the budget is spent.
    pub(super) fn stage(&mut self) -> impl FnMut(usize) -> bool + use<'_, 'a> {
        let base = self.spent;
        move |done| {
            let total = base + done;
            self.spent = total;
            if total >= self.limit {
                self.exhausted = true;
                return false;
            }
            (self.progress)(total)
        }
    }

    /// The result of a stage run with [`Sweeps::stage`]: `Ok(None)` if the budget stopped it
    /// (what it did before is kept where the stage keeps partial work), the stage's own
    /// result otherwise (a cancellation by the caller stays an error).
    pub(super) fn absorb<T>(&self, result: Result<T>) -> Result<Option<T>> {
        match result {
            Err(e) if self.exhausted && e.kind == ErrorKind::Cancelled => Ok(None),
            other => other.map(Some),
        }
    }

    /// Whether the budget is spent: no further stage should start.
    pub(super) fn exhausted(&self) -> bool {
        self.exhausted
    }

    /// The sweeps of all stages so far.
    pub(super) fn spent(&self) -> u32 {
        u32::try_from(self.spent).unwrap_or(u32::MAX)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    #[test]
    fn stages_add_up_and_stop_at_the_budget() {
        let mut seen = Vec::new();
        let mut progress = |d: usize| {
            seen.push(d);
            true
        };
        let mut sweeps = Sweeps::new(5, &mut progress);
        {
            let mut first = sweeps.stage();
            assert!(first(1) && first(2));
        }
        {
            let mut second = sweeps.stage();
            assert!(second(1) && second(2));
            assert!(!second(3), "the fifth sweep spends the budget");
        }
        assert!(sweeps.exhausted());
        assert_eq!(sweeps.spent(), 5);
        assert_eq!(sweeps.absorb::<()>(Err(Error::cancelled())), Ok(None));
        assert!(sweeps.absorb::<()>(Err(Error::invalid("x"))).is_err());
        assert_eq!(seen, vec![1, 2, 3, 4]);
    }

    #[test]
    fn a_cancel_by_the_caller_stays_an_error() {
        let mut progress = |d: usize| d < 2;
        let mut sweeps = Sweeps::new(100, &mut progress);
        {
            let mut stage = sweeps.stage();
            assert!(stage(1));
            assert!(!stage(2));
        }
        assert!(!sweeps.exhausted());
        assert!(sweeps.absorb::<()>(Err(Error::cancelled())).is_err());
    }
}
