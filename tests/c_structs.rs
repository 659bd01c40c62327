//! The checked-in C mirrors of the core option and report structs (`src/capi/options_gen.rs`,
//! `src/capi/reports_gen.rs`) must be what `tools/c_structs/generate.rs` generates from the core
//! structs. `IGAPARAM_BLESS=1 cargo test --release --test c_structs` rewrites them; when a changed
//! core struct has made them fail to compile, `cargo run --release --manifest-path
//! tools/c_structs/Cargo.toml` does (it does not build the crate). Then bless the header:
//! `IGAPARAM_BLESS=1 cargo test --release --test header`, which regenerates the Python
//! declarations too.

use std::path::Path;

#[path = "../tools/c_structs/generate.rs"]
mod generate;

#[test]
fn c_structs_are_current() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let bless = std::env::var_os("IGAPARAM_BLESS").is_some();
    for (file, generated) in generate::generate(root) {
        let path = root.join(file);
        if bless {
            std::fs::write(&path, &generated).unwrap();
            continue;
        }
        let current = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            current == generated,
            "{file} is stale (a core option or report struct changed): regenerate it with \
             `IGAPARAM_BLESS=1 cargo test --release --test c_structs` (or, when it no longer \
             compiles, `cargo run --release --manifest-path tools/c_structs/Cargo.toml`), then \
             bless the header with `IGAPARAM_BLESS=1 cargo test --release --test header`.\n{}",
            generate::diff(&current, &generated)
        );
    }
}
