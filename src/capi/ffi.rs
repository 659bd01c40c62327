//! The foreign-function support every entry point runs in: panic catching, status mapping, the
//! thread's last error message, and checked conversions of raw pointers to slices, paths,
//! options and optional outputs.

use std::cell::RefCell;
use std::ffi::{c_char, CStr};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

use crate::error::{Error, ErrorKind, Result};

/// Status of a call. `IGAPARAM_STATUS_OK` is zero; every other value comes with a message from
/// `igaparam_last_error_message`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum igaparam_status {
    /// Success.
    IGAPARAM_STATUS_OK = 0,
    /// A required pointer argument was NULL.
    IGAPARAM_STATUS_NULL_ARGUMENT = 1,
    /// An argument is out of range, of the wrong size or inconsistent with the others.
    IGAPARAM_STATUS_INVALID_ARGUMENT = 2,
    /// An input value is NaN or infinite.
    IGAPARAM_STATUS_NOT_FINITE = 3,
    /// The mesh is unusable: its connectivity refers to a node that does not exist or repeats a
    /// node within a cell.
    IGAPARAM_STATUS_INVALID_MESH = 4,
    /// A caller-provided output buffer is too small; the message says the size needed.
    IGAPARAM_STATUS_BUFFER_TOO_SMALL = 5,
    /// The progress callback returned non-zero.
    IGAPARAM_STATUS_CANCELLED = 6,
    /// A file could not be read or written.
    IGAPARAM_STATUS_IO = 7,
    /// An internal error (a bug): the message says what; please report it.
    IGAPARAM_STATUS_INTERNAL = 8,
    /// A handle argument is in use by another call: one made from the progress callback of a
    /// running call on it, or from another thread. A handle takes one call at a time; the call
    /// was refused and changed nothing.
    IGAPARAM_STATUS_BUSY = 9,
    /// The work asked for exceeds a resource limit (e.g. the cells of a domain build beyond
    /// `max_cells`); the message gives the estimate and the option that raises the limit.
    IGAPARAM_STATUS_LIMIT_EXCEEDED = 10,
}

thread_local! {
    static LAST_ERROR: RefCell<String> = const { RefCell::new(String::new()) };
}

fn set_last_error(message: String) {
    LAST_ERROR.with(|e| *e.borrow_mut() = message);
}

fn status_of(kind: ErrorKind) -> igaparam_status {
    use igaparam_status::*;
    match kind {
        ErrorKind::InvalidArgument => IGAPARAM_STATUS_INVALID_ARGUMENT,
        ErrorKind::NotFinite => IGAPARAM_STATUS_NOT_FINITE,
        ErrorKind::InvalidMesh => IGAPARAM_STATUS_INVALID_MESH,
        ErrorKind::BufferTooSmall => IGAPARAM_STATUS_BUFFER_TOO_SMALL,
        ErrorKind::Cancelled => IGAPARAM_STATUS_CANCELLED,
        ErrorKind::Io => IGAPARAM_STATUS_IO,
        ErrorKind::LimitExceeded => IGAPARAM_STATUS_LIMIT_EXCEEDED,
        ErrorKind::Busy => IGAPARAM_STATUS_BUSY,
    }
}

/// A NULL pointer error for argument `name` of `function`.
pub(crate) struct NullArgument(pub &'static str);

/// What a body may fail with: a library error, a NULL argument, or a handle argument (name,
/// kind) in use by another call.
pub(crate) enum Failure {
    Library(Error),
    Null(&'static str),
    Busy(&'static str, &'static str),
}

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        Failure::Library(e)
    }
}

impl From<NullArgument> for Failure {
    fn from(n: NullArgument) -> Self {
        Failure::Null(n.0)
    }
}

/// Runs the body of entry point `function`, catching panics and mapping errors to statuses.
pub(crate) fn run(
    function: &str,
    body: impl FnOnce() -> std::result::Result<(), Failure>,
) -> igaparam_status {
    set_last_error(String::new());
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => igaparam_status::IGAPARAM_STATUS_OK,
        Ok(Err(Failure::Library(e))) => {
            set_last_error(format!("{function}: {}", e.message));
            status_of(e.kind)
        }
        Ok(Err(Failure::Null(name))) => {
            set_last_error(format!("{function}: argument `{name}` is NULL"));
            igaparam_status::IGAPARAM_STATUS_NULL_ARGUMENT
        }
        Ok(Err(Failure::Busy(name, kind))) => {
            set_last_error(format!(
                "{function}: the {kind} `{name}` is in use by another call (one from the \
                 progress callback of a running call on it, or from another thread); a handle \
                 takes one call at a time"
            ));
            igaparam_status::IGAPARAM_STATUS_BUSY
        }
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            set_last_error(format!("{function}: internal error: {what}"));
            igaparam_status::IGAPARAM_STATUS_INTERNAL
        }
    }
}

/// A shared reference from a pointer that must not be NULL.
pub(crate) fn non_null<'a, T>(
    ptr: *const T,
    name: &'static str,
) -> std::result::Result<&'a T, NullArgument> {
    // SAFETY: the caller passes a pointer to a live, properly aligned object (documented contract);
    // NULL is rejected here.
    unsafe { ptr.as_ref() }.ok_or(NullArgument(name))
}

