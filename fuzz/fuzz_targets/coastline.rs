//! Fuzz target `coastline`: see `igaparam_fuzz::coastline`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| igaparam_fuzz::coastline::run(data));
