//! `.vtu` output of a spline map: each element sampled on a small grid of quads (2D) or
//! hexahedra (3D), with point data `quality` (mean ratio q_S) and `det` (det J_S), and cell
//! data `level` and `element`.

use super::map::SplineMap;
use super::space::SplineSpace;
use crate::io::vtu::{DataArray, UnstructuredGrid};
use crate::optimize::metric::mean_ratio;
use crate::optimize::small_matrix::det;

impl<const D: usize, S: SplineSpace<D>> SplineMap<D, S> {
    /// The map sampled on `n × n (× n)` sub-cells per element (`n ≥ 1`).
    pub fn to_grid(&self, n: usize) -> UnstructuredGrid {
        let n = n.max(1);
        let m = n + 1;
        let per = m.pow(D as u32);
        let mut grid = UnstructuredGrid::default();
        let (mut quality, mut dets, mut level, mut element) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let corners: &[[usize; 3]] = &[
            [0, 0, 0],
            [1, 0, 0],
            [1, 1, 0],
            [0, 1, 0],
            [0, 0, 1],
            [1, 0, 1],
            [1, 1, 1],
            [0, 1, 1],
        ];
        for e in 0..self.element_count() {
            let base = grid.points.len() / 3;
            let (lo, hi) = self.element_bounds(e);
            for s in 0..per {
                let x: [f64; D] = std::array::from_fn(|k| {
                    let i = s / m.pow(k as u32) % m;
                    lo[k] + (hi[k] - lo[k]) * i as f64 / n as f64
                });
                let (y, j) = self
                    .eval_with_jacobian(x)
                    .unwrap_or(([f64::NAN; D], [[f64::NAN; D]; D]));
                grid.points.extend(y);
                grid.points.extend(std::iter::repeat_n(0.0, 3 - D));
                quality.push(mean_ratio(&j));
                dets.push(det(&j));
            }
            for c in 0..n.pow(D as u32) {
                let cell: [usize; D] = std::array::from_fn(|k| c / n.pow(k as u32) % n);
                for corner in &corners[..1 << D] {
                    let flat: usize = (0..D)
                        .map(|k| (cell[k] + corner[k]) * m.pow(k as u32))
                        .sum();
                    grid.connectivity.push((base + flat) as i64);
                }
                grid.offsets.push(grid.connectivity.len() as i64);
                grid.types.push(if D == 2 { 9 } else { 12 });
                level.push(self.element_level(e) as f64);
                element.push(e as f64);
            }
        }
        let array = |name: &str, values: Vec<f64>| DataArray {
            name: name.to_string(),
            components: 1,
            values,
        };
        grid.point_data = vec![array("quality", quality), array("det", dets)];
        grid.cell_data = vec![array("level", level), array("element", element)];
        grid
    }
}
