//! A split of a supernodal Cholesky factor's elimination tree into two sets of whole subtrees,
//! whose parts of a triangular solve are independent (two threads run them), and the supernodes
//! above them, the top, solved after them (forward) or before them (backward).
//!
//! The split depends on the factor's structure alone, never on the thread count, and the solve
//! follows it on any number of threads: the result is the same on one thread as on two. Each
//! part works on its own copy of its columns followed by the top's, so its supernodes' patterns
//! are stored again in that local numbering; the forward pass's updates of the top's unknowns
//! are summed per part, then added part by part in a fixed order.
//!
//! The subtrees are chosen greedily (Geist and Ng's scheme): starting from the roots, the
//! heaviest subtree of the frontier is replaced by its children, up to 64 times or a leaf; of
//! the frontiers met, the one of the least estimated time is kept: the larger part's work plus
//! the top's, the frontier's subtrees dealt to the two parts, heaviest first, each to the
//! lighter part. Work is counted in factor values.

use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;

/// Factors with fewer values are solved whole: splitting them saves less than handing half the
/// solve to another thread costs (twice a solve, tens of microseconds each on a shared
/// machine). Measured on the refined airfoil, runs alternated: its 2,060-node mesh (a factor of
/// 198,152 values) made warm loop steps slower split, 5.4–6.0 → 7.8–7.9 ms; 8,040 nodes
/// (1,076,840 values) relocate in 0.17–0.20 s against 0.20–0.21 s whole, 17,940 nodes (2.9
/// million) in 0.84–0.85 s against 1.01–1.03 s, 96,740 nodes in 25.4–26.1 s against 28.3–29.1
/// s, the same iterations.
pub(super) const SMALLEST: usize = 1_000_000;

/// Frontier expansions tried.
const EXPANSIONS: usize = 64;

/// A split is kept where its estimated time is at most this fraction of the whole solve's.
const WORTHWHILE: f64 = 0.75;

/// Marks a supernode of the top.
const TOP: usize = usize::MAX;

/// One part: whole subtrees of the elimination tree, with their patterns in its local numbering
/// (its own columns first, in ascending order, then the top's).
pub struct Part {
    /// The supernodes, ascending.
    pub nodes: Vec<usize>,
    /// Per supernode, its first column in the local numbering.
    pub starts: Vec<usize>,
    /// Per supernode, where its pattern starts in `rows` (one more entry at the end).
    pub pointers: Vec<usize>,
    /// The patterns, in the local numbering.
    pub rows: Vec<usize>,
    /// The factor's column of each of the part's own local columns.
    pub columns: Vec<usize>,
}

/// Two parts solved independently and the top.
pub struct Split {
    /// The two parts.
    pub parts: [Part; 2],
    /// The top's supernodes, ascending.
    pub top: Vec<usize>,
    /// The top's columns, ascending (the local numbering's last ones in each part).
    pub top_columns: Vec<usize>,
}

/// The tree of supernodes: each one's parent and children, the factor values of each subtree,
/// and the supernode of each column (`owner`).
struct Tree {
    parent: Vec<Option<usize>>,
    children: Vec<Vec<usize>>,
    subtree: Vec<usize>,
    owner: Vec<usize>,
}

impl Tree {
    /// The tree of `symbolic`; `None` where a parent does not follow its child (not a factor's
    /// tree).
    fn new(symbolic: &SymbolicSupernodalCholesky<usize>) -> Option<Self> {
        let (begin, end) = (symbolic.supernode_begin(), symbolic.supernode_end());
        let count = symbolic.n_supernodes();
        let mut owner = vec![0; end.last().copied().unwrap_or(0)];
        for s in 0..count {
            owner[begin[s]..end[s]].fill(s);
        }
        let mut tree = Tree {
            parent: vec![None; count],
            children: vec![Vec::new(); count],
            subtree: vec![0; count],
            owner,
        };
        for s in 0..count {
            let pattern = symbolic.supernode(s).pattern();
            let columns = end[s] - begin[s];
            tree.subtree[s] += (columns + pattern.len()) * columns;
            if let Some(&row) = pattern.first() {
                let p = tree.owner[row];
                if p <= s {
                    return None;
                }
                (tree.parent[s], tree.subtree[p]) = (Some(p), tree.subtree[p] + tree.subtree[s]);
                tree.children[p].push(s);
            }
        }
        Some(tree)
    }

    /// The frontier's subtrees dealt to two parts, heaviest first, each to the lighter part;
    /// the parts' roots and work.
    fn deal(&self, frontier: &[usize]) -> ([Vec<usize>; 2], [usize; 2]) {
        let mut sorted = frontier.to_vec();
        sorted.sort_by_key(|&s| (std::cmp::Reverse(self.subtree[s]), s));
        let (mut roots, mut work) = ([Vec::new(), Vec::new()], [0, 0]);
        for s in sorted {
            let lighter = usize::from(work[1] < work[0]);
            roots[lighter].push(s);
            work[lighter] += self.subtree[s];
        }
        (roots, work)
    }
}