/// A mutable reference from a pointer that must not be NULL.
pub(crate) fn non_null_mut<'a, T>(
    ptr: *mut T,
    name: &'static str,
) -> std::result::Result<&'a mut T, NullArgument> {
    // SAFETY: as in `non_null`, and the object is not aliased during the call.
    unsafe { ptr.as_mut() }.ok_or(NullArgument(name))
}

/// A slice of `len` elements; NULL is allowed only for `len == 0`.
pub(crate) fn slice<'a, T>(
    ptr: *const T,
    len: usize,
    name: &'static str,
) -> std::result::Result<&'a [T], NullArgument> {
    if len == 0 {
        return Ok(&[]);
    }
    if ptr.is_null() {
        return Err(NullArgument(name));
    }
    // SAFETY: the caller guarantees `len` readable elements at `ptr` (documented contract).
    Ok(unsafe { std::slice::from_raw_parts(ptr, len) })
}

/// A writable slice of `len` elements; NULL is allowed only for `len == 0`.
pub(crate) fn slice_mut<'a, T>(
    ptr: *mut T,
    len: usize,
    name: &'static str,
) -> std::result::Result<&'a mut [T], NullArgument> {
    if len == 0 {
        return Ok(&mut []);
    }
    if ptr.is_null() {
        return Err(NullArgument(name));
    }
    // SAFETY: the caller guarantees `len` writable elements at `ptr` (documented contract).
    Ok(unsafe { std::slice::from_raw_parts_mut(ptr, len) })
}

/// The first `needed` elements of an optional output buffer, `None` when `ptr` is NULL. Only
/// what is written is sliced (the caller has checked that the buffer holds `needed`), so that
/// a call validates all its buffers before it writes to any and an overstated length is harmless.
pub(crate) fn optional_out<'a, T>(ptr: *mut T, needed: usize) -> Option<&'a mut [T]> {
    if ptr.is_null() {
        return None;
    }
    // SAFETY: `ptr` is not NULL and the caller checked that it holds `needed` elements.
    Some(unsafe { std::slice::from_raw_parts_mut(ptr, needed) })
}

/// The options at `ptr`, or `default` when it is NULL (every entry point's rule for its
/// `options` argument).
pub(crate) fn options_or<T: Copy>(ptr: *const T, default: T) -> T {
    // SAFETY: a non-NULL `ptr` points to a live, properly aligned options struct (documented
    // contract).
    match unsafe { ptr.as_ref() } {
        Some(options) => *options,
        None => default,
    }
}

/// Writes `value` to the optional output `ptr` (a report); NULL skips it.
pub(crate) fn write_optional<T>(ptr: *mut T, value: T) {
    // SAFETY: a non-NULL `ptr` points to a live, writable object not aliased during the call
    // (documented contract).
    if let Some(out) = unsafe { ptr.as_mut() } {
        *out = value;
    }
}

/// A path from a NUL-terminated C string that must not be NULL.
pub(crate) fn c_path<'a>(
    ptr: *const c_char,
    name: &'static str,
) -> std::result::Result<&'a Path, Failure> {
    non_null(ptr, name)?;
    // SAFETY: `ptr` is not NULL and the caller passes a NUL-terminated string (documented
    // contract) that outlives the call.
    let s = unsafe { CStr::from_ptr(ptr) };
    let s = s
        .to_str()
        .map_err(|_| Error::invalid(format!("`{name}` is not valid UTF-8")))?;
    if s.is_empty() {
        return Err(Error::invalid(format!("`{name}` is empty")).into());
    }
    Ok(Path::new(s))
}

/// Checks that an output buffer of `len` elements holds `needed`.
pub(crate) fn check_capacity(name: &str, len: usize, needed: usize) -> Result<()> {
    if len < needed {
        return Err(Error::new(
            ErrorKind::BufferTooSmall,
            format!("`{name}` holds {len} values, {needed} are needed"),
        ));
    }
    Ok(())
}

/// Copies the message of the calling thread's latest call into `buf` (at most `len` bytes including the
/// terminating NUL, truncated if needed) and returns the length of the whole message plus one,
/// so a caller can size the buffer. `buf` may be NULL (with any `len`) to ask for the size only.
/// The message is empty (returns 1) when that call succeeded: every call that returns an
/// `igaparam_status` replaces it.
#[no_mangle]
pub extern "C" fn igaparam_last_error_message(buf: *mut c_char, len: usize) -> usize {
    LAST_ERROR.with(|e| {
        let message = e.borrow();
        let bytes = message.as_bytes();
        if !buf.is_null() && len > 0 {
            let n = bytes.len().min(len - 1);
            // SAFETY: the caller provides `len` writable bytes at `buf`; we write n + 1 <= len.
            unsafe {
                std::ptr::copy_nonoverlapping(bytes.as_ptr(), buf as *mut u8, n);
                *buf.add(n) = 0;
            }
        }
        bytes.len() + 1
    })
}

/// The library version as a static NUL-terminated string, e.g. `"0.1.0"`. Never NULL; not to be
/// freed.
#[no_mangle]
pub extern "C" fn igaparam_version() -> *const c_char {
    static VERSION: &CStr =
        match CStr::from_bytes_with_nul(concat!(env!("CARGO_PKG_VERSION"), "\0").as_bytes()) {
            Ok(v) => v,
            Err(_) => panic!("version string"),
        };
    VERSION.as_ptr()
}
