//! Builds the optimized T-mesh of a solid and writes it as `.vtu`:
//! `solid INPUT OUT.vtu [tolerance] [max_level] [boundary_offset]` (INPUT a G+Smo XML B-rep of six surfaces or a
//! folder of six OBJ faces).

use igaparam::boundary::SolidBoundary;
use igaparam::domain::{SolidDomain, SolidOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = std::path::Path::new(&args[1]);
    let boundary = if path.is_dir() {
        SolidBoundary::from_obj_dir(path)?
    } else {
        SolidBoundary::from_gismo_file(path)?
    };
    let mut options = SolidOptions::default();
    if let Some(t) = args.get(3) {
        options.tolerance = t.parse()?;
    }
    if let Some(l) = args.get(4) {
        options.max_level = l.parse()?;
    }
    if let Some(o) = args.get(5) {
        options.boundary_offset = o.parse()?;
    }
    let (domain, report) = SolidDomain::build(boundary, &options, &mut |done, _| {
        if done % 50 == 0 {
            eprintln!("sweep {done}");
        }
        true
    })?;
    eprintln!();
    igaparam::io::vtu::write(std::path::Path::new(&args[2]), &domain.to_grid())?;
    println!("{report:?}");
    Ok(())
}
