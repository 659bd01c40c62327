//! Fuzz target `gismo_xml`: see `igaparam_fuzz::gismo_xml`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| igaparam_fuzz::gismo_xml::run(data));
