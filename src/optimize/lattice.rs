//! The 3^d lattice of a quadratic Lagrange cell: node numbering, shape-function gradients at the
//! lattice points (which are also the 3-point Gauss–Lobatto points), and the completion of
//! missing nodes by transfinite (Coons) interpolation.
//!
//! A lattice point has integer coordinates `c ∈ {0,1,2}^d` (parameter ξ = c − 1 ∈ {−1,0,1}^d)
//! and index `Σ c_k 3^k`.

/// Number of lattice points, `3^d`.
pub const fn count(d: usize) -> usize {
    3usize.pow(d as u32)
}

/// Integer coordinates of lattice point `index`.
pub fn coords<const D: usize>(index: usize) -> [usize; D] {
    let mut c = [0; D];
    let mut rest = index;
    for ck in c.iter_mut() {
        *ck = rest % 3;
        rest /= 3;
    }
    c
}

/// Index of the lattice point with integer coordinates `c`.
pub fn index<const D: usize>(c: &[usize; D]) -> usize {
    c.iter().rev().fold(0, |acc, &ck| acc * 3 + ck)
}

/// `L_i'(ξ_m)`: derivative of the 1D quadratic Lagrange polynomial of node `i` at node `m`,
/// nodes at ξ = −1, 0, 1.
const LAGRANGE_DERIVATIVE: [[f64; 3]; 3] = [
    [-1.5, 2.0, -0.5], // at ξ = −1
    [-0.5, 0.0, 0.5],  // at ξ = 0
    [0.5, -2.0, 1.5],  // at ξ = 1
];

/// Gradient (with respect to ξ) of the shape function of lattice node `a` at lattice point `q`.
pub fn shape_gradient<const D: usize>(a: usize, q: usize) -> [f64; D] {
    let (ca, cq) = (coords::<D>(a), coords::<D>(q));
    let mut g = [0.0; D];
    for (k, gk) in g.iter_mut().enumerate() {
        let others_match = (0..D).all(|l| l == k || ca[l] == cq[l]);
        if others_match {
            *gk = LAGRANGE_DERIVATIVE[cq[k]][ca[k]];
        }
    }
    g
}

/// Expresses every lattice point as a linear combination of the given real nodes.
///
/// `real[r]` is the lattice index of real node `r`. The result has one row per lattice point,
/// each a list of `(r, coefficient)`. A missing point is completed from the boundary of the
/// smallest face (edge, face, cell) it is the centre of, by the Boolean-sum rule
/// `x = Σ_{∅≠S⊆M} (−1)^{|S|+1} 2^{−|S|} Σ_{choices} x(c with S moved to 0 or 2)`, M being the
/// coordinates equal to 1: a mid-edge node is the mean of its ends, a face centre
/// `½Σ mid-edges − ¼Σ corners`, the body centre `⅛Σ corners − ¼Σ mid-edges + ½Σ face centres`.
/// Returns `None` if a corner is missing (corners cannot be completed).
pub fn completion<const D: usize>(real: &[usize]) -> Option<Vec<Vec<(usize, f64)>>> {
    let n = count(D);
    let mut rows: Vec<Option<Vec<(usize, f64)>>> = vec![None; n];
    for (r, &l) in real.iter().enumerate() {
        rows[l] = Some(vec![(r, 1.0)]);
    }
    // Complete points in order of increasing number of middle coordinates.
    for middle_count in 1..=D {
        for p in 0..n {
            let c = coords::<D>(p);
            let middles: Vec<usize> = (0..D).filter(|&k| c[k] == 1).collect();
            if middles.len() != middle_count || rows[p].is_some() {
                continue;
            }
            let mut dense = vec![0.0; real.len()];
            // Each middle coordinate becomes 0, 2 (moved, in S) or stays 1.
            for choice in 0..3usize.pow(middle_count as u32) {
                let mut q = c;
                let mut moved = 0;
                let mut rest = choice;
                for &k in &middles {
                    match rest % 3 {
                        0 => {}
                        v => {
                            q[k] = if v == 1 { 0 } else { 2 };
                            moved += 1;
                        }
                    }
                    rest /= 3;
                }
                if moved == 0 {
                    continue;
                }
                let sign = if moved % 2 == 1 { 1.0 } else { -1.0 };
                let coef = sign * 0.5f64.powi(moved);
                for &(r, v) in rows[index(&q)].as_ref()? {
                    dense[r] += coef * v;
                }
            }
            rows[p] = Some(
                dense
                    .into_iter()
                    .enumerate()
                    .filter(|&(_, v)| v != 0.0)
                    .collect(),
            );
        }
    }
    rows.into_iter().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coordinates_round_trip() {
        for i in 0..27 {
            assert_eq!(index(&coords::<3>(i)), i);
        }
    }

    #[test]
    fn gradients_sum_to_zero_and_reproduce_linear_maps() {
        for q in 0..9 {
            let mut sum = [0.0; 2];
            let mut grad_x = [0.0; 2];
            for a in 0..9 {
                let g = shape_gradient::<2>(a, q);
                let xa = coords::<2>(a)[0] as f64 - 1.0;
                for k in 0..2 {
                    sum[k] += g[k];
                    grad_x[k] += xa * g[k];
                }
            }
            assert_eq!(sum, [0.0, 0.0]);
            assert_eq!(grad_x, [1.0, 0.0]);
        }
    }

    #[test]
    fn completion_of_linear_hex_reproduces_trilinear_centre() {
        let corners: Vec<usize> = (0..27)
            .filter(|&p| coords::<3>(p).iter().all(|&c| c != 1))
            .collect();
        let rows = completion::<3>(&corners).unwrap();
        let centre = &rows[13];
        assert_eq!(centre.len(), 8);
        for &(_, v) in centre {
            assert!((v - 0.125).abs() < 1e-15);
        }
        // Every row is a partition of unity.
        for row in &rows {
            let s: f64 = row.iter().map(|(_, v)| v).sum();
            assert!((s - 1.0).abs() < 1e-15);
        }
    }
}
