//! A mesh partitioned over ranks (threads here, through an in-process exchange) relocates to the
//! positions of the whole mesh's sweeps, bit for bit, at every rank count; bad partitions are
//! refused on every rank with one message.

use std::sync::{Arc, Barrier, Mutex};

use igaparam::fe_mesh::{CellType, Mesh, Method, RelocateOptions};
use igaparam::partition::{Exchange, PartInput, Partition, Ranks};
use igaparam::threads::{cores, MAX_THREADS};
use igaparam::Result;

/// All-to-all among threads: each writes its blocks into the mailbox, waits, reads its own.
struct Hub {
    mailbox: Mutex<Vec<Vec<Vec<u8>>>>,
    barrier: Barrier,
}

struct ThreadRank {
    hub: Arc<Hub>,
    rank: usize,
    size: usize,
}

impl Exchange for ThreadRank {
    fn size(&self) -> usize {
        self.size
    }
    fn rank(&self) -> usize {
        self.rank
    }
    fn exchange(&mut self, sc: &[usize], send: &[u8], rc: &[usize], recv: &mut [u8]) -> Result<()> {
        let mut at = 0;
        {
            let mut mail = self.hub.mailbox.lock().unwrap();
            for (r, &c) in sc.iter().enumerate() {
                mail[r][self.rank] = send[at..at + c].to_vec();
                at += c;
            }
        }
        self.hub.barrier.wait();
        {
            let mail = self.hub.mailbox.lock().unwrap();
            let mut at = 0;
            for (r, &c) in rc.iter().enumerate() {
                assert_eq!(mail[self.rank][r].len(), c, "receive count");
                recv[at..at + c].copy_from_slice(&mail[self.rank][r]);
                at += c;
            }
        }
        self.hub.barrier.wait();
        Ok(())
    }
}

/// Runs `body(rank, exchange)` on `size` threads.
fn on_ranks<T: Send + 'static>(
    size: usize,
    body: impl Fn(usize, &mut dyn Exchange) -> T + Send + Sync + 'static,
) -> Vec<T> {
    let hub = Arc::new(Hub {
        mailbox: Mutex::new(vec![vec![Vec::new(); size]; size]),
        barrier: Barrier::new(size),
    });
    let body = Arc::new(body);
    let handles: Vec<_> = (0..size)
        .map(|rank| {
            let (hub, body) = (hub.clone(), body.clone());
            std::thread::spawn(move || body(rank, &mut ThreadRank { hub, rank, size }))
        })
        .collect();
    handles.into_iter().map(|h| h.join().unwrap()).collect()
}

/// A Q4 grid on [0,3]×[0,1] whose top side bulges; boundary nodes fixed.
struct Case {
    xyz: Vec<f64>,
    moved: Vec<f64>,
    fixed: Vec<u8>,
    conn: Vec<i64>,
}

fn case() -> Case {
    let (nx, ny) = (12usize, 5usize);
    let mut xyz = Vec::new();
    let mut moved = Vec::new();
    let mut fixed = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let (x, y) = (3.0 * i as f64 / nx as f64, j as f64 / ny as f64);
            xyz.extend([x, y, 0.0]);
            let lift = if j == ny {
                0.35 * (std::f64::consts::PI * x / 3.0).sin()
            } else {
                0.0
            };
            moved.extend([x, y + lift, 0.0]);
            fixed.push(if i == 0 || j == 0 || i == nx || j == ny {
                3
            } else {
                0
            });
        }
    }
    let id = |i: usize, j: usize| (j * (nx + 1) + i) as i64;
    let mut conn = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            conn.extend([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    Case {
        xyz,
        moved,
        fixed,
        conn,
    }
}

fn options() -> RelocateOptions {
    options_with(1)
}

fn options_with(threads: usize) -> RelocateOptions {
    RelocateOptions {
        method: Method::Sweeps,
        threads,
        ..Default::default()
    }
}

/// The threads of this process now (Linux: /proc/self/status), 0 where unknown.
fn process_threads() -> usize {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("Threads:"))
                .and_then(|n| n.trim().parse().ok())
        })
        .unwrap_or(0)
}

/// A rank's part: strips of cells by centre x, nodes owned by the lowest rank holding them,
/// the cells around owned nodes added (`halo`).
struct Part {
    gids: Vec<u64>,
    owned: Vec<u8>,
    xyz: Vec<f64>,
    moved: Vec<f64>,
    fixed: Vec<u8>,
    cells: Vec<u64>,
    conn: Vec<i64>,
}

