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

/// Fields added to core structs reach their C structs with their docs and both conversions, so
/// the generated files differ from the checked-in ones: `c_structs_are_current` (and, once that
/// is blessed, the header test) fails until they are blessed. Run on a copy of the generator's
/// inputs, with a field added to the options of a quality bound and of a fit, to the untangling
/// options a fit's C options flatten, and to a fit's report.
#[test]
fn a_new_core_field_reaches_the_c_struct() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let copy = std::env::temp_dir().join(format!("igaparam-c-structs-{}", std::process::id()));
    for file in generate::inputs() {
        let to = copy.join(file);
        std::fs::create_dir_all(to.parent().unwrap()).unwrap();
        std::fs::copy(root.join(file), &to).unwrap();
    }
    let options_field = "    /// A new option (default 7).\n    pub extra: u32,\n";
    let fit_field = "    /// A new fit option (default 0).\n    pub fit_extra: u32,\n";
    let untangle_field = "    /// A new untangling option.\n    pub untangle_extra: u32,\n";
    let report_field = "    /// A new figure of a fit.\n    pub report_extra: usize,\n";
    // (file of src/spline, the last field of the struct, the field added after it)
    let edits = [
        ("quality_bound", "gap: f64", options_field),
        ("fit_options", "threads: usize", fit_field),
        ("untangle", "smoothing_power: f64", untangle_field),
        ("fit", "boundary_distance: f64", report_field),
    ];
    for (file, last, field) in edits {
        let source = copy.join(format!("src/spline/{file}.rs"));
        let text = std::fs::read_to_string(&source).unwrap();
        let last = format!("    pub {last},\n");
        let changed = text.replacen(&format!("{last}}}"), &format!("{last}{field}}}"), 1);
        assert_ne!(
            text, changed,
            "{file}.rs: the struct no longer ends with `{last}`"
        );
        std::fs::write(&source, changed).unwrap();
    }
    let generated = generate::generate(&copy);
    std::fs::remove_dir_all(&copy).unwrap();
    let [(options_file, options), (reports_file, reports)] = &generated;
    assert_eq!(*options_file, generate::OPTIONS_FILE);
    assert_eq!(*reports_file, generate::REPORTS_FILE);
    assert!(
        options.contains(options_field)
            && options.contains(fit_field)
            && reports.contains(report_field),
        "a field or its doc is not in its C struct"
    );
    assert!(options.contains("extra: o.extra,") && options.contains("extra: self.extra,"));
    assert!(options.contains("fit_extra: o.fit_extra,"));
    assert!(options.contains("fit_extra: self.fit_extra,"));
    // The flattened untangling options: the field takes the C struct's level, its doc included.
    assert!(options.contains(untangle_field));
    assert!(options.contains("untangle_extra: o.untangle.untangle_extra,"));
    assert!(options.contains("untangle_extra: self.untangle_extra,"));
    assert!(reports.contains("report_extra: o.report_extra,"));
    for (file, text) in &generated {
        assert_ne!(text, &std::fs::read_to_string(root.join(file)).unwrap());
    }
}
