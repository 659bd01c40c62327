//! The C API tests (`tests/c/*.c`, and the C++ wrapper's test) compiled with the system's C and
//! C++ compilers (found by the `cc` crate) against `include/igaparam.h` and the shared library
//! cargo built for this test, then run: `cargo test` alone exercises the ABI, as ctest does.
//!
//! Each program is built and run in a directory of its own (named after the process and the
//! program), holding a copy of the library under its SONAME, so that tests running in parallel,
//! or a concurrent build of the library, do not disturb each other. (ELF platforms: the library
//! is `libigaparam.so` with its SONAME.)
#![cfg(target_os = "linux")]

use std::path::{Path, PathBuf};
use std::process::Command;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// The shared library cargo built along with this test: `target/<profile>/deps/libigaparam.so`,
/// next to the test executable (the copy in `target/<profile>` is refreshed only by
/// `cargo build`).
fn library() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable");
    exe.parent().expect("deps directory").join("libigaparam.so")
}

/// A fresh directory for `name`, with the shared library copied in under its SONAME.
fn work_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("igaparam-c-api-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("work directory");
    let library = library();
    let major = env!("CARGO_PKG_VERSION_MAJOR");
    std::fs::copy(&library, dir.join(format!("libigaparam.so.{major}")))
        .unwrap_or_else(|e| panic!("cannot copy {}: {e}", library.display()));
    dir
}

/// The C or C++ compiler of this target, as the `cc` crate finds it (honouring `CC`, `CXX`,
/// `CFLAGS`, ...).
fn compiler(cpp: bool) -> cc::Tool {
    let target = env!("IGAPARAM_BUILD_TARGET");
    cc::Build::new()
        .cpp(cpp)
        .target(target)
        .host(target)
        .opt_level(1)
        .debug(false)
        .cargo_metadata(false)
        .cargo_warnings(false)
        .get_compiler()
}

/// Compiles `source` (in `tests/c`) into `dir` and returns the program's path.
fn build(source: &str, dir: &Path, defines: &[(&str, String)]) -> PathBuf {
    let cpp = source.ends_with(".cpp");
    let root = Path::new(ROOT);
    let program = dir.join(source.split('.').next().unwrap());
    let major = env!("CARGO_PKG_VERSION_MAJOR");
    let mut command = compiler(cpp).to_command();
    command
        .arg(if cpp { "-std=c++17" } else { "-std=c11" })
        .args(["-Wall", "-Wextra"])
        .arg("-I")
        .arg(root.join("include"))
        .arg("-I")
        .arg(root.join("examples-c"))
        .arg("-I")
        .arg(root.join("bindings/cpp"))
        .arg(root.join("tests/c").join(source))
        .arg("-o")
        .arg(&program)
        .arg(dir.join(format!("libigaparam.so.{major}")))
        .arg(format!("-Wl,-rpath,{}", dir.display()))
        .args(["-lpthread", "-lm"]);
    for (name, value) in defines {
        command.arg(format!("-D{name}=\"{value}\""));
    }
    let out = command.output().expect("the compiler runs");
    assert!(
        out.status.success(),
        "compiling {source} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    program
}

/// Builds and runs one test program with `args`; it must exit with 0 and report no failure.
fn run(source: &str, args: &[&Path], defines: &[(&str, String)]) {
    let dir = work_dir(source.split('.').next().unwrap());
    let program = build(source, &dir, defines);
    // Without cargo's LD_LIBRARY_PATH, which comes before the program's RUNPATH and may name
    // the target directory, where a CMake build leaves its own (possibly older)
    // libigaparam.so.0: the program must load the library built along with this test.
    let out = Command::new(&program)
        .args(args)
        .env_remove("LD_LIBRARY_PATH")
        .current_dir(&dir)
        .output()
        .expect("the test program runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{source} failed ({}):\n{stdout}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains(" 0 failed"), "{source}: {stdout}");
    std::fs::remove_dir_all(&dir).ok();
}

fn boundary_data() -> PathBuf {
    Path::new(ROOT).join("tests/data/boundary")
}

#[test]
fn capi() {
    run("test_capi.c", &[], &[]);
}

#[test]
fn sensitivity_capi() {
    run("test_sensitivity.c", &[], &[]);
}

#[test]
fn domain_capi() {
    let out = work_dir("domain-out");
    run("test_domain.c", &[&boundary_data(), &out], &[]);
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn spline_capi() {
    let out = work_dir("spline-out");
    run("test_spline.c", &[&boundary_data(), &out], &[]);
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn morph_capi() {
    let out = work_dir("morph-out");
    run("test_morph.c", &[&boundary_data(), &out], &[]);
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn cpp_wrapper() {
    let out = work_dir("cpp-out");
    let data = boundary_data().display().to_string();
    run(
        "test_cpp_wrapper.cpp",
        &[],
        &[
            ("IGAPARAM_TEST_DATA", data),
            ("IGAPARAM_TEST_OUT", out.display().to_string()),
        ],
    );
    std::fs::remove_dir_all(&out).ok();
}
