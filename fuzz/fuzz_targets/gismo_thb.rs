//! Fuzz target `gismo_thb`: see `igaparam_fuzz::gismo_thb`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| igaparam_fuzz::gismo_thb::run(data));
