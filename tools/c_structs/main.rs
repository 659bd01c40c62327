//! Writes `src/capi/options_gen.rs`, the C mirrors of the core option structs, from the core
//! structs (see `generate.rs`); `--check` only compares and exits with status 1 when the file is
//! stale. Run from anywhere: `cargo run --release --manifest-path tools/c_structs/Cargo.toml`.

use std::path::Path;

mod generate;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let generated = generate::generate(&root);
    let path = generate::target(&root);
    if std::env::args().any(|a| a == "--check") {
        let current = std::fs::read_to_string(&path).unwrap_or_default();
        if current != generated {
            eprintln!(
                "{} is stale:\n{}",
                path.display(),
                generate::diff(&current, &generated)
            );
            std::process::exit(1);
        }
        return;
    }
    std::fs::write(&path, generated).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    println!("wrote {}", path.display());
}
