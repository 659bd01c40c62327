//! The same input gives the same output, bit for bit, at 1, 2 and 4 explicit threads: the
//! planar and solid (a curved box) domain builds (positions and report), the checked spline fit (control
//! points, fit and validity reports) and the adaptive loop (map, rounds, final T-mesh). Each run
//! is made on a rayon pool of that many workers with the thread option set to the same count, so
//! the stages that use the caller's pool (the fit, the certification) run on exactly that many
//! workers, and those that build their own pool (the T-mesh optimization) on that many capped
//! to the machine's cores (`igaparam::threads::effective_threads`). Relocation is compared in
//! tests/it/relocate.rs and tests/it/limits.rs. Small inputs: about a second in all.

use crate::common;

use common::{curved_box, planar_boundary, MappedCube};
use igaparam::domain::{Domain, DomainOptions, DomainReport, PlanarDomain, PlanarOptions};
use igaparam::spline::{adapt, AdaptOptions, AdaptReport, FitReport};

const THREADS: [usize; 3] = [1, 2, 4];

/// Runs `job` on a pool of `n` workers.
fn on_pool<T: Send>(n: usize, job: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .unwrap()
        .install(job)
}

/// The report without its wall times (the only members allowed to differ).
fn untimed(mut r: DomainReport) -> DomainReport {
    r.seconds = 0.0;
    r.stages = Default::default();
    r
}

fn untimed_fit(mut r: FitReport) -> FitReport {
    r.seconds = 0.0;
    r.stages = Default::default();
    r
}

fn untimed_adapt(mut r: AdaptReport) -> AdaptReport {
    r.seconds = 0.0;
    r.fit = untimed_fit(r.fit);
    r
}

/// Asserts that every run's value equals the first one's.
fn all_equal<T: PartialEq + std::fmt::Debug>(what: &str, runs: &[T]) {
    for (n, run) in THREADS.iter().zip(runs).skip(1) {
        assert!(
            *run == runs[0],
            "{what}: {n} threads differ from 1 thread:\n{run:?}\n{:?}",
            runs[0]
        );
    }
}

type PlanarRun = (
    Vec<[f64; 2]>,
    DomainReport,
    Vec<[f64; 2]>,
    FitReport,
    igaparam::spline::ValidityReport,
);

/// The male piece's domain built with `n` threads and its checked fit.
fn planar_run(n: usize) -> PlanarRun {
    on_pool(n, || {
        let options = PlanarOptions {
            threads: n,
            ..Default::default()
        };
        let (domain, report) =
            PlanarDomain::build(planar_boundary("male_bdry.xml"), &options, &mut |_, _| true)
                .unwrap();
        let (map, fit, validity) = common::checked_fit(&domain);
        let positions = domain.positions().to_vec();
        (
            positions,
            untimed(report),
            map.control_points().to_vec(),
            untimed_fit(fit),
            validity,
        )
    })
}

#[test]
fn planar_build_and_fit_are_the_same_at_1_2_and_4_threads() {
    let runs: Vec<PlanarRun> = THREADS.iter().map(|&n| planar_run(n)).collect();
    assert!(
        runs[0].1.sweeps > 0 && runs[0].1.invalid_cells == 0,
        "{:?}",
        runs[0].1
    );
    all_equal(
        "T-mesh positions",
        &runs.iter().map(|r| &r.0).collect::<Vec<_>>(),
    );
    all_equal(
        "domain report",
        &runs.iter().map(|r| r.1).collect::<Vec<_>>(),
    );
    all_equal(
        "control points",
        &runs.iter().map(|r| &r.2).collect::<Vec<_>>(),
    );
    all_equal("fit report", &runs.iter().map(|r| r.3).collect::<Vec<_>>());
    all_equal("validity", &runs.iter().map(|r| &r.4).collect::<Vec<_>>());
}

#[test]
fn adaptive_loop_is_the_same_at_1_2_and_4_threads() {
    let run = |n: usize| {
        on_pool(n, || {
            let build = PlanarOptions {
                threads: n,
                ..Default::default()
            };
            let (mut domain, _) =
                PlanarDomain::build(planar_boundary("rotor_bdry.xml"), &build, &mut |_, _| true)
                    .unwrap();
            let mut options = AdaptOptions {
                target_quality: 0.4,
                ..Default::default()
            };
            options.domain.threads = n;
            let (map, report) = adapt(&mut domain, &options, &mut |_, _| true).unwrap();
            (
                map.control_points().to_vec(),
                untimed_adapt(report),
                domain.positions().to_vec(),
            )
        })
    };
    let runs: Vec<_> = THREADS.iter().map(|&n| run(n)).collect();
    assert!(
        runs[0].1.rounds.len() > 1 && runs[0].1.reached,
        "the loop must refine"
    );
    all_equal(
        "adapted control points",
        &runs.iter().map(|r| &r.0).collect::<Vec<_>>(),
    );
    all_equal(
        "adapt report",
        &runs.iter().map(|r| &r.1).collect::<Vec<_>>(),
    );
    all_equal(
        "adapted T-mesh",
        &runs.iter().map(|r| &r.2).collect::<Vec<_>>(),
    );
}

#[test]
fn solid_build_is_the_same_at_1_2_and_4_threads() {
    let run = |n: usize| {
        on_pool(n, || {
            let options = DomainOptions {
                tolerance: 1e-2,
                max_level: 3,
                threads: n,
                ..DomainOptions::solid()
            };
            let (domain, report) =
                Domain::<3, _>::build(MappedCube(curved_box), &options, &mut |_, _| true).unwrap();
            (domain.positions().to_vec(), untimed(report))
        })
    };
    let runs: Vec<_> = THREADS.iter().map(|&n| run(n)).collect();
    assert!(
        runs[0].1.sweeps > 0 && runs[0].1.max_level > 1,
        "{:?}",
        runs[0].1
    );
    all_equal(
        "solid positions",
        &runs.iter().map(|r| &r.0).collect::<Vec<_>>(),
    );
    all_equal(
        "solid report",
        &runs.iter().map(|r| r.1).collect::<Vec<_>>(),
    );
}
