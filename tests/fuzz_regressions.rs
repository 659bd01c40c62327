//! Replays the inputs kept from fuzzing (`tests/data/fuzz/regressions/TARGET/`: inputs that once
//! crashed, hung or failed a check, fixed since) and the seeds (`tests/data/fuzz/seeds/`, and
//! the bundled data the fuzz runs start from) through the same code the fuzz targets run
//! (`fuzz/src/`, included here), so that `cargo test` catches a regression without a nightly
//! compiler.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

#[path = "../fuzz/src/capi/mod.rs"]
mod capi;
#[path = "../fuzz/src/coastline.rs"]
mod coastline;
#[path = "../fuzz/src/common.rs"]
mod common;
#[path = "../fuzz/src/gismo_thb.rs"]
mod gismo_thb;
#[path = "../fuzz/src/gismo_xml.rs"]
mod gismo_xml;
#[path = "../fuzz/src/obj.rs"]
mod obj;
#[path = "../fuzz/src/vtu.rs"]
mod vtu;

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data");

/// The files of `dir` (none if it does not exist), sorted.
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .flatten()
                .map(|e| e.path())
                .filter(|p| p.is_file())
                .collect()
        })
        .unwrap_or_default();
    out.sort();
    out
}

/// Runs `run` on each file, naming the file that fails.
fn replay(paths: &[PathBuf], run: fn(&[u8])) {
    for path in paths {
        let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        if std::panic::catch_unwind(|| run(&bytes)).is_err() {
            panic!("{} fails (see the panic above)", path.display());
        }
    }
}

/// The kept inputs and seeds of `target`, with `extra` files of the bundled data.
fn kept(target: &str, extra: &[&str]) -> Vec<PathBuf> {
    let mut paths = files(&Path::new(DATA).join("fuzz/regressions").join(target));
    paths.extend(files(&Path::new(DATA).join("fuzz/seeds").join(target)));
    paths.extend(extra.iter().map(|f| Path::new(DATA).join(f)));
    paths
}

#[test]
fn gismo_xml_inputs() {
    let bundled = [
        "boundary/puzzle3_bdry.xml",
        "boundary/rotor_bdry.xml",
        "boundary/male_bdry.xml",
        "boundary/duck2d_BRep.xml",
        "boundary/duck3d_BRep.xml",
    ];
    replay(&kept("gismo_xml", &bundled), gismo_xml::run);
}

#[test]
fn gismo_thb_inputs() {
    replay(&kept("gismo_thb", &[]), gismo_thb::run);
}

#[test]
fn vtu_inputs() {
    replay(&kept("vtu", &["airfoil_0012_q9.vtu"]), vtu::run);
}

#[test]
fn coastline_inputs() {
    let bundled = ["boundary/gran_canaria.txt", "boundary/tenerife.txt"];
    replay(&kept("coastline", &bundled), coastline::run);
}

#[test]
fn obj_inputs() {
    replay(&kept("obj", &["boundary/duck_faces/xmin.obj"]), obj::run);
}

#[test]
fn capi_inputs() {
    replay(&kept("capi", &[]), capi::run);
}
