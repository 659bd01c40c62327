//! Solves with a supernodal Cholesky factor computed by faer, `L Lᵀ x = b`, by plain loops over
//! its supernodes.
//!
//! Hand-written because it is the hot path of warm relocations in a loop (a dozen solves per
//! step): faer's solve goes through its dense kernels supernode by supernode (a triangular
//! solve and a matrix-vector product, each dispatched at run time), and on the small supernodes
//! of a mesh Hessian that dispatch costs more than the arithmetic. On the bundled airfoil's
//! Hessian (3,720 unknowns, 213,172 factor values in 578 supernodes, half of them of 2 columns)
//! a solve takes 130–140 µs here against faer's 165–175 µs, the same result to round-off.
//!
//! The loops read the factor in faer's layout: per supernode, its columns one after the other,
//! each with the supernode's diagonal-block rows first, then the rows of its pattern. They
//! multiply by the reciprocals of the diagonal values, computed once per factor
//! ([`reciprocal_diagonal`]), where a division lengthened the chain of dependent operations down
//! a supernode's columns, and sum the backward pass's dot products by four partial sums: together
//! 198–203 → 188–194 µs a solve of that Hessian (warm relocation steps, alternated runs, in a
//! slower hour than the figures above). The values are single precision (`sparse::Factor`),
//! the arithmetic double: the airfoil's warm loop steps 6.2–6.5 → 6.0–6.2 ms. A factor of a
//! million values or more whose tree has two balanced parts is solved in two parts on two
//! threads (`subtrees.rs`).

use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use rayon::ThreadPool;

use super::subtrees::{Part, Split};

/// One supernode: its first column, its columns' count, its pattern (the rows below its
/// diagonal block), both in the numbering of the vector solved, its values (column-major,
/// `columns + pattern.len()` rows) and the reciprocals of its diagonal values.
struct Supernode<'a> {
    start: usize,
    columns: usize,
    pattern: &'a [usize],
    values: &'a [f32],
    inverse: &'a [f64],
}

impl<'a> Supernode<'a> {
    /// Supernode `s` of the factor with structure `symbolic` and values `values`, in the
    /// factor's own numbering, without the reciprocals of its diagonal values (empty).
    fn of(symbolic: &'a SymbolicSupernodalCholesky<usize>, values: &'a [f32], s: usize) -> Self {
        let (begin, end) = (symbolic.supernode_begin(), symbolic.supernode_end());
        let pointers = symbolic.col_ptr_for_val();
        Supernode {
            start: begin[s],
            columns: end[s] - begin[s],
            pattern: symbolic.supernode(s).pattern(),
            values: &values[pointers[s]..pointers[s + 1]],
            inverse: &[],
        }
    }

    /// Column `j` of the supernode: its diagonal-block part from the diagonal down, and its
    /// pattern part.
    fn column(&self, j: usize) -> (&[f32], &[f32]) {
        let rows = self.columns + self.pattern.len();
        let column = &self.values[j * rows..(j + 1) * rows];
        let (block, below) = column.split_at(self.columns);
        (&block[j..], below)
    }
}

/// A factor: its structure, its values and the reciprocals of its diagonal values.
#[derive(Clone, Copy)]
pub struct FactorRef<'a> {
    /// The structure.
    pub symbolic: &'a SymbolicSupernodalCholesky<usize>,
    /// The values, in faer's layout.
    pub values: &'a [f32],
    /// [`reciprocal_diagonal`] of the values.
    pub inverse: &'a [f64],
}

impl<'a> FactorRef<'a> {
    /// Supernode `s`, in the factor's own numbering.
    fn supernode(&self, s: usize) -> Supernode<'a> {
        let node = Supernode::of(self.symbolic, self.values, s);
        Supernode {
            inverse: &self.inverse[node.start..node.start + node.columns],
            ..node
        }
    }

    /// The supernodes of `part`, in its local numbering.
    fn part_nodes(self, part: &'a Part) -> impl DoubleEndedIterator<Item = Supernode<'a>> {
        (0..part.nodes.len()).map(move |i| Supernode {
            start: part.starts[i],
            pattern: &part.rows[part.pointers[i]..part.pointers[i + 1]],
            ..self.supernode(part.nodes[i])
        })
    }
}

/// `1 / L_jj` for every column `j` of the factor with structure `symbolic` and values `values`.
pub fn reciprocal_diagonal(
    symbolic: &SymbolicSupernodalCholesky<usize>,
    values: &[f32],
) -> Vec<f64> {
    (0..symbolic.n_supernodes())
        .map(|s| Supernode::of(symbolic, values, s))
        .flat_map(|node| (0..node.columns).map(move |j| 1.0 / f64::from(node.column(j).0[0])))
        .collect()
}

/// Solves `L Lᵀ x = b` in place (`x` holds `b` on entry), the unknowns in the factor's own
/// order; with `split`, its two parts on two threads of `pool` where it has them (the same
/// result on one).
pub fn solve(pool: &ThreadPool, factor: FactorRef<'_>, split: Option<&Split>, x: &mut [f64]) {
    let mut below = Vec::new();
    let Some(split) = split else {
        let all = (0..factor.symbolic.n_supernodes()).map(|s| factor.supernode(s));
        forward(all.clone(), x, &mut below);
        backward(all.rev(), x, &mut below);
        return;
    };
    let top = &split.top_columns;
    let [a, b] = &split.parts;
    let parts = pool.join(
        || forward_part(factor, a, top, x),
        || forward_part(factor, b, top, x),
    );
    let updates = [parts.0, parts.1];
    write_back(split, &updates, x);
    // The top's unknowns less the parts' updates, part by part (a fixed order).
    for (j, &c) in top.iter().enumerate() {
        let [da, db] = [0, 1].map(|p| updates[p][split.parts[p].columns.len() + j]);
        x[c] = (x[c] + da) + db;
    }
    let top_nodes = split.top.iter().map(|&s| factor.supernode(s));
    forward(top_nodes.clone(), x, &mut below);
    backward(top_nodes.rev(), x, &mut below);
    let parts = pool.join(
        || backward_part(factor, a, top, x),
        || backward_part(factor, b, top, x),
    );
    write_back(split, &[parts.0, parts.1], x);
}

