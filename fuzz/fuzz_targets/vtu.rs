//! Fuzz target `vtu`: see `igaparam_fuzz::vtu`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| igaparam_fuzz::vtu::run(data));
