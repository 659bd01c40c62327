//! Where a domain's boundary map sits: its orientation (the sign of the volume it encloses) and
//! the affine frame, each axis scaled by its own extent, in which the T-mesh is optimized.

use super::cube_map::CubeMap;
use crate::optimize::small_matrix::{bounding_box, det, Matrix};

/// Samples per side of the parametric square or cube face used to measure the boundary.
const SAMPLES: usize = 16;

/// Bits of the dyadic grid of the frame onto which framed boundary points are rounded: a step
/// of 2⁻³⁸ ≈ 3.6·10⁻¹² of the bounding box, far below any tolerance (finite differences of
/// updates with steps of 10⁻⁴ see it as a noise of 10⁻⁸), and far above the round-off
/// (a few 10⁻¹⁶) by which the framed points of a scaled boundary differ. Which basin the
/// untangling of a deeply folded start ends in depends on the grid as on any perturbation: at
/// 38 bits every bundled domain ends as well as it did unrounded (at 36 and 40 the puzzle
/// piece's min quality is 0.05 or 0.04 instead of 0.53).
const GRID_BITS: i32 = 38;

/// `v` rounded to the nearest multiple of 2^−[`GRID_BITS`] (exactly: the products and quotient
/// by a power of two are exact).
fn snap(v: f64) -> f64 {
    let scale = 2f64.powi(GRID_BITS);
    (v * scale).round() / scale
}

/// Whether the framed points `a` and `b` are within one step of the grid of [`snap`] of each
/// other, coordinate by coordinate.
pub(super) fn on_grid_point<const D: usize>(a: [f64; D], b: [f64; D]) -> bool {
    let step = 2f64.powi(-GRID_BITS);
    (0..D).all(|k| (a[k] - b[k]).abs() <= step)
}

/// A boundary map seen in a frame, with its first two parametric coordinates swapped when
/// `swap` is set: a left-handed boundary parameterization becomes right-handed, so the cells are
/// not inverted.
///
/// With a frame, the points are in the frame's coordinates rounded onto a fixed dyadic grid
/// (see [`GRID_BITS`]): the boundary scaled by any factor (and moved by any modest translation)
/// then gives the same framed points bit for bit, except with a probability of the order of
/// 10⁻⁴ per coordinate, and so does everything computed from them. Without the rounding, the
/// untangling of a deeply folded start (the puzzle piece's 94 cells) is chaotic in the
/// round-off of the framed data, and the T-mesh it ends in changed with the units. Without a
/// frame (`None`), the points are the physical ones.
pub(super) struct Framed<'a, B, const D: usize> {
    pub(super) inner: &'a B,
    pub(super) swap: bool,
    pub(super) frame: Option<Frame<D>>,
}

impl<const D: usize, B: CubeMap<D>> CubeMap<D> for Framed<'_, B, D> {
    fn boundary_point(&self, mut p: [f64; D]) -> [f64; D] {
        if self.swap {
            p.swap(0, 1);
        }
        let x = self.inner.boundary_point(p);
        match &self.frame {
            Some(frame) => frame.to_frame(x).map(snap),
            None => x,
        }
    }
}

