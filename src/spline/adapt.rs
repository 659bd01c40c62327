//! The adaptive loop of the method (stage 5): fit the spline map of a domain's T-mesh, assess the
//! mean-ratio Jacobian of the map per element, refine the T-mesh cells of poor or uncertified
//! quality, optimize the T-mesh again and refit, until the target quality or the level limit.

use std::time::Instant;

use super::fit::FitReport;
use super::fit_options::FitOptions;
use super::map::SplineMap;
use super::untangle::UntangleOptions;
use super::validity::{ValidityOptions, ValidityReport};
use crate::domain::{CubeMap, Domain, DomainOptions};
use crate::error::{Error, ErrorKind, Result};
use crate::tmesh::MAX_LEVEL;

/// The deepest level the loop refines to (that of a domain's repair; within the tree's
/// [`MAX_LEVEL`]).
const MAX_ADAPT_LEVEL: u8 = 16;
const _: () = assert!(MAX_ADAPT_LEVEL <= MAX_LEVEL);

/// Options of [`adapt`].
#[derive(Clone, Copy, Debug)]
pub struct AdaptOptions {
    /// The loop stops once every element is certified valid and its smallest sampled mean ratio
    /// `q_S` reaches this (in [0, 1); default 0.1). Elements below it, or not certified, are
    /// refined.
    pub target_quality: f64,
    /// Largest number of refinement rounds (default 4).
    pub max_rounds: u32,
    /// Cells at this level are not refined further (default 10, at most 16).
    pub max_level: u8,
    /// Certification and sampling of the spline map.
    pub validity: ValidityOptions,
    /// Threads and sweep limit of the T-mesh optimization after each refinement (`threads`,
    /// `max_sweeps`); its other fields are not used: the boundary offset, relief and repair
    /// rules are those the domain was built with.
    pub domain: DomainOptions,
}

impl Default for AdaptOptions {
    fn default() -> Self {
        AdaptOptions {
            target_quality: 0.1,
            max_rounds: 4,
            max_level: 10,
            validity: ValidityOptions::default(),
            domain: DomainOptions::default(),
        }
    }
}

impl AdaptOptions {
    /// Checks the ranges of every field [`adapt`] uses: `target_quality` finite and in [0, 1),
    /// `max_level` at most 16, the certification's (see [`ValidityOptions::validate`]) and
    /// `domain.threads` at most 4096.
    pub fn validate(&self) -> Result<()> {
        if !self.target_quality.is_finite() {
            return Err(Error::new(
                ErrorKind::NotFinite,
                format!(
                    "target_quality is {}, it must be finite",
                    self.target_quality
                ),
            ));
        }
        if !(0.0..1.0).contains(&self.target_quality) {
            return Err(Error::invalid(format!(
                "target_quality = {} must be in [0, 1)",
                self.target_quality
            )));
        }
        if self.max_level > MAX_ADAPT_LEVEL {
            return Err(Error::invalid(format!(
                "max_level = {} must be at most {MAX_ADAPT_LEVEL}",
                self.max_level
            )));
        }
        self.validity.validate()?;
        crate::threads::check(self.domain.threads)
    }
}

/// One round of [`adapt`]: the map fitted and assessed, and the cells then refined.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AdaptRound {
    /// Elements (= T-mesh cells) of the map.
    pub elements: usize,
    /// Basis functions.
    pub basis: usize,
    /// Whether every element is certified valid.
    pub certified_positive: bool,
    /// Elements not certified valid.
    pub uncertified: usize,
    /// Smallest sampled mean ratio of the map.
    pub min_quality: f64,
    /// Mean sampled mean ratio of the map.
    pub mean_quality: f64,
    /// Cells refined after this round (0 in the last round).
    pub refined: usize,
    /// Invalid T-mesh cells after the optimization that followed the refinement.
    pub invalid_cells: usize,
}

/// What [`adapt`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AdaptReport {
    /// One entry per fit, the last one being the map returned.
    pub rounds: Vec<AdaptRound>,
    /// The fit of the map returned.
    pub fit: FitReport,
    /// The validity of the map returned, computed with [`AdaptOptions::validity`].
    pub validity: ValidityReport,
    /// Whether the map returned meets the target (certified, and min quality at least the
    /// target).
    pub reached: bool,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// The options of the T-mesh optimization after a refinement: the domain's own build options
/// (a domain built to keep its boundary, `boundary_offset = 0`, keeps it through the loop), with
/// the loop's threads and sweep limit.
fn refinement_options(built: &DomainOptions, options: &AdaptOptions) -> DomainOptions {
    DomainOptions {
        threads: options.domain.threads,
        max_sweeps: options.domain.max_sweeps,
        ..*built
    }
}

