//! The planar G+Smo comparison domains, G+Smo's spline maps and ours evaluated by the same code.
//!
//! `cargo bench --bench peers` reads G+Smo's maps of the four boundaries
//! (`tests/data/peers/gismo`: its barrier method, and its PDE method on the duck, with their
//! times as recorded in that folder's README — G+Smo does not run here), fits ours by the default
//! checked fit of the default T-mesh, and prints for both the smallest mean ratio
//! `2 det J/‖J‖²_F` and scaled Jacobian `det J/(|J e₁||J e₂|)` sampled on 200 × 200 and
//! 801 × 801 grids of the parameter square, with our certified lower bound and our fit's time
//! (the median of five).

use std::path::Path;
use std::time::Instant;

use igaparam::boundary::{read_gismo_surfaces, BoundaryLoop2};
use igaparam::domain::{PlanarDomain, PlanarOptions};
use igaparam::spline::{QualityBoundOptions, SplineMap, UntangleOptions, ValidityOptions};

/// Smallest mean ratio and scaled Jacobian of `jacobian` (columns ∂/∂u, ∂/∂v) on an `n × n`
/// grid of the unit square (0 where `det J ≤ 0`).
fn grid_minima(n: usize, jacobian: &dyn Fn(f64, f64) -> [[f64; 2]; 2]) -> (f64, f64) {
    let (mut q, mut scaled) = (f64::INFINITY, f64::INFINITY);
    for j in 0..n {
        for i in 0..n {
            let t = |k: usize| k as f64 / (n - 1) as f64;
            let m = jacobian(t(i), t(j));
            let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
            let (cu, cv) = (m[0][0].hypot(m[1][0]), m[0][1].hypot(m[1][1]));
            let norm = cu * cu + cv * cv;
            let positive = det > 0.0;
            q = q.min(if positive { 2.0 * det / norm } else { 0.0 });
            scaled = scaled.min(if positive { det / (cu * cv) } else { 0.0 });
        }
    }
    (q, scaled)
}

/// G+Smo's seconds for `file` from the table of the peers' README.
fn recorded_seconds(readme: &str, file: &str) -> String {
    readme
        .lines()
        .find(|l| l.starts_with(&format!("| {file} |")))
        .and_then(|l| l.split('|').nth(3))
        .map_or("?".into(), |s| s.trim().to_string())
}

fn gismo_row(peers: &Path, readme: &str, file: &str) {
    let patches = read_gismo_surfaces(peers.join(file)).expect("G+Smo map");
    let patch = &patches[0];
    let ((u0, u1), (v0, v1)) = patch.domain();
    let jacobian = |s: f64, t: f64| {
        let (_, du, dv) = patch.eval_derivs(u0 + s * (u1 - u0), v0 + t * (v1 - v0));
        [[du[0], dv[0]], [du[1], dv[1]]]
    };
    let (q200, s200) = grid_minima(200, &jacobian);
    let (q801, _) = grid_minima(801, &jacobian);
    println!(
        "| G+Smo {file} | {q200:.3} / {s200:.3} | {q801:.3} | — | {} (recorded) |",
        recorded_seconds(readme, file)
    );
}

fn ours_row(boundary: &Path) {
    let b = BoundaryLoop2::from_gismo_file(boundary).expect("boundary");
    let (domain, _) =
        PlanarDomain::build(b, &PlanarOptions::default(), &mut |_, _| true).expect("domain");
    // Tens of milliseconds on a shared machine: the median of five fits (the same map each
    // time; the first one also pays for waking the threads and first touches of memory).
    let mut times = Vec::new();
    let mut fitted = None;
    for _ in 0..5 {
        let start = Instant::now();
        fitted = Some(
            SplineMap::fit_tmesh_checked(
                domain.mesh(),
                domain.positions(),
                &ValidityOptions::default(),
                &UntangleOptions::default(),
            )
            .expect("fit"),
        );
        times.push(start.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    let seconds = times[times.len() / 2];
    let (map, _, validity) = fitted.expect("five fits");
    let bound = map
        .quality_bound(&QualityBoundOptions::default())
        .expect("bound");
    let jacobian = |s: f64, t: f64| {
        let x = [s.min(1.0 - 1e-12), t.min(1.0 - 1e-12)];
        map.eval_with_jacobian(x).expect("inside").1
    };
    let (q200, s200) = grid_minima(200, &jacobian);
    let (q801, _) = grid_minima(801, &jacobian);
    println!(
        "| igaparam (certified: {}) | {q200:.3} / {s200:.3} | {q801:.3} | {:.3} | {seconds:.3} |",
        validity.certified_positive, bound.lower_bound
    );
}

fn main() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let peers = data.join("peers/gismo");
    let readme = std::fs::read_to_string(peers.join("README.md")).unwrap_or_default();
    println!("| map | min q / min scaled J (200²) | min q (801²) | certified min q | seconds |");
    println!("|---|---|---|---|---|");
    for (boundary, theirs) in [
        ("puzzle3_bdry.xml", &["puzzle3_barrier.xml"][..]),
        (
            "rotor_bdry.xml",
            &["rotor_barrier.xml", "rotor_barrier_refined.xml"],
        ),
        ("male_bdry.xml", &["male_barrier.xml"]),
        ("duck2d_BRep.xml", &["duck_barrier.xml", "duck_pde.xml"]),
    ] {
        println!("| **{boundary}** | | | | |");
        for file in theirs {
            gismo_row(&peers, &readme, file);
        }
        ours_row(&data.join("boundary").join(boundary));
    }
}
