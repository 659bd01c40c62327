//! Benchmark of the fixed costs on a small mesh: a tangled 10 × 20 Q4 grid (200 cells) untangled
//! in place.
//!
//! `cargo bench --bench small` builds the unit grid, moves every interior node by a fixed
//! pseudo-random offset of up to 0.9 cell sizes (which folds about half the cells), fixes the
//! boundary and relocates with `Placement::Current` (the tangled positions are the start), 1 and
//! 2 threads, 50 repetitions each (median and minimum), by the default method (`Auto`: 3 sweeps
//! untangle, Newton's method converges) and by the sweeps alone (`Sweeps`, the method before).
//! It also times the pieces every call pays: making the thread pool, the first call on a new
//! mesh (problem, colouring, solver setup) and a repeated call on the same mesh.

use std::time::Instant;

use igaparam::{CellType, Mesh, Method, Placement, RelocateOptions};

const NX: usize = 10;
const NY: usize = 20;

/// The regular grid and the tangled positions of its nodes.
fn grid() -> (Vec<f64>, Vec<i64>, Vec<f64>, Vec<u8>) {
    let mut xyz = Vec::new();
    let mut tangled = Vec::new();
    let mut fixed = Vec::new();
    let mut seed = 12345u64;
    let mut random = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    for j in 0..=NY {
        for i in 0..=NX {
            let boundary = i == 0 || j == 0 || i == NX || j == NY;
            let (x, y) = (i as f64, j as f64);
            xyz.extend_from_slice(&[x, y, 0.0]);
            let (dx, dy) = match boundary {
                true => (0.0, 0.0),
                false => (1.8 * random(), 1.8 * random()),
            };
            tangled.extend_from_slice(&[x + dx, y + dy, 0.0]);
            fixed.push(if boundary { 3 } else { 0 });
        }
    }
    let node = |i: usize, j: usize| (j * (NX + 1) + i) as i64;
    let mut cells = Vec::new();
    for j in 0..NY {
        for i in 0..NX {
            cells.extend_from_slice(&[
                node(i, j),
                node(i + 1, j),
                node(i + 1, j + 1),
                node(i, j + 1),
            ]);
        }
    }
    (xyz, cells, tangled, fixed)
}

fn median_min(mut values: Vec<f64>) -> (f64, f64) {
    values.sort_by(f64::total_cmp);
    (values[values.len() / 2], values[0])
}

fn main() {
    let (xyz, cells, tangled, fixed) = grid();
    let fresh = || {
        let mut mesh = Mesh::new(CellType::Quad4, &xyz, &cells).expect("grid");
        mesh.set_fixed(&fixed).expect("mask");
        mesh.move_nodes(None, &tangled).expect("tangle");
        mesh
    };
    println!("| method | threads | invalid before | after | min q | sweeps | newton | first call ms (median / min) | repeated call ms | pool ms |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (method, threads) in [
        (Method::Auto, 1),
        (Method::Sweeps, 1),
        (Method::Auto, 2),
        (Method::Sweeps, 2),
    ] {
        let options = RelocateOptions {
            threads,
            placement: Placement::Current,
            method,
            ..Default::default()
        };
        let (mut first, mut again, mut pool) = (Vec::new(), Vec::new(), Vec::new());
        let mut last = None;
        for _ in 0..50 {
            let mut mesh = fresh();
            let start = Instant::now();
            let report = mesh
                .relocate(&options, &mut |_, _, _| true)
                .expect("relocation");
            first.push(start.elapsed().as_secs_f64());
            mesh.move_nodes(None, &tangled).expect("tangle");
            let start = Instant::now();
            mesh.relocate(&options, &mut |_, _, _| true)
                .expect("relocation");
            again.push(start.elapsed().as_secs_f64());
            let start = Instant::now();
            drop(igaparam::threads::pool(threads).expect("pool"));
            pool.push(start.elapsed().as_secs_f64());
            last = Some(report);
        }
        let r = last.expect("runs");
        let ((f, fmin), (a, _), (p, _)) = (median_min(first), median_min(again), median_min(pool));
        println!(
            "| {method:?} | {threads} | {} | {} | {:.3} | {} | {} | {:.2} / {:.2} | {:.2} | {:.2} |",
            r.invalid_before,
            r.invalid_after,
            r.min_quality,
            r.sweeps,
            r.newton_iterations,
            1e3 * f,
            1e3 * fmin,
            1e3 * a,
            1e3 * p
        );
    }
}
