//! Communication among the ranks of a partition through the host's exchange: one collective
//! primitive (an all-to-all of bytes, as `MPI_Alltoallv`), on which the library builds its
//! ghost refreshes, reductions and agreements. The library never calls MPI itself.

use std::time::Instant;

use crate::error::{Error, ErrorKind, Result};

/// The host's collective exchange among the ranks of its communicator.
pub trait Exchange {
    /// Number of ranks.
    fn size(&self) -> usize;
    /// This rank, in `0..size()`.
    fn rank(&self) -> usize;
    /// Sends `send_counts[r]` bytes to each rank `r` (the blocks of `send` in rank order) and
    /// receives `recv_counts[r]` bytes from each into `recv` (in rank order). Collective: every
    /// rank calls it with matching counts. `send` and `recv` are distinct, never empty buffers.
    fn exchange(
        &mut self,
        send_counts: &[usize],
        send: &[u8],
        recv_counts: &[usize],
        recv: &mut [u8],
    ) -> Result<()>;
}

/// The ranks of a partition seen through an [`Exchange`], with the time spent in it.
pub struct Ranks<'a> {
    exchange: &'a mut dyn Exchange,
    /// Seconds spent in the host's exchange.
    pub seconds: f64,
    /// Calls of the host's exchange.
    pub calls: usize,
}

impl<'a> Ranks<'a> {
    /// The ranks of `exchange`.
    pub fn new(exchange: &'a mut dyn Exchange) -> Self {
        Ranks {
            exchange,
            seconds: 0.0,
            calls: 0,
        }
    }

    /// Number of ranks.
    pub fn size(&self) -> usize {
        self.exchange.size()
    }

    /// This rank.
    pub fn rank(&self) -> usize {
        self.exchange.rank()
    }

    /// Sends `send[r]` to rank `r`, knowing that `recv_counts[r]` bytes come from each.
    pub fn known(&mut self, send: &[Vec<u8>], recv_counts: &[usize]) -> Result<Vec<Vec<u8>>> {
        let counts: Vec<usize> = send.iter().map(Vec::len).collect();
        // Buffers are never empty, so the host's send and receive pointers always differ
        // (MPI refuses equal ones).
        let mut flat: Vec<u8> = send.concat();
        if flat.is_empty() {
            flat.push(0);
        }
        let total = recv_counts
            .iter()
            .try_fold(0usize, |a, &b| a.checked_add(b))
            .ok_or_else(|| Error::invalid("exchange too large"))?;
        let mut recv = vec![0u8; total.max(1)];
        let start = Instant::now();
        let result = self
            .exchange
            .exchange(&counts, &flat, recv_counts, &mut recv);
        self.seconds += start.elapsed().as_secs_f64();
        self.calls += 1;
        result?;
        let mut out = Vec::with_capacity(recv_counts.len());
        let mut at = 0;
        for &c in recv_counts {
            out.push(recv[at..at + c].to_vec());
            at += c;
        }
        Ok(out)
    }

    /// Sends `send[r]` to rank `r`; returns what each rank sent here.
    pub fn all_to_all(&mut self, send: &[Vec<u8>]) -> Result<Vec<Vec<u8>>> {
        let p = self.size();
        if send.len() != p {
            return Err(Error::invalid("one message per rank is needed"));
        }
        let counts: Vec<Vec<u8>> = send.iter().map(|m| words(&[m.len() as u64])).collect();
        let received = self.known(&counts, &vec![8; p])?;
        let recv_counts = received
            .iter()
            .map(|b| read_words(b).first().map(|&c| c as usize))
            .collect::<Option<Vec<usize>>>()
            .ok_or_else(|| exchange_failed("a count was lost"))?;
        self.known(send, &recv_counts)
    }

    /// Sends `message` to every rank; returns every rank's message, in rank order.
    pub fn all_gather(&mut self, message: &[u8]) -> Result<Vec<Vec<u8>>> {
        let p = self.size();
        self.all_to_all(&vec![message.to_vec(); p])
    }

    /// Every rank's words of equal length `n`, in rank order.
    pub fn all_gather_words(&mut self, message: &[u64]) -> Result<Vec<Vec<u64>>> {
        let p = self.size();
        let bytes = words(message);
        let got = self.known(&vec![bytes.clone(); p], &vec![bytes.len(); p])?;
        Ok(got.iter().map(|b| read_words(b)).collect())
    }

    /// Agrees on the outcome of a step: when it failed on some rank, every rank returns the
    /// error of the lowest such rank, prefixed by its number.
    pub fn agree(&mut self, local: Result<()>) -> Result<()> {
        let mine = match &local {
            Ok(()) => Vec::new(),
            Err(e) => {
                let mut m = vec![kind_code(e.kind)];
                m.extend_from_slice(e.message.as_bytes());
                m
            }
        };
        let all = self.all_gather(&mine)?;
        match all.iter().enumerate().find(|(_, m)| !m.is_empty()) {
            None => Ok(()),
            Some((rank, m)) => Err(Error::new(
                kind_of(m[0]),
                format!("rank {rank}: {}", String::from_utf8_lossy(&m[1..])),
            )),
        }
    }
}

/// An error of the host's exchange.
pub fn exchange_failed(why: &str) -> Error {
    Error::new(
        ErrorKind::Io,
        format!("the exchange among ranks failed: {why}"),
    )
}

fn kind_code(kind: ErrorKind) -> u8 {
    ALL_KINDS.iter().position(|&k| k == kind).unwrap_or(0) as u8
}

fn kind_of(code: u8) -> ErrorKind {
    ALL_KINDS
        .get(code as usize)
        .copied()
        .unwrap_or(ErrorKind::InvalidMesh)
}

/// The kinds an agreement carries from rank to rank.
const ALL_KINDS: [ErrorKind; 6] = [
    ErrorKind::InvalidMesh,
    ErrorKind::InvalidArgument,
    ErrorKind::NotFinite,
    ErrorKind::Cancelled,
    ErrorKind::BufferTooSmall,
    ErrorKind::Io,
];

/// Little-endian bytes of words.
pub fn words(w: &[u64]) -> Vec<u8> {
    w.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// Words of little-endian bytes (a trailing partial word is dropped).
pub fn read_words(b: &[u8]) -> Vec<u64> {
    b.chunks_exact(8)
        .map(|c| u64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
        .collect()
}
