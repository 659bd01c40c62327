//! Planar domains bounded by four curves.

use std::time::Instant;

use crate::boundary::{BoundaryLoop2, Point2, Side};
use crate::error::{Error, Result};
use crate::io::vtu::{DataArray, UnstructuredGrid};
use crate::optimize::laplace::MeshGraph;
use crate::optimize::motion::{follow_motion, optimize_in_place};
use crate::optimize::{invalid_cells, NodeSolverOptions, Problem, SweepOptions};
use crate::tmesh::{TMesh, Tree, UNIT};

/// VTK's polygon cell type.
const VTK_POLYGON: u8 = 7;

/// Options of [`PlanarDomain::build`].
#[derive(Clone, Copy, Debug)]
pub struct PlanarOptions {
    /// Boundary tolerance: a boundary cell edge is refined while the triangle formed by its end
    /// images and the image of its parametric midpoint has an area above
    /// `tolerance × (bounding-box diagonal)²`.
    pub tolerance: f64,
    /// Level of the initial uniform refinement.
    pub min_level: u8,
    /// Deepest level of the adaptation.
    pub max_level: u8,
    /// Largest number of optimization sweeps.
    pub max_sweeps: u32,
    /// Worker threads; 0 uses one per core.
    pub threads: usize,
}

impl Default for PlanarOptions {
    fn default() -> Self {
        PlanarOptions {
            tolerance: 1e-5,
            min_level: 2,
            max_level: 9,
            max_sweeps: 200,
            threads: 0,
        }
    }
}

/// What [`PlanarDomain::build`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PlanarReport {
    /// Cells of the T-mesh.
    pub cells: usize,
    /// Vertices of the T-mesh, hanging ones included.
    pub vertices: usize,
    /// Deepest level.
    pub max_level: u8,
    /// Largest boundary error (triangle area over the squared diagonal).
    pub boundary_error: f64,
    /// Invalid cells after the Coons placement.
    pub invalid_after_placement: usize,
    /// Invalid cells after the optimization.
    pub invalid_cells: usize,
    /// Smallest cell quality (1/mean distortion against the parametric cell).
    pub min_quality: f64,
    /// Mean cell quality.
    pub mean_quality: f64,
    /// Optimization sweeps (with those of the fallback growth from the bounding box).
    pub sweeps: u32,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// A planar domain with its optimized T-mesh: parametric vertices in [0,1]², physical ones in the
/// domain.
#[derive(Clone, Debug)]
pub struct PlanarDomain {
    boundary: BoundaryLoop2,
    mesh: TMesh<2>,
    positions: Vec<Point2>,
    quality: Vec<f64>,
}

/// Bounding box centre and diagonal of the boundary's corners and samples.
fn extent(boundary: &BoundaryLoop2) -> (Point2, f64) {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for side in Side::all() {
        for i in 0..=64 {
            let p = boundary.eval(side, i as f64 / 64.0);
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
    }
    let centre = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
    (
        centre,
        ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2)).sqrt(),
    )
}

/// Lower and upper corners of the box around the points.
fn bounding_box(points: &[Point2]) -> (Point2, Point2) {
    points.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        },
    )
}

/// The side and side parameter of a boundary point of the unit square.
fn side_of([u, v]: [f64; 2]) -> Option<(Side, f64)> {
    if u == 0.0 || u == 1.0 {
        Some((if u == 0.0 { Side::U0 } else { Side::U1 }, v))
    } else if v == 0.0 || v == 1.0 {
        Some((if v == 0.0 { Side::V0 } else { Side::V1 }, u))
    } else {
        None
    }
}

/// The Coons patch of the boundary at parametric point `(u, v)`.
pub fn coons(boundary: &BoundaryLoop2, [u, v]: [f64; 2]) -> Point2 {
    let (w, e) = (boundary.eval(Side::U0, v), boundary.eval(Side::U1, v));
    let (s, n) = (boundary.eval(Side::V0, u), boundary.eval(Side::V1, u));
    let c00 = boundary.eval(Side::V0, 0.0);
    let c10 = boundary.eval(Side::V0, 1.0);
    let c01 = boundary.eval(Side::V1, 0.0);
    let c11 = boundary.eval(Side::V1, 1.0);
    std::array::from_fn(|k| {
        (1.0 - u) * w[k] + u * e[k] + (1.0 - v) * s[k] + v * n[k]
            - ((1.0 - u) * (1.0 - v) * c00[k]
                + u * (1.0 - v) * c10[k]
                + (1.0 - u) * v * c01[k]
                + u * v * c11[k])
    })
}

