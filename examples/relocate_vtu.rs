//! Relocates the free nodes of a `.vtu` mesh (any storage: ASCII, binary, appended, compressed)
//! whose point arrays `fixed_components` / `moved` prescribe the boundary's motion, and writes the
//! result (zlib-compressed binary `.vtu`, point data `displacement`, cell data `quality`).
//!
//! `cargo run --release --example relocate_vtu -- IN.vtu OUT.vtu [threads] [master]`
//!
//! Prints the report as one JSON object.

use igaparam::{io::vtu::Format, Mesh, RelocateOptions, TargetKind};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 3 {
        return Err("usage: relocate_vtu IN.vtu OUT.vtu [threads] [master]".into());
    }
    let mut mesh = Mesh::read_vtu(std::path::Path::new(&args[1]))?;
    let mut options = RelocateOptions::default();
    if let Some(t) = args.get(3) {
        options.threads = t.parse()?;
    }
    if args.get(4).is_some_and(|s| s == "master") {
        options.target = TargetKind::Master;
    }
    let r = mesh.relocate(&options, &mut |_, _, _| true)?;
    mesh.write_vtu(std::path::Path::new(&args[2]), Format::default())?;
    println!(
        "{{\"cells\": {}, \"nodes\": {}, \"invalid_before\": {}, \"invalid_after\": {}, \"min_quality\": {:?}, \"mean_quality\": {:?}, \"sweeps\": {}}}",
        r.cells, r.nodes, r.invalid_before, r.invalid_after, r.min_quality, r.mean_quality, r.sweeps
    );
    Ok(())
}
