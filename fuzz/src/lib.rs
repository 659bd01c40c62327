//! What the fuzz targets run, one module per target: each `run(data)` feeds the bytes to a
//! reader of the library (or decodes a sequence of C API calls from them) and checks what the
//! library promises about the result; a panic, a crash, a hang or a failed check is a finding.
//! `tests/fuzz_regressions.rs` includes these files too and replays the kept inputs of
//! `tests/data/fuzz/` under `cargo test`.

pub mod capi;
pub mod coastline;
pub mod common;
pub mod gismo_thb;
pub mod gismo_xml;
pub mod obj;
pub mod vtu;
