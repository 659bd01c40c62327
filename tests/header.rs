//! The checked-in C header must match what cbindgen generates from the sources.

use std::path::Path;

#[test]
fn header_is_current() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(root.join("cbindgen.toml")).expect("cbindgen.toml");
    let mut generated = Vec::new();
    cbindgen::Builder::new()
        .with_crate(root)
        .with_config(config)
        .generate()
        .expect("cbindgen failed")
        .write(&mut generated);
    let generated = String::from_utf8(generated).unwrap();
    let path = root.join("include/igaparam.h");
    if std::env::var_os("IGAPARAM_BLESS").is_some() {
        std::fs::write(&path, &generated).unwrap();
        return;
    }
    let current = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        current == generated,
        "include/igaparam.h is stale: regenerate it with `IGAPARAM_BLESS=1 cargo test --test header`"
    );
}

#[test]
fn version_macros_match_the_crate() {
    let header =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("include/igaparam.h"))
            .unwrap();
    for (name, value) in [
        ("IGAPARAM_VERSION_MAJOR", env!("CARGO_PKG_VERSION_MAJOR")),
        ("IGAPARAM_VERSION_MINOR", env!("CARGO_PKG_VERSION_MINOR")),
        ("IGAPARAM_VERSION_PATCH", env!("CARGO_PKG_VERSION_PATCH")),
    ] {
        assert!(
            header.contains(&format!("#define {name} {value}")),
            "{name} in the header is not {value} (Cargo.toml)"
        );
    }
}

/// Every name the header declares carries the library's prefix, so that it cannot collide with
/// a host's own macros and identifiers (an unprefixed `#define` breaks any header included after
/// it that uses the same word).
#[test]
fn every_declared_name_is_prefixed() {
    let header =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("include/igaparam.h"))
            .unwrap();
    let unprefixed: Vec<&str> = header
        .lines()
        .filter_map(|line| line.strip_prefix("#define "))
        .filter_map(|rest| rest.split_whitespace().next())
        .filter(|name| !name.starts_with("IGAPARAM_"))
        .collect();
    assert!(unprefixed.is_empty(), "unprefixed macros: {unprefixed:?}");
}
