//! A sequence of C API calls decoded from bytes: meshes, domains and splines created, changed,
//! queried and freed through the public `extern "C"` functions with hostile arguments (NULL
//! pointers, wrong sizes, NaN and huge values, indices out of range, bad codes, cancelling
//! callbacks), so that what is fuzzed is the C boundary's own checking.
//!
//! After every call it checks the conventions of the API: no `IGAPARAM_STATUS_INTERNAL` (a
//! caught panic), a message naming the function exactly when the call failed, outputs written
//! only on success (caller buffers filled with a sentinel stay as they were), and a failed call
//! leaving its handle as it was; and some promises of the results (counts that agree, qualities
//! in [0, 1], a refined spline being the same map, an inverted point mapping back).
//!
//! Work per input is bounded: at most [`MAX_CALLS`] calls and small inputs (meshes of a few
//! cells, domains up to level 5 in 2D and 2 in 3D). Those bounds also keep clear of
//! options that are legal but costly (domains at level 16, thousands of threads): a matter of
//! resource limits, not of checking.

mod domain;
mod mesh;
mod spline;

use std::ffi::{c_char, c_int, c_void, CString};
use std::path::PathBuf;

use igaparam::capi::{igaparam_last_error_message, igaparam_stage, igaparam_status};

pub use domain::Domains;
pub use mesh::Meshes;
pub use spline::Splines;

/// Calls decoded from one input, at most.
pub const MAX_CALLS: usize = 48;

/// Handles of each kind kept alive at once, at most.
pub const MAX_HANDLES: usize = 3;

/// Reads the fuzz input as a stream of choices; past its end every choice is 0.
pub struct Choices<'a> {
    data: &'a [u8],
}

impl<'a> Choices<'a> {
    /// Choices from `data`.
    pub fn new(data: &'a [u8]) -> Self {
        Choices { data }
    }

    /// Whether the input is used up.
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// The next byte (0 past the end).
    pub fn byte(&mut self) -> u8 {
        match self.data.split_first() {
            Some((&b, rest)) => {
                self.data = rest;
                b
            }
            None => 0,
        }
    }

    /// A number in `0..n` (`n > 0`).
    pub fn below(&mut self, n: usize) -> usize {
        self.byte() as usize % n
    }

    /// A yes/no choice, yes about once in `n`.
    pub fn one_in(&mut self, n: usize) -> bool {
        self.below(n) == 0
    }

    /// One of `table`.
    pub fn pick<T: Copy>(&mut self, table: &[T]) -> T {
        table[self.below(table.len())]
    }

    /// A double in [0, 1] in steps of 1/255.
    pub fn unit(&mut self) -> f64 {
        self.byte() as f64 / 255.0
    }

    /// A hostile double: a special value or 8 raw bytes.
    pub fn double(&mut self) -> f64 {
        const TABLE: [f64; 15] = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            1e-300,
            1e300,
            -1e300,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            1e-9,
        ];
        if self.one_in(4) {
            f64::from_le_bytes(std::array::from_fn(|_| self.byte()))
        } else {
            self.pick(&TABLE)
        }
    }

    /// A buffer length around `needed`: exact, one short, one over, zero or double.
    pub fn len_around(&mut self, needed: usize) -> usize {
        match self.below(8) {
            0 => needed.saturating_sub(1),
            1 => needed + 1,
            2 => 0,
            3 => 2 * needed,
            _ => needed,
        }
    }
}

/// The sentinel caller buffers are filled with, to see what a call wrote.
pub const SENTINEL: f64 = -7.25e77;

/// The calling thread's last message.
pub fn last_message() -> String {
    let len = igaparam_last_error_message(std::ptr::null_mut(), 0);
    let mut buf = vec![0u8; len];
    let again = igaparam_last_error_message(buf.as_mut_ptr() as *mut c_char, buf.len());
    assert_eq!(again, len, "igaparam_last_error_message: the size changed");
    assert_eq!(
        buf[len - 1],
        0,
        "igaparam_last_error_message: not NUL-terminated"
    );
    buf.truncate(len - 1);
    String::from_utf8(buf).expect("the message is UTF-8")
}

/// Checks the conventions after a call of `function`; true when it succeeded.
pub fn ok(function: &str, status: igaparam_status) -> bool {
    let message = last_message();
    assert_ne!(
        status,
        igaparam_status::IGAPARAM_STATUS_INTERNAL,
        "{function}: {message}"
    );
    if status == igaparam_status::IGAPARAM_STATUS_OK {
        assert!(
            message.is_empty(),
            "{function} succeeded with message {message:?}"
        );
        return true;
    }
    assert!(
        message.starts_with(function) && message.len() > function.len() + 2,
        "{function} failed ({status:?}) with message {message:?}"
    );
    false
}