/// Boundary error of the edge `[a, b]` (parametric points on one side of the square).
fn edge_error(boundary: &BoundaryLoop2, side: Side, t0: f64, t1: f64) -> f64 {
    let a = boundary.eval(side, t0);
    let b = boundary.eval(side, t1);
    let m = boundary.eval(side, 0.5 * (t0 + t1));
    0.5 * ((b[0] - a[0]) * (m[1] - a[1]) - (b[1] - a[1]) * (m[0] - a[0])).abs()
}

/// Largest boundary error over the boundary edges of leaf `c`.
fn cell_boundary_error(tree: &Tree<2>, c: usize, boundary: &BoundaryLoop2) -> f64 {
    let cell = tree.cells()[c];
    let lo = cell.lower.map(|v| v as f64 / UNIT as f64);
    let h = cell.side() as f64 / UNIT as f64;
    let hi = [lo[0] + h, lo[1] + h];
    let mut worst = 0.0f64;
    for (side, on, t0) in [
        (Side::U0, lo[0] == 0.0, lo[1]),
        (Side::U1, hi[0] == 1.0, lo[1]),
        (Side::V0, lo[1] == 0.0, lo[0]),
        (Side::V1, hi[1] == 1.0, lo[0]),
    ] {
        if on {
            worst = worst.max(edge_error(boundary, side, t0, t0 + h));
        }
    }
    worst
}

impl PlanarDomain {
    /// Adapts a T-mesh to the boundary, places its vertices and optimizes them.
    pub fn build(
        boundary: BoundaryLoop2,
        options: &PlanarOptions,
        progress: &mut dyn FnMut(usize, usize) -> bool,
    ) -> Result<(PlanarDomain, PlanarReport)> {
        let start = Instant::now();
        if !(options.tolerance.is_finite() && options.tolerance > 0.0) {
            return Err(Error::invalid(format!(
                "tolerance = {} must be positive",
                options.tolerance
            )));
        }
        if options.min_level > options.max_level || options.max_level > 16 {
            return Err(Error::invalid(
                "levels must satisfy min_level <= max_level <= 16",
            ));
        }
        let (centre, diagonal) = extent(&boundary);
        let area_tolerance = options.tolerance * diagonal * diagonal;
        let mut tree = Tree::<2>::new();
        tree.refine_uniformly(options.min_level)?;
        loop {
            let marked: Vec<usize> = tree
                .leaves()
                .into_iter()
                .filter(|&c| {
                    tree.cells()[c].level < options.max_level
                        && cell_boundary_error(&tree, c, &boundary) > area_tolerance
                })
                .collect();
            if marked.is_empty() {
                break;
            }
            for c in marked {
                tree.refine(c)?;
            }
            tree.balance()?;
        }
        let mesh = TMesh::new(tree)?;
        let boundary_error = mesh
            .tree()
            .leaves()
            .into_iter()
            .map(|c| cell_boundary_error(mesh.tree(), c, &boundary))
            .fold(0.0, f64::max)
            / (diagonal * diagonal);
        // Place in coordinates normalised to the bounding box, so the optimizer's tolerances
        // are dimensionless.
        let normalise = |p: Point2| [(p[0] - centre[0]) / diagonal, (p[1] - centre[1]) / diagonal];
        let mut x: Vec<Point2> = mesh
            .parametric()
            .into_iter()
            .map(|uv| match side_of(uv) {
                Some((side, t)) => normalise(boundary.eval(side, t)),
                None => normalise(coons(&boundary, uv)),
            })
            .collect();
        let problem: Problem<2> = mesh.problem()?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(options.threads)
            .build()
            .map_err(|e| Error::invalid(format!("cannot start threads: {e}")))?;
        let invalid_after_placement = invalid_cells(&pool, &problem, &x).len();
        let sweep_options = SweepOptions {
            max_sweeps: options.max_sweeps,
            move_tolerance: 1e-3,
            node: NodeSolverOptions {
                gradient_tolerance: 1e-3,
                max_iterations: 150,
                relaxation: 1.8,
            },
        };
        let mut stats = optimize_in_place(&pool, &problem, &mut x, &sweep_options, &mut |d| {
            progress(d, 0)
        })?;
        if !invalid_cells(&pool, &problem, &x).is_empty() {
            // The Coons start folds too much (deep necks): grow the domain instead from the
            // bounding box, where the parametric grid is valid, following the boundary in steps.
            let (lo, hi) = bounding_box(&x);
            let start: Vec<Point2> = mesh
                .parametric()
                .into_iter()
                .map(|uv| std::array::from_fn(|k| lo[k] + uv[k] * (hi[k] - lo[k])))
                .collect();
            let graph = MeshGraph::new(&problem);
            let (grown, grown_stats) = follow_motion(
                &pool,
                &problem,
                &graph,
                &start,
                &x,
                &sweep_options,
                &mut |d| progress(stats.sweeps as usize + d, 0),
            )?;
            stats.sweeps += grown_stats.sweeps;
            if invalid_cells(&pool, &problem, &grown).len()
                < invalid_cells(&pool, &problem, &x).len()
            {
                x = grown;
            }
        }
        let quality: Vec<f64> = (0..problem.cell_count())
            .map(|c| problem.cell_quality(c, &x))
            .collect();
        let report = PlanarReport {
            cells: mesh.cell_count(),
            vertices: mesh.vertex_count(),
            max_level: (0..mesh.cell_count())
                .map(|c| mesh.cell_level(c))
                .max()
                .unwrap_or(0),
            boundary_error,
            invalid_after_placement,
            invalid_cells: invalid_cells(&pool, &problem, &x).len(),
            min_quality: quality.iter().copied().fold(f64::INFINITY, f64::min),
            mean_quality: quality.iter().sum::<f64>() / quality.len() as f64,
            sweeps: stats.sweeps,
            seconds: start.elapsed().as_secs_f64(),
        };
        let positions = x
            .into_iter()
            .map(|p| [p[0] * diagonal + centre[0], p[1] * diagonal + centre[1]])
            .collect();
        let domain = PlanarDomain {
            boundary,
            mesh,
            positions,
            quality,
        };
        Ok((domain, report))
    }

