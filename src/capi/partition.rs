//! The partition handle: a rank's part of a mesh partitioned over the ranks of the host's MPI
//! job, relocated on all ranks together through a host-supplied exchange callback.
//!
//! The library links no MPI: the host passes an `igaparam_exchange` (its communicator behind a
//! callback), so any MPI implementation, and the host's own communicator, serve.

use std::ffi::{c_int, c_void};

use super::ffi::{
    check_capacity, non_null, non_null_mut, options_or, run, slice, slice_mut, write_optional,
    Failure,
};
use super::handle::{acquire, handle_type, into_raw, release, Guarded};
use super::mesh::cell_type;
use super::options_gen::igaparam_relocate_options;
use super::relocate::{igaparam_relocate_options_default, relocation_progress};
use super::reports_gen::igaparam_partition_report;
use super::{igaparam_cell_type, igaparam_status};
use crate::error::{Error, Result};
use crate::partition::{Exchange, PartInput, Partition, Ranks};

/// A rank's part of a partitioned mesh (opaque). Create with `igaparam_partition_new`, release
/// with `igaparam_partition_free`. One call at a time (see `IGAPARAM_STATUS_BUSY`).
pub struct igaparam_partition(Guarded<Partition>);
handle_type!(igaparam_partition, Partition, "partition");

/// The host's all-to-all exchange of bytes among the ranks of its communicator, as
/// `MPI_Alltoallv` with `MPI_BYTE`: send `send_counts[r]` bytes to each rank `r` (the blocks of
/// `send` in rank order) and receive `recv_counts[r]` bytes from each into `recv` (in rank
/// order; the library knows the counts in advance). `user` is the exchange's `user`. Return 0
/// on success. Called only on the thread that called the library.
pub type igaparam_exchange_fn = Option<
    unsafe extern "C" fn(
        user: *mut c_void,
        send_counts: *const usize,
        send: *const u8,
        recv_counts: *const usize,
        recv: *mut u8,
    ) -> c_int,
>;

/// The ranks a partition lives on: this rank's number in `0..size` and the host's exchange.
/// The library never starts, ends or calls MPI itself.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct igaparam_exchange {
    /// This rank, in `0..size` (e.g. from `MPI_Comm_rank`).
    pub rank: c_int,
    /// Number of ranks (e.g. from `MPI_Comm_size`).
    pub size: c_int,
    /// The exchange callback.
    pub exchange: igaparam_exchange_fn,
    /// Passed to `exchange` as its first argument (e.g. a pointer to the communicator).
    pub user: *mut c_void,
}

/// The host's exchange as the library sees it.
struct HostExchange {
    rank: usize,
    size: usize,
    f: unsafe extern "C" fn(*mut c_void, *const usize, *const u8, *const usize, *mut u8) -> c_int,
    user: *mut c_void,
}

impl Exchange for HostExchange {
    fn size(&self) -> usize {
        self.size
    }
    fn rank(&self) -> usize {
        self.rank
    }
    fn exchange(&mut self, sc: &[usize], send: &[u8], rc: &[usize], recv: &mut [u8]) -> Result<()> {
        // SAFETY: the host's callback with its user pointer, given buffers of the sizes the
        // counts say (checked by the caller of this method).
        let code = unsafe {
            (self.f)(
                self.user,
                sc.as_ptr(),
                send.as_ptr(),
                rc.as_ptr(),
                recv.as_mut_ptr(),
            )
        };
        match code {
            0 => Ok(()),
            c => Err(Error::io(format!("the exchange callback returned {c}"))),
        }
    }
}

/// The exchange of `ex`, checked on this rank alone (nothing can be agreed without it).
fn host_exchange(ex: *const igaparam_exchange) -> std::result::Result<HostExchange, Failure> {
    let ex = non_null(ex, "exchange")?;
    let f = ex
        .exchange
        .ok_or_else(|| Error::invalid("exchange.exchange is NULL"))?;
    if ex.size < 1 || ex.rank < 0 || ex.rank >= ex.size {
        return Err(Error::invalid(format!(
            "exchange.rank = {} is not in 0..exchange.size = {}",
            ex.rank, ex.size
        ))
        .into());
    }
    Ok(HostExchange {
        rank: ex.rank as usize,
        size: ex.size as usize,
        f,
        user: ex.user,
    })
}

