//! Builds the optimized T-mesh of a planar domain and writes it as `.vtu`:
//! `planar FILE OUT.vtu [tolerance] [min_level] [sweeps]` (FILE a G+Smo XML B-rep or a coastline
//! `.txt`).

use igaparam::boundary::{BoundaryLoop2, Coastline};
use igaparam::domain::{PlanarDomain, PlanarOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = &args[1];
    let boundary = if path.ends_with(".txt") {
        BoundaryLoop2::from_coastline(&Coastline::read(path)?)?
    } else {
        BoundaryLoop2::from_gismo_file(path)?
    };
    let mut options = PlanarOptions::default();
    if let Some(t) = args.get(3) {
        options.tolerance = t.parse()?;
    }
    if let Some(l) = args.get(4) {
        options.min_level = l.parse()?;
    }
    if let Some(s) = args.get(5) {
        options.max_sweeps = s.parse()?;
    }
    let (domain, report) = PlanarDomain::build(boundary, &options, &mut |_, _| true)?;
    igaparam::io::vtu::write(std::path::Path::new(&args[2]), &domain.to_grid())?;
    println!("{report:?}");
    Ok(())
}