impl Split {
    /// The split of the factor with structure `symbolic`; `None` where solving it whole is
    /// as fast: fewer than `smallest` values ([`SMALLEST`] but in tests), or a tree without two
    /// balanced subtrees.
    pub fn new(symbolic: &SymbolicSupernodalCholesky<usize>, smallest: usize) -> Option<Self> {
        if symbolic.len_val() < smallest {
            return None;
        }
        let tree = Tree::new(symbolic)?;
        let count = tree.parent.len();
        let mut frontier: Vec<usize> = (0..count).filter(|&s| tree.parent[s].is_none()).collect();
        let total: usize = frontier.iter().map(|&s| tree.subtree[s]).sum();
        let mut best: Option<(usize, [Vec<usize>; 2])> = None;
        for _ in 0..EXPANSIONS {
            let (roots, work) = tree.deal(&frontier);
            let cost = work[0].max(work[1]) + (total - work[0] - work[1]);
            if best.as_ref().is_none_or(|(c, _)| cost < *c) {
                best = Some((cost, roots));
            }
            let weight = |i: usize| (tree.subtree[frontier[i]], std::cmp::Reverse(frontier[i]));
            let Some(heaviest) = (0..frontier.len()).max_by_key(|&i| weight(i)) else {
                break;
            };
            if tree.children[frontier[heaviest]].is_empty() {
                break;
            }
            let s = frontier.swap_remove(heaviest);
            frontier.extend(&tree.children[s]);
        }
        let (cost, roots) = best?;
        if cost as f64 > WORTHWHILE * total as f64 {
            return None;
        }
        Self::of_roots(symbolic, &tree, &roots)
    }

    /// The split whose parts are the subtrees of `roots`.
    fn of_roots(
        symbolic: &SymbolicSupernodalCholesky<usize>,
        tree: &Tree,
        roots: &[Vec<usize>; 2],
    ) -> Option<Self> {
        let count = tree.parent.len();
        let mut assigned = vec![TOP; count];
        for (part, roots) in roots.iter().enumerate() {
            for &s in roots {
                assigned[s] = part;
            }
        }
        for s in (0..count).rev() {
            if let (TOP, Some(p)) = (assigned[s], tree.parent[s]) {
                assigned[s] = assigned[p];
            }
        }
        let (begin, end) = (symbolic.supernode_begin(), symbolic.supernode_end());
        let top: Vec<usize> = (0..count).filter(|&s| assigned[s] == TOP).collect();
        // The top's patterns stay in the top (its supernodes' ancestors), as the solve assumes.
        let above = |s: usize| {
            symbolic
                .supernode(s)
                .pattern()
                .iter()
                .all(|&r| assigned[tree.owner[r]] == TOP)
        };
        if !top.iter().all(|&s| above(s)) {
            return None;
        }
        let top_columns: Vec<usize> = top.iter().flat_map(|&s| begin[s]..end[s]).collect();
        let mut local = vec![0; tree.owner.len()];
        let part = |p: usize, local: &mut Vec<usize>| {
            Part::new(symbolic, (tree, &assigned, p), &top_columns, local)
        };
        let parts = [part(0, &mut local)?, part(1, &mut local)?];
        Some(Split {
            parts,
            top,
            top_columns,
        })
    }
}

impl Part {
    /// Part `p` of the supernodes `assigned` to parts in `tree`; `None` where a pattern reaches
    /// the other part (not a split of the tree). `local` is scratch of one entry per column.
    fn new(
        symbolic: &SymbolicSupernodalCholesky<usize>,
        (tree, assigned, p): (&Tree, &[usize], usize),
        top_columns: &[usize],
        local: &mut [usize],
    ) -> Option<Self> {
        let (begin, end) = (symbolic.supernode_begin(), symbolic.supernode_end());
        let nodes: Vec<usize> = (0..assigned.len()).filter(|&s| assigned[s] == p).collect();
        let columns: Vec<usize> = nodes.iter().flat_map(|&s| begin[s]..end[s]).collect();
        for (i, &c) in columns.iter().chain(top_columns).enumerate() {
            local[c] = i;
        }
        let mut part = Part {
            starts: nodes.iter().map(|&s| local[begin[s]]).collect(),
            pointers: vec![0],
            rows: Vec::new(),
            nodes,
            columns,
        };
        for &s in &part.nodes {
            for &row in symbolic.supernode(s).pattern() {
                let owner = assigned[tree.owner[row]];
                if owner != p && owner != TOP {
                    return None;
                }
                part.rows.push(local[row]);
            }
            part.pointers.push(part.rows.len());
        }
        Some(part)
    }
}
