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
