//! The worker threads of every parallel stage: one place that turns a thread count option into
//! a rayon pool, capped to the machine's cores.
//!
//! More threads than cores cannot make a stage faster, only slower (each extra thread adds its
//! start-up and its share of every synchronisation: 4096 threads made a 0.15 s relocation of a
//! 2-core machine take minutes), and the results do not depend on the thread count, so a larger
//! count is capped to the cores rather than refused.
//!
//! Every call starts its own pool (about 0.1 ms) rather than sharing a process-wide one: calls
//! on different handles from different host threads then never queue behind each other, and a
//! progress callback that waits for another thread's call cannot deadlock on a shared worker.

use rayon::prelude::*;
use rayon::ThreadPool;

use crate::error::{Error, Result};

/// The largest thread count an option accepts (larger ones are refused as invalid).
pub const MAX_THREADS: usize = 4096;

/// Refuses a thread count above [`MAX_THREADS`] (the rule of every option named `threads`).
pub fn check(threads: usize) -> Result<()> {
    if threads > MAX_THREADS {
        return Err(Error::invalid(format!(
            "threads = {threads} must be at most {MAX_THREADS}"
        )));
    }
    Ok(())
}

/// The cores of this machine (`std::thread::available_parallelism`, 1 if unknown).
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// The threads a stage runs with for option `threads`: one per core for 0, else `threads`
/// capped to the cores.
pub fn effective_threads(threads: usize) -> usize {
    let cores = cores();
    if threads == 0 {
        cores
    } else {
        threads.min(cores)
    }
}

/// A pool of [`effective_threads`]`(threads)` workers.
pub fn pool(threads: usize) -> Result<rayon::ThreadPool> {
    let n = effective_threads(threads);
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .map_err(|e| Error::invalid(format!("cannot start {n} threads: {e}")))
}

/// Loops costing fewer multiply-adds than this run on the calling thread: handing a loop to a
/// pool wakes its workers, tens of microseconds on a shared machine, which is more than such a
/// loop takes (the bundled airfoil's Hessian product, 2,060 nodes and 127,040 multiply-adds,
/// takes 60 µs on one thread; in runs alternated on 2 cores, a warm relocation step of that
/// mesh, eleven products, took 3–15% longer with them in parallel).
pub(crate) const SERIAL_WORK: usize = 1 << 18;

/// `f(i, &mut items[i])` for every item: in parallel on `pool` where the loop costs `work`
/// multiply-adds, at least [`SERIAL_WORK`], else on the calling thread. The items are
/// independent, so the result is the same either way.
pub(crate) fn for_each_mut<T: Send>(
    pool: &ThreadPool,
    work: usize,
    items: &mut [T],
    f: impl Fn(usize, &mut T) + Sync + Send,
) {
    match work < SERIAL_WORK {
        true => items.iter_mut().enumerate().for_each(|(i, t)| f(i, t)),
        false => pool.install(|| items.par_iter_mut().enumerate().for_each(|(i, t)| f(i, t))),
    }
}
