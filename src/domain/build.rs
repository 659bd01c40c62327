//! The pipeline shared by planar and solid domains, written once for d = 2 and 3: adapt a
//! balanced tree to the boundary, place the vertices (boundary ones on the boundary, inner ones by
//! transfinite interpolation), then untangle and smooth with the optimizer.

use std::time::Instant;

use super::budget::Sweeps;
use super::frame::{signed_measure, Frame, Framed};
use crate::error::{Error, ErrorKind, Result};
use crate::io::vtu::{DataArray, UnstructuredGrid};
use crate::optimize::laplace::MeshGraph;
use crate::optimize::motion::{follow_motion, optimize_in_place};
use crate::optimize::small::{bounding_box, det, Matrix};
use crate::optimize::{
    invalid_cells, lattice, NodeSolverOptions, Problem, QualitySummary, SweepOptions,
};
use crate::tmesh::{TMesh, Tree, UNIT};

/// A map from the boundary of the unit square (d = 2) or cube (d = 3) onto the boundary of a
/// domain.
pub trait CubeMap<const D: usize> {
    /// The image of `p`, a point of the boundary of [0,1]^d (some coordinate is exactly 0 or 1).
    fn boundary_point(&self, p: [f64; D]) -> [f64; D];
}

/// Options of [`Domain::build`].
#[derive(Clone, Copy, Debug)]
pub struct DomainOptions {
    /// Boundary tolerance, relative to the bounding box: a boundary facet of a cell is refined
    /// while the triangle (2D: its end images and the image of its midpoint) or the four
    /// tetrahedra (3D: consecutive corner images and the image of the face centre), measured in
    /// coordinates that map the bounding box onto a unit box (see [`Frame`]), exceed
    /// `tolerance × √d^d` (for a square or cube box: `tolerance × diagonal^d`).
    pub tolerance: f64,
    /// Level of the initial uniform refinement.
    pub min_level: u8,
    /// Deepest level of the adaptation.
    pub max_level: u8,
    /// Largest number of optimization sweeps of one stage (the first optimization, each step of
    /// the growth from the bounding box, each round of the seam relief and of the repair).
    pub max_sweeps: u32,
    /// Largest number of sweeps of all stages together, at least 1 (default
    /// [`DEFAULT_MAX_TOTAL_SWEEPS`]): once spent, the running stage stops after its sweep and no
    /// later stage starts; the T-mesh is what the sweeps so far made of it, and the report says
    /// so ([`DomainReport::sweep_budget_exhausted`]).
    pub max_total_sweeps: u32,
    /// Worker threads; 0 uses one per core.
    pub threads: usize,
    /// Rounds of repair after the optimization: while cells stay invalid, they are refined (as
    /// by [`Domain::refine_cells`], past `max_level` up to level 16) and the mesh re-optimized.
    pub repair_rounds: u32,
    /// Largest distance, in coordinates that map the bounding box onto a unit box (see
    /// [`Frame`]), by which a boundary vertex may leave the boundary to open a cell that stays
    /// folded with every boundary vertex on the boundary (see [`MARGIN`](super::relief::MARGIN)
    /// and the seam relief); 0 keeps every boundary vertex on the boundary. Default 1e-2: the
    /// jagged terrain edge of the Jacksboro block needs offsets near it, the jittered duck faces
    /// 1e-3 with a few more levels of refinement.
    pub boundary_offset: f64,
    /// Largest number of cells of the T-mesh (default [`DEFAULT_MAX_CELLS`]): a build whose
    /// uniform refinement to `min_level` would exceed it is refused before any work, and one
    /// whose adaptation or repair exceeds it stops there, with [`ErrorKind::LimitExceeded`].
    pub max_cells: usize,
}

/// The default cell budget of a domain build (`max_cells` of its options): a million cells, a
/// planar T-mesh of level 10 everywhere (minutes of optimization and about a gigabyte; a
/// solid's cells cost more).
pub const DEFAULT_MAX_CELLS: usize = 1_000_000;

/// The default total sweep budget of a domain build (`max_total_sweeps` of its options): 25
/// times the default `max_sweeps`. The bundled domains need at most 4,071 (the duck's B-rep at
/// tolerance 1e-4, level 4, with its growth from the bounding box and its repair); inputs that
/// fold at every level stop here, after seconds, instead of running for minutes.
pub const DEFAULT_MAX_TOTAL_SWEEPS: u32 = 5_000;

impl DomainOptions {
    /// Checks the ranges of every field (what [`Domain::build`] checks before any work).
    pub fn validate(&self) -> Result<()> {
        check_options(self)
    }

