//! Where a domain's boundary map sits: its orientation (the sign of the volume it encloses) and
//! the affine frame, each axis scaled by its own extent, in which the T-mesh is optimized.

use super::cube_map::CubeMap;
use crate::optimize::small_matrix::{bounding_box, det, Matrix};

/// Samples per side of the parametric square or cube face used to measure the boundary.
const SAMPLES: usize = 16;

/// A boundary map seen in a frame, with its first two parametric coordinates swapped when
/// `swap` is set: a left-handed boundary parameterization becomes right-handed, so the cells are
/// not inverted.
pub(super) struct Framed<'a, B, const D: usize> {
    pub(super) inner: &'a B,
    pub(super) swap: bool,
    pub(super) frame: Frame<D>,
}

impl<const D: usize, B: CubeMap<D>> CubeMap<D> for Framed<'_, B, D> {
    fn boundary_point(&self, mut p: [f64; D]) -> [f64; D] {
        if self.swap {
            p.swap(0, 1);
        }
        self.frame.to_frame(self.inner.boundary_point(p))
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
