//! Checks shared by the fuzz targets.

use igaparam::Error;

/// The input as text, or `None` when it is not UTF-8 (the text readers take `&str`; a file
/// that is not UTF-8 is refused by `read_to_string` before they see it).
pub fn text(data: &[u8]) -> Option<&str> {
    std::str::from_utf8(data).ok()
}

/// A refusal must say why.
pub fn check_error(what: &str, e: &Error) {
    assert!(
        !e.message.trim().is_empty(),
        "{what}: an error without a message"
    );
}

/// `Ok` values pass through; an error must carry a message and becomes `None`.
pub fn checked<T>(what: &str, r: igaparam::Result<T>) -> Option<T> {
    r.map_err(|e| check_error(what, &e)).ok()
}

/// Asserts that every value is finite.
pub fn assert_finite(what: &str, values: &[f64]) {
    if let Some(v) = values.iter().find(|v| !v.is_finite()) {
        panic!("{what}: non-finite value {v} in an accepted input");
    }
}

/// `n + 1` parameters evenly spaced in [0, 1].
pub fn params(n: usize) -> impl Iterator<Item = f64> {
    (0..=n).map(move |i| i as f64 / n as f64)
}
