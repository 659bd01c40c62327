//! The C ABI: every `extern "C"` function and every `unsafe` block of the crate.
//!
//! Conventions: functions return an [`igaparam_status`]; outputs go through out-parameters that
//! are written only on success; arrays are caller-owned, flat, with explicit sizes; a failed call
//! leaves its handle as it was; `igaparam_last_error_message` gives the calling thread's last
//! message. No panic crosses this boundary.
//!
//! The doc comments of the exported items are the header's comments, plain text: an interval
//! `[0,1]^d` there is no link, so the items that write one allow rustdoc's link lint.
#![allow(non_camel_case_types)]
// Entry points take raw pointers from C by design; each dereference is checked for NULL and
// documented as the caller's contract, which a C caller cannot see as `unsafe` anyway.
#![allow(clippy::not_unsafe_ptr_arg_deref)]

// First (cbindgen writes the entry points in the order of these declarations): the library-wide
// calls, `igaparam_last_error_message` and `igaparam_version`, open the header's functions.
mod ffi;

mod domain;
mod domain_build;
mod domain_input;
mod domain_query;
mod domain_update;
mod handle;
mod mesh;
mod mesh_io;
mod node_order;
mod option_enums;
mod options_gen;
mod partition;
mod progress;
mod relocate;
mod reports_gen;
mod spline;

pub use domain::*;
pub use domain_build::*;
pub use domain_input::*;
pub use domain_query::*;
pub use domain_update::*;
pub use ffi::{igaparam_last_error_message, igaparam_status, igaparam_version};
pub use mesh::*;
pub use mesh_io::*;
pub use node_order::*;
pub use option_enums::*;
pub use options_gen::*;
pub use partition::*;
pub use progress::*;
pub use relocate::*;
pub use reports_gen::*;
pub use spline::*;

/// Major version of the library this header belongs to.
pub const IGAPARAM_VERSION_MAJOR: u32 = 0;
/// Minor version of the library this header belongs to.
pub const IGAPARAM_VERSION_MINOR: u32 = 1;
/// Patch version of the library this header belongs to.
pub const IGAPARAM_VERSION_PATCH: u32 = 0;

/// The fingerprint of the declarations of the header this library was built with: a 64-bit
/// hash of `include/igaparam.h` without its comments. Bindings generated from a header (the
/// Python package's declarations carry the same number) compare it before their first call,
/// so that they refuse a library of another layout instead of calling it with wrong structs.
#[no_mangle]
pub extern "C" fn igaparam_abi_fingerprint() -> u64 {
    const FINGERPRINT: u64 = decimal(env!("IGAPARAM_ABI_FINGERPRINT"));
    FINGERPRINT
}

/// The value of a decimal number known at compile time.
const fn decimal(text: &str) -> u64 {
    let bytes = text.as_bytes();
    let mut value = 0u64;
    let mut i = 0;
    while i < bytes.len() {
        value = value * 10 + (bytes[i] - b'0') as u64;
        i += 1;
    }
    value
}