/// Each part's own columns of `x` from the first values of its local vector.
fn write_back(split: &Split, locals: &[Vec<f64>; 2], x: &mut [f64]) {
    for (part, local) in split.parts.iter().zip(locals) {
        for (&c, v) in part.columns.iter().zip(local) {
            x[c] = *v;
        }
    }
}

/// The forward pass of `part` on a copy of its columns of `x`: its columns solved, followed by
/// its (negated) updates of the `top` columns.
fn forward_part(factor: FactorRef<'_>, part: &Part, top: &[usize], x: &[f64]) -> Vec<f64> {
    let mut local: Vec<f64> = part.columns.iter().map(|&c| x[c]).collect();
    local.resize(part.columns.len() + top.len(), 0.0);
    forward(factor.part_nodes(part), &mut local, &mut Vec::new());
    local
}

/// The backward pass of `part` on a copy of its columns of `x` and of the (solved) `top`
/// columns: its columns solved.
fn backward_part(factor: FactorRef<'_>, part: &Part, top: &[usize], x: &[f64]) -> Vec<f64> {
    let mut local: Vec<f64> = part.columns.iter().chain(top).map(|&c| x[c]).collect();
    backward(factor.part_nodes(part).rev(), &mut local, &mut Vec::new());
    local.truncate(part.columns.len());
    local
}

/// `L y = b` over `nodes` (in order): a supernode's unknowns are final once the supernodes
/// before it are applied. `below` is scratch for the pattern rows of a supernode's product, in
/// contiguous storage so that the loops over a column run over contiguous arrays (the columns
/// go by pairs, one pass over it for two).
fn forward<'a>(nodes: impl Iterator<Item = Supernode<'a>>, x: &mut [f64], below: &mut Vec<f64>) {
    for node in nodes {
        let top = &mut x[node.start..node.start + node.columns];
        for j in 0..node.columns {
            let (block, _) = node.column(j);
            let xj = top[j] * node.inverse[j];
            top[j] = xj;
            for (xi, l) in top[j + 1..].iter_mut().zip(&block[1..]) {
                *xi -= f64::from(*l) * xj;
            }
        }
        below.clear();
        below.resize(node.pattern.len(), 0.0);
        for j in (0..node.columns).step_by(2) {
            let (_, a) = node.column(j);
            let (xa, (b, xb)) = match j + 1 < node.columns {
                true => (top[j], (node.column(j + 1).1, top[j + 1])),
                false => (top[j], (a, 0.0)),
            };
            for ((s, a), b) in below.iter_mut().zip(a).zip(b) {
                *s += f64::from(*a) * xa + f64::from(*b) * xb;
            }
        }
        for (&i, b) in node.pattern.iter().zip(below.iter()) {
            x[i] -= b;
        }
    }
}

/// `Lᵀ x = y` over `nodes` (in reverse order): a supernode's unknowns need those of the
/// supernodes after it, final by then.
fn backward<'a>(nodes: impl Iterator<Item = Supernode<'a>>, x: &mut [f64], below: &mut Vec<f64>) {
    for node in nodes {
        below.clear();
        below.extend(node.pattern.iter().map(|&i| x[i]));
        let top = &mut x[node.start..node.start + node.columns];
        for j in (0..node.columns).step_by(2) {
            let (_, a) = node.column(j);
            match j + 1 < node.columns {
                true => {
                    let [da, db] = dots([a, node.column(j + 1).1], below);
                    top[j] -= da;
                    top[j + 1] -= db;
                }
                false => top[j] -= dots([a], below)[0],
            }
        }
        for j in (0..node.columns).rev() {
            let (block, _) = node.column(j);
            let [after] = dots([&block[1..]], &top[j + 1..]);
            top[j] = (top[j] - after) * node.inverse[j];
        }
    }
}

/// `a[c]·v` for each of the `N` columns `a[c]`, each by four partial sums in a fixed order (the
/// same result on every run, and vector registers for the compiler: one running sum is a
/// chain of dependent additions).
fn dots<const N: usize>(a: [&[f32]; N], v: &[f64]) -> [f64; N] {
    let mut sums = [[0.0; 4]; N];
    let v4 = v.chunks_exact(4);
    let tail = v4.remainder();
    for (i, v) in v4.enumerate() {
        for (s, a) in sums.iter_mut().zip(&a) {
            for k in 0..4 {
                s[k] += f64::from(a[4 * i + k]) * v[k];
            }
        }
    }
    let start = v.len() - tail.len();
    for (s, a) in sums.iter_mut().zip(&a) {
        for (k, v) in tail.iter().enumerate() {
            s[k] += f64::from(a[start + k]) * v;
        }
    }
    sums.map(|s| (s[0] + s[1]) + (s[2] + s[3]))
}
