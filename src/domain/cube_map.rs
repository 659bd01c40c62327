//! A map from the boundary of the unit square or cube onto a domain's boundary ([`CubeMap`]):
//! its transfinite extension to the inside, and how far a cell's boundary facets stray from it.

use crate::optimize::small_matrix::{det, Matrix};
use crate::tmesh::{Tree, UNIT};

/// A map from the boundary of the unit square (d = 2) or cube (d = 3) onto the boundary of a
/// domain.
pub trait CubeMap<const D: usize> {
    /// The image of `p`, a point of the boundary of \[0,1\]^d (some coordinate is exactly 0 or 1).
    fn boundary_point(&self, p: [f64; D]) -> [f64; D];
}

/// The transfinite interpolation of the boundary at `p` (Coons patch in 2D, Boolean sum of the
/// six faces minus the twelve edges plus the eight corners in 3D): with `P_k` the linear
/// interpolation between the two boundary values along coordinate `k`, the Boolean sum
/// `Σ_{∅≠S} (−1)^{|S|+1} Π_{k∈S} P_k`. Reproduces the boundary on the boundary.
pub fn transfinite<const D: usize>(boundary: &impl CubeMap<D>, p: [f64; D]) -> [f64; D] {
    let mut x = [0.0; D];
    for subset in 1..1usize << D {
        let dims: Vec<usize> = (0..D).filter(|&k| subset >> k & 1 == 1).collect();
        let sign = if dims.len() % 2 == 1 { 1.0 } else { -1.0 };
        for choice in 0..1usize << dims.len() {
            let mut q = p;
            let mut weight = sign;
            for (i, &k) in dims.iter().enumerate() {
                let one = choice >> i & 1 == 1;
                weight *= if one { p[k] } else { 1.0 - p[k] };
                q[k] = if one { 1.0 } else { 0.0 };
            }
            if weight != 0.0 {
                let b = boundary.boundary_point(q);
                for k in 0..D {
                    x[k] += weight * b[k];
                }
            }
        }
    }
    x
}

/// Measure of the boundary error of one boundary facet, given the images of its corners in cyclic
/// order (2 in 2D, 4 in 3D) and of its centre.
fn facet_error<const D: usize>(corners: &[[f64; D]], centre: [f64; D]) -> f64 {
    let simplex = |points: &[[f64; D]]| -> f64 {
        let m: Matrix<D> =
            std::array::from_fn(|i| std::array::from_fn(|k| points[i + 1][k] - points[0][k]));
        det(&m).abs()
    };
    match D {
        2 => 0.5 * simplex(&[corners[0], corners[1], centre]),
        _ => {
            (0..4)
                .map(|i| {
                    simplex(&[
                        corners[i],
                        corners[(i + 1) % 4],
                        corners[(i + 2) % 4],
                        centre,
                    ])
                })
                .sum::<f64>()
                / 6.0
        }
    }
}

/// Largest boundary error over the facets of leaf `c` that lie on the boundary of \[0,1\]^d.
pub(super) fn cell_boundary_error<const D: usize>(
    tree: &Tree<D>,
    c: usize,
    boundary: &impl CubeMap<D>,
) -> f64 {
    let cell = tree.cells()[c];
    let lo = cell.lower.map(|v| v as f64 / UNIT as f64);
    let h = cell.side() as f64 / UNIT as f64;
    let point =
        |l: [usize; D]| -> [f64; D] { std::array::from_fn(|k| lo[k] + 0.5 * h * l[k] as f64) };
    let mut worst = 0.0f64;
    for k in 0..D {
        for end in [0usize, 2] {
            let at = if end == 0 { lo[k] } else { lo[k] + h };
            if at != 0.0 && at != 1.0 {
                continue;
            }
            // The facet's lattice points: coordinate k fixed, the others cycling round.
            let others: Vec<usize> = (0..D).filter(|&j| j != k).collect();
            let ring: &[[usize; 2]] = if D == 2 {
                &[[0, 0], [2, 0]]
            } else {
                &[[0, 0], [2, 0], [2, 2], [0, 2]]
            };
            let lattice_at = |a: usize, b: usize| -> [usize; D] {
                let mut l = [0; D];
                l[k] = end;
                l[others[0]] = a;
                if D == 3 {
                    l[others[1]] = b;
                }
                l
            };
            let corners: Vec<[f64; D]> = ring
                .iter()
                .map(|&[a, b]| boundary.boundary_point(point(lattice_at(a, b))))
                .collect();
            let centre = boundary.boundary_point(point(lattice_at(1, 1)));
            worst = worst.max(facet_error(&corners, centre));
        }
    }
    worst
}

/// `√d^d`: the measure of a facet error equal to the tolerance, in frame coordinates (the
/// diagonal of the unit box to the power d).
pub(super) fn facet_scale<const D: usize>() -> f64 {
    (D as f64).powf(D as f64 / 2.0)
}
