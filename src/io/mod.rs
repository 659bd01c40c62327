//! File formats.

pub mod gismo;
pub mod vtu;