fn part_of(c: &Case, rank: usize, size: usize, halo: bool) -> Part {
    let cells = c.conn.len() / 4;
    let nodes = c.fixed.len();
    let rank_of: Vec<usize> = (0..cells)
        .map(|k| {
            let x: f64 = c.conn[4 * k..4 * k + 4]
                .iter()
                .map(|&v| c.xyz[3 * v as usize])
                .sum();
            ((x / 4.0 / 3.0 * size as f64) as usize).min(size - 1)
        })
        .collect();
    let mut owner = vec![usize::MAX; nodes];
    for (cell, &r) in c.conn.chunks(4).zip(&rank_of) {
        for &v in cell {
            owner[v as usize] = owner[v as usize].min(r);
        }
    }
    let take: Vec<usize> = (0..cells)
        .filter(|&k| {
            rank_of[k] == rank
                || (halo
                    && c.conn[4 * k..4 * k + 4]
                        .iter()
                        .any(|&v| owner[v as usize] == rank))
        })
        .collect();
    let mut local = vec![usize::MAX; nodes];
    let mut p = Part {
        gids: Vec::new(),
        owned: Vec::new(),
        xyz: Vec::new(),
        moved: Vec::new(),
        fixed: Vec::new(),
        cells: Vec::new(),
        conn: Vec::new(),
    };
    // Nodes in reverse id order, to show that the local order does not matter.
    let mut used: Vec<usize> = take
        .iter()
        .flat_map(|&k| c.conn[4 * k..4 * k + 4].iter().map(|&v| v as usize))
        .collect();
    used.sort_unstable();
    used.dedup();
    for &v in used.iter().rev() {
        local[v] = p.gids.len();
        p.gids.push(v as u64);
        p.owned.push((owner[v] == rank) as u8);
        p.xyz.extend_from_slice(&c.xyz[3 * v..3 * v + 3]);
        p.moved.extend_from_slice(&c.moved[3 * v..3 * v + 3]);
        p.fixed.push(c.fixed[v]);
    }
    for &k in take.iter().rev() {
        p.cells.push(k as u64);
        p.conn.extend(
            c.conn[4 * k..4 * k + 4]
                .iter()
                .map(|&v| local[v as usize] as i64),
        );
    }
    p
}

fn input(p: &Part) -> PartInput<'_> {
    PartInput {
        cell_type: CellType::from_vtk(9).unwrap(),
        node_ids: &p.gids,
        owned: &p.owned,
        xyz: &p.xyz,
        cell_ids: &p.cells,
        connectivity: &p.conn,
    }
}

/// Relocates on `size` ranks; returns the whole mesh's positions from the owners.
fn relocate_on(size: usize) -> Vec<f64> {
    relocate_with(size, 1).0
}

/// Relocates on `size` ranks with `threads` per rank; returns the whole mesh's positions from
/// the owners and the most threads the process had at a progress call.
fn relocate_with(size: usize, threads: usize) -> (Vec<f64>, usize) {
    let parts = on_ranks(size, move |rank, ex| {
        let c = case();
        let p = part_of(&c, rank, size, true);
        let mut ranks = Ranks::new(ex);
        let mut part = Partition::new(&mut ranks, Ok(&input(&p))).unwrap();
        part.set_fixed(&p.fixed).unwrap();
        part.set_positions(&p.moved).unwrap();
        let mut most = 0;
        let mut progress = |_, _, _| {
            most = most.max(process_threads());
            true
        };
        let report = part
            .relocate(&mut ranks, Ok(options_with(threads)), &mut progress)
            .unwrap();
        assert_eq!(report.relocation.invalid_after, 0);
        assert_eq!(report.relocation.cells, c.conn.len() / 4);
        (p, part.positions(), most)
    });
    let mut whole = case().moved;
    let most = parts.iter().map(|p| p.2).max().unwrap_or(0);
    for (p, x, _) in parts {
        for (l, &g) in p.gids.iter().enumerate() {
            if p.owned[l] == 1 {
                whole[3 * g as usize..3 * g as usize + 3].copy_from_slice(&x[3 * l..3 * l + 3]);
            }
        }
    }
    (whole, most)
}

