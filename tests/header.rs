//! The checked-in C header must match what cbindgen generates from the sources, and the
//! checked-in Python declarations (`bindings/python/igaparam/_ffi.py`) what
//! `bindings/python/gen_ffi.py` generates from the header. `IGAPARAM_BLESS=1` regenerates both,
//! the header first.

use std::path::Path;
use std::process::Command;

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
    let bless = std::env::var_os("IGAPARAM_BLESS").is_some();
    if bless {
        std::fs::write(&path, &generated).unwrap();
    } else {
        let current = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            current == generated,
            "include/igaparam.h is stale: regenerate it with `IGAPARAM_BLESS=1 cargo test --test header`"
        );
    }
    python_declarations(root, bless);
}

/// Runs the Python generator on the (blessed or checked) header: writes the declarations when
/// blessing, otherwise fails when they are stale.
fn python_declarations(root: &Path, bless: bool) {
    let python = std::env::var("PYTHON").unwrap_or_else(|_| "python3".into());
    let mut command = Command::new(&python);
    command.arg(root.join("bindings/python/gen_ffi.py"));
    if !bless {
        command.arg("--check");
    }
    let output = command
        .output()
        .unwrap_or_else(|e| panic!("cannot run `{python}` (set PYTHON to a Python 3.9+): {e}"));
    assert!(
        output.status.success(),
        "bindings/python/gen_ffi.py: {}",
        String::from_utf8_lossy(&output.stderr)
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