/// The signed area (d = 2) or volume (d = 3) enclosed by the image of the square's or cube's
/// boundary, oriented by the outward normal of the parametric domain and measured on a
/// `SAMPLES`-per-side grid: positive when the boundary map preserves orientation. Unlike a
/// Jacobian at one point, the enclosed measure is not fooled by a needle-shaped domain or by
/// boundary wiggles.
pub(super) fn signed_measure<const D: usize>(boundary: &impl CubeMap<D>) -> f64 {
    let n = SAMPLES;
    let at = |p: [f64; 3]| -> [f64; 3] {
        let x = boundary.boundary_point(std::array::from_fn(|k| p[k]));
        std::array::from_fn(|k| if k < D { x[k] } else { 0.0 })
    };
    if D == 2 {
        // Counter-clockwise round the square.
        let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let mut loop_points = Vec::with_capacity(4 * n);
        for s in 0..4 {
            let (a, b) = (corners[s], corners[(s + 1) % 4]);
            for i in 0..n {
                let t = i as f64 / n as f64;
                loop_points.push(at([
                    a[0] + t * (b[0] - a[0]),
                    a[1] + t * (b[1] - a[1]),
                    0.0,
                ]));
            }
        }
        return (0..loop_points.len())
            .map(|i| {
                let (p, q) = (loop_points[i], loop_points[(i + 1) % loop_points.len()]);
                0.5 * (p[0] * q[1] - q[0] * p[1])
            })
            .sum();
    }
    let mut volume = 0.0;
    for axis in 0..3 {
        let (a, b) = match axis {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        };
        for end in 0..2 {
            // e_a × e_b is +e_axis except for axis 1; the outward normal is ±e_axis.
            let sign = if end == 1 { 1.0 } else { -1.0 } * if axis == 1 { -1.0 } else { 1.0 };
            let point = |i: usize, j: usize| {
                let mut p = [0.0; 3];
                p[axis] = end as f64;
                p[a] = i as f64 / n as f64;
                p[b] = j as f64 / n as f64;
                at(p)
            };
            for j in 0..n {
                for i in 0..n {
                    let (p00, p10, p11, p01) = (
                        point(i, j),
                        point(i + 1, j),
                        point(i + 1, j + 1),
                        point(i, j + 1),
                    );
                    for tri in [[p00, p10, p11], [p00, p11, p01]] {
                        let m: Matrix<3> = tri;
                        volume += sign * det(&m) / 6.0;
                    }
                }
            }
        }
    }
    volume
}

/// The affine frame of the optimization: `(x − centre) / extent`, axis by axis, maps the bounding
/// box of the boundary onto a unit box. Validity is invariant under it, and every tolerance of
/// the optimizer becomes dimensionless, whatever the units and however elongated the domain
/// (a needle 2700:1 is optimized as a cube); the target of a cell, its parametric shape, then
/// stands for that shape mapped onto the bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame<const D: usize> {
    /// Centre of the bounding box.
    pub centre: [f64; D],
    /// Side lengths of the bounding box.
    pub extent: [f64; D],
}

impl<const D: usize> Frame<D> {
    /// The frame that changes nothing.
    pub const IDENTITY: Self = Frame {
        centre: [0.0; D],
        extent: [1.0; D],
    };

    /// The frame of the box around the images of a grid of boundary points, or `None` when the
    /// box is flat or not finite.
    pub(super) fn of(boundary: &impl CubeMap<D>) -> Option<Self> {
        let n = SAMPLES;
        let (lo, hi) = bounding_box(
            (0..(n + 1).pow(D as u32))
                .map(|i| -> [f64; D] {
                    std::array::from_fn(|k| (i / (n + 1).pow(k as u32) % (n + 1)) as f64 / n as f64)
                })
                .filter(|p| p.iter().any(|&v| v == 0.0 || v == 1.0))
                .map(|p| boundary.boundary_point(p)),
        );
        let extent: [f64; D] = std::array::from_fn(|k| hi[k] - lo[k]);
        if extent.iter().any(|&e| !(e.is_finite() && e > 0.0)) {
            return None;
        }
        Some(Frame {
            centre: std::array::from_fn(|k| 0.5 * (lo[k] + hi[k])),
            extent,
        })
    }

    /// Length of the box's diagonal.
    pub fn diagonal(&self) -> f64 {
        self.extent.iter().map(|e| e * e).sum::<f64>().sqrt()
    }

    /// Physical to frame coordinates.
    pub fn to_frame(&self, p: [f64; D]) -> [f64; D] {
        std::array::from_fn(|k| (p[k] - self.centre[k]) / self.extent[k])
    }

    /// Frame to physical coordinates.
    pub fn to_physical(&self, p: [f64; D]) -> [f64; D] {
        std::array::from_fn(|k| p[k] * self.extent[k] + self.centre[k])
    }
}
