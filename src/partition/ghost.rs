//! The plan of a partition's ghost refreshes: which owned values go to which rank, which ghosts
//! come from which.

use super::exchange::{read_words, Ranks};
use crate::error::Result;

/// Where ghost values come from: per rank, the local nodes whose values are sent to it and the
/// local ghosts filled from it, in ascending global id.
#[derive(Clone, Debug, Default)]
pub struct GhostPlan {
    pub(super) send: Vec<Vec<u32>>,
    pub(super) recv: Vec<Vec<u32>>,
}

impl GhostPlan {
    /// Copies `width` values per node from the owners to the ghost copies. Collective.
    pub fn refresh(&self, ranks: &mut Ranks<'_>, values: &mut [f64], width: usize) -> Result<()> {
        let send: Vec<Vec<u8>> = self
            .send
            .iter()
            .map(|nodes| {
                let v = nodes.iter().map(|&i| i as usize * width);
                v.flat_map(|i| values[i..i + width].iter().flat_map(|x| x.to_le_bytes()))
                    .collect()
            })
            .collect();
        let counts: Vec<usize> = self.recv.iter().map(|r| r.len() * width * 8).collect();
        let got = ranks.known(&send, &counts)?;
        for (nodes, bytes) in self.recv.iter().zip(got) {
            let x = read_words(&bytes);
            for (k, &i) in nodes.iter().enumerate() {
                for j in 0..width {
                    values[i as usize * width + j] = f64::from_bits(x[k * width + j]);
                }
            }
        }
        Ok(())
    }
}
