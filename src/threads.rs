//! The worker threads of every parallel stage: one place that turns a thread count option into
//! a rayon pool, capped to the machine's cores.
//!
//! More threads than cores cannot make a stage faster, only slower (each extra thread adds its
//! start-up and its share of every synchronisation: 4096 threads made a 0.15 s relocation of a
//! 2-core machine take minutes), and the results do not depend on the thread count, so a larger
//! count is capped to the cores rather than refused.
//!
//! Starting a pool costs about 0.1 ms and its threads start cold: a call that repeats at every
//! step of a loop (a warm relocation takes a few ms) uses [`shared_pool`], one pool per thread
//! count kept for the process (at most one per core count, so a handful of idle threads).

use std::sync::{Arc, Mutex, OnceLock};

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

/// The kept pools, by thread count.
type Pools = Vec<(usize, Arc<ThreadPool>)>;

/// The process's pool of [`effective_threads`]`(threads)` workers, started at its first use.
pub fn shared_pool(threads: usize) -> Result<Arc<ThreadPool>> {
    static POOLS: OnceLock<Mutex<Pools>> = OnceLock::new();
    let n = effective_threads(threads);
    let mut pools = POOLS
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some((_, pool)) = pools.iter().find(|(count, _)| *count == n) {
        return Ok(pool.clone());
    }
    let pool = Arc::new(pool(n)?);
    pools.push((n, pool.clone()));
    Ok(pool)
}

/// A pool of [`effective_threads`]`(threads)` workers.
pub fn pool(threads: usize) -> Result<rayon::ThreadPool> {
    let n = effective_threads(threads);
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .map_err(|e| Error::invalid(format!("cannot start {n} threads: {e}")))
}