#[test]
fn ranks_reproduce_the_whole_mesh_bit_for_bit() {
    let c = case();
    let mut mesh = Mesh::new(CellType::from_vtk(9).unwrap(), &c.xyz, &c.conn).unwrap();
    mesh.set_fixed(&c.fixed).unwrap();
    mesh.move_nodes(None, &c.moved).unwrap();
    let report = mesh.relocate(&options(), &mut |_, _, _| true).unwrap();
    assert_eq!(report.invalid_after, 0);
    assert!(report.sweeps > 1);
    let serial: Vec<f64> = mesh.positions().iter().flatten().copied().collect();
    assert_ne!(serial, c.moved, "the interior moved");
    for size in 1..=3 {
        let parted = relocate_on(size);
        let same = serial
            .iter()
            .zip(&parted)
            .all(|(a, b)| a.to_bits() == b.to_bits());
        assert!(same, "{size} ranks differ from the whole mesh");
    }
}

/// The thread count is capped to the cores on a partition too: 4096 per rank starts no more
/// threads than the machine has cores (per rank), and gives the 1-thread result bit for bit.
#[test]
fn partition_thread_counts_are_capped_to_the_cores() {
    let (one, _) = relocate_with(2, 1);
    let (many, most) = relocate_with(2, MAX_THREADS);
    assert!(one
        .iter()
        .zip(&many)
        .all(|(a, b)| a.to_bits() == b.to_bits()));
    // The test harness's own threads, the two ranks and their pools: far below 4096.
    assert!(
        most > 0 && most < 64 + 2 * cores(),
        "{most} threads at once"
    );
}

/// Builds the parts on 3 ranks after `spoil(rank, part)`; returns every rank's error message.
fn refused(spoil: impl Fn(usize, &mut Part) + Send + Sync + 'static, halo: bool) -> Vec<String> {
    on_ranks(3, move |rank, ex| {
        let mut p = part_of(&case(), rank, 3, halo);
        spoil(rank, &mut p);
        let mut ranks = Ranks::new(ex);
        match Partition::new(&mut ranks, Ok(&input(&p))) {
            Ok(_) => String::new(),
            Err(e) => e.message,
        }
    })
}

fn assert_refused_everywhere(messages: &[String], needle: &str) {
    assert!(
        !messages[0].is_empty(),
        "the partition was accepted ({needle})"
    );
    assert!(messages.iter().all(|m| m == &messages[0]), "{messages:?}");
    assert!(messages[0].contains(needle), "{}", messages[0]);
}

#[test]
fn bad_partitions_are_refused_on_every_rank() {
    // Rank 1 also claims every node it holds.
    let twice = refused(
        |rank, p| {
            if rank == 1 {
                p.owned.iter_mut().for_each(|o| *o = 1)
            }
        },
        true,
    );
    assert_refused_everywhere(&twice, "owned by 2 ranks");
    // Rank 0 gives up its nodes: those only it holds have no owner.
    let nobody = refused(
        |rank, p| {
            if rank == 0 {
                p.owned.iter_mut().for_each(|o| *o = 0)
            }
        },
        true,
    );
    assert_refused_everywhere(&nobody, "owned by no rank");
    // No halo: owners of interface nodes lack cells around them.
    assert_refused_everywhere(&refused(|_, _| {}, false), "lacks its cell");
    // A cell refers to a node the part does not have.
    let absent = refused(
        |rank, p| {
            if rank == 2 {
                p.conn[0] = p.gids.len() as i64
            }
        },
        true,
    );
    assert_refused_everywhere(&absent, "rank 2: cell");
    // A ghost that no rank owns (rank 2 renames one of its ghosts).
    let ghost = refused(
        |rank, p| {
            if rank == 2 {
                let l = p.owned.iter().position(|&o| o == 0).unwrap();
                p.gids[l] = 1_000_000;
            }
        },
        true,
    );
    assert_refused_everywhere(&ghost, "node");
}

#[test]
fn newton_is_refused_on_every_rank() {
    let messages = on_ranks(2, |rank, ex| {
        let p = part_of(&case(), rank, 2, true);
        let mut ranks = Ranks::new(ex);
        let mut part = Partition::new(&mut ranks, Ok(&input(&p))).unwrap();
        let mut o = options();
        if rank == 1 {
            o.method = Method::Newton;
        }
        part.relocate(&mut ranks, Ok(o), &mut |_, _, _| true)
            .unwrap_err()
            .message
    });
    assert!(
        messages
            .iter()
            .all(|m| m.starts_with("rank 1: ") && m.contains("SWEEPS")),
        "{messages:?}"
    );
}