    /// The defaults of a solid: [`DomainOptions::default`] with a boundary tolerance of 1e-3
    /// instead of 1e-5. A tolerance bounds a volume in 3D (an area in 2D), and at 1e-3 the
    /// shared solids (the duck's B-rep and faces, the Jacksboro block with its axes in km) give
    /// valid T-meshes of 64–92 cells and certified spline maps in seconds, where 1e-5 refines
    /// for many minutes.
    pub fn solid() -> Self {
        DomainOptions {
            tolerance: 1e-3,
            ..Default::default()
        }
    }
}

/// The defaults of a planar domain (see [`DomainOptions::solid`] for a solid's).
impl Default for DomainOptions {
    fn default() -> Self {
        DomainOptions {
            tolerance: 1e-5,
            min_level: 2,
            max_level: 9,
            max_sweeps: 200,
            max_total_sweeps: DEFAULT_MAX_TOTAL_SWEEPS,
            threads: 0,
            repair_rounds: 6,
            boundary_offset: 1e-2,
            max_cells: DEFAULT_MAX_CELLS,
        }
    }
}

/// What [`Domain::build`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DomainReport {
    /// Cells of the T-mesh.
    pub cells: usize,
    /// Vertices of the T-mesh, hanging ones included.
    pub vertices: usize,
    /// Deepest level.
    pub max_level: u8,
    /// Largest boundary error, relative (see [`DomainOptions::tolerance`]).
    pub boundary_error: f64,
    /// Largest distance of a boundary vertex from its point on the boundary, in coordinates
    /// that map the bounding box onto a unit box (at most [`DomainOptions::boundary_offset`]).
    pub boundary_offset: f64,
    /// Invalid cells after the transfinite placement.
    pub invalid_after_placement: usize,
    /// Invalid cells after the optimization.
    pub invalid_cells: usize,
    /// Smallest cell quality (1/mean distortion against the parametric cell).
    pub min_quality: f64,
    /// Mean cell quality.
    pub mean_quality: f64,
    /// Optimization sweeps (with those of the fallback growth from the bounding box and of the
    /// repair).
    pub sweeps: u32,
    /// Whether the optimization stopped because it spent
    /// [`DomainOptions::max_total_sweeps`]: the T-mesh is the state the sweeps reached, less
    /// optimized (and possibly with more invalid cells) than a larger budget would give.
    pub sweep_budget_exhausted: bool,
    /// Repair rounds that refined invalid cells.
    pub repair_rounds: u32,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// Wall-clock seconds of each stage.
    pub stages: StageSeconds,
    /// Whether the boundary's parameterization is left-handed, so that the T-mesh's first two
    /// parametric coordinates are swapped relative to it.
    pub swapped: bool,
}

/// Wall-clock seconds of the stages of [`Domain::build`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StageSeconds {
    /// Adapting the tree to the boundary and building the T-mesh.
    pub adaptation: f64,
    /// Placing the vertices (boundary and transfinite interpolation).
    pub placement: f64,
    /// Optimizing, with the fallback growth from the bounding box.
    pub optimization: f64,
    /// Refining the cells left invalid and optimizing again.
    pub repair: f64,
}

/// A domain with its optimized T-mesh: parametric vertices in [0,1]^d, physical ones in the
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

/// Largest boundary error over the facets of leaf `c` that lie on the boundary of [0,1]^d.
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

impl<const D: usize, B: CubeMap<D>> Domain<D, B> {
    /// Adapts a T-mesh to the boundary, places its vertices and optimizes them.
    /// `progress(sweeps, 0)` is called after every sweep; returning false cancels.
    pub fn build(
        boundary: B,
        options: &DomainOptions,
        progress: &mut dyn FnMut(usize, usize) -> bool,
    ) -> Result<(Self, DomainReport)> {
        let start = Instant::now();
        check_options(options)?;
        let swapped = signed_measure(&boundary) < 0.0;
        let frame = Frame::of(&Framed {
            inner: &boundary,
            swap: swapped,
            frame: Frame::IDENTITY,
        })
        .ok_or_else(|| {
            Error::invalid("the boundary has no extent: its bounding box is flat or not finite")
        })?;
        let framed_boundary = Framed {
            inner: &boundary,
            swap: swapped,
            frame,
        };
        let limit = options.tolerance * facet_scale::<D>();
        check_uniform_cells::<D>(options)?;
        let mut tree = Tree::<D>::new();
        tree.refine_uniformly(options.min_level)?;
        let marked = |tree: &Tree<D>, c: usize| {
            tree.cells()[c].level < options.max_level
                && cell_boundary_error(tree, c, &framed_boundary) > limit
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
        let mesh = TMesh::new(tree)?;
        let mut stages = StageSeconds {
            adaptation: start.elapsed().as_secs_f64(),
            ..Default::default()
        };
        let clock = Instant::now();
        let mut x: Vec<[f64; D]> = mesh
            .parametric()
            .into_iter()
            .enumerate()
            .map(|(v, p)| {
                if mesh.on_boundary(v) {
                    framed_boundary.boundary_point(p)
                } else {
                    transfinite(&framed_boundary, p)
                }
            })
            .collect();
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
            positions: x.iter().map(|&p| frame.to_physical(p)).collect(),
            quality: QualitySummary::of(&pool, &problem, &x).quality,
            framed: x,
        };
        let repair_rounds = domain.relieve_and_repair(options, &pool, &mut sweeps)?;
        stages.repair = clock.elapsed().as_secs_f64();
        let mut report = domain.report(&pool)?;
        report.invalid_after_placement = invalid_after_placement;
        report.sweeps = sweeps.spent();
        report.sweep_budget_exhausted = sweeps.exhausted();
        report.repair_rounds = repair_rounds;
        report.stages = stages;
        report.seconds = start.elapsed().as_secs_f64();
        Ok((domain, report))
    }

