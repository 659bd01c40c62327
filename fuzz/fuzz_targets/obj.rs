//! Fuzz target `obj`: see `igaparam_fuzz::obj`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| igaparam_fuzz::obj::run(data));
