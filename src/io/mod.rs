//! File formats.

pub mod vtu;
