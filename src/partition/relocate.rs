//! Relocation of a partitioned mesh on all its ranks together: the harmonic placement and the
//! coloured sweeps of the whole mesh, each rank updating the nodes it owns.

use std::time::Instant;

use super::exchange::Ranks;
use super::team::PartTeam;
use super::Partition;
use crate::error::{Error, Result};
use crate::fe_mesh::{cell_node_box, extent, lift, problem_of, project, sweep_motion, unit_of};
use crate::fe_mesh::{Method, Placement, RelocateOptions, RelocateReport, Stage};
use crate::optimize::motion::Ends;
use crate::optimize::small_matrix::Vector;
use crate::optimize::sweep::invalid_count_on;
use crate::optimize::team::Team;
use crate::optimize::{laplace::MeshGraph, Problem, QualitySummary};

/// What [`Partition::relocate`] did: the figures of the whole mesh (the same on every rank)
/// and this rank's time in the host's exchange.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PartitionReport {
    /// The relocation's figures over the whole mesh, the same on every rank (`gradient_norm`
    /// is not computed on a partition: infinity; `seconds` is this rank's wall-clock time).
    pub relocation: RelocateReport,
    /// Seconds this rank spent in the host's exchange (the exchange callback in C), waiting
    /// for the other ranks included.
    pub exchange_seconds: f64,
    /// Calls of the host's exchange (the exchange callback in C) on this rank.
    pub exchanges: usize,
}

/// Refuses the options a partition cannot honour.
fn check_options(options: &RelocateOptions) -> Result<rayon::ThreadPool> {
    options.validate()?;
    if options.method == Method::Newton {
        return Err(Error::invalid(
            "IGAPARAM_METHOD_NEWTON needs a factorisation of the whole Hessian, which a partition does not make; use IGAPARAM_METHOD_SWEEPS (IGAPARAM_METHOD_AUTO means SWEEPS on a partition)",
        ));
    }
    if options.stationarity_tolerance > 0.0 {
        return Err(Error::invalid(
            "stationarity_tolerance > 0 needs the Newton stage on the whole Hessian, which a partition does not make; use 0",
        ));
    }
    // Capped to the cores, as every other stage: 4096 threads on 2 cores would only slow it down.
    crate::threads::pool(options.threads)
}

impl Partition {
    /// Relocates the free components of the nodes of the whole partitioned mesh, as
    /// `Mesh::relocate` with `Method::Sweeps` does on the whole mesh (the same positions, bit for
    /// bit, whatever the number of ranks). Collective. `Method::Auto` means the sweeps here;
    /// `Method::Newton` and a positive stationarity tolerance are refused on every rank. The
    /// progress callback is called on every rank; a cancellation on one cancels all. On error
    /// or cancellation the part is unchanged. `options` is an error when the host's options
    /// were bad on this rank: that too is agreed.
    pub fn relocate(
        &mut self,
        ranks: &mut Ranks<'_>,
        options: Result<RelocateOptions>,
        progress: &mut dyn FnMut(Stage, usize, usize) -> bool,
    ) -> Result<PartitionReport> {
        let start = Instant::now();
        let (seconds, calls) = (ranks.seconds, ranks.calls);
        let checked = options.and_then(|o| check_options(&o).map(|pool| (o, pool)));
        ranks.agree(checked.as_ref().map(|_| ()).map_err(Clone::clone))?;
        let (options, pool) = checked?;
        let options = &options;
        let mut relocation = match self.cell_type.dimension() {
            2 => self.relocate_d::<2>(ranks, &pool, options, progress)?,
            _ => self.relocate_d::<3>(ranks, &pool, options, progress)?,
        };
        relocation.seconds = start.elapsed().as_secs_f64();
        Ok(PartitionReport {
            relocation,
            exchange_seconds: ranks.seconds - seconds,
            exchanges: ranks.calls - calls,
        })
    }

    /// The owners' positions and masks at every local node.
    fn owners_state(&self, ranks: &mut Ranks<'_>) -> Result<(Vec<[f64; 3]>, Vec<u8>)> {
        let mut values: Vec<f64> = self.positions.concat();
        self.plan.refresh(ranks, &mut values, 3)?;
        let mut fixed: Vec<f64> = self.fixed.iter().map(|&m| m as f64).collect();
        self.plan.refresh(ranks, &mut fixed, 1)?;
        let positions = values.chunks(3).map(|p| [p[0], p[1], p[2]]).collect();
        Ok((positions, fixed.iter().map(|&m| m as u8).collect()))
    }

