//! The Jacobian determinant of a polynomial map in tensor Bernstein form, itself a Bernstein
//! polynomial, and a lower bound of such a polynomial by subdivision: what certifies that a map
//! does not fold.

use super::bernstein::Bernstein;

/// Lower bound of a Bernstein polynomial on \[0,1\]^d by subdivision, stopping at positive
/// bounds, at a non-positive corner value (the polynomial's own value there) or at `depth`.
pub(crate) fn lower_bound<const D: usize>(p: &Bernstein<D>, depth: u32) -> f64 {
    let m = p.min_coef();
    if m > 0.0 || depth == 0 {
        return m;
    }
    let corner_min = (0..1usize << D)
        .map(|c| p.eval(std::array::from_fn(|k| (c >> k & 1) as f64)))
        .fold(f64::INFINITY, f64::min);
    if corner_min <= 0.0 {
        return m;
    }
    let mut pieces = vec![p.clone()];
    for k in 0..D {
        pieces = pieces
            .into_iter()
            .flat_map(|q| {
                let (a, b) = q.split(k);
                [a, b]
            })
            .collect();
    }
    pieces
        .iter()
        .map(|q| lower_bound(q, depth - 1))
        .fold(f64::INFINITY, f64::min)
}

/// The Jacobian entries `J[a][b] = ∂S_a/∂x_b` of the map whose components are the Bernstein
/// `patches` (all of one degree p per direction) on the box `[lo, hi]` mapped to \[0,1\]^d, the
/// derivatives taken with respect to the box's coordinates: degree `p − 1` in direction `b`, `p`
/// in the others.
pub(crate) fn jacobian_entries<const D: usize>(
    patches: &[Bernstein<D>],
    lo: [f64; D],
    hi: [f64; D],
) -> Vec<Vec<Bernstein<D>>> {
    patches
        .iter()
        .map(|p| {
            (0..D)
                .map(|b| {
                    let mut d = p.derivative(b);
                    let scale = 1.0 / (hi[b] - lo[b]);
                    d.coef.iter_mut().for_each(|v| *v *= scale);
                    d
                })
                .collect()
        })
        .collect()
}

/// `det J` of the map whose components are the Bernstein `patches` (all of one degree p per
/// direction) on the box `[lo, hi]` mapped to \[0,1\]^d, the Jacobian taken with respect to the
/// box's coordinates: a polynomial of degree `d·p − 1` per direction.
pub(crate) fn jacobian_determinant<const D: usize>(
    patches: &[Bernstein<D>],
    lo: [f64; D],
    hi: [f64; D],
) -> Bernstein<D> {
    let jac = jacobian_entries(patches, lo, hi);
    let degree = patches[0].degree.map(|p| D * p - 1);
    let mut total = Bernstein::zero(degree);
    for (perm, sign) in permutations(D) {
        let mut term = jac[0][perm[0]].clone();
        for a in 1..D {
            term = term.mul(&jac[a][perm[a]]);
        }
        total.add_scaled(sign, &term);
    }
    total
}

/// All permutations of `0..n` with their signs.
fn permutations(n: usize) -> Vec<(Vec<usize>, f64)> {
    if n == 1 {
        return vec![(vec![0], 1.0)];
    }
    let mut out = Vec::new();
    for (p, s) in permutations(n - 1) {
        // Insert n − 1 at every position; moving it left past k entries flips the sign k times.
        for pos in (0..n).rev() {
            let mut q = p.clone();
            q.insert(pos, n - 1);
            let flips = n - 1 - pos;
            out.push((q, if flips % 2 == 0 { s } else { -s }));
        }
    }
    out
}
