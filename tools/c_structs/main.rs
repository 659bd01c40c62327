//! Writes `src/capi/options_gen.rs` and `src/capi/reports_gen.rs`, the C mirrors of the core
//! option and report structs, from the core structs (see `generate.rs`); `--check` only compares
//! and exits with status 1 when a file is stale. Run from anywhere:
//! `cargo run --release --manifest-path tools/c_structs/Cargo.toml`.

use std::path::Path;

mod generate;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let check = std::env::args().any(|a| a == "--check");
    let mut stale = false;
    for (file, generated) in generate::generate(&root) {
        let path = root.join(file);
        let current = std::fs::read_to_string(&path).unwrap_or_default();
        if current == generated {
            continue;
        }
        if check {
            eprintln!("{file} is stale:\n{}", generate::diff(&current, &generated));
            stale = true;
        } else {
            std::fs::write(&path, generated).unwrap_or_else(|e| panic!("{file}: {e}"));
            println!("wrote {file}");
        }
    }
    if stale {
        std::process::exit(1);
    }
}
