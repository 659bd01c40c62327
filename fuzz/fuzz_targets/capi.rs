//! Fuzz target `capi`: see `igaparam_fuzz::capi`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| igaparam_fuzz::capi::run(data));