    /// The boundary map as the optimizer sees it: oriented, in the frame's coordinates.
    pub(super) fn framed_boundary(&self) -> Framed<'_, B, D> {
        Framed {
            inner: &self.boundary,
            swap: self.swapped,
            frame: self.frame,
        }
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

/// Deepest level the repair refines to.
pub(super) const MAX_REPAIR_LEVEL: u8 = 16;

/// `√d^d`: the measure of a facet error equal to the tolerance, in frame coordinates (the
/// diagonal of the unit box to the power d).
pub(super) fn facet_scale<const D: usize>() -> f64 {
    (D as f64).powf(D as f64 / 2.0)
}

/// Refuses a build whose uniform refinement to `min_level` alone exceeds `max_cells`.
fn check_uniform_cells<const D: usize>(options: &DomainOptions) -> Result<()> {
    let cells = 1u128 << (D * options.min_level as usize);
    if cells > options.max_cells as u128 {
        return Err(Error::new(
            ErrorKind::LimitExceeded,
            format!(
                "min_level = {} refines [0,1]^{D} into {cells} cells, above max_cells = {}: \
                 lower min_level or raise max_cells",
                options.min_level, options.max_cells
            ),
        ));
    }
    Ok(())
}

/// Refuses a T-mesh of `cells` cells beyond `max_cells`; `stage` names what made them.
pub(super) fn cells_within(options: &DomainOptions, cells: usize, stage: &str) -> Result<()> {
    if cells > options.max_cells {
        return Err(Error::new(
            ErrorKind::LimitExceeded,
            format!(
                "{stage} reached {cells} cells, above max_cells = {}: raise the tolerance or \
                 max_cells, or lower max_level",
                options.max_cells
            ),
        ));
    }
    Ok(())
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
    if sweeps.exhausted() || invalid_cells(pool, problem, x).is_empty() {
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
        if invalid_cells(pool, problem, &grown).len() < invalid_cells(pool, problem, x).len() {
            *x = grown;
        }
    }
    Ok(())
}

/// Checks the options shared by [`Domain::build`] and [`Domain::refine_cells`].
pub(super) fn check_options(options: &DomainOptions) -> Result<()> {
    for (name, value) in [
        ("tolerance", options.tolerance),
        ("boundary_offset", options.boundary_offset),
    ] {
        if !value.is_finite() {
            return Err(Error::new(
                ErrorKind::NotFinite,
                format!("{name} is {value}, it must be finite"),
            ));
        }
    }
    crate::threads::check(options.threads)?;
    if options.tolerance <= 0.0 {
        return Err(Error::invalid(format!(
            "tolerance = {} must be positive",
            options.tolerance
        )));
    }
    if options.min_level > options.max_level || options.max_level > MAX_REPAIR_LEVEL {
        return Err(Error::invalid(format!(
            "levels must satisfy min_level <= max_level <= 16, got min_level = {}, max_level = {}",
            options.min_level, options.max_level
        )));
    }
    if options.max_total_sweeps == 0 {
        return Err(Error::invalid(
            "max_total_sweeps = 0: the sweep budget of a build must be at least 1",
        ));
    }
    if options.boundary_offset < 0.0 {
        return Err(Error::invalid(format!(
            "boundary_offset = {} must be at least 0",
            options.boundary_offset
        )));
    }
    Ok(())
}

/// The worker threads of the options.
pub(super) fn thread_pool(options: &DomainOptions) -> Result<rayon::ThreadPool> {
    crate::threads::pool(options.threads)
}

/// The sweep options of a domain's optimization.
pub(super) fn sweep_options(options: &DomainOptions) -> SweepOptions {
    SweepOptions {
        max_sweeps: options.max_sweeps,
        move_tolerance: 1e-3,
        node: NodeSolverOptions {
            gradient_tolerance: 1e-3,
            max_iterations: 150,
            relaxation: 1.8,
        },
    }
}

/// VTK's polygon cell type.
const VTK_POLYGON: u8 = 7;
/// VTK's hexahedron cell type.
const VTK_HEXAHEDRON: u8 = 12;
