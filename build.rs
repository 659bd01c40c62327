//! Gives the shared library a SONAME carrying the major version (`libigaparam.so.0`) on ELF
//! platforms, so that programs linked against it keep working across compatible updates; gives
//! the tests the target triple (`IGAPARAM_BUILD_TARGET`: `tests/it/c_api.rs` asks the `cc` crate for
//! that target's C compiler); and gives the library the fingerprint of the declarations of
//! `include/igaparam.h` (`IGAPARAM_ABI_FINGERPRINT`, returned by `igaparam_abi_fingerprint`),
//! which the generated Python declarations carry too (`bindings/python/gen_ffi.py` computes it
//! the same way), so that a binding never calls a library built from other declarations.

fn main() {
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let major = std::env::var("CARGO_PKG_VERSION_MAJOR").unwrap_or_else(|_| "0".into());
    if matches!(
        os.as_str(),
        "linux" | "freebsd" | "netbsd" | "openbsd" | "dragonfly"
    ) {
        println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,libigaparam.so.{major}");
    }
    let target = std::env::var("TARGET").unwrap_or_default();
    println!("cargo:rustc-env=IGAPARAM_BUILD_TARGET={target}");
    let header = std::fs::read_to_string("include/igaparam.h").unwrap_or_default();
    println!(
        "cargo:rustc-env=IGAPARAM_ABI_FINGERPRINT={}",
        fingerprint(&header)
    );
    println!("cargo:rerun-if-changed=include/igaparam.h");
    println!("cargo:rerun-if-changed=build.rs");
}

/// FNV-1a (64 bits) of `header` with its comments removed (block comments first, then line
/// comments) and each run of white space made one space; 0 for a missing header.
fn fingerprint(header: &str) -> u64 {
    if header.is_empty() {
        return 0;
    }
    let mut text = String::with_capacity(header.len());
    let mut rest = header;
    while let Some(start) = rest.find("/*") {
        let Some(length) = rest[start + 2..].find("*/") else {
            break;
        };
        text.push_str(&rest[..start]);
        text.push(' ');
        rest = &rest[start + 2 + length + 2..];
    }
    text.push_str(rest);
    let code: Vec<&str> = text
        .lines()
        .map(|line| line.find("//").map_or(line, |at| &line[..at]))
        .collect();
    let words: Vec<&str> = code
        .iter()
        .flat_map(|line| line.split_whitespace())
        .collect();
    words
        .join(" ")
        .bytes()
        .fold(0xcbf2_9ce4_8422_2325, |hash, byte| {
            (hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3)
        })
}