/// A message of an argument failure, to agree on.
fn failed(f: Failure) -> Error {
    match f {
        Failure::Library(e) => e,
        Failure::Null(name) => Error::invalid(format!("argument `{name}` is NULL")),
        Failure::Busy(name, kind) => Error::new(
            crate::error::ErrorKind::Busy,
            format!("the {kind} `{name}` is in use by another call"),
        ),
    }
}

/// The error of a NULL argument, to agree on.
fn null(e: super::ffi::NullArgument) -> Error {
    failed(e.into())
}

/// Creates this rank's part of a partitioned mesh; collective (every rank of `exchange` calls
/// it). `num_nodes` local nodes: `node_ids` their global ids (non-negative, each node owned by
/// exactly one rank), `owned` 1 where this rank owns the node else 0, `xyz` 3 coordinates each
/// (the reference shape). `num_cells` local cells: `cell_ids` their global ids, `connectivity`
/// their local node indices (`0..num_nodes`, VTK node order, `cell_type` the same on every
/// rank). The owner of a node must hold every cell around it (a one-cell halo); a cell held on
/// several ranks must have the same nodes everywhere. Global ids fix the order of the colouring
/// and of every sum: numbered as in the whole mesh, the result equals the whole mesh's.
///
/// A bad part on any rank (argument, NULL, a node owned twice or by no rank, a missing cell or
/// node) makes the call fail on every rank with the same message; only a bad `exchange` fails
/// on its own rank (the others then wait for it in their callback).
#[no_mangle]
pub extern "C" fn igaparam_partition_new(
    exchange: *const igaparam_exchange,
    cell_type_code: igaparam_cell_type,
    num_nodes: usize,
    node_ids: *const i64,
    owned: *const u8,
    xyz: *const f64,
    num_cells: usize,
    cell_ids: *const i64,
    connectivity: *const i64,
    out: *mut *mut igaparam_partition,
) -> igaparam_status {
    run("igaparam_partition_new", || {
        let mut host = host_exchange(exchange)?;
        let mut ranks = Ranks::new(&mut host);
        let ids = |p: *const i64, n: usize, name: &'static str| -> Result<Vec<u64>> {
            let raw = slice(p, n, name).map_err(null)?;
            let id = |(i, &g): (usize, &i64)| {
                u64::try_from(g)
                    .map_err(|_| Error::invalid(format!("{name}[{i}] = {g} is negative")))
            };
            raw.iter().enumerate().map(id).collect()
        };
        let node_ids = ids(node_ids, num_nodes, "node_ids");
        let cell_ids = ids(cell_ids, num_cells, "cell_ids");
        let input = (|| -> Result<PartInput<'_>> {
            let ct = cell_type(cell_type_code)?;
            let too_large = || Error::invalid("num_nodes or num_cells is too large");
            let n3 = num_nodes.checked_mul(3).ok_or_else(too_large)?;
            let nc = num_cells
                .checked_mul(ct.node_count())
                .ok_or_else(too_large)?;
            if out.is_null() {
                return Err(Error::invalid("argument `out` is NULL"));
            }
            Ok(PartInput {
                cell_type: ct,
                node_ids: node_ids.as_ref().map_err(Clone::clone)?,
                owned: slice(owned, num_nodes, "owned").map_err(null)?,
                xyz: slice(xyz, n3, "xyz").map_err(null)?,
                cell_ids: cell_ids.as_ref().map_err(Clone::clone)?,
                connectivity: slice(connectivity, nc, "connectivity").map_err(null)?,
            })
        })();
        let part = Partition::new(&mut ranks, input.as_ref().map_err(Clone::clone))?;
        *non_null_mut(out, "out")? = into_raw::<igaparam_partition>(part);
        Ok(())
    })
}

/// Releases a part. NULL is a no-op. Not collective. Called on a part in use (from the
/// progress callback of `igaparam_partition_relocate`, or from another thread), the release
/// waits for that call, which cancels on every rank at its next progress point.
#[no_mangle]
pub extern "C" fn igaparam_partition_free(part: *mut igaparam_partition) {
    release(part);
}