thread_local! {
    static PROGRESS_LEFT: std::cell::Cell<usize> = const { std::cell::Cell::new(usize::MAX) };
}

/// A progress callback that cancels after the number of calls [`set_cancel_after`] set.
pub extern "C" fn progress(_: *mut c_void, _: igaparam_stage, _: usize, _: usize) -> c_int {
    PROGRESS_LEFT.with(|left| match left.get() {
        0 => 1,
        n => {
            left.set(n - 1);
            0
        }
    })
}

/// The number of progress calls before [`progress`] cancels.
pub fn set_cancel_after(calls: usize) {
    PROGRESS_LEFT.with(|left| left.set(calls));
}

/// A directory for the files the calls write, one per process.
pub fn scratch(name: &str) -> CString {
    static DIR: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    let dir = DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("igaparam-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("scratch directory");
        dir
    });
    CString::new(dir.join(name).to_str().expect("UTF-8 path")).expect("no NUL")
}

/// Hostile paths: empty, missing, a folder, not writable, not UTF-8.
pub fn hostile_path(c: &mut Choices) -> CString {
    let table: [&[u8]; 5] = [
        b"",
        b"/nonexistent/igaparam/file.xml",
        b"/",
        b"/proc/igaparam.vtu",
        b"\xff\xfe.xml",
    ];
    CString::new(c.pick(&table)).expect("no NUL")
}

/// A file of the bundled data, `tests/data/<relative>`.
pub fn data_path(relative: &str) -> CString {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/");
    let root = if std::path::Path::new(root).exists() {
        root.to_string()
    } else {
        // Included by the crate's own tests, whose manifest is the repository's.
        concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/").to_string()
    };
    CString::new(format!("{root}{relative}")).expect("no NUL")
}

/// Runs the calls decoded from `data`.
pub fn run(data: &[u8]) {
    let mut c = Choices::new(data);
    let mut meshes = Meshes::default();
    let mut domains = Domains::default();
    let mut splines = Splines::default();
    for _ in 0..MAX_CALLS {
        if c.is_empty() {
            break;
        }
        match c.below(4) {
            0 => meshes.call(&mut c),
            1 => domains.call(&mut c),
            2 => {
                let domain = domains.pick(&mut c);
                splines.call(&mut c, domain)
            }
            _ => general(&mut c),
        }
    }
}

/// Calls about no handle: messages, versions, node tables.
fn general(c: &mut Choices) {
    use igaparam::capi::*;
    match c.below(3) {
        0 => {
            let len = c.pick(&[0usize, 1, 2, 7, 4096]);
            let mut buf = vec![0x55u8; len];
            let ptr = if c.one_in(3) {
                std::ptr::null_mut()
            } else {
                buf.as_mut_ptr() as *mut c_char
            };
            let whole = igaparam_last_error_message(ptr, len);
            assert!(whole >= 1, "igaparam_last_error_message returned 0");
            if !ptr.is_null() && len > 0 {
                let nul = buf.iter().position(|&b| b == 0).expect("a NUL within len");
                assert_eq!(nul, (whole - 1).min(len - 1), "truncated message length");
            }
        }
        1 => {
            let code = c.pick(&mesh::CELL_CODES).0;
            let mut n = 777usize;
            let out = if c.one_in(4) {
                std::ptr::null_mut()
            } else {
                &mut n as *mut usize
            };
            if !ok(
                "igaparam_cell_type_node_count",
                igaparam_cell_type_node_count(code, out),
            ) {
                assert_eq!(n, 777, "igaparam_cell_type_node_count wrote on failure");
            }
        }
        _ => {
            let code = c.pick(&mesh::CELL_CODES).0;
            let order = c.pick(&[IGAPARAM_ORDER_VTK, IGAPARAM_ORDER_GMSH, 2, -1]);
            let len = c.pick(&[0usize, 7, 8, 16, 54, 81, 100]);
            let mut xi = vec![SENTINEL; len];
            let status =
                igaparam_cell_type_copy_node_coordinates(code, order, xi.as_mut_ptr(), len);
            if ok("igaparam_cell_type_copy_node_coordinates", status) {
                assert!(xi
                    .iter()
                    .all(|&v| v == SENTINEL || [-1.0, 0.0, 1.0].contains(&v)));
            } else {
                assert!(xi.iter().all(|&v| v == SENTINEL), "written on failure");
            }
        }
    }
}
