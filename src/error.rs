//! The crate's error type: a kind a caller can branch on and a message a person can read.

use std::fmt;

/// What went wrong, coarsely; the C API maps each kind to a status code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorKind {
    /// An argument is out of range, of the wrong size or inconsistent with others.
    InvalidArgument,
    /// A coordinate or parameter is NaN or infinite.
    NotFinite,
    /// The mesh itself is unusable: repeated node in a cell, bad cell type, out-of-range index.
    InvalidMesh,
    /// A caller-provided output buffer is too small.
    BufferTooSmall,
    /// The progress callback asked to stop.
    Cancelled,
    /// Reading or writing a file failed, or its content is not understood.
    Io,
    /// The work asked for exceeds a resource limit (cells, memory) the caller can raise.
    LimitExceeded,
    /// A handle is in use by another call (agreed among the ranks of a partitioned call).
    Busy,
}

/// An error with its kind and a readable message.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Error {
    /// The coarse kind of the error.
    pub kind: ErrorKind,
    /// A sentence saying what is wrong and, where it helps, where.
    pub message: String,
}

impl Error {
    /// Builds an error of the given kind.
    pub fn new(kind: ErrorKind, message: impl Into<String>) -> Self {
        Error {
            kind,
            message: message.into(),
        }
    }

    /// An [`ErrorKind::InvalidArgument`] error.
    pub fn invalid(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::InvalidArgument, message)
    }

    /// An [`ErrorKind::InvalidMesh`] error.
    pub fn mesh(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::InvalidMesh, message)
    }

    /// The [`ErrorKind::Cancelled`] error of a progress callback that asked to stop.
    pub fn cancelled() -> Self {
        Self::new(ErrorKind::Cancelled, "cancelled by the progress callback")
    }

    /// An [`ErrorKind::Io`] error.
    pub fn io(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Io, message)
    }

    /// The error with `hint` (what the caller can do about it) after its message, where it is
    /// of kind `kind`; else unchanged.
    pub fn hinted(mut self, kind: ErrorKind, hint: &str) -> Self {
        if self.kind == kind {
            self.message = format!("{}; {hint}", self.message);
        }
        self
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Error {}

/// The crate's result type.
pub type Result<T> = std::result::Result<T, Error>;

/// Checks that every value is finite; `what` names the array in the message.
pub fn check_finite(what: &str, values: &[f64]) -> Result<()> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(Error::new(
            ErrorKind::NotFinite,
            format!("{what}[{i}] is {}, every value must be finite", values[i]),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A hint follows the message of an error of its kind only.
    #[test]
    fn a_hint_is_added_to_its_kind_only() {
        let e = Error::new(ErrorKind::LimitExceeded, "no room")
            .hinted(ErrorKind::LimitExceeded, "try less");
        assert_eq!(e.message, "no room; try less");
        assert_eq!(
            Error::invalid("bad")
                .hinted(ErrorKind::LimitExceeded, "try less")
                .message,
            "bad"
        );
    }
}
