//! Gives the shared library a SONAME carrying the major version (`libigaparam.so.0`) on ELF
//! platforms, so that programs linked against it keep working across compatible updates; gives
//! the tests the target triple (`IGAPARAM_BUILD_TARGET`: `tests/c_api.rs` asks the `cc` crate for
//! that target's C compiler).

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
    println!("cargo:rerun-if-changed=build.rs");
}