/// Writes the number of local nodes (owned and ghosts) to `*out`.
#[no_mangle]
pub extern "C" fn igaparam_partition_node_count(
    part: *const igaparam_partition,
    out: *mut usize,
) -> igaparam_status {
    run("igaparam_partition_node_count", || {
        *non_null_mut(out, "out")? = acquire(part, "part")?.node_count();
        Ok(())
    })
}

/// Sets the constraint mask of every local node (`num_nodes` entries, in the order given to
/// `igaparam_partition_new`; bits as in `igaparam_mesh_set_fixed`). A ghost copy takes its
/// owner's mask at the next relocation. Not collective.
#[no_mangle]
pub extern "C" fn igaparam_partition_set_fixed(
    part: *mut igaparam_partition,
    num_nodes: usize,
    mask: *const u8,
) -> igaparam_status {
    run("igaparam_partition_set_fixed", || {
        let mut p = acquire(part, "part")?;
        p.set_fixed(slice(mask, num_nodes, "mask")?)?;
        Ok(())
    })
}

/// Sets the current positions of all local nodes (`len` = 3 × num_nodes doubles, in the order
/// given to `igaparam_partition_new`), e.g. with the boundary moved. A ghost copy takes its
/// owner's position at the next relocation. Not collective.
#[no_mangle]
pub extern "C" fn igaparam_partition_set_positions(
    part: *mut igaparam_partition,
    len: usize,
    xyz: *const f64,
) -> igaparam_status {
    run("igaparam_partition_set_positions", || {
        let mut p = acquire(part, "part")?;
        p.set_positions(slice(xyz, len, "xyz")?)?;
        Ok(())
    })
}

/// Copies the current positions of the local nodes into `xyz` (`len` doubles, at least
/// 3 × num_nodes), in the order given to `igaparam_partition_new`. Not collective.
#[no_mangle]
pub extern "C" fn igaparam_partition_copy_positions(
    part: *const igaparam_partition,
    xyz: *mut f64,
    len: usize,
) -> igaparam_status {
    run("igaparam_partition_copy_positions", || {
        let p = acquire(part, "part")?;
        let positions = p.positions();
        check_capacity("xyz", len, positions.len())?;
        slice_mut(xyz, len, "xyz")?[..positions.len()].copy_from_slice(&positions);
        Ok(())
    })
}

/// Relocates the whole partitioned mesh on all ranks together; collective. The result equals,
/// bit for bit, `igaparam_mesh_relocate` of the whole mesh (numbered by the global ids) with
/// `IGAPARAM_METHOD_SWEEPS`, whatever the number of ranks. `IGAPARAM_METHOD_AUTO` means the
/// sweeps here; `IGAPARAM_METHOD_NEWTON` and `stationarity_tolerance > 0` are refused (they
/// need a factorisation of the whole Hessian). `options` may be NULL for the defaults; its
/// progress callback runs on every rank, and a cancellation on one cancels all. An error on
/// any rank fails the call on all with one message; the parts are then unchanged.
#[no_mangle]
pub extern "C" fn igaparam_partition_relocate(
    part: *mut igaparam_partition,
    exchange: *const igaparam_exchange,
    options: *const igaparam_relocate_options,
    report: *mut igaparam_partition_report,
) -> igaparam_status {
    run("igaparam_partition_relocate", || {
        let mut host = host_exchange(exchange)?;
        let mut ranks = Ranks::new(&mut host);
        let raw = options_or(options, igaparam_relocate_options_default());
        let opts = raw.to_core();
        let mut held = match acquire(part, "part") {
            Ok(held) => held,
            Err(f) => {
                let e = failed(f);
                ranks.agree(Err(e.clone()))?;
                return Err(e.into());
            }
        };
        let (handle, watch) = held.split();
        let mut relocation = relocation_progress(&raw);
        let mut progress =
            |stage, done, total| relocation(stage, done, total) && !watch.requested();
        let r = handle
            .relocate(&mut ranks, opts, &mut progress)
            .map_err(|e| watch.explain(e))?;
        write_optional(report, igaparam_partition_report::from(&r));
        Ok(())
    })
}
