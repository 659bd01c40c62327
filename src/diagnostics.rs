//! Diagnostics on standard error, for finding where a long relocation spends its time: with the
//! environment variable `IGAPARAM_DEBUG` set, the relocation's stages (the Hessian's layout, the
//! multigrid's levels, the prediction, every Newton iteration and line-search trial) each print
//! a line, prefixed with the seconds since the process's first such line. Off (the default),
//! a line costs one look at the environment and its text is not made.

use std::sync::OnceLock;
use std::time::Instant;

/// Whether diagnostics are on (`IGAPARAM_DEBUG` set).
fn enabled() -> bool {
    std::env::var_os("IGAPARAM_DEBUG").is_some()
}

/// Prints the line `message()` makes, with its time stamp, where diagnostics are on.
pub(crate) fn note(message: impl FnOnce() -> String) {
    if enabled() {
        static START: OnceLock<Instant> = OnceLock::new();
        let seconds = START.get_or_init(Instant::now).elapsed().as_secs_f64();
        eprintln!("[{seconds:10.3} s] {}", message());
    }
}