    /// The boundary.
    pub fn boundary(&self) -> &BoundaryLoop2 {
        &self.boundary
    }

    /// The T-mesh (parametric).
    pub fn mesh(&self) -> &TMesh<2> {
        &self.mesh
    }

    /// Physical position of every vertex.
    pub fn positions(&self) -> &[Point2] {
        &self.positions
    }

    /// Quality of every cell.
    pub fn quality(&self) -> &[f64] {
        &self.quality
    }

    /// The physical T-mesh as an unstructured grid: one polygon per cell through its corners and
    /// hanging vertices, counter-clockwise; point data `parametric` (u, v, 0), cell data
    /// `quality` and `level`.
    pub fn to_grid(&self) -> UnstructuredGrid {
        // Lattice points of a cell's boundary, counter-clockwise from (0, 0).
        const RING: [usize; 8] = [0, 1, 2, 5, 8, 7, 6, 3];
        let mut grid = UnstructuredGrid {
            points: self
                .positions
                .iter()
                .flat_map(|p| [p[0], p[1], 0.0])
                .collect(),
            ..Default::default()
        };
        for c in 0..self.mesh.cell_count() {
            let (lattice, vertices) = self.mesh.cell_vertices(c);
            for l in RING {
                if let Some(i) = lattice.iter().position(|&x| x == l) {
                    grid.connectivity.push(vertices[i] as i64);
                }
            }
            grid.offsets.push(grid.connectivity.len() as i64);
            grid.types.push(VTK_POLYGON);
        }
        grid.point_data.push(DataArray {
            name: "parametric".into(),
            components: 3,
            values: self
                .mesh
                .parametric()
                .iter()
                .flat_map(|p| [p[0], p[1], 0.0])
                .collect(),
        });
        grid.cell_data.push(DataArray {
            name: "quality".into(),
            components: 1,
            values: self.quality.clone(),
        });
        grid.cell_data.push(DataArray {
            name: "level".into(),
            components: 1,
            values: (0..self.mesh.cell_count())
                .map(|c| self.mesh.cell_level(c) as f64)
                .collect(),
        });
        grid
    }
}
