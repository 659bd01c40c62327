//! The pipeline shared by planar and solid domains, written once for d = 2 and 3: adapt a
//! balanced tree to the boundary, place the vertices (boundary ones on the boundary, inner ones by
//! transfinite interpolation), then untangle and smooth with the optimizer.

use std::time::Instant;

use super::budget::Sweeps;
use super::cube_map::{cell_boundary_error, facet_scale, transfinite, CubeMap};
use super::frame::{on_grid_point, signed_measure, Frame, Framed};
use super::options::{
    cells_within, check_uniform_cells, sweep_options, thread_pool, DomainOptions, DomainReport,
    StageSeconds,
};
use crate::error::{Error, Result};
use crate::io::vtu::{DataArray, UnstructuredGrid};
use crate::optimize::laplace::MeshGraph;
use crate::optimize::motion::{follow_motion, optimize_in_place};
use crate::optimize::small_matrix::bounding_box;
use crate::optimize::{invalid_cells, lattice, Problem, QualitySummary};
use crate::tmesh::{TMesh, Tree};

/// A domain with its optimized T-mesh: parametric vertices in \[0,1\]^d, physical ones in the
/// domain.
#[derive(Clone, Debug)]
pub struct Domain<const D: usize, B> {
    pub(super) boundary: B,
    /// Whether the boundary map's first two parametric coordinates are swapped.
    pub(super) swapped: bool,
    pub(super) frame: Frame<D>,
    /// The options it was built with.
    pub(super) options: DomainOptions,
    pub(super) mesh: TMesh<D>,
    /// Vertex positions in the frame's coordinates.
    pub(super) framed: Vec<[f64; D]>,
    pub(super) positions: Vec<[f64; D]>,
    pub(super) quality: Vec<f64>,
}

impl<const D: usize, B: CubeMap<D>> Domain<D, B> {
    /// Adapts a T-mesh to the boundary, places its vertices and optimizes them.
    /// `progress(sweeps, 0)` is called after every sweep; returning false cancels. Fails when
    /// cells stay invalid on a planar T-mesh whose boundary facets' images cross each other (the
    /// boundary comes closer to itself than the cells resolve), saying where.
    pub fn build(
        boundary: B,
        options: &DomainOptions,
        progress: &mut dyn FnMut(usize, usize) -> bool,
    ) -> Result<(Self, DomainReport)> {
        let start = Instant::now();
        options.validate()?;
        let (swapped, frame) = oriented_frame(&boundary)?;
        let framed_boundary = Framed {
            inner: &boundary,
            swap: swapped,
            frame: Some(frame),
        };
        let mesh = adapted_mesh(&framed_boundary, options, progress)?;
        let mut stages = StageSeconds {
            adaptation: start.elapsed().as_secs_f64(),
            ..Default::default()
        };
        let clock = Instant::now();
        let mut x = placed(&mesh, &framed_boundary);
        let problem = mesh.problem()?;
        let pool = thread_pool(options)?;
        let invalid_after_placement = invalid_cells(&pool, &problem, &x).len();
        stages.placement = clock.elapsed().as_secs_f64();
        let clock = Instant::now();
        let mut per_sweep = |d: usize| progress(d, 0);
        let mut sweeps = Sweeps::new(options.max_total_sweeps, &mut per_sweep);
        optimize_or_grow(&pool, &problem, &mesh, &mut x, options, &mut sweeps)?;
        stages.optimization = clock.elapsed().as_secs_f64();
        let clock = Instant::now();
        let mut domain = Domain {
            boundary,
            swapped,
            frame,
            options: *options,
            mesh,
            positions: Vec::new(),
            quality: QualitySummary::of(&pool, &problem, &x).quality,
            framed: Vec::new(),
        };
        domain.set_framed(x);
        let repair_rounds = domain.relieve_and_repair(options, &pool, &mut sweeps)?;
        stages.repair = clock.elapsed().as_secs_f64();
        let (spent, exhausted) = (sweeps.spent(), sweeps.exhausted());
        let clock = Instant::now();
        let polished = domain.polish(options, &pool, &mut |_| progress(spent as usize, 0))?;
        stages.polish = clock.elapsed().as_secs_f64();
        let mut report = domain.report(&pool)?;
        report.invalid_after_placement = invalid_after_placement;
        report.sweeps = spent;
        report.sweep_budget_exhausted = exhausted;
        report.repair_rounds = repair_rounds;
        report.newton_iterations = polished.iterations;
        report.gradient_norm = polished.gradient_norm;
        report.stages = stages;
        report.seconds = start.elapsed().as_secs_f64();
        domain.refuse_crossing_image(report.invalid_cells)?;
        Ok((domain, report))
    }

