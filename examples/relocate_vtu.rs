//! Relocates the free nodes of an ASCII `.vtu` mesh with `fixed_components` / `moved` arrays.
//! `cargo run --release --example relocate_vtu -- IN.vtu [threads] [master|initial]
//! [stationarity tolerance]`

use igaparam::{io::vtu, Mesh, RelocateOptions, TargetKind};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let grid = vtu::read(std::path::Path::new(&args[1]))?;
    let mut mesh = Mesh::from_grid_with_motion(&grid)?;
    let mut options = RelocateOptions::default();
    if let Some(t) = args.get(2) {
        options.threads = t.parse()?;
    }
    if args.get(3).map(|s| s == "master").unwrap_or(false) {
        options.target = TargetKind::Master;
    }
    if let Some(t) = args.get(4) {
        options.stationarity_tolerance = t.parse()?;
    }
    if let Some(t) = args.get(5) {
        options.move_tolerance = t.parse()?;
    }
    let start = std::time::Instant::now();
    let report = mesh.relocate(&options, &mut |stage, done, total| {
        eprintln!("{:8.3} s {stage:?} {done}/{total}", start.elapsed().as_secs_f64());
        true
    })?;
    println!("{report:#?}");
    Ok(())
}
