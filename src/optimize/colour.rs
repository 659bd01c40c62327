//! Colouring of the free nodes so that no two nodes of one colour share a cell: the nodes of a
//! colour can then be optimized in parallel with the result of a sequential sweep.

use super::problem::Problem;

/// Greedy colouring in node order (deterministic). Returns the nodes of each colour, in order.
pub fn colour_nodes<const D: usize>(problem: &Problem<D>, nodes: &[usize]) -> Vec<Vec<usize>> {
    const NONE: u32 = u32::MAX;
    let mut colour = vec![NONE; problem.node_count()];
    let mut classes: Vec<Vec<usize>> = Vec::new();
    let mut used: Vec<bool> = Vec::new();
    for &n in nodes {
        used.iter_mut().for_each(|u| *u = false);
        for &(c, _) in problem.incident_cells(n) {
            for &m in problem.cell_nodes(c as usize) {
                let k = colour[m as usize];
                if k != NONE {
                    used[k as usize] = true;
                }
            }
        }
        let k = used.iter().position(|&u| !u).unwrap_or(used.len());
        if k == classes.len() {
            classes.push(Vec::new());
            used.push(false);
        }
        colour[n] = k as u32;
        classes[k].push(n);
    }
    classes
}