    /// The boundary map as the optimizer sees it: oriented, in the frame's coordinates.
    pub(super) fn framed_boundary(&self) -> Framed<'_, B, D> {
        Framed {
            inner: &self.boundary,
            swap: self.swapped,
            frame: Some(self.frame),
        }
    }

    /// Sets the vertex positions in the frame's coordinates, `x`, and the physical ones: those of
    /// [`Frame::to_physical`], except that a boundary vertex at its point of the boundary (to
    /// the grid onto which the framed boundary is rounded) goes to the exact physical point: the
    /// rounding moves no boundary vertex off the boundary (two domains sharing a curve keep
    /// their vertices on it, each exactly).
    pub(super) fn set_framed(&mut self, x: Vec<[f64; D]>) {
        debug_assert_eq!(x.len(), self.mesh.vertex_count());
        let framed = self.framed_boundary();
        let parametric = self.mesh.parametric();
        self.positions = x
            .iter()
            .zip(parametric)
            .enumerate()
            .map(|(v, (&y, p))| {
                if self.mesh.on_boundary(v) && on_grid_point(y, framed.boundary_point(p)) {
                    self.boundary_point(p)
                } else {
                    self.frame.to_physical(y)
                }
            })
            .collect();
        self.framed = x;
    }

    /// The report of the current T-mesh (`invalid_after_placement`, `sweeps`, `seconds` and the
    /// stage times left 0).
    pub(super) fn report(&self, pool: &rayon::ThreadPool) -> Result<DomainReport> {
        let problem = self.mesh.problem()?;
        let framed = self.framed_boundary();
        let boundary_error = self
            .mesh
            .tree()
            .leaves()
            .into_iter()
            .map(|c| cell_boundary_error(self.mesh.tree(), c, &framed))
            .fold(0.0, f64::max)
            / facet_scale::<D>();
        let quality = QualitySummary::of(pool, &problem, &self.framed);
        Ok(DomainReport {
            cells: self.mesh.cell_count(),
            vertices: self.mesh.vertex_count(),
            max_level: (0..self.mesh.cell_count())
                .map(|c| self.mesh.cell_level(c))
                .max()
                .unwrap_or(0),
            boundary_error,
            boundary_offset: self.boundary_offset(),
            invalid_cells: quality.invalid.len(),
            min_quality: quality.min,
            mean_quality: quality.mean,
            swapped: self.swapped,
            ..Default::default()
        })
    }

    /// The affine frame in which the T-mesh is optimized.
    pub fn frame(&self) -> Frame<D> {
        self.frame
    }

    /// The options the domain was built with (its `boundary_offset` also caps how far
    /// [`SplineMap::untangle`](crate::spline::SplineMap::untangle) may move the boundary of
    /// the spline map fitted by the C API).
    pub fn options(&self) -> &DomainOptions {
        &self.options
    }

    /// The boundary.
    pub fn boundary(&self) -> &B {
        &self.boundary
    }

    /// The physical point of the boundary at `p`, a point of the boundary of \[0,1\]^d in the
    /// T-mesh's parametric coordinates (the boundary's own, or with the first two swapped when
    /// the report says `swapped`).
    pub fn boundary_point(&self, p: [f64; D]) -> [f64; D] {
        Framed {
            frame: None,
            ..self.framed_boundary()
        }
        .boundary_point(p)
    }

    /// The T-mesh (parametric).
    pub fn mesh(&self) -> &TMesh<D> {
        &self.mesh
    }

    /// Physical position of every vertex.
    pub fn positions(&self) -> &[[f64; D]] {
        &self.positions
    }

    /// Quality of every cell.
    pub fn quality(&self) -> &[f64] {
        &self.quality
    }

    /// The physical T-mesh as an unstructured grid: in 2D one polygon per cell through its corners
    /// and hanging vertices, counter-clockwise; in 3D one hexahedron per cell through its corners.
    /// Point data `parametric`, cell data `quality` and `level`.
    pub fn to_grid(&self) -> UnstructuredGrid {
        // 2D: the lattice points of a cell's boundary, counter-clockwise; 3D: the corners in VTK's
        // hexahedron order.
        let (ring, cell_type): (&[usize], u8) = if D == 2 {
            (&[0, 1, 2, 5, 8, 7, 6, 3], VTK_POLYGON)
        } else {
            (&[0, 2, 8, 6, 18, 20, 26, 24], VTK_HEXAHEDRON)
        };
        let pad =
            |p: &[f64; D]| -> [f64; 3] { std::array::from_fn(|k| if k < D { p[k] } else { 0.0 }) };
        let mut grid = UnstructuredGrid {
            points: self.positions.iter().flat_map(pad).collect(),
            ..Default::default()
        };
        for c in 0..self.mesh.cell_count() {
            let (lattice_points, vertices) = self.mesh.cell_vertices(c);
            for &l in ring {
                if let Some(i) = lattice_points.iter().position(|&x| x == l) {
                    grid.connectivity.push(vertices[i] as i64);
                }
            }
            grid.offsets.push(grid.connectivity.len() as i64);
            grid.types.push(cell_type);
        }
        debug_assert!(ring.iter().all(|&l| l < lattice::count(D)));
        grid.point_data.push(DataArray {
            name: "parametric".into(),
            components: 3,
            values: self.mesh.parametric().iter().flat_map(pad).collect(),
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

/// Whether the boundary map is left-handed (then its first two parametric coordinates are
/// swapped), and the frame of the map so oriented; fails on a boundary without extent.
fn oriented_frame<const D: usize, B: CubeMap<D>>(boundary: &B) -> Result<(bool, Frame<D>)> {
    let swapped = signed_measure(boundary) < 0.0;
    let frame = Frame::of(&Framed {
        inner: boundary,
        swap: swapped,
        frame: None,
    })
    .ok_or_else(|| {
        Error::invalid("the boundary has no extent: its bounding box is flat or not finite")
    })?;
    Ok((swapped, frame))
}

/// The T-mesh of the tree adapted to `boundary`: refined uniformly to `min_level`, then where a
/// cell's boundary error is over the tolerance (up to `max_level`), within the cell budget.
/// `progress(0, 0)` is called between the refinement rounds; returning false cancels.
fn adapted_mesh<const D: usize>(
    boundary: &impl CubeMap<D>,
    options: &DomainOptions,
    progress: &mut dyn FnMut(usize, usize) -> bool,
) -> Result<TMesh<D>> {
    let limit = options.tolerance * facet_scale::<D>();
    check_uniform_cells::<D>(options)?;
    let mut tree = Tree::<D>::new();
    tree.refine_uniformly(options.min_level)?;
    let marked = |tree: &Tree<D>, c: usize| {
        tree.cells()[c].level < options.max_level && cell_boundary_error(tree, c, boundary) > limit
    };
    let within = |cells: usize| cells_within(options, cells, "the adaptation to the boundary");
    tree.refine_while_bounded(true, marked, &mut |cells| {
        within(cells)?;
        // Between rounds: a chance to cancel a long adaptation (0 sweeps so far).
        match progress(0, 0) {
            true => Ok(()),
            false => Err(Error::cancelled()),
        }
    })?;
    within(tree.leaves().len())?;
    TMesh::new(tree)
}

/// The first positions of the vertices: the boundary ones on the boundary, the inner ones by
/// transfinite interpolation.
fn placed<const D: usize>(mesh: &TMesh<D>, boundary: &impl CubeMap<D>) -> Vec<[f64; D]> {
    mesh.parametric()
        .into_iter()
        .enumerate()
        .map(|(v, p)| {
            if mesh.on_boundary(v) {
                boundary.boundary_point(p)
            } else {
                transfinite(boundary, p)
            }
        })
        .collect()
}

/// The first optimization of a build's placed vertices `x`; if cells stay folded, the growth of
/// the domain from its bounding box instead, kept if it leaves fewer folded cells. Stops where
/// the sweep budget runs out.
fn optimize_or_grow<const D: usize>(
    pool: &rayon::ThreadPool,
    problem: &Problem<D>,
    mesh: &TMesh<D>,
    x: &mut Vec<[f64; D]>,
    options: &DomainOptions,
    sweeps: &mut Sweeps<'_>,
) -> Result<()> {
    let sweep_options = sweep_options(options);
    let first = optimize_in_place(pool, problem, x, &sweep_options, &mut sweeps.stage());
    sweeps.absorb(first)?;
    let invalid = invalid_cells(pool, problem, x);
    // The growth is kept only if it leaves fewer folded cells; it cannot when every folded cell
    // has a fold that only fixed (boundary) vertices make, as on a solid's seams.
    if sweeps.exhausted() || invalid.iter().all(|&c| problem.has_fixed_fold(c, x)) {
        return Ok(());
    }
    // The transfinite start folds too much (deep necks): grow the domain instead from its
    // bounding box, where the parametric grid is valid, following the boundary in steps.
    let (lo, hi) = bounding_box(x.iter().copied());
    let start: Vec<[f64; D]> = mesh
        .parametric()
        .into_iter()
        .map(|p| std::array::from_fn(|k| lo[k] + p[k] * (hi[k] - lo[k])))
        .collect();
    let graph = MeshGraph::new(problem);
    let grown = follow_motion(
        pool,
        problem,
        &graph,
        &start,
        x,
        &sweep_options,
        &mut sweeps.stage(),
    );
    if let Some((grown, _)) = sweeps.absorb(grown)? {
        if invalid_cells(pool, problem, &grown).len() < invalid.len() {
            *x = grown;
        }
    }
    Ok(())
}

/// VTK's polygon cell type.
const VTK_POLYGON: u8 = 7;
/// VTK's hexahedron cell type.
const VTK_HEXAHEDRON: u8 = 12;