/// The cells to refine: not certified, or of smallest sampled quality under the target, and
/// below the level limit.
fn marked<const D: usize>(
    map: &SplineMap<D>,
    validity: &ValidityReport,
    options: &AdaptOptions,
) -> Vec<usize> {
    validity
        .elements
        .iter()
        .enumerate()
        .filter(|(e, v)| {
            (!v.certified_positive || v.min_quality < options.target_quality)
                && map.element_level(*e) < options.max_level
        })
        .map(|(e, _)| e)
        .collect()
}

/// Fits the spline map of a built domain, then refines the T-mesh where the map is of poor
/// quality (elements not certified valid or whose smallest sampled mean ratio is under
/// `options.target_quality`), optimizes the T-mesh again and refits, for at most
/// `options.max_rounds` rounds. The domain keeps its last T-mesh; the map returned is the fit of
/// that T-mesh. `progress(round, max_rounds)` is called before each refinement; returning false
/// cancels (`Error` of kind `Cancelled`), the domain keeping the T-mesh of the round reached.
pub fn adapt<const D: usize, B: CubeMap<D> + Sync>(
    domain: &mut Domain<D, B>,
    options: &AdaptOptions,
    progress: &mut dyn FnMut(usize, usize) -> bool,
) -> Result<(SplineMap<D>, AdaptReport)> {
    let start = Instant::now();
    options.validate()?;
    let mut report = AdaptReport::default();
    let mut round = 0u32;
    loop {
        let fit_options = FitOptions::of(
            &options.validity,
            &UntangleOptions {
                boundary_offset: domain.options().boundary_offset,
                ..Default::default()
            },
        );
        let (map, fit, validity) =
            SplineMap::fit_domain_with(domain, &fit_options, &mut |_, _, _| true)?;
        let reached = validity.certified_positive && validity.min_quality >= options.target_quality;
        let cells = if reached || round == options.max_rounds {
            Vec::new()
        } else {
            marked(&map, &validity, options)
        };
        report.rounds.push(AdaptRound {
            elements: map.element_count(),
            basis: map.basis_count(),
            certified_positive: validity.certified_positive,
            uncertified: validity.uncertified,
            min_quality: validity.min_quality,
            mean_quality: validity.mean_quality,
            refined: cells.len(),
            invalid_cells: 0,
        });
        if cells.is_empty() {
            report.fit = fit;
            report.validity = validity;
            report.reached = reached;
            report.seconds = start.elapsed().as_secs_f64();
            return Ok((map, report));
        }
        if !progress(round as usize, options.max_rounds as usize) {
            return Err(Error::cancelled());
        }
        let refinement = refinement_options(domain.options(), options);
        let refined = domain.refine_cells(&cells, &refinement, &mut |_, _| true)?;
        if let Some(last) = report.rounds.last_mut() {
            last.invalid_cells = refined.invalid_cells;
        }
        round += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validate_refuses_every_field_out_of_range() {
        assert!(AdaptOptions::default().validate().is_ok());
        let with = |f: &dyn Fn(&mut AdaptOptions)| {
            let mut o = AdaptOptions::default();
            f(&mut o);
            o.validate().unwrap_err()
        };
        assert_eq!(
            with(&|o| o.target_quality = f64::NAN).kind,
            ErrorKind::NotFinite
        );
        assert_eq!(
            with(&|o| o.target_quality = 1.0).kind,
            ErrorKind::InvalidArgument
        );
        assert_eq!(
            with(&|o| o.target_quality = -0.1).kind,
            ErrorKind::InvalidArgument
        );
        assert!(with(&|o| o.max_level = 17)
            .message
            .contains("max_level = 17"));
        assert!(with(&|o| o.validity.samples = 65)
            .message
            .contains("samples = 65"));
        assert!(with(&|o| o.validity.max_depth = 13)
            .message
            .contains("max_depth = 13"));
        assert!(with(&|o| o.domain.threads = 4097)
            .message
            .contains("threads = 4097"));
        let edge = AdaptOptions {
            max_level: 16,
            target_quality: 0.0,
            ..AdaptOptions::default()
        };
        assert!(edge.validate().is_ok());
    }

    #[test]
    fn refinements_keep_the_domains_own_boundary_rules() {
        let built = DomainOptions {
            boundary_offset: 0.0,
            repair_rounds: 0,
            threads: 1,
            max_sweeps: 10,
            ..DomainOptions::default()
        };
        let options = AdaptOptions {
            domain: DomainOptions {
                threads: 2,
                max_sweeps: 50,
                ..DomainOptions::default()
            },
            ..AdaptOptions::default()
        };
        let used = refinement_options(&built, &options);
        assert_eq!(used.boundary_offset, 0.0);
        assert_eq!(used.repair_rounds, 0);
        assert_eq!((used.threads, used.max_sweeps), (2, 50));
    }
}
