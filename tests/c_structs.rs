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

/// A field added to a core struct reaches its C struct with its doc and both conversions, so the
/// generated file differs from the checked-in one: `c_structs_are_current` (and, once that is
/// blessed, the header test) fails until it is blessed. Run on a copy of the generator's inputs.
#[test]
fn a_new_core_field_reaches_the_c_struct() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let copy = std::env::temp_dir().join(format!("igaparam-c-structs-{}", std::process::id()));
    for file in generate::inputs() {
        let to = copy.join(file);
        std::fs::create_dir_all(to.parent().unwrap()).unwrap();
        std::fs::copy(root.join(file), &to).unwrap();
    }
    let source = copy.join("src/spline/quality_bound.rs");
    let text = std::fs::read_to_string(&source).unwrap();
    let field = "    /// A new option (default 7).\n    pub extra: u32,\n}";
    let changed = text.replacen(
        "    pub gap: f64,\n}",
        &format!("    pub gap: f64,\n{field}"),
        1,
    );
    assert_ne!(
        text, changed,
        "QualityBoundOptions no longer ends with `gap`"
    );
    std::fs::write(&source, changed).unwrap();
    let generated = generate::generate(&copy);
    std::fs::remove_dir_all(&copy).unwrap();
    let (file, options) = &generated[0];
    assert_eq!(*file, generate::OPTIONS_FILE);
    assert!(
        options.contains(field),
        "the field and its doc are not in the C struct"
    );
    assert!(options.contains("extra: o.extra,") && options.contains("extra: self.extra,"));
    assert_ne!(options, &std::fs::read_to_string(root.join(file)).unwrap());
}