    fn relocate_d<const D: usize>(
        &mut self,
        ranks: &mut Ranks<'_>,
        pool: &rayon::ThreadPool,
        options: &RelocateOptions,
        progress: &mut dyn FnMut(Stage, usize, usize) -> bool,
    ) -> Result<RelocateReport> {
        let (positions, fixed) = self.owners_state(ranks)?;
        let unit = self.unit(ranks)?;
        let problem = problem_of::<D>(
            self.cell_type,
            &self.connectivity,
            &fixed,
            &self.reference,
            options.target,
            unit,
        );
        ranks.agree(problem.as_ref().map(|_| ()).map_err(Clone::clone))?;
        let problem = problem?;
        let per = self.cell_type.node_count();
        let counted = self
            .connectivity
            .chunks(per)
            .map(|nodes| self.owned[nodes[0] as usize])
            .collect();
        let mut team = PartTeam {
            ranks,
            plan: &self.plan,
            owned: &self.owned,
            counted,
        };
        let goal = project::<D>(&positions, unit);
        let owned = |v: &usize| self.owned[*v];
        let mut report = RelocateReport {
            cells: team.count((0..self.cell_count()).filter(|&c| team.counts(c)).count())?,
            nodes: team.count((0..self.node_count()).filter(owned).count())?,
            free_nodes: team.count(
                (0..self.node_count())
                    .filter(owned)
                    .filter(|&v| problem.free_mask(v) != 0)
                    .count(),
            )?,
            invalid_before: invalid_count_on(&mut team, pool, &problem, &goal)?,
            gradient_norm: f64::INFINITY,
            ..Default::default()
        };
        let x = self.place_and_sweep(
            &mut team,
            pool,
            (&problem, unit),
            &goal,
            options,
            &mut report,
            progress,
        )?;
        let quality = QualitySummary::on(&mut team, pool, &problem, &x)?;
        report.invalid_after = quality.invalid_count;
        report.min_quality = quality.min;
        report.mean_quality = quality.mean;
        let relocated = lift(&positions, &x, unit, &fixed);
        self.positions = relocated.clone();
        self.fixed = fixed;
        self.last = Some(relocated);
        Ok(report)
    }

    /// The factor that brings the whole mesh to unit size, as `Mesh::relocate` takes it: from
    /// the bounding box of the reference positions of every rank's cell nodes.
    fn unit(&self, ranks: &mut Ranks<'_>) -> Result<f64> {
        let d = self.cell_type.dimension();
        let (lo, hi) = cell_node_box(&self.connectivity, &self.reference, d);
        let words: Vec<u64> = lo.iter().chain(&hi).map(|v| v.to_bits()).collect();
        let mut all = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for w in ranks.all_gather_words(&words)? {
            if w.len() != 6 {
                return Err(super::exchange::exchange_failed(
                    "a bounding box was garbled",
                ));
            }
            for k in 0..3 {
                all.0[k] = all.0[k].min(f64::from_bits(w[k]));
                all.1[k] = all.1[k].max(f64::from_bits(w[3 + k]));
            }
        }
        Ok(unit_of(extent(all.0, all.1)))
    }

    /// The first placement and the sweeps, as `Mesh::relocate` makes them.
    #[allow(clippy::too_many_arguments)]
    fn place_and_sweep<const D: usize>(
        &self,
        team: &mut PartTeam<'_, '_>,
        pool: &rayon::ThreadPool,
        (problem, unit): (&Problem<D>, f64),
        goal: &[Vector<D>],
        options: &RelocateOptions,
        report: &mut RelocateReport,
        progress: &mut dyn FnMut(Stage, usize, usize) -> bool,
    ) -> Result<Vec<Vector<D>>> {
        if team.any(!progress(Stage::Placement, 0, 1))? {
            return Err(Error::cancelled());
        }
        let from = match (options.placement, &self.last) {
            (Placement::Incremental, Some(last)) => project::<D>(last, unit),
            _ => project::<D>(&self.reference, unit),
        };
        let mut x = goal.to_vec();
        let graph = MeshGraph::new(problem);
        if options.placement != Placement::Current {
            graph.harmonic_placement_on(team, pool, problem, &from, &mut x)?;
        }
        report.invalid_after_placement = invalid_count_on(team, pool, problem, &x)?;
        if team.any(!progress(Stage::Placement, 1, 1))? {
            return Err(Error::cancelled());
        }
        if !options.optimize {
            return Ok(x);
        }
        let ends = Ends { start: &from, goal };
        sweep_motion(
            team, pool, problem, &graph, ends, &mut x, options, report, progress,
        )?;
        Ok(x)
    }
}
