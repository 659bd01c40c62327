"""ctypes declarations of the C API, generated from ``include/igaparam.h``; do not edit.

Regenerate with ``IGAPARAM_BLESS=1 cargo test --test header`` (which runs
``bindings/python/gen_ffi.py`` after cbindgen). Structures and enums carry the Python names
of their C types (``igaparam_relocate_options`` is ``RelocateOptions``), constants lose the
``IGAPARAM_`` prefix, and ``PROTOTYPES`` maps every function to its ctypes ``restype``,
``argtypes`` and documentation. Use :mod:`igaparam` rather than this module.
"""

import ctypes
import enum

# The fingerprint of the header's declarations (see ``igaparam_abi_fingerprint``): the loader
# refuses a library built from other declarations instead of calling it with wrong layouts.
ABI_FINGERPRINT = 0xd03185e8e07d7b25

# Major version of the library this header belongs to.
VERSION_MAJOR = 0

# Minor version of the library this header belongs to.
VERSION_MINOR = 1

# Patch version of the library this header belongs to.
VERSION_PATCH = 0

# Number of bins of the quality histogram of `igaparam_validity_report`.
HISTOGRAM_BINS = 10

# The default cell budget of a domain build (`max_cells` of its options): a million cells, a
# planar T-mesh of level 10 everywhere (minutes of optimization and about a gigabyte; a
# solid's cells cost more).
DEFAULT_MAX_CELLS = 1000000

# The default total sweep budget of a domain build (`max_total_sweeps` of its options): 25
# times the default `max_sweeps`. The bundled domains need at most 4,071 (the duck's B-rep at
# tolerance 1e-4, level 4, with its growth from the bounding box and its repair); inputs that
# fold at every level stop here, after seconds, instead of running for minutes.
DEFAULT_MAX_TOTAL_SWEEPS = 5000

# Where the Newton method stops when no stationarity tolerance is asked for.
DEFAULT_NEWTON_TOLERANCE = 1e-8

# The largest `max_depth` accepted.
QUALITY_BOUND_MAX_DEPTH = 8

# The depth a solid's bound is subdivided to at most, whatever `max_depth` says.
QUALITY_BOUND_MAX_SOLID_DEPTH = 3

# The largest thread count an option accepts (larger ones are refused as invalid).
MAX_THREADS = 4096


class Status(enum.IntEnum):
    """Status of a call. `IGAPARAM_STATUS_OK` is zero; every other value comes with a message from
    `igaparam_last_error_message`.

    (``igaparam_status``)
    """
    OK = 0
    """Success."""
    NULL_ARGUMENT = 1
    """A required pointer argument was NULL."""
    INVALID_ARGUMENT = 2
    """An argument is out of range, of the wrong size or inconsistent with the others."""
    NOT_FINITE = 3
    """An input value is NaN or infinite."""
    INVALID_MESH = 4
    """The mesh is unusable: its connectivity refers to a node that does not exist or repeats a
    node within a cell.
    """
    BUFFER_TOO_SMALL = 5
    """A caller-provided output buffer is too small; the message says the size needed."""
    CANCELLED = 6
    """The progress callback returned non-zero."""
    IO = 7
    """A file could not be read or written."""
    INTERNAL = 8
    """An internal error (a bug): the message says what; please report it."""
    BUSY = 9
    """A handle argument is in use by another call: one made from the progress callback of a
    running call on it, or from another thread. A handle takes one call at a time; the call
    was refused and changed nothing.
    """
    LIMIT_EXCEEDED = 10
    """The work asked for exceeds a resource limit (e.g. the cells of a domain build beyond
    `max_cells`); the message gives the estimate and the option that raises the limit.
    """


class Stage(enum.IntEnum):
    """A stage of long work, passed to the progress callback.

    (``igaparam_stage``)
    """
    PLACEMENT = 0
    """First placement of the free nodes."""
    OPTIMIZATION = 1
    """Optimization sweeps: `done` sweeps so far over all steps; `total` is 0 (not known in
    advance, as large motions may be split into more steps).
    """
    ADAPTATION = 2
    """Adaptive refinement of a domain's T-mesh from the quality of its spline map: `done`
    rounds of `total` at most.
    """
    STATIONARITY = 3
    """Newton iterations on the global objective (`stationarity_tolerance`): `done` so far,
    `total` 0.
    """
    FIT = 4
    """The fits and certifications of `igaparam_spline_fit_domain_with`: `done` of `total`."""
    UNTANGLING = 5
    """Untangling rounds of a fitted map that is not certified: `done` of at most `total`."""
    SMOOTHING = 6
    """Smoothing sweeps of a certified map: `done` of at most `total`."""


class FitRule(enum.IntEnum):
    """How the control points of a spline come from the T-mesh's map.

    (``igaparam_fit_rule``)
    """
    INTERPOLATION = 0
    """Interpolation at the Greville points."""
    LEAST_SQUARES = 1
    """Least squares at the Greville points and 4^d points per element."""
    QUASI_INTERPOLATION = 2
    """The local quasi-interpolant."""


# A planar domain bounded by four curves or a solid bounded by six surfaces, and once built
# its T-mesh parameterization (opaque). Create a planar one with
# `igaparam_domain_new_from_file` or `igaparam_domain_new_from_polylines`, a solid with
# `igaparam_domain_new_solid_from_file`, `igaparam_domain_new_solid_from_file_scaled` or
# `igaparam_domain_new_solid_from_triangulations`; build with `igaparam_domain_build`,
# release with `igaparam_domain_free`. One call at a time (see `IGAPARAM_STATUS_BUSY`).
# igaparam_domain * is passed as ctypes.c_void_p

# A quadrilateral or hexahedral finite-element mesh with node constraints (opaque).
# Create with `igaparam_mesh_new`, release with `igaparam_mesh_free`. One call at a time
# (see `IGAPARAM_STATUS_BUSY`).
# igaparam_mesh * is passed as ctypes.c_void_p

# A rank's part of a partitioned mesh (opaque). Create with `igaparam_partition_new`, release
# with `igaparam_partition_free`. One call at a time (see `IGAPARAM_STATUS_BUSY`).
# igaparam_partition * is passed as ctypes.c_void_p

# A cubic truncated hierarchical B-spline (THB) map `S: [0,1]^d → Ω`, d = 2 or 3 (opaque).
# Create with `igaparam_spline_fit_domain` or `igaparam_spline_read_gismo`, release with
# `igaparam_spline_free`. Parametric points are `d` doubles in [0,1]^d, physical points `d`
# doubles; arrays of points are flat, `n × d` (x0 y0 x1 y1 ... in 2D). One call at a time
# (see `IGAPARAM_STATUS_BUSY`).
# igaparam_spline * is passed as ctypes.c_void_p

# Progress callback: `user` is the options' `progress_user`; `done` of `total` steps of `stage`
# are complete. Return 0 to go on, non-zero to cancel (the call then returns
# `IGAPARAM_STATUS_CANCELLED` and leaves the mesh unchanged). Called on the calling thread.
# int (*igaparam_progress_fn)(void * user, igaparam_stage stage, size_t done, size_t total)
PROGRESS_FN = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_int, ctypes.c_size_t, ctypes.c_size_t)


class DomainOptions(ctypes.Structure):
    """Options of `igaparam_domain_build`; get the defaults from `igaparam_domain_options_default`
    (planar) or `igaparam_domain_options_default_solid`.

    (``igaparam_domain_options``)

    Fields:

    tolerance:
        Boundary tolerance, positive: a boundary cell edge (planar domain) is refined while the
        triangle formed by its end images and the image of its parametric midpoint, or a boundary
        cell face (solid) while the four tetrahedra of consecutive corner images and the image of
        its centre, measured in coordinates that map the bounding box onto the unit box, exceed
        `tolerance × √d^d` (for a square or cube box: `tolerance × diagonal^d`; default 1e-5 for a
        planar domain, 1e-3 for a solid).
    min_level:
        Level of the initial uniform refinement (default 2).
    max_level:
        Deepest level of the adaptation, at least `min_level` and at most 16 (default 9).
    max_sweeps:
        Largest number of optimization sweeps of one stage (default 200): the first optimization,
        each step of the growth from the bounding box, each round of the seam relief and of the
        repair.
    max_total_sweeps:
        Largest number of sweeps of all stages together, at least 1 (default 5,000,
        `IGAPARAM_DEFAULT_MAX_TOTAL_SWEEPS`): once spent, the running stage stops after its sweep
        and no later stage starts; the build succeeds with the T-mesh the sweeps reached, and the
        report's `sweep_budget_exhausted` is set (check `invalid_cells`). The bundled domains need
        at most about 4,100; inputs that fold at every level stop here after seconds instead of
        running for minutes.
    threads:
        Worker threads, at most 4096, capped to the machine's cores; 0 (default) uses one per core.
    repair_rounds:
        Rounds of repair after the optimization (default 6): while cells stay invalid, they are
        refined (past `max_level`, up to level 16) and the mesh optimized again; 0 disables it.
    boundary_offset:
        Seam relief cap, finite and at least 0: the largest distance, in coordinates that map the
        bounding box onto the unit box, by which a boundary vertex may leave the boundary to open a
        cell that stays folded with every boundary vertex on it (default 1e-2: the jagged terrain
        edge of the Jacksboro block needs offsets near it, the jittered duck faces 1e-3 with a few
        more levels of refinement); 0 keeps every boundary vertex on the boundary.
    max_cells:
        Largest number of cells of the T-mesh (default 1,000,000, `IGAPARAM_DEFAULT_MAX_CELLS`): a
        build whose uniform refinement to `min_level` alone exceeds it (4^min_level cells for a
        planar domain, 8^min_level for a solid) is refused before any work, one whose adaptation or
        repair exceeds it stops there; both fail with `IGAPARAM_STATUS_LIMIT_EXCEEDED`
        (`ErrorKind::LimitExceeded`). Raise it for finer T-meshes (time and memory grow with the
        cells: minutes and about a gigabyte at the default in 2D, more for a solid).
    stationarity_tolerance:
        The Newton polish after the sweeps, finite and at least 0 (default 0: off): when positive
        and every cell is valid, the inner vertices go to a stationary point of the global objective
        (the sum of the cells' mean distortions, `F = Σ_cells η̄*_c` with δ = 0) to this scaled
        max-norm of its gradient (1e-8 is typical: a few to a few tens of Newton iterations). The
        stationary point depends on the basin the sweeps end in, not on their round-off within it;
        it raises the mean cell quality and may lower the smallest (the bundled planar domains: mean
        +3–11%, min −6% to −51%), so it is off by default.
    progress:
        Progress callback, or NULL (default). Called with `IGAPARAM_STAGE_OPTIMIZATION`, `done`
        sweeps so far and `total` 0, also between the rounds of the adaptation of the tree (with
        `done` 0); returning non-zero cancels the build.
    progress_user:
        Passed to `progress` as its first argument.
    """

    _fields_ = [
        ("tolerance", ctypes.c_double),
        ("min_level", ctypes.c_uint32),
        ("max_level", ctypes.c_uint32),
        ("max_sweeps", ctypes.c_uint32),
        ("max_total_sweeps", ctypes.c_uint32),
        ("threads", ctypes.c_uint32),
        ("repair_rounds", ctypes.c_uint32),
        ("boundary_offset", ctypes.c_double),
        ("max_cells", ctypes.c_size_t),
        ("stationarity_tolerance", ctypes.c_double),
        ("progress", PROGRESS_FN),
        ("progress_user", ctypes.c_void_p),
    ]


class DomainReport(ctypes.Structure):
    """What `igaparam_domain_build` did. Quality is the inverse mean distortion of a cell against its
    parametric (square) cell: 1 is a square, 0 an inverted cell.

    (``igaparam_domain_report``)

    Fields:

    cells:
        Cells of the T-mesh.
    vertices:
        Vertices of the T-mesh, hanging ones included.
    max_level:
        Deepest level of a cell.
    boundary_error:
        Largest boundary error, relative as `tolerance`.
    boundary_offset:
        Largest distance of a boundary vertex from its point on the boundary, in coordinates that
        map the bounding box onto the unit box (at most the option `boundary_offset`; 0 when no seam
        relief was needed).
    invalid_after_placement:
        Invalid cells (`det J ≤ 0` somewhere) after the transfinite (Coons) placement.
    invalid_cells:
        Invalid cells after the optimization; 0 for a usable parameterization.
    min_quality:
        Smallest cell quality (1/mean distortion against the parametric cell).
    mean_quality:
        Mean cell quality.
    sweeps:
        Optimization sweeps (with those of the fallback growth from the bounding box and of the
        repair).
    sweep_budget_exhausted:
        Whether the optimization stopped because it spent `max_total_sweeps` (1 in C, else 0): the
        T-mesh is the state the sweeps reached, less optimized (and possibly with more invalid
        cells) than a larger budget would give.
    newton_iterations:
        Newton iterations of the polish (`stationarity_tolerance > 0`; 0 when it is off or a cell
        stays invalid).
    gradient_norm:
        Scaled max-norm of the global objective's gradient after the polish: at most
        `stationarity_tolerance` when it converged (the state the sensitivities of a fitted spline,
        `igaparam_spline_tangent` and `igaparam_spline_adjoint`, differentiate), infinite when a
        cell stays invalid, 0 when the polish is off.
    seconds:
        Wall-clock seconds of the call.
    """

    _fields_ = [
        ("cells", ctypes.c_size_t),
        ("vertices", ctypes.c_size_t),
        ("max_level", ctypes.c_uint32),
        ("boundary_error", ctypes.c_double),
        ("boundary_offset", ctypes.c_double),
        ("invalid_after_placement", ctypes.c_size_t),
        ("invalid_cells", ctypes.c_size_t),
        ("min_quality", ctypes.c_double),
        ("mean_quality", ctypes.c_double),
        ("sweeps", ctypes.c_uint32),
        ("sweep_budget_exhausted", ctypes.c_int),
        ("newton_iterations", ctypes.c_uint32),
        ("gradient_norm", ctypes.c_double),
        ("seconds", ctypes.c_double),
    ]


class Curve(ctypes.Structure):
    """A B-spline or NURBS curve of the plane given by arrays, read (and copied) by the functions
    that take it. The curve is `C(t) = Σ w_i N_i(t) P_i / Σ w_i N_i(t)` over its knot domain
    `[knots[degree], knots[control_point_count]]` (all `w_i` = 1 without weights).

    (``igaparam_curve``)

    Fields:

    degree:
        Polynomial degree p, at least 1.
    knot_count:
        Number of knots: `control_point_count + degree + 1`.
    knots:
        `knot_count` knots: finite, non-decreasing, none repeated more than p + 1 times.
    control_point_count:
        Number of control points n.
    control_points:
        `n × 2` doubles (x0 y0 x1 y1 ...), finite.
    weights:
        `n` positive finite weights (a NURBS curve), or NULL (a B-spline curve).
    """

    _fields_ = [
        ("degree", ctypes.c_uint32),
        ("knot_count", ctypes.c_size_t),
        ("knots", ctypes.POINTER(ctypes.c_double)),
        ("control_point_count", ctypes.c_size_t),
        ("control_points", ctypes.POINTER(ctypes.c_double)),
        ("weights", ctypes.POINTER(ctypes.c_double)),
    ]


class Surface(ctypes.Structure):
    """A tensor-product B-spline or NURBS surface in 3D given by arrays, read (and copied) by the
    functions that take it. Control point `(i, j)` (i along u, j along v) is number
    `i + j × control_point_count_u`: the first parameter runs fastest, as in G+Smo.

    (``igaparam_surface``)

    Fields:

    degree_u:
        Degree in u, at least 1.
    degree_v:
        Degree in v, at least 1.
    knot_count_u:
        Number of knots in u: `control_point_count_u + degree_u + 1`.
    knots_u:
        `knot_count_u` knots in u (finite, non-decreasing).
    knot_count_v:
        Number of knots in v: `control_point_count_v + degree_v + 1`.
    knots_v:
        `knot_count_v` knots in v (finite, non-decreasing).
    control_point_count_u:
        Control points in u, n_u.
    control_point_count_v:
        Control points in v, n_v.
    control_points:
        `n_u × n_v × 3` doubles (x y z of point (0, 0), then (1, 0), ...), finite.
    weights:
        `n_u × n_v` positive finite weights in the order of the control points (a NURBS
        surface), or NULL (a B-spline surface).
    """

    _fields_ = [
        ("degree_u", ctypes.c_uint32),
        ("degree_v", ctypes.c_uint32),
        ("knot_count_u", ctypes.c_size_t),
        ("knots_u", ctypes.POINTER(ctypes.c_double)),
        ("knot_count_v", ctypes.c_size_t),
        ("knots_v", ctypes.POINTER(ctypes.c_double)),
        ("control_point_count_u", ctypes.c_size_t),
        ("control_point_count_v", ctypes.c_size_t),
        ("control_points", ctypes.POINTER(ctypes.c_double)),
        ("weights", ctypes.POINTER(ctypes.c_double)),
    ]


class DomainUpdateOptions(ctypes.Structure):
    """Options of `igaparam_domain_update`; get the defaults from
    `igaparam_domain_update_options_default`. The boundary tolerance, levels, repair rounds and
    boundary offset are those the domain was built with.

    (``igaparam_domain_update_options``)

    Fields:

    max_sweeps:
        Largest number of optimization sweeps per step of the motion (default 200).
    threads:
        Worker threads, at most 4096, capped to the machine's cores; 0 (default) uses one per core.
    refine:
        Whether to refine where the boundary moved out of tolerance. Off (false, 0 in C; the
        default): keep the tree, and only report whether its tolerance still holds. On (true, 1):
        refine the boundary cells whose error exceeds the build's tolerance (below its `max_level`)
        until none does, and repair cells left folded as the build does; the T-mesh, and with it the
        spline space of a fit, then changes (a spline fitted before can no longer be refitted to
        it).
    progress:
        Progress callback, or NULL (default). Called with `IGAPARAM_STAGE_OPTIMIZATION`, `done`
        sweeps so far and `total` 0; returning non-zero cancels the update.
    progress_user:
        Passed to `progress` as its first argument.
    """

    _fields_ = [
        ("max_sweeps", ctypes.c_uint32),
        ("threads", ctypes.c_uint32),
        ("refine", ctypes.c_int32),
        ("progress", PROGRESS_FN),
        ("progress_user", ctypes.c_void_p),
    ]


class DomainUpdateReport(ctypes.Structure):
    """What `igaparam_domain_update` did.

    (``igaparam_domain_update_report``)

    Fields:

    domain:
        The T-mesh as a build reports it (`igaparam_domain_build`, `Domain::build` in Rust):
        `invalid_after_placement` counts the cells the harmonic placement (old positions plus the
        harmonic extension of the boundary motion) left invalid, `boundary_error` is measured in the
        new boundary's own bounding box (as a build would), `sweeps` and `seconds` are those of the
        update.
    tolerance_met:
        Whether the tree still meets the build's tolerance (1 in C, else 0): no boundary cell below
        the build's `max_level` has an error above it (a build's adaptation would refine none).
    cells_over_tolerance:
        Boundary cells below the build's `max_level` whose error exceeds its tolerance (after the
        refinement when the option `refine` is set).
    refined_cells:
        Cells added by refinement (0 unless the option `refine` is set).
    boundary_motion:
        Largest move of a boundary vertex, in coordinates that map the build's bounding box onto the
        unit box.
    steps:
        Steps the motion was applied in (a motion of more than about four cell sizes is split).
    """

    _fields_ = [
        ("domain", DomainReport),
        ("tolerance_met", ctypes.c_int32),
        ("cells_over_tolerance", ctypes.c_size_t),
        ("refined_cells", ctypes.c_size_t),
        ("boundary_motion", ctypes.c_double),
        ("steps", ctypes.c_uint32),
    ]


# A cell type: one of the `IGAPARAM_CELL_*` values (VTK's cell type codes). The local order of
# each type's nodes, VTK's and Gmsh's, is tabulated at `igaparam_node_order`.
# typedef int igaparam_cell_type

# The ideal shape of a cell: one of the `IGAPARAM_TARGET_*` values.
# typedef int igaparam_target

# The storage of a written `.vtu` file: one of `IGAPARAM_VTU_ASCII`, `IGAPARAM_VTU_BINARY`,
# `IGAPARAM_VTU_APPENDED`, `IGAPARAM_VTU_APPENDED_BASE64`, the binary ones optionally OR-ed with
# `IGAPARAM_VTU_ZLIB`.
# typedef int igaparam_vtu_format

# A local node order: one of the `IGAPARAM_ORDER_*` values.
#
# VTK order (the library's own; meshio's and ParaView's), nodes by reference coordinates in
# [-1,1]^d (xi, eta[, zeta]):
# - Q4: 0 (-1,-1), 1 (1,-1), 2 (1,1), 3 (-1,1); Q8 adds the mid-edges 4 (0,-1), 5 (1,0),
#   6 (0,1), 7 (-1,0); Q9 adds the centre 8 (0,0).
# - H8: 0-3 the corners of the face zeta = -1 as in Q4, 4-7 those of zeta = 1;
#   H20 adds the mid-edges 8-11 of the bottom face (edges 0-1, 1-2, 2-3, 3-0), 12-15 of the top
#   face (4-5, 5-6, 6-7, 7-4), 16-19 of the vertical edges (0-4, 1-5, 2-6, 3-7);
#   H27 adds the face centres 20 (xi = -1), 21 (xi = 1), 22 (eta = -1), 23 (eta = 1),
#   24 (zeta = -1), 25 (zeta = 1) and the body centre 26.
#
# Gmsh order: quadrilaterals as VTK. Hexahedra: the same corners 0-7, then the mid-edges of the
# edges 0-1, 0-3, 0-4, 1-2, 1-5, 2-3, 2-6, 3-7, 4-5, 4-7, 5-6, 6-7 (8-19), then the face centres
# zeta = -1, eta = -1, xi = -1, xi = 1, eta = 1, zeta = 1 (20-25) and the body centre 26.
# `igaparam_cell_type_copy_node_coordinates` gives these tables.
# typedef int igaparam_node_order

# The host's all-to-all exchange of bytes among the ranks of its communicator, as
# `MPI_Alltoallv` with `MPI_BYTE`: send `send_counts[r]` bytes to each rank `r` (the blocks of
# `send` in rank order) and receive `recv_counts[r]` bytes from each into `recv` (in rank
# order; the library knows the counts in advance). `user` is the exchange's `user`. Return 0
# on success. Called only on the thread that called the library.
# int (*igaparam_exchange_fn)(void * user, const size_t * send_counts, const uint8_t * send, const size_t * recv_counts, uint8_t * recv)
EXCHANGE_FN = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t), ctypes.POINTER(ctypes.c_uint8), ctypes.POINTER(ctypes.c_size_t), ctypes.POINTER(ctypes.c_uint8))


class Exchange(ctypes.Structure):
    """The ranks a partition lives on: this rank's number in `0..size` and the host's exchange.
    The library never starts, ends or calls MPI itself.

    (``igaparam_exchange``)

    Fields:

    rank:
        This rank, in `0..size` (e.g. from `MPI_Comm_rank`).
    size:
        Number of ranks (e.g. from `MPI_Comm_size`).
    exchange:
        The exchange callback.
    user:
        Passed to `exchange` as its first argument (e.g. a pointer to the communicator).
    """

    _fields_ = [
        ("rank", ctypes.c_int),
        ("size", ctypes.c_int),
        ("exchange", EXCHANGE_FN),
        ("user", ctypes.c_void_p),
    ]


# Where free nodes start: one of the `IGAPARAM_PLACEMENT_*` values.
# typedef int igaparam_placement

# How the free nodes are carried to the optimum: one of the `IGAPARAM_METHOD_*` values.
# typedef int igaparam_method


class RelocateOptions(ctypes.Structure):
    """Options of `igaparam_mesh_relocate`; get the defaults from `igaparam_relocate_options_default`.

    (``igaparam_relocate_options``)

    Fields:

    target:
        The ideal shape of each cell. Either `IGAPARAM_TARGET_INITIAL` (default) or
        `IGAPARAM_TARGET_MASTER`.
    placement:
        The first placement of the free nodes. One of `IGAPARAM_PLACEMENT_LAPLACIAN` (default),
        `IGAPARAM_PLACEMENT_CURRENT` or `IGAPARAM_PLACEMENT_INCREMENTAL`.
    optimize:
        Whether the optimizer runs after the placement (default: true, non-zero in C); false (0)
        stops after the placement.
    max_sweeps:
        Largest number of Gauss–Seidel sweeps (default 100 per step).
    move_tolerance:
        Stop when the mesh is valid and no node moved more than this fraction of its local cell size
        in a sweep (default 1e-3).
    gradient_tolerance:
        A node's Newton iteration stops when the gradient of its objective times its local cell size
        is below this (default 1e-3: nodes are revisited by the following sweeps, so an inexact
        solve per sweep suffices, and reaches the same meshes in less time than the tight 6·10⁻⁶ of
        a one-pass optimizer).
    max_newton_iterations:
        Largest number of Newton iterations per node and sweep (default 150).
    relaxation:
        Over-relaxation of each node's move, in [1, 2) (default 1.8; 1 disables it): speeds up
        smoothing. A relaxed move is kept only if it lowers the node's objective and inverts
        nothing.
    threads:
        Worker threads, at most 4096, capped to the machine's cores; 0 (default) uses one per core.
        The result does not depend on it.
    stationarity_tolerance:
        When positive, the result is a stationary point of the one global objective F, the sum over
        cells of their mean distortion η̄*_c (regularisation δ = 0, so F is infinite at a fold): the
        report's `gradient_norm` is at most this (e.g. 1e-10), reached by Newton's method with the
        sparse Hessian on a valid mesh; the sensitivities (`igaparam_mesh_adjoint` and
        `igaparam_mesh_tangent`, `Mesh::adjoint` and `Mesh::tangent` in Rust) then differentiate the
        result. 0 (default): no such guarantee (the sweeps stop on their own rule, the Newton method
        at 1e-8, `IGAPARAM_DEFAULT_NEWTON_TOLERANCE`).
    method:
        How the optimum is reached. One of `IGAPARAM_METHOD_AUTO` (default),
        `IGAPARAM_METHOD_SWEEPS` or `IGAPARAM_METHOD_NEWTON`.
    progress:
        Progress callback, or NULL (default).
    progress_user:
        Passed to `progress` as its first argument.
    """

    _fields_ = [
        ("target", ctypes.c_int),
        ("placement", ctypes.c_int),
        ("optimize", ctypes.c_int),
        ("max_sweeps", ctypes.c_uint32),
        ("move_tolerance", ctypes.c_double),
        ("gradient_tolerance", ctypes.c_double),
        ("max_newton_iterations", ctypes.c_uint32),
        ("relaxation", ctypes.c_double),
        ("threads", ctypes.c_uint32),
        ("stationarity_tolerance", ctypes.c_double),
        ("method", ctypes.c_int),
        ("progress", PROGRESS_FN),
        ("progress_user", ctypes.c_void_p),
    ]


class RelocateReport(ctypes.Structure):
    """What `igaparam_mesh_relocate` did. Quality is the inverse mean distortion of a cell against its
    target over its Gauss–Lobatto points: 1 is the target shape, 0 an inverted cell.

    (``igaparam_relocate_report``)

    Fields:

    cells:
        Number of cells.
    nodes:
        Number of nodes.
    free_nodes:
        Nodes with at least one free coordinate.
    invalid_before:
        Cells with `det J ≤ 0` at a Gauss–Lobatto point when the call started.
    invalid_after_placement:
        Invalid cells after the first placement.
    invalid_after:
        Invalid cells at the end.
    min_quality:
        Smallest cell quality at the end (against the target; 0 for an invalid cell).
    mean_quality:
        Mean cell quality at the end.
    sweeps:
        Optimization sweeps performed (over all steps).
    steps:
        Steps the prescribed motion was applied in (large motions are split so that no prescribed
        node moves more than about one cell size per step).
    converged:
        Whether the sweeps met their stopping rule (valid mesh, small moves) and, when asked for,
        the Newton stage its `stationarity_tolerance` (1 in C, else 0).
    gradient_norm:
        Scaled max-norm of the gradient of the global objective F at the end: over the free
        coordinates, |∂F/∂x| times the node's local cell size divided by its number of cells (the
        gradient of the node's own objective times its size; dimensionless). Infinite for an invalid
        mesh.
    newton_iterations:
        Newton iterations of the stationarity stage.
    seconds:
        Wall-clock seconds of the call.
    """

    _fields_ = [
        ("cells", ctypes.c_size_t),
        ("nodes", ctypes.c_size_t),
        ("free_nodes", ctypes.c_size_t),
        ("invalid_before", ctypes.c_size_t),
        ("invalid_after_placement", ctypes.c_size_t),
        ("invalid_after", ctypes.c_size_t),
        ("min_quality", ctypes.c_double),
        ("mean_quality", ctypes.c_double),
        ("sweeps", ctypes.c_uint32),
        ("steps", ctypes.c_uint32),
        ("converged", ctypes.c_int),
        ("gradient_norm", ctypes.c_double),
        ("newton_iterations", ctypes.c_uint32),
        ("seconds", ctypes.c_double),
    ]


class PartitionReport(ctypes.Structure):
    """What `igaparam_partition_relocate` did.

    (``igaparam_partition_report``)

    Fields:

    relocation:
        The relocation's figures over the whole mesh, the same on every rank (`gradient_norm` is not
        computed on a partition: infinity; `seconds` is this rank's wall-clock time).
    exchange_seconds:
        Seconds this rank spent in the host's exchange (the exchange callback in C), waiting for the
        other ranks included.
    exchanges:
        Calls of the host's exchange (the exchange callback in C) on this rank.
    """

    _fields_ = [
        ("relocation", RelocateReport),
        ("exchange_seconds", ctypes.c_double),
        ("exchanges", ctypes.c_size_t),
    ]


class FitReport(ctypes.Structure):
    """What a fit (`igaparam_spline_fit_domain`, `igaparam_spline_refine`) did.

    (``igaparam_fit_report``)

    Fields:

    basis_count:
        Basis functions (= control points).
    element_count:
        Elements of the space (the leaves of the hierarchical mesh).
    residual:
        Largest coordinate difference between the spline and the data at the fit points.
    least_squares:
        Whether a least-squares fit replaced a singular or badly conditioned interpolation at the
        Greville points (1 in C, else 0).
    quasi_interpolation:
        Whether the control points come from the local quasi-interpolant
        (`SplineMap::fit_quasi_interpolation`: in a checked fit, when its map was certified valid,
        or less invalid, than that of the interpolation; and every exact refinement,
        `igaparam_spline_refine` in C) (1 in C, else 0).
    untangled:
        Control points moved by the untangling (`SplineMap::untangle`) of a fitted map that was not
        certified valid (inner ones first; boundary ones, at most the untangling's `boundary_offset`
        of the bounding box, only when that was not enough); 0 when the fitted map was kept as it
        was.
    boundary_offset:
        Largest move of a boundary control point by that untangling, relative to the bounding box
        (each axis scaled to 1; see `UntangleOptions::boundary_offset`); 0 when the boundary was
        kept.
    seconds:
        Wall-clock seconds (with the certification and untangling of `SplineMap::fit_checked`).
    smoothed:
        Inner control points moved by the smoothing stage (`SplineMap::smooth`: on the map's own
        mean ratio, kept only when the map stays certified and its smallest sampled mean ratio
        rises); 0 when the map was kept as it was.
    boundary_distance:
        Largest distance from the map's boundary to the domain's boundary, in coordinates that map
        the domain's bounding box onto the unit box, sampled on every boundary facet of the elements
        (`SplineMap::boundary_distance`; an upper bound at the samples); 0 for a fit without a
        domain (`SplineMap::fit_checked` of a function).
    """

    _fields_ = [
        ("basis_count", ctypes.c_size_t),
        ("element_count", ctypes.c_size_t),
        ("residual", ctypes.c_double),
        ("least_squares", ctypes.c_int32),
        ("quasi_interpolation", ctypes.c_int32),
        ("untangled", ctypes.c_size_t),
        ("boundary_offset", ctypes.c_double),
        ("seconds", ctypes.c_double),
        ("smoothed", ctypes.c_size_t),
        ("boundary_distance", ctypes.c_double),
    ]


class AdaptOptions(ctypes.Structure):
    """Options of `igaparam_domain_fit_adaptive`; get the defaults from
    `igaparam_adapt_options_default`.

    (``igaparam_adapt_options``)

    Fields:

    target_quality:
        The loop stops once every element is certified valid and its smallest sampled mean ratio
        `q_S` reaches this (in [0, 1); default 0.1). Elements below it, or not certified, are
        refined.
    max_rounds:
        Largest number of refinement rounds (default 4).
    max_level:
        Cells at this level are not refined further (default 10, at most 16).
    max_sweeps:
        Largest number of optimization sweeps after each refinement (default 200).
    threads:
        Worker threads, at most 4096, capped to the machine's cores; 0 (default) uses one per core.
    progress:
        Progress callback, or NULL (default). Called with `IGAPARAM_STAGE_ADAPTATION`, `done`
        rounds and `total` = `max_rounds` before each refinement; returning non-zero cancels.
    progress_user:
        Passed to `progress` as its first argument.
    """

    _fields_ = [
        ("target_quality", ctypes.c_double),
        ("max_rounds", ctypes.c_uint32),
        ("max_level", ctypes.c_uint32),
        ("max_sweeps", ctypes.c_uint32),
        ("threads", ctypes.c_uint32),
        ("progress", PROGRESS_FN),
        ("progress_user", ctypes.c_void_p),
    ]


class AdaptReport(ctypes.Structure):
    """What `igaparam_domain_fit_adaptive` did.

    (``igaparam_adapt_report``)

    Fields:

    rounds:
        Refinement rounds done (0 when the first fit met the target).
    reached:
        1 when the map returned meets the target, else 0 (the round or level limit stopped it).
    refined_cells:
        T-mesh cells refined over all rounds.
    elements:
        Elements of the map returned (= cells of the domain's final T-mesh).
    basis:
        Basis functions of the map returned.
    certified_positive:
        1 when every element of the map returned is certified valid.
    min_quality:
        Smallest sampled mean ratio of the map returned.
    mean_quality:
        Mean sampled mean ratio of the map returned.
    seconds:
        Wall-clock seconds.
    untangled:
        Control points moved to untangle the fit of the map returned (as
        `igaparam_fit_report.untangled`); 0 when that fit was kept.
    boundary_offset:
        Largest move of a boundary control point by that untangling, relative to the bounding
        box (as `igaparam_fit_report.boundary_offset`); 0 when the boundary was kept.
    boundary_distance:
        Largest distance from the boundary of the map returned to the domain's boundary,
        relative to the bounding box (as `igaparam_fit_report.boundary_distance`).
    """

    _fields_ = [
        ("rounds", ctypes.c_uint32),
        ("reached", ctypes.c_int32),
        ("refined_cells", ctypes.c_size_t),
        ("elements", ctypes.c_size_t),
        ("basis", ctypes.c_size_t),
        ("certified_positive", ctypes.c_int32),
        ("min_quality", ctypes.c_double),
        ("mean_quality", ctypes.c_double),
        ("seconds", ctypes.c_double),
        ("untangled", ctypes.c_size_t),
        ("boundary_offset", ctypes.c_double),
        ("boundary_distance", ctypes.c_double),
    ]


# Which fit rule `igaparam_spline_fit_domain_with` uses: one of the `IGAPARAM_FIT_CHOICE_*`
# values.
# typedef int igaparam_fit_choice


class ValidityOptions(ctypes.Structure):
    """Options of `igaparam_spline_check_validity`; get the defaults from
    `igaparam_validity_options_default`.

    (``igaparam_validity_options``)

    Fields:

    max_depth:
        Largest number of subdivisions of an element's Jacobian determinant polynomial when its
        Bernstein coefficients are inconclusive (each halves every direction; default 5, at most
        12).
    samples:
        Sample points per direction and element for the mean ratio and the sampled determinant
        (default 5, from 2 to 64).
    """

    _fields_ = [
        ("max_depth", ctypes.c_uint32),
        ("samples", ctypes.c_uint32),
    ]


class FitOptions(ctypes.Structure):
    """Options of `igaparam_spline_fit_domain_with`; get the defaults (those of
    `igaparam_spline_fit_domain`) from `igaparam_fit_options_default`.

    (``igaparam_fit_options``)

    Fields:

    choice:
        The fit rule. One of `IGAPARAM_FIT_CHOICE_BEST` (default),
        `IGAPARAM_FIT_CHOICE_INTERPOLATION` or `IGAPARAM_FIT_CHOICE_QUASI_INTERPOLATION`.
    validity:
        The certification of the fitted maps and of the untangled and smoothed ones (default: the
        defaults of `ValidityOptions`); a spline handle of the C API keeps its result for
        `igaparam_spline_check_validity` with equal options.
    untangle_rounds:
        Largest number of untangling rounds (mark the uncertified elements, optimize the control
        points around them, certify again) per stage for a map that is not certified (default 4); a
        round that leaves as many elements uncertified as it found ends the stage. In a checked fit
        0 turns the untangling off: such a map is returned as fitted, with its uncertified elements
        in its validity report (`igaparam_spline_check_validity` in C).
    untangle_sweeps:
        Sweeps over the free control points per untangling round (default 20).
    boundary_offset:
        Largest move of a boundary control point by the untangling, relative to the bounding box;
        negative (default) uses the `boundary_offset` the domain was built with, 0 keeps the
        boundary.
    smoothing_sweeps:
        Largest number of smoothing sweeps over the inner control points of a certified map
        (`SplineMap::smooth`, the stage that follows the untangling, or a fit certified as it is, in
        a checked fit; default 8); 0 turns the smoothing off.
    smoothing_power:
        Exponent `p` of the smoothing's objective, the sum of the distortions `η*^p` at the samples:
        0 (default) chooses 4 for planar maps and 1 for solids; else at least 1, at most 16. Above 1
        the worst samples weigh most, which lifts the smallest q_S where the mean distortion (`p =
        1`) would not move it. Such a smoothing samples two points more per direction than `samples`
        (with four, `p = 4` folded Gran Canaria's map between samples; with five, its certified
        bound fell while the sampled minimum rose), and where it cannot lift the map the `p = 1`
        smoothing runs instead. On the 3D duck it lifted nothing (the smallest q_S is held at the
        boundary) and doubled the smoothing's time, hence 1 for solids by default.
    threads:
        Worker threads, at most 4096, capped to the machine's cores; 0 (default) runs on the
        caller's thread pool: one thread per core, unless a Rust caller installed another. The
        result does not depend on it.
    progress:
        Progress callback, or NULL (default): called on the calling thread with
        `IGAPARAM_STAGE_FIT` (`done` of `total` fits and certifications),
        `IGAPARAM_STAGE_UNTANGLING` (rounds) and `IGAPARAM_STAGE_SMOOTHING` (sweeps); returning
        non-zero cancels (`IGAPARAM_STATUS_CANCELLED`, nothing written).
    progress_user:
        Passed to `progress` as its first argument.
    """

    _fields_ = [
        ("choice", ctypes.c_int),
        ("validity", ValidityOptions),
        ("untangle_rounds", ctypes.c_uint32),
        ("untangle_sweeps", ctypes.c_uint32),
        ("boundary_offset", ctypes.c_double),
        ("smoothing_sweeps", ctypes.c_uint32),
        ("smoothing_power", ctypes.c_double),
        ("threads", ctypes.c_uint32),
        ("progress", PROGRESS_FN),
        ("progress_user", ctypes.c_void_p),
    ]


class QualityBoundOptions(ctypes.Structure):
    """Options of `igaparam_spline_quality_bound`; get the defaults from
    `igaparam_quality_bound_options_default`.

    (``igaparam_quality_bound_options``)

    Fields:

    max_depth:
        Largest number of subdivisions of an element where the bound is loose (each halves every
        direction; default 6, at most `IGAPARAM_QUALITY_BOUND_MAX_DEPTH` = 8: 4^8 pieces of an
        element in 2D); solids use at most `IGAPARAM_QUALITY_BOUND_MAX_SOLID_DEPTH` (3: 8^3 pieces
        per element), which bounds the work on any map.
    samples:
        Sample points per direction and element for the sampled minimum (default 5, from 2 to 64).
    gap:
        Relative gap in [0, 1) (default 0.05): a piece is not subdivided once its bound is within
        this fraction of the map's sampled minimum.
    """

    _fields_ = [
        ("max_depth", ctypes.c_uint32),
        ("samples", ctypes.c_uint32),
        ("gap", ctypes.c_double),
    ]


class QualityBoundReport(ctypes.Structure):
    """What `igaparam_spline_quality_bound` found: the true smallest mean ratio of the map lies in
    `[lower_bound, sampled_min]`.

    (``igaparam_quality_bound_report``)

    Fields:

    lower_bound:
        Certified lower bound of the mean ratio `q_S = d·det(J)^(2/d)/‖J‖²` over the whole map (0
        when `det J_S > 0` is not proven somewhere).
    sampled_min:
        Smallest mean ratio at the samples (an upper bound of the true minimum).
    element:
        The element of the smallest bound (index into the map's elements).
    """

    _fields_ = [
        ("lower_bound", ctypes.c_double),
        ("sampled_min", ctypes.c_double),
        ("element", ctypes.c_size_t),
    ]


class RefitReport(ctypes.Structure):
    """What `igaparam_spline_refit` did.

    (``igaparam_refit_report``)

    Fields:

    fit:
        The fit: basis and element counts (unchanged), residual, the rule's flags
        (`least_squares`, `quasi_interpolation`), the control points this refit's untangling
        moved (`untangled`, 0 when the correction carried over from an earlier untangling kept
        the map certified) and seconds.
    rule:
        The rule the control points came from: the rule of the spline's first fit.
    corrected:
        Control points carrying the correction of an untangling (this refit's or an earlier
        one's): the map is `A X + c` with `A` the rule's linear map of the T-mesh vertices `X`
        and `c` that correction, non-zero at these control points; 0 when the map is the
        rule's own fit.
    certified_positive:
        1 when every element of the new map is certified valid (`det J > 0`), else 0.
    uncertified:
        Elements where positivity is not proven.
    min_quality:
        Smallest sampled mean ratio `q_S` of the new map.
    mean_quality:
        Mean sampled mean ratio of the new map.
    """

    _fields_ = [
        ("fit", FitReport),
        ("rule", ctypes.c_int),
        ("corrected", ctypes.c_size_t),
        ("certified_positive", ctypes.c_int32),
        ("uncertified", ctypes.c_size_t),
        ("min_quality", ctypes.c_double),
        ("mean_quality", ctypes.c_double),
    ]


class ValidityReport(ctypes.Structure):
    """Certified validity and quality of a spline map.

    (``igaparam_validity_report``)

    Fields:

    certified_positive:
        Whether `det J_S > 0` is proven on every element (Bernstein coefficients of the determinant,
        with subdivision; 1 in C, else 0).
    uncertified:
        Elements where positivity is not proven.
    det_lower_bound:
        Smallest lower bound of `det J_S` over the elements (Jacobian with respect to the parametric
        coordinates).
    min_quality:
        Smallest mean ratio `q_S = d·det(J)^(2/d)/‖J‖²` at the samples (0 where det ≤ 0).
    mean_quality:
        Mean of the element means of `q_S` at the samples (every element has as many).
    histogram:
        Samples per quality bin `[i/10, (i+1)/10)` (the last bin includes 1).
    """

    _fields_ = [
        ("certified_positive", ctypes.c_int32),
        ("uncertified", ctypes.c_size_t),
        ("det_lower_bound", ctypes.c_double),
        ("min_quality", ctypes.c_double),
        ("mean_quality", ctypes.c_double),
        ("histogram", ctypes.c_size_t * HISTOGRAM_BINS),
    ]


# Bilinear quadrilateral, 4 nodes (VTK_QUAD).
CELL_QUAD4 = 9

# Serendipity quadratic quadrilateral, 8 nodes (VTK_QUADRATIC_QUAD).
CELL_QUAD8 = 23

# Biquadratic quadrilateral, 9 nodes (VTK_BIQUADRATIC_QUAD).
CELL_QUAD9 = 28

# Trilinear hexahedron, 8 nodes (VTK_HEXAHEDRON).
CELL_HEX8 = 12

# Serendipity quadratic hexahedron, 20 nodes (VTK_QUADRATIC_HEXAHEDRON).
CELL_HEX20 = 25

# Triquadratic hexahedron, 27 nodes (VTK_TRIQUADRATIC_HEXAHEDRON).
CELL_HEX27 = 29

# The cell's own shape in the reference positions (those given to `igaparam_mesh_new`, or set by
# `igaparam_mesh_reset_reference`): keeps size grading and anisotropy.
TARGET_INITIAL = 0

# The master square/cube (scaled to the cell's size).
TARGET_MASTER = 1

# Numbers as text: large, for reading by eye.
VTU_ASCII = 0

# Base64 inside each array (`format="binary"`): valid XML, read by VTK, ParaView and meshio.
VTU_BINARY = 1

# Raw bytes in an appended section: the smallest, VTK's own default (not valid XML).
VTU_APPENDED = 2

# Base64 in an appended section.
VTU_APPENDED_BASE64 = 3

# Flag: zlib-compress the binary data (`vtkZLibDataCompressor`).
VTU_ZLIB = 16

# The default: `IGAPARAM_VTU_BINARY | IGAPARAM_VTU_ZLIB`.
VTU_DEFAULT = 17

# VTK's node order (the default of `igaparam_mesh_new`).
ORDER_VTK = 0

# Gmsh's node order (`.msh` files, the Gmsh API).
ORDER_GMSH = 1

# Harmonic extension of the prescribed displacements (a discrete Laplace equation): every free
# coordinate starts from its reference position plus that extension, whatever position
# `igaparam_mesh_move_nodes` gave it.
PLACEMENT_LAPLACIAN = 0

# The current positions, as they are.
PLACEMENT_CURRENT = 1

# Warm start for loops: the positions of the last successful relocation plus the harmonic
# extension of the prescribed motion since then (the first relocation of a mesh starts as
# `IGAPARAM_PLACEMENT_LAPLACIAN`); the targets stay the reference shapes. Use it when the
# boundary moves a little at every call, as in a shape-optimization loop.
PLACEMENT_INCREMENTAL = 2

# `IGAPARAM_METHOD_NEWTON` where the Hessian's Cholesky factor is small (2D meshes, 3D meshes
# up to about 20,000 nodes) or, beyond, where the Hessian has at most 10⁸ values (about
# 310,000 H27 nodes; multigrid-preconditioned steps, about 17 bytes per value at the peak),
# else `IGAPARAM_METHOD_SWEEPS` (default). Where memory is short, `IGAPARAM_METHOD_SWEEPS`
# needs about a quarter (the bundled wing: 0.16 GB against 0.59 GB).
METHOD_AUTO = 0

# The per-node optimizer's coloured Gauss–Seidel sweeps, large motions in steps placed
# harmonically; with `stationarity_tolerance > 0`, followed by the Newton stage.
METHOD_SWEEPS = 1

# Path following of the optimum of the global objective: each step predicted by the tangent of
# the optimum (the linearised response of the mesh to the motion) and corrected by Newton's
# method; the sweeps are the fallback where a step cannot be made (e.g. a tangled start). With
# `IGAPARAM_PLACEMENT_CURRENT` (untangling in place): 3 sweeps (more while cells stay invalid),
# then Newton's method to the stationarity tolerance (1e-8 when none is asked for). A Hessian,
# or a multigrid preconditioner beside it, whose storage cannot be reserved (past an
# address-space limit, strict overcommit's commit limit, or the machine's memory and swap) is
# refused with `IGAPARAM_STATUS_LIMIT_EXCEEDED`.
METHOD_NEWTON = 2

# Interpolation at the Greville points (least squares when that system is singular or badly
# conditioned) and, unless that map is certified valid, the local quasi-interpolant too; the
# better of the two is kept (what `igaparam_spline_fit_domain` does).
FIT_CHOICE_BEST = 0

# Interpolation at the Greville points only (least squares when singular).
FIT_CHOICE_INTERPOLATION = 1

# The local quasi-interpolant only.
FIT_CHOICE_QUASI_INTERPOLATION = 2


# name: (restype, argtypes, documentation)
PROTOTYPES = {
    "igaparam_abi_fingerprint": (
        ctypes.c_uint64,
        [],
        "uint64_t igaparam_abi_fingerprint(void);\n\nThe fingerprint of the declarations of the header this library was built with: a 64-bit\nhash of `include/igaparam.h` without its comments. Bindings generated from a header (the\nPython package's declarations carry the same number) compare it before their first call,\nso that they refuse a library of another layout instead of calling it with wrong structs.",
    ),
    "igaparam_last_error_message": (
        ctypes.c_size_t,
        [ctypes.c_char_p, ctypes.c_size_t],
        "size_t igaparam_last_error_message(char *buf, size_t len);\n\nCopies the message of the calling thread's latest call into `buf` (at most `len` bytes including the\nterminating NUL, truncated if needed) and returns the length of the whole message plus one,\nso a caller can size the buffer. `buf` may be NULL (with any `len`) to ask for the size only.\nThe message is empty (returns 1) when that call succeeded: every call that returns an\n`igaparam_status` replaces it.",
    ),
    "igaparam_version": (
        ctypes.c_char_p,
        [],
        'const char *igaparam_version(void);\n\nThe library version as a static NUL-terminated string, e.g. `"0.1.0"`. Never NULL; not to be\nfreed.',
    ),
    "igaparam_domain_free": (
        None,
        [ctypes.c_void_p],
        'void igaparam_domain_free(igaparam_domain *domain);\n\nReleases a domain. NULL is a no-op. Called on a domain in use (from the progress callback of\n`igaparam_domain_build`, `igaparam_domain_update` or `igaparam_domain_fit_adaptive`, or from\nanother thread), the release waits for that call: the call stops at its next progress point\nwith `IGAPARAM_STATUS_CANCELLED` and the domain is released as it returns; the handle must\nnot be used after this call in either case.',
    ),
    "igaparam_domain_dimension": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t)],
        'igaparam_status igaparam_domain_dimension(const igaparam_domain *domain, size_t *out);\n\nWrites to `*out` the dimension of the domain: 2 for a planar domain, 3 for a solid.',
    ),
    "igaparam_domain_is_built": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_int)],
        'igaparam_status igaparam_domain_is_built(const igaparam_domain *domain, int *out);\n\nWrites to `*out` 1 if the domain has been built (by a successful `igaparam_domain_build`),\nelse 0.',
    ),
    "igaparam_domain_options_default": (
        DomainOptions,
        [],
        'igaparam_domain_options igaparam_domain_options_default(void);\n\nThe default options of a planar domain (tolerance 1e-5).',
    ),
    "igaparam_domain_options_default_solid": (
        DomainOptions,
        [],
        'igaparam_domain_options igaparam_domain_options_default_solid(void);\n\nThe default options of a solid: those of `igaparam_domain_options_default` with a\ntolerance of 1e-3 (a tolerance bounds a volume in 3D; 1e-5 refines for many minutes).\n`igaparam_domain_build` with NULL options uses these for a solid.',
    ),
    "igaparam_domain_build": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(DomainOptions), ctypes.POINTER(DomainReport)],
        "igaparam_status igaparam_domain_build(igaparam_domain *domain, const igaparam_domain_options *options, igaparam_domain_report *report);\n\nAdapts a T-mesh to the boundary (refining boundary cells until `options.tolerance` or\n`options.max_level` is met), places its vertices (boundary ones on the curves, inner ones by\nthe Coons patch) and optimizes them; the result is kept in the handle, replacing that of an\nearlier build. `options` may be NULL for the defaults (`igaparam_domain_options_default`, or\n`igaparam_domain_options_default_solid` for a solid); `report` may be NULL. On any error or\ncancellation the handle is unchanged (an earlier build stays) and `*report` is not written.\nA planar build fails with `IGAPARAM_STATUS_INVALID_ARGUMENT` when cells stay invalid because\nthe T-mesh's boundary facets cut across the boundary (it comes closer to itself than the\ncells resolve); the message says where.",
    ),
    "igaparam_domain_new_from_file": (
        ctypes.c_int,
        [ctypes.c_char_p, ctypes.POINTER(ctypes.c_void_p)],
        'igaparam_status igaparam_domain_new_from_file(const char *path, igaparam_domain **out);\n\nCreates a domain from a boundary file, chosen by its extension (case-insensitive):\n\n- `.xml`: a G+Smo XML B-rep of four B-spline curves;\n- `.txt`: a coastline (points with four marked corners).\n\n`path` is a NUL-terminated UTF-8 path. `out` receives the new handle, to be released with\n`igaparam_domain_free`. Errors: `IGAPARAM_STATUS_IO` when the file cannot be read or parsed\n(the message says why), `IGAPARAM_STATUS_INVALID_ARGUMENT` for another extension or when the\ncurves do not make a closed loop with convex corners.',
    ),
    "igaparam_domain_new_from_polylines": (
        ctypes.c_int,
        [ctypes.POINTER(ctypes.c_size_t), ctypes.POINTER(ctypes.POINTER(ctypes.c_double)), ctypes.POINTER(ctypes.c_void_p)],
        'igaparam_status igaparam_domain_new_from_polylines(const size_t *counts, const double *const *points, igaparam_domain **out);\n\nCreates a domain bounded by four polylines.\n\n- `counts`: 4 entries; `counts[i]` is the number of points of polyline i (at least 2).\n- `points`: 4 pointers; `points[i]` holds `counts[i] × 2` doubles (x0 y0 x1 y1 ...).\n- `out`: receives the new handle, to be released with `igaparam_domain_free`.\n\nThe polylines may be given in any order and direction: they are chained end to end into a\ncounter-clockwise loop, the first one becoming the side u = 0. Errors:\n`IGAPARAM_STATUS_NOT_FINITE` for a NaN or infinite coordinate, `IGAPARAM_STATUS_INVALID_ARGUMENT`\nfor a polyline of fewer than two distinct points, a loop that does not close, one of zero area,\na loop that crosses or touches itself (the message names the two polylines and the point) or\na corner whose interior angle reaches 180 degrees. The arrays are copied.',
    ),
    "igaparam_domain_new_from_curves": (
        ctypes.c_int,
        [ctypes.c_size_t, ctypes.POINTER(Curve), ctypes.POINTER(ctypes.c_void_p)],
        "igaparam_status igaparam_domain_new_from_curves(size_t count, const igaparam_curve *curves, igaparam_domain **out);\n\nCreates a domain bounded by four B-spline or NURBS curves given as arrays (see\n`igaparam_curve`).\n\n- `count`: the number of curves, 4;\n- `curves`: `count` curve descriptions;\n- `out`: receives the new handle, to be released with `igaparam_domain_free`.\n\nThe curves are read as `igaparam_domain_new_from_file` reads those of a G+Smo file (a domain\nmade from the same curves is the same, bit for bit): in any order and direction, chained end\nto end into a counter-clockwise loop, the first one becoming the side u = 0. Errors:\n`IGAPARAM_STATUS_NULL_ARGUMENT` for a NULL array (weights may be NULL),\n`IGAPARAM_STATUS_NOT_FINITE` for a NaN or infinite knot, coordinate or weight,\n`IGAPARAM_STATUS_INVALID_ARGUMENT` for a count other than 4, a degree of 0, a knot count\nother than control points + degree + 1, decreasing knots or a knot repeated more than\ndegree + 1 times, a weight that is not positive, and curves whose ends do not meet, whose\nloop encloses no area, crosses or touches itself (the curves' polygons are checked, sampled\n16 points per control point) or has a corner whose interior angle reaches 180 degrees (each\nmessage names the curves or corner). The arrays are copied.",
    ),
    "igaparam_domain_new_solid_from_file": (
        ctypes.c_int,
        [ctypes.c_char_p, ctypes.POINTER(ctypes.c_void_p)],
        "igaparam_status igaparam_domain_new_solid_from_file(const char *path, igaparam_domain **out);\n\nCreates a solid from a boundary file or folder:\n\n- a `.xml` file: a G+Smo XML B-rep of six B-spline surfaces (found and oriented from their\n  shared edges and corners);\n- a folder: six triangulated faces `xmin, xmax, ymin, ymax, zmin, zmax` (`.obj`), each mapped\n  onto its face of the unit cube by Floater's mean-value parameterization.\n\n`path` is a NUL-terminated UTF-8 path. `out` receives the new handle, to be released with\n`igaparam_domain_free`. Errors: `IGAPARAM_STATUS_IO` when a file cannot be read or parsed,\n`IGAPARAM_STATUS_INVALID_ARGUMENT` for another kind of path, `IGAPARAM_STATUS_INVALID_MESH` when\nthe surfaces do not share their edges and corners (the message says which). Same as\n`igaparam_domain_new_solid_from_file_scaled` with `scale` NULL.",
    ),
    "igaparam_domain_new_solid_from_file_scaled": (
        ctypes.c_int,
        [ctypes.c_char_p, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_void_p)],
        "igaparam_status igaparam_domain_new_solid_from_file_scaled(const char *path, const double *scale, igaparam_domain **out);\n\nCreates a solid from a boundary file or folder as `igaparam_domain_new_solid_from_file`,\nwith every coordinate of the input multiplied by its axis' factor first: `scale` is NULL (no\nscaling) or points to 3 doubles `fx, fy, fz`, each finite and positive. The vertices of\ntriangulated faces, or the control points of a B-rep's surfaces (exact for B-splines and\nNURBS), are scaled before the faces are parameterized; the solid, its T-mesh and its spline\nmap are in the scaled coordinates. Use it for data whose axes are in different units (a\nterrain in degrees and kilometres, say): Floater's map measures angles in the coordinates it\nis given, so the T-mesh depends on them, not only on the solid's figure.\n\nErrors: those of `igaparam_domain_new_solid_from_file`, and\n`IGAPARAM_STATUS_INVALID_ARGUMENT` for a factor that is NaN, infinite, zero or negative\n(checked before any file is read). `*out` is left unchanged on error.",
    ),
    "igaparam_domain_new_solid_from_triangulations": (
        ctypes.c_int,
        [ctypes.POINTER(ctypes.c_size_t), ctypes.POINTER(ctypes.POINTER(ctypes.c_double)), ctypes.POINTER(ctypes.c_size_t), ctypes.POINTER(ctypes.POINTER(ctypes.c_uint32)), ctypes.POINTER(ctypes.c_void_p)],
        "igaparam_status igaparam_domain_new_solid_from_triangulations(const size_t *vertex_counts, const double *const *xyz, const size_t *triangle_counts, const uint32_t *const *triangles, igaparam_domain **out);\n\nCreates a solid bounded by six triangulated faces, in the order `xmin, xmax, ymin, ymax, zmin,\nzmax` of the unit cube's faces.\n\n- `vertex_counts`, `triangle_counts`: 6 entries each;\n- `xyz`: 6 pointers; `xyz[f]` holds `vertex_counts[f] × 3` doubles (x0 y0 z0 x1 ...);\n- `triangles`: 6 pointers; `triangles[f]` holds `triangle_counts[f] × 3` vertex indices of\n  face f, counting from 0;\n- `out`: receives the new handle, to be released with `igaparam_domain_free`.\n\nEach face must be a disk; faces that touch share their edge vertices with identical\ncoordinates, and the vertex shared by three faces is a cube corner. Errors:\n`IGAPARAM_STATUS_NULL_ARGUMENT` for a NULL array (a face's arrays may be NULL only when\nempty), `IGAPARAM_STATUS_NOT_FINITE` for a NaN or infinite coordinate,\n`IGAPARAM_STATUS_INVALID_MESH` for a triangle with an index out of range or a repeated vertex,\nand for faces that do not match on their edges or corners. The arrays are copied.",
    ),
    "igaparam_domain_new_solid_from_surfaces": (
        ctypes.c_int,
        [ctypes.c_size_t, ctypes.POINTER(Surface), ctypes.POINTER(ctypes.c_void_p)],
        'igaparam_status igaparam_domain_new_solid_from_surfaces(size_t count, const igaparam_surface *surfaces, igaparam_domain **out);\n\nCreates a solid bounded by six tensor-product B-spline or NURBS surfaces in 3D given as\narrays (see `igaparam_surface`).\n\n- `count`: the number of surfaces, 6;\n- `surfaces`: `count` surface descriptions;\n- `out`: receives the new handle, to be released with `igaparam_domain_free`.\n\nThe surfaces are read as `igaparam_domain_new_solid_from_file` reads those of a G+Smo B-rep\n(a solid made from the same surfaces is the same, bit for bit): their corners are matched\ninto the 8 corners of a cube, opposite surfaces found, each surface oriented onto its cube\nface, and the surfaces must agree on their shared edges. Errors:\n`IGAPARAM_STATUS_NULL_ARGUMENT` for a NULL array (weights may be NULL),\n`IGAPARAM_STATUS_NOT_FINITE` for a NaN or infinite knot, coordinate or weight,\n`IGAPARAM_STATUS_INVALID_ARGUMENT` for a count other than 6, a degree of 0, knot counts\nother than control points + degree + 1, decreasing knots, weights that are not positive,\n`IGAPARAM_STATUS_INVALID_MESH` for surfaces whose corners do not form a cube or that do not\nshare their edges (the messages name the surfaces). The arrays are copied.',
    ),
    "igaparam_domain_vertex_count": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t)],
        'igaparam_status igaparam_domain_vertex_count(const igaparam_domain *domain, size_t *out);\n\nWrites the number of vertices of the built T-mesh (hanging ones included) to `*out`.\nFails with `IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain has not been built.',
    ),
    "igaparam_domain_cell_count": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t)],
        'igaparam_status igaparam_domain_cell_count(const igaparam_domain *domain, size_t *out);\n\nWrites the number of cells of the built T-mesh to `*out`. Fails with\n`IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain has not been built.',
    ),
    "igaparam_domain_copy_vertices": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double), ctypes.c_size_t],
        'igaparam_status igaparam_domain_copy_vertices(const igaparam_domain *domain, double *parametric, double *physical, size_t len_each);\n\nCopies the vertices of the built T-mesh: `parametric` receives their parametric coordinates\nin [0,1]^d (u, v; u, v, w for a solid), and `physical` their coordinates in the domain (x, y;\nx, y, z), each `num_vertices × d` doubles (d = 2 for a planar domain, 3 for a solid; see\n`igaparam_domain_dimension`). Either may be NULL to skip it; `len_each` is the number of\ndoubles each non-NULL buffer holds (at least `d × num_vertices`). Fails with\n`IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain has not been built.',
    ),
    "igaparam_domain_copy_cell_quality": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t],
        'igaparam_status igaparam_domain_copy_cell_quality(const igaparam_domain *domain, double *quality, size_t len);\n\nCopies the quality of every cell of the built T-mesh into `quality` (`len` doubles, at least\n`num_cells`): the inverse mean distortion against its parametric cell, in (0, 1], or 0 for a\ncell with det J <= 0 somewhere. Fails with `IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain\nhas not been built.',
    ),
    "igaparam_domain_copy_cells": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint8), ctypes.POINTER(ctypes.c_double), ctypes.c_size_t],
        'igaparam_status igaparam_domain_copy_cells(const igaparam_domain *domain, uint8_t *levels, double *bounds, size_t len);\n\nCopies the cells of the built T-mesh, in the order of their qualities:\n\n- `levels`: the refinement level of every cell (`num_cells` bytes), or NULL to skip it;\n- `bounds`: the parametric box of every cell, `num_cells × 2d` doubles (lower then upper\n  corner: `u0 v0 u1 v1` for a planar domain, `u0 v0 w0 u1 v1 w1` for a solid), or NULL to\n  skip it.\n\n`len` is the number of cells the buffers hold (`levels` has `len` bytes, `bounds` `2d × len`\ndoubles), at least `num_cells`. Fails with `IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain has\nnot been built.',
    ),
    "igaparam_domain_copy_cell_corners": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t), ctypes.c_size_t],
        "igaparam_status igaparam_domain_copy_cell_corners(const igaparam_domain *domain, size_t *corners, size_t len);\n\nCopies the corner vertices of every cell of the built T-mesh into `corners`: `num_cells × 2^d`\nvertex indices (4 per cell for a planar domain, counter-clockwise from the lower-left corner;\n8 per cell for a solid, in VTK's hexahedron order), indices into the vertices of\n`igaparam_domain_copy_vertices`. Hanging vertices on a cell's edges or faces are not listed.\n`len` is the number of entries `corners` holds, at least `2^d × num_cells`. Fails with\n`IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain has not been built.",
    ),
    "igaparam_domain_write_vtu": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_char_p],
        'igaparam_status igaparam_domain_write_vtu(const igaparam_domain *domain, const char *path);\n\nWrites the built T-mesh to a VTK XML unstructured grid (`.vtu`) at `path` (NUL-terminated\nUTF-8): for a planar domain one polygon per cell through its corners and hanging vertices,\nfor a solid one hexahedron per cell through its corners, at the physical positions; point data\n`parametric` (u, v, 0 or u, v, w), cell data `quality` and `level`. Fails with\n`IGAPARAM_STATUS_IO` if the file cannot be written, `IGAPARAM_STATUS_INVALID_ARGUMENT` if the\ndomain has not been built.',
    ),
    "igaparam_domain_update_options_default": (
        DomainUpdateOptions,
        [],
        'igaparam_domain_update_options igaparam_domain_update_options_default(void);\n\nThe default update options.',
    ),
    "igaparam_domain_set_boundary_curves": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(Curve)],
        "igaparam_status igaparam_domain_set_boundary_curves(igaparam_domain *domain, size_t count, const igaparam_curve *curves);\n\nReplaces the boundary of a domain by four B-spline or NURBS curves given as arrays (`count`\n= 4 entries of `curves`, read as by `igaparam_domain_new_from_curves`: give them in the order\nand direction of the first ones, so that each lands on the same side). The T-mesh of a built\ndomain stays where it is until `igaparam_domain_update` moves it onto the new boundary (or\n`igaparam_domain_build` builds anew); fits need that first. Errors: those of\n`igaparam_domain_new_from_curves`, `IGAPARAM_STATUS_INVALID_ARGUMENT` for a solid or, once\nbuilt, a boundary oriented the other way round (its parameterization mirrored relative to\nthe domain's). On error the domain is unchanged. The arrays are copied.",
    ),
    "igaparam_domain_set_boundary_polylines": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t), ctypes.POINTER(ctypes.POINTER(ctypes.c_double))],
        'igaparam_status igaparam_domain_set_boundary_polylines(igaparam_domain *domain, const size_t *counts, const double *const *points);\n\nReplaces the boundary of a planar domain by four polylines (the arrays of\n`igaparam_domain_new_from_polylines`), as `igaparam_domain_set_boundary_curves` does.',
    ),
    "igaparam_domain_set_boundary_surfaces": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(Surface)],
        'igaparam_status igaparam_domain_set_boundary_surfaces(igaparam_domain *domain, size_t count, const igaparam_surface *surfaces);\n\nReplaces the boundary of a solid by six B-spline or NURBS surfaces given as arrays (`count`\n= 6 entries of `surfaces`, read as by `igaparam_domain_new_solid_from_surfaces`: give them in\nthe order and with the parameterizations of the first ones), as\n`igaparam_domain_set_boundary_curves` does for planar domains. Errors: those of\n`igaparam_domain_new_solid_from_surfaces`, `IGAPARAM_STATUS_INVALID_ARGUMENT` for a planar\ndomain or a boundary oriented the other way round. On error the domain is unchanged.',
    ),
    "igaparam_domain_set_boundary_triangulations": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t), ctypes.POINTER(ctypes.POINTER(ctypes.c_double)), ctypes.POINTER(ctypes.c_size_t), ctypes.POINTER(ctypes.POINTER(ctypes.c_uint32))],
        "igaparam_status igaparam_domain_set_boundary_triangulations(igaparam_domain *domain, const size_t *vertex_counts, const double *const *xyz, const size_t *triangle_counts, const uint32_t *const *triangles);\n\nReplaces the boundary of a solid by six triangulated faces (the arrays of\n`igaparam_domain_new_solid_from_triangulations`, each face parameterized anew by Floater's\nmap), as `igaparam_domain_set_boundary_surfaces` does.",
    ),
    "igaparam_domain_set_boundary_from_file": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_char_p],
        'igaparam_status igaparam_domain_set_boundary_from_file(igaparam_domain *domain, const char *path);\n\nReplaces the boundary of a domain by the one of a file: for a planar domain a `.xml` G+Smo\nB-rep of four curves or a `.txt` coastline (as `igaparam_domain_new_from_file`), for a solid a\n`.xml` B-rep of six surfaces or a folder of six `.obj` faces (as\n`igaparam_domain_new_solid_from_file`); otherwise as `igaparam_domain_set_boundary_curves`.',
    ),
    "igaparam_domain_set_boundary_from_file_scaled": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_char_p, ctypes.POINTER(ctypes.c_double)],
        'igaparam_status igaparam_domain_set_boundary_from_file_scaled(igaparam_domain *domain, const char *path, const double *scale);\n\nReplaces the boundary of a solid by the one of a file or folder, its coordinates scaled\nfirst (`scale`: NULL or 3 finite positive factors, as\n`igaparam_domain_new_solid_from_file_scaled`); otherwise as\n`igaparam_domain_set_boundary_from_file`.',
    ),
    "igaparam_domain_update": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(DomainUpdateOptions), ctypes.POINTER(DomainUpdateReport)],
        "igaparam_status igaparam_domain_update(igaparam_domain *domain, const igaparam_domain_update_options *options, igaparam_domain_update_report *report);\n\nMoves the built T-mesh onto the domain's current boundary (the one given by the last\n`igaparam_domain_set_boundary_*`), keeping its tree: every boundary vertex goes to the point\nof its parameters on the new boundary (keeping the offset the seam relief gave it, if any),\nthe inner vertices to their current positions plus the harmonic extension of that motion\n(a motion of more than about four cell sizes in steps), and all are optimized again (with\nthe seam relief of the build where cells stay folded). The targets of the cells stay those\nof the build (its bounding box), as for relocated meshes. The report says whether the\ntree's tolerance still holds; the tree changes only when `options->refine` is set. A spline\nfitted to the domain is refitted in its own space with `igaparam_spline_refit`.\n\n`options` may be NULL for the defaults (`igaparam_domain_update_options_default`); `report`\nmay be NULL. Errors: `IGAPARAM_STATUS_INVALID_ARGUMENT` when the domain has not been built\n(call `igaparam_domain_build` first) or for threads above 4096, `IGAPARAM_STATUS_CANCELLED`,\n`IGAPARAM_STATUS_LIMIT_EXCEEDED` when the build's `max_total_sweeps` runs out while the\nvertices follow the boundary (later stages stop there and succeed, setting the report's\n`sweep_budget_exhausted`), `IGAPARAM_STATUS_INVALID_ARGUMENT` also when cells stay invalid\non a planar T-mesh whose boundary facets cut across the new boundary (the message says\nwhere). On any error the domain is unchanged and `*report` is not written.",
    ),
    "igaparam_mesh_new": (
        ctypes.c_int,
        [ctypes.c_int, ctypes.c_size_t, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t, ctypes.POINTER(ctypes.c_int64), ctypes.POINTER(ctypes.c_void_p)],
        "igaparam_status igaparam_mesh_new(igaparam_cell_type cell_type_code, size_t num_nodes, const double *xyz, size_t num_cells, const int64_t *connectivity, igaparam_mesh **out);\n\nCreates a mesh of `num_cells` cells of one type.\n\n- `xyz`: `num_nodes × 3` coordinates, flat (x0 y0 z0 x1 ...); always 3 per node, as in VTK; for\n  quadrilaterals z is carried unchanged. These positions are the reference shape.\n- `connectivity`: `num_cells × n` node indices (n = nodes per cell of `cell_type`), in VTK's\n  node order, each in `0..num_nodes`.\n- `out`: receives the new handle, to be released with `igaparam_mesh_free`.\n\nAll nodes start free (see `igaparam_mesh_set_fixed`). The arrays are copied. For Gmsh's node\norder see `igaparam_mesh_new_ordered`; a mesh every cell of which is inverted or folded is\nrefused with `IGAPARAM_STATUS_INVALID_MESH` (likely a connectivity in another node order, or\ncells oriented the wrong way).",
    ),
    "igaparam_mesh_free": (
        None,
        [ctypes.c_void_p],
        'void igaparam_mesh_free(igaparam_mesh *mesh);\n\nReleases a mesh. NULL is a no-op. Called on a mesh in use (from the progress callback of\n`igaparam_mesh_relocate`, or from another thread), the release waits for that call: the call\nstops at its next progress point with `IGAPARAM_STATUS_CANCELLED` and the mesh is released\nas it returns; the handle must not be used after this call in either case.',
    ),
    "igaparam_mesh_node_count": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t)],
        'igaparam_status igaparam_mesh_node_count(const igaparam_mesh *mesh, size_t *out);\n\nWrites the number of nodes to `*out`.',
    ),
    "igaparam_mesh_cell_count": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t)],
        'igaparam_status igaparam_mesh_cell_count(const igaparam_mesh *mesh, size_t *out);\n\nWrites the number of cells to `*out`.',
    ),
    "igaparam_mesh_dimension": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_int)],
        'igaparam_status igaparam_mesh_dimension(const igaparam_mesh *mesh, int *out);\n\nWrites the spatial dimension of the cells (2 or 3) to `*out`.',
    ),
    "igaparam_mesh_set_fixed": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_uint8)],
        "igaparam_status igaparam_mesh_set_fixed(igaparam_mesh *mesh, size_t num_nodes, const uint8_t *mask);\n\nSets the constraint of every node: `mask` has `num_nodes` entries; bit 0 keeps x, bit 1 keeps\ny, bit 2 keeps z (0 free, 3 fixed in 2D, 7 fixed in 3D, 4 sliding in its plane z = const).\n`num_nodes` must equal the mesh's node count.",
    ),
    "igaparam_mesh_move_nodes": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_int64), ctypes.POINTER(ctypes.c_double)],
        "igaparam_status igaparam_mesh_move_nodes(igaparam_mesh *mesh, size_t count, const int64_t *indices, const double *xyz);\n\nSets the positions of `count` nodes: node `indices[i]` moves to `xyz[3i..3i+3]`. `indices`\nmay be NULL, meaning nodes `0..count-1`. Typically used for the boundary nodes before\n`igaparam_mesh_relocate`; the reference shape is not changed. A free coordinate moved here is\nwhere the next relocation starts only with `IGAPARAM_PLACEMENT_CURRENT`: the default\n`IGAPARAM_PLACEMENT_LAPLACIAN` computes every free coordinate from the motion of the\nprescribed ones, and `IGAPARAM_PLACEMENT_INCREMENTAL` from the last relocation's result, so\nthere the move of a free coordinate has no effect.",
    ),
    "igaparam_mesh_reset_reference": (
        ctypes.c_int,
        [ctypes.c_void_p],
        'igaparam_status igaparam_mesh_reset_reference(igaparam_mesh *mesh);\n\nMakes the current positions the reference shape of the targets (e.g. after an accepted step of\na shape-optimization loop).',
    ),
    "igaparam_mesh_copy_positions": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t],
        'igaparam_status igaparam_mesh_copy_positions(const igaparam_mesh *mesh, double *xyz, size_t len);\n\nCopies the current node positions into `xyz` (`len` doubles, at least `3 × num_nodes`; x0 y0\nz0 x1 ...).',
    ),
    "igaparam_mesh_copy_cell_quality": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_int, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t],
        "igaparam_status igaparam_mesh_copy_cell_quality(const igaparam_mesh *mesh, igaparam_target target_kind, double *quality, size_t len);\n\nCopies the quality of every cell against `target` (an `IGAPARAM_TARGET_*` value) into\n`quality` (`len` doubles, at least `num_cells`): the inverse mean distortion over the cell's\nGauss–Lobatto points, in (0, 1], or 0 for a cell with det J <= 0 somewhere.",
    ),
    "igaparam_mesh_copy_reference": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t],
        'igaparam_status igaparam_mesh_copy_reference(const igaparam_mesh *mesh, double *xyz, size_t len);\n\nCopies the reference positions (the shape the targets are taken from) into `xyz` (`len`\ndoubles, at least `3 × num_nodes`).',
    ),
    "igaparam_mesh_copy_fixed": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint8), ctypes.c_size_t],
        'igaparam_status igaparam_mesh_copy_fixed(const igaparam_mesh *mesh, uint8_t *mask, size_t len);\n\nCopies the constraint mask of every node (see `igaparam_mesh_set_fixed`) into `mask` (`len`\nbytes, at least `num_nodes`).',
    ),
    "igaparam_cell_type_node_count": (
        ctypes.c_int,
        [ctypes.c_int, ctypes.POINTER(ctypes.c_size_t)],
        'igaparam_status igaparam_cell_type_node_count(igaparam_cell_type cell_type_code, size_t *out);\n\nWrites to `*out` the number of nodes of one cell of type `cell_type_code`, e.g. 9 for\n`IGAPARAM_CELL_QUAD9`.',
    ),
    "igaparam_mesh_invalid_cell_count": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t)],
        'igaparam_status igaparam_mesh_invalid_cell_count(const igaparam_mesh *mesh, size_t *out);\n\nWrites to `*out` the number of cells with det J <= 0 at some Gauss–Lobatto point.',
    ),
    "igaparam_mesh_read_vtu": (
        ctypes.c_int,
        [ctypes.c_char_p, ctypes.POINTER(ctypes.c_void_p)],
        "igaparam_status igaparam_mesh_read_vtu(const char *path, igaparam_mesh **out);\n\nReads a mesh from a VTK XML unstructured grid (`.vtu`) at `path` (NUL-terminated UTF-8), in\nany storage VTK and meshio write: ASCII, inline base64, appended raw or base64 data,\nuncompressed or zlib-compressed. The cells must all have one supported type (node order VTK's).\nThe point arrays `fixed_components` (integer masks, see `igaparam_mesh_set_fixed`) and `moved`\n(3 components), when present, are applied: every node's fixed coordinates are set to `moved`\nand its mask is set; a mask without `moved` fixes the nodes where they are. The file's points\nare the reference shape. `out` receives the new handle (release with `igaparam_mesh_free`).\nFails with `IGAPARAM_STATUS_IO` for a file that cannot be read or is not understood,\n`IGAPARAM_STATUS_INVALID_MESH` for unsupported or mixed cells or bad masks.",
    ),
    "igaparam_mesh_write_vtu_format": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int],
        "igaparam_status igaparam_mesh_write_vtu_format(const igaparam_mesh *mesh, const char *path, igaparam_vtu_format format);\n\nWrites the mesh to a `.vtu` file at `path` (NUL-terminated UTF-8) in format `format` (an\n`IGAPARAM_VTU_*` value): the current positions and the cells (VTK node order), point data\n`displacement` (current minus reference positions) and `fixed_components` (UInt8 masks),\ncell data `quality` (against the cells' reference shapes, 0 for an invalid cell).\nFails with `IGAPARAM_STATUS_IO` if the file cannot be written.",
    ),
    "igaparam_mesh_write_vtu": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_char_p],
        'igaparam_status igaparam_mesh_write_vtu(const igaparam_mesh *mesh, const char *path);\n\n`igaparam_mesh_write_vtu_format` with `IGAPARAM_VTU_DEFAULT` (zlib-compressed base64).',
    ),
    "igaparam_mesh_cell_type": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_int)],
        "igaparam_status igaparam_mesh_cell_type(const igaparam_mesh *mesh, igaparam_cell_type *out);\n\nWrites the mesh's cell type (an `IGAPARAM_CELL_*` value) to `*out`.",
    ),
    "igaparam_mesh_new_ordered": (
        ctypes.c_int,
        [ctypes.c_int, ctypes.c_int, ctypes.c_size_t, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t, ctypes.POINTER(ctypes.c_int64), ctypes.POINTER(ctypes.c_void_p)],
        'igaparam_status igaparam_mesh_new_ordered(igaparam_cell_type cell_type_code, igaparam_node_order order, size_t num_nodes, const double *xyz, size_t num_cells, const int64_t *connectivity, igaparam_mesh **out);\n\n`igaparam_mesh_new` for a connectivity whose cells list their nodes in `order` (an\n`IGAPARAM_ORDER_*` value, see `igaparam_node_order` for the tables). The mesh keeps the order:\n`igaparam_mesh_copy_connectivity` gives the cells back in it. A mesh every cell of which is\ninverted or folded in the given positions is refused (`IGAPARAM_STATUS_INVALID_MESH`, with a\nmessage naming the likely cause: a connectivity in another node order, or cells oriented the\nwrong way).',
    ),
    "igaparam_mesh_order": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_int)],
        "igaparam_status igaparam_mesh_order(const igaparam_mesh *mesh, igaparam_node_order *out);\n\nWrites to `*out` the node order the mesh's connectivity was given in (`IGAPARAM_ORDER_VTK`\nfor meshes from `igaparam_mesh_new` and `igaparam_mesh_read_vtu`).",
    ),
    "igaparam_mesh_copy_connectivity": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_int, ctypes.POINTER(ctypes.c_int64), ctypes.c_size_t],
        "igaparam_status igaparam_mesh_copy_connectivity(const igaparam_mesh *mesh, igaparam_node_order order, int64_t *connectivity, size_t len);\n\nCopies the connectivity into `connectivity` (`len` values, at least `num_cells × nodes per\ncell`), each cell's nodes in `order` (an `IGAPARAM_ORDER_*` value; pass the one of\n`igaparam_mesh_order` to get the cells back as given).",
    ),
    "igaparam_cell_type_copy_node_coordinates": (
        ctypes.c_int,
        [ctypes.c_int, ctypes.c_int, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t],
        'igaparam_status igaparam_cell_type_copy_node_coordinates(igaparam_cell_type cell_type_code, igaparam_node_order order, double *xi, size_t len);\n\nCopies the reference coordinates in [-1,1]^d of the local nodes of `cell_type_code` in\n`order` into `xi` (`len` doubles, at least `nodes per cell × d`; d = 2 for quadrilaterals,\n3 for hexahedra): node i at `xi[d i .. d i + d]`.',
    ),
    "igaparam_partition_new": (
        ctypes.c_int,
        [ctypes.POINTER(Exchange), ctypes.c_int, ctypes.c_size_t, ctypes.POINTER(ctypes.c_int64), ctypes.POINTER(ctypes.c_uint8), ctypes.POINTER(ctypes.c_double), ctypes.c_size_t, ctypes.POINTER(ctypes.c_int64), ctypes.POINTER(ctypes.c_int64), ctypes.POINTER(ctypes.c_void_p)],
        "igaparam_status igaparam_partition_new(const igaparam_exchange *exchange, igaparam_cell_type cell_type_code, size_t num_nodes, const int64_t *node_ids, const uint8_t *owned, const double *xyz, size_t num_cells, const int64_t *cell_ids, const int64_t *connectivity, igaparam_partition **out);\n\nCreates this rank's part of a partitioned mesh; collective (every rank of `exchange` calls\nit). `num_nodes` local nodes: `node_ids` their global ids (non-negative, each node owned by\nexactly one rank), `owned` 1 where this rank owns the node else 0, `xyz` 3 coordinates each\n(the reference shape). `num_cells` local cells: `cell_ids` their global ids, `connectivity`\ntheir local node indices (`0..num_nodes`, VTK node order, `cell_type` the same on every\nrank). The owner of a node must hold every cell around it (a one-cell halo); a cell held on\nseveral ranks must have the same nodes everywhere. Global ids fix the order of the colouring\nand of every sum: numbered as in the whole mesh, the result equals the whole mesh's.\n\nA bad part on any rank (argument, NULL, a node owned twice or by no rank, a missing cell or\nnode) makes the call fail on every rank with the same message; only a bad `exchange` fails\non its own rank (the others then wait for it in their callback).",
    ),
    "igaparam_partition_free": (
        None,
        [ctypes.c_void_p],
        'void igaparam_partition_free(igaparam_partition *part);\n\nReleases a part. NULL is a no-op. Not collective. Called on a part in use (from the\nprogress callback of `igaparam_partition_relocate`, or from another thread), the release\nwaits for that call, which cancels on every rank at its next progress point.',
    ),
    "igaparam_partition_node_count": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t)],
        'igaparam_status igaparam_partition_node_count(const igaparam_partition *part, size_t *out);\n\nWrites the number of local nodes (owned and ghosts) to `*out`.',
    ),
    "igaparam_partition_set_fixed": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_uint8)],
        "igaparam_status igaparam_partition_set_fixed(igaparam_partition *part, size_t num_nodes, const uint8_t *mask);\n\nSets the constraint mask of every local node (`num_nodes` entries, in the order given to\n`igaparam_partition_new`; bits as in `igaparam_mesh_set_fixed`). A ghost copy takes its\nowner's mask at the next relocation. Not collective.",
    ),
    "igaparam_partition_set_positions": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_double)],
        "igaparam_status igaparam_partition_set_positions(igaparam_partition *part, size_t len, const double *xyz);\n\nSets the current positions of all local nodes (`len` = 3 × num_nodes doubles, in the order\ngiven to `igaparam_partition_new`), e.g. with the boundary moved. A ghost copy takes its\nowner's position at the next relocation. Not collective.",
    ),
    "igaparam_partition_copy_positions": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t],
        'igaparam_status igaparam_partition_copy_positions(const igaparam_partition *part, double *xyz, size_t len);\n\nCopies the current positions of the local nodes into `xyz` (`len` doubles, at least\n3 × num_nodes), in the order given to `igaparam_partition_new`. Not collective.',
    ),
    "igaparam_partition_relocate": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(Exchange), ctypes.POINTER(RelocateOptions), ctypes.POINTER(PartitionReport)],
        'igaparam_status igaparam_partition_relocate(igaparam_partition *part, const igaparam_exchange *exchange, const igaparam_relocate_options *options, igaparam_partition_report *report);\n\nRelocates the whole partitioned mesh on all ranks together; collective. The result equals,\nbit for bit, `igaparam_mesh_relocate` of the whole mesh (numbered by the global ids) with\n`IGAPARAM_METHOD_SWEEPS`, whatever the number of ranks. `IGAPARAM_METHOD_AUTO` means the\nsweeps here; `IGAPARAM_METHOD_NEWTON` and `stationarity_tolerance > 0` are refused (they\nneed a factorisation of the whole Hessian). `options` may be NULL for the defaults; its\nprogress callback runs on every rank, and a cancellation on one cancels all. An error on\nany rank fails the call on all with one message; the parts are then unchanged.',
    ),
    "igaparam_relocate_options_default": (
        RelocateOptions,
        [],
        'igaparam_relocate_options igaparam_relocate_options_default(void);\n\nThe default relocation options.',
    ),
    "igaparam_mesh_relocate": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(RelocateOptions), ctypes.POINTER(RelocateReport)],
        "igaparam_status igaparam_mesh_relocate(igaparam_mesh *mesh, const igaparam_relocate_options *options, igaparam_relocate_report *report);\n\nRelocates the free coordinates of the nodes so that every cell is valid and close to its\ntarget shape, keeping the connectivity. `options` may be NULL for the defaults; `report` may\nbe NULL. On any error or cancellation the mesh is unchanged and `*report` is not written.\n\nUnits: the result does not depend on them. The mesh is optimized in coordinates scaled by\nthe power of two `2^-k` with `2^k <= L < 2^(k+1)`, L the largest side of the bounding box of\nthe reference shape's cell nodes, so every tolerance inside (and every option's tolerance,\ngiven relative to a local cell size) is relative to the mesh's size; a mesh scaled by a\npower of two relocates to the same result scaled bit for bit, by any other factor to the\nsame result to round-off. Prescribed coordinates are returned with the bits they were\ngiven.",
    ),
    "igaparam_mesh_adjoint": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double)],
        "igaparam_status igaparam_mesh_adjoint(const igaparam_mesh *mesh, size_t size, const double *dj_dx, double *dj_dprescribed);\n\nThe adjoint product of the last relocation: `dj_dx` holds the partial derivatives dJ/dx of a\nscalar J of the node positions (`size` = 3 × num_nodes doubles, x0 y0 z0 x1 ...);\n`dj_dprescribed` (`size` doubles) receives the total derivative of J with respect to every\nprescribed coordinate, dJ/dx_p = dJ/dx_p (partial) − H_pf H_ff⁻¹ dJ/dx_f, through the\nrelocation's dependence of the free coordinates on the prescribed ones (implicit function\ntheorem at the stationary point; H the Hessian of F), and 0 at the free coordinates.\n\nFree coordinates: those whose constraint bit is clear, of nodes that belong to a cell\n(sliding nodes have both kinds); all others are prescribed, and z of every node of a 2D mesh.\nNeeds a last relocation with `stationarity_tolerance > 0` that reached it on a valid mesh;\n`igaparam_mesh_move_nodes`, `igaparam_mesh_set_fixed`, `igaparam_mesh_reset_reference` and\na new relocation invalidate the state (the call then fails and says why). The factorisation\nof H_ff (2D meshes and small 3D ones) is kept on the handle, so further products at one\nstate cost a solve each; larger 3D meshes solve by preconditioned conjugate gradients.\nUses the thread count of the last relocation.",
    ),
    "igaparam_mesh_tangent": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double)],
        'igaparam_status igaparam_mesh_tangent(const igaparam_mesh *mesh, size_t size, const double *dx_prescribed, double *dx);\n\nThe tangent product of the last relocation (the transpose of `igaparam_mesh_adjoint`):\n`dx_prescribed` (`size` = 3 × num_nodes doubles) is a motion of the prescribed coordinates\n(its entries at free coordinates are ignored); `dx` (`size` doubles) receives the first-order\nmotion of every node: the given motion at prescribed coordinates, −H_ff⁻¹ H_fp dx_p at free\nones. Same conditions as `igaparam_mesh_adjoint`.',
    ),
    "igaparam_spline_fit_domain": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(FitReport)],
        "igaparam_status igaparam_spline_fit_domain(const igaparam_domain *domain, igaparam_spline **out, igaparam_fit_report *report);\n\nFits the cubic THB spline space of a built domain's T-mesh to its optimized piecewise\nquadratic map (interpolation at the Greville points, sparse LU; a least-squares fit when that\nsystem is singular) and writes the new handle to `*out`. `report` may be NULL. Fails with\n`IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain has not been built; `*out` is written only\non success. The spline does not refer to the domain afterwards. The fit certifies the map\nas `igaparam_spline_check_validity` does with the default options, and the handle keeps that\nresult for it. When the interpolation's map is not certified, the local quasi-interpolant is\nmade too and the better kept; when that is still not certified, the map is untangled: the\ncontrol points around the uncertified elements move to lift det J (inner ones first, keeping\nthe boundary; then boundary ones, at most the `boundary_offset` the domain was built with,\nrelative to the bounding box, none when it is 0), kept only if fewer elements stay uncertified (`report->untangled`,\n`report->boundary_offset`).",
    ),
    "igaparam_spline_read_gismo": (
        ctypes.c_int,
        [ctypes.c_char_p, ctypes.POINTER(ctypes.c_void_p)],
        'igaparam_status igaparam_spline_read_gismo(const char *path, igaparam_spline **out);\n\nReads a THB-spline map written by `igaparam_spline_write_gismo` or by G+Smo (G+Smo XML, a\ncubic `THBSpline2` or `THBSpline3` geometry whose level-0 knots are clamped and uniform with\n2^s spans; its tree as the file gives it, balanced or not) from `path` (NUL-terminated UTF-8)\nand writes the new handle to `*out`. Fails with `IGAPARAM_STATUS_IO` if the file cannot be read or holds no\nsuch map.',
    ),
    "igaparam_spline_free": (
        None,
        [ctypes.c_void_p],
        'void igaparam_spline_free(igaparam_spline *spline);\n\nReleases a spline created by this library; NULL is a no-op. Called on a spline in use (from\nthe progress callback of a call on it, or from another thread), the release waits for that\ncall and happens as it returns; the handle must not be used after this call in either case.',
    ),
    "igaparam_spline_clone": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_void_p)],
        'igaparam_status igaparam_spline_clone(const igaparam_spline *spline, igaparam_spline **out);\n\nWrites to `*out` a new, independent copy of `spline` (to refine one while keeping the other).',
    ),
    "igaparam_spline_dimension": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t)],
        "igaparam_status igaparam_spline_dimension(const igaparam_spline *spline, size_t *out);\n\nWrites the map's dimension d (2 or 3) to `*out`.",
    ),
    "igaparam_spline_basis_count": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t)],
        'igaparam_status igaparam_spline_basis_count(const igaparam_spline *spline, size_t *out);\n\nWrites the number of basis functions (= control points) to `*out`.',
    ),
    "igaparam_spline_element_count": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t)],
        'igaparam_status igaparam_spline_element_count(const igaparam_spline *spline, size_t *out);\n\nWrites the number of elements (boxes on which every basis function is a polynomial) to\n`*out`.',
    ),
    "igaparam_spline_copy_control_points": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t],
        'igaparam_status igaparam_spline_copy_control_points(const igaparam_spline *spline, double *xyz, size_t len);\n\nCopies the control points, `num_basis × d` doubles, into `xyz` (`len` doubles).',
    ),
    "igaparam_spline_copy_greville_points": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t],
        'igaparam_status igaparam_spline_copy_greville_points(const igaparam_spline *spline, double *params, size_t len);\n\nCopies the Greville points of the basis functions, `num_basis × d` doubles in [0,1]^d (in the\norder of the global function indices), into `params` (`len` doubles). A function whose\nGreville point lies inside (0,1)^d vanishes on the boundary of the parametric domain (the\nknots are clamped): the functions with a Greville point on the boundary (some coordinate 0 or\n1) are the degrees of freedom a Dirichlet condition sets.',
    ),
    "igaparam_spline_copy_elements": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint8), ctypes.POINTER(ctypes.c_double), ctypes.c_size_t],
        'igaparam_status igaparam_spline_copy_elements(const igaparam_spline *spline, uint8_t *levels, double *bounds, size_t len);\n\nCopies the elements: `levels` receives the refinement level of each (`num_elements` bytes;\nan element of level l has side 2^-l), `bounds` the parametric box of each,\n`num_elements × 2d` doubles (lower corner then upper corner). Either may be NULL to skip it;\n`len` is the number of elements the buffers hold, at least `num_elements`.',
    ),
    "igaparam_spline_element_function_count": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_size_t)],
        'igaparam_status igaparam_spline_element_function_count(const igaparam_spline *spline, size_t element, size_t *out);\n\nWrites to `*out` the number of basis functions that are non-zero on element `element`: the\nrows of its Bézier extraction operator (which has `4^d` columns).',
    ),
    "igaparam_spline_copy_element_extraction": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_size_t), ctypes.c_size_t, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t],
        "igaparam_status igaparam_spline_copy_element_extraction(const igaparam_spline *spline, size_t element, size_t *functions, size_t len_functions, double *operator_, size_t len_operator);\n\nCopies the Bézier extraction of element `element`: `functions` receives the global indices\nof the `m` basis functions non-zero on it (increasing; `m` from\n`igaparam_spline_element_function_count`, `len_functions` at least `m`), and `operator` the\n`m × 4^d` matrix C (row-major, `len_operator` at least `m × 4^d` doubles) such that\n`N_functions[i] = Σ_k C[i][k] B_k` on the element, with `B_k` the tensor Bernstein\npolynomials of degree 3 on the element's box mapped to [0,1]^d, `k = k0 + 4 k1 (+ 16 k2)`.\nEither buffer may be NULL to skip it.",
    ),
    "igaparam_spline_refine": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_size_t), ctypes.POINTER(FitReport)],
        "igaparam_status igaparam_spline_refine(igaparam_spline *spline, size_t n, const size_t *elements, igaparam_fit_report *report);\n\nh-refines the spline space, the map staying the same (the refined space contains the old\none; the new control points reproduce the map to round-off, see `report->residual`): the\nelements listed in `elements` (`n` indices) are split into 2^d, and more where the mesh's\n2:1 balance requires it; `n = 0` (with `elements` NULL) refines every element once. An\nelement already at the deepest level, 20 (side 2^-20; see `igaparam_spline_copy_elements`),\nis left as it is. Element and function indices change. `report` may be NULL. On failure the\nspline is unchanged.",
    ),
    "igaparam_spline_write_vtu": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_uint32],
        'igaparam_status igaparam_spline_write_vtu(const igaparam_spline *spline, const char *path, uint32_t samples);\n\nWrites the map sampled on `samples^d` sub-cells per element (`samples` from 1 to 32) to a VTK\nXML unstructured grid (`.vtu`) at `path`: quads (2D) or hexahedra (3D) at the physical\npositions, point data `quality` (q_S) and `det` (det J_S), cell data `level` and `element`.',
    ),
    "igaparam_spline_write_gismo": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_char_p],
        "igaparam_status igaparam_spline_write_gismo(const igaparam_spline *spline, const char *path);\n\nWrites the map to G+Smo XML at `path` (a `THBSpline2`/`THBSpline3` geometry over a\n`THBSplineBasis2`/`3`, readable by G+Smo's `gsReadFile` and by `igaparam_spline_read_gismo`).",
    ),
    "igaparam_adapt_options_default": (
        AdaptOptions,
        [],
        'igaparam_adapt_options igaparam_adapt_options_default(void);\n\nThe default adaptation options.',
    ),
    "igaparam_domain_fit_adaptive": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(AdaptOptions), ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(AdaptReport)],
        'igaparam_status igaparam_domain_fit_adaptive(igaparam_domain *domain, const igaparam_adapt_options *options, igaparam_spline **out, igaparam_adapt_report *report);\n\nThe adaptive loop of the method: fits the spline map of the built domain, refines the T-mesh\ncells whose spline element is not certified valid or has a sampled mean ratio under\n`options->target_quality`, optimizes the T-mesh again and refits, for at most\n`options->max_rounds` rounds. On success the domain keeps its refined T-mesh and `*out`\nreceives the spline of that T-mesh (`report` may be NULL; `options` may be NULL for the\ndefaults). Each fit untangles, and each refinement optimizes, by the rules the domain was\nbuilt with (its `boundary_offset`, relief and repair rounds: a domain built with\n`boundary_offset = 0` keeps its boundary); `options` gives the threads and sweep limit. On\nfailure or cancellation (`IGAPARAM_STATUS_CANCELLED`) the domain is unchanged and `*out` is\nnot written.',
    ),
    "igaparam_fit_options_default": (
        FitOptions,
        [],
        'igaparam_fit_options igaparam_fit_options_default(void);\n\nThe default fit options: those of `igaparam_spline_fit_domain`.',
    ),
    "igaparam_spline_fit_domain_with": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(FitOptions), ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(FitReport)],
        "igaparam_status igaparam_spline_fit_domain_with(const igaparam_domain *domain, const igaparam_fit_options *options, igaparam_spline **out, igaparam_fit_report *report);\n\nFits the cubic THB spline space of a built domain's T-mesh to its optimized map as\n`igaparam_spline_fit_domain` does, with `options` (NULL for the defaults, which make the\ntwo calls equal): the fit rule, the certification, the untangling and smoothing, the threads\nand a progress callback that can cancel. `report` may be NULL. Errors:\n`IGAPARAM_STATUS_INVALID_ARGUMENT` for an unbuilt domain or an option out of range,\n`IGAPARAM_STATUS_CANCELLED` when the callback cancels; `*out` is written only on success.",
    ),
    "igaparam_quality_bound_options_default": (
        QualityBoundOptions,
        [],
        'igaparam_quality_bound_options igaparam_quality_bound_options_default(void);\n\nThe default options of `igaparam_spline_quality_bound`.',
    ),
    "igaparam_spline_quality_bound": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(QualityBoundOptions), ctypes.POINTER(QualityBoundReport)],
        "igaparam_status igaparam_spline_quality_bound(const igaparam_spline *spline, const igaparam_quality_bound_options *options, igaparam_quality_bound_report *report);\n\nA certified lower bound of the map's mean ratio: on each element `det J_S` and `‖J‖²` in\nBernstein form bound `q_S` from below by `d·(min coefficient of det)^(2/d) / (max\ncoefficient of ‖J‖²)`, refined by subdivision where it is more than `gap` below the sampled\nminimum. The sampled minimum of `igaparam_spline_check_validity` is an upper bound of the\ntrue minimum only (finer samples find lower values); this gives the interval. `options` may\nbe NULL for the defaults. Errors: `IGAPARAM_STATUS_INVALID_ARGUMENT` for options out of\nrange, `IGAPARAM_STATUS_NULL_ARGUMENT`.",
    ),
    "igaparam_spline_evaluate": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double)],
        'igaparam_status igaparam_spline_evaluate(const igaparam_spline *spline, size_t n, const double *params, double *points, double *jacobians);\n\nEvaluates the map at `n` parametric points `params` (`n × d` doubles in [0,1]^d): `points`\nreceives `S(params)` (`n × d` doubles) and `jacobians` the Jacobian matrices `dS/du`\n(`n × d × d` doubles, row-major: entry (i, j) = ∂S_i/∂u_j). Either may be NULL to skip it.\nFails with `IGAPARAM_STATUS_INVALID_ARGUMENT` when a point is outside [0,1]^d.',
    ),
    "igaparam_spline_mean_ratio": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double)],
        'igaparam_status igaparam_spline_mean_ratio(const igaparam_spline *spline, size_t n, const double *params, double *quality);\n\nWrites the mean ratio of the Jacobian, `q_S = d·det(J)^(2/d)/‖J‖²_F` in [0, 1] (1 for a\nconformal map, 0 where det J ≤ 0), at `n` parametric points `params` (`n × d` doubles) into\n`quality` (`n` doubles).',
    ),
    "igaparam_spline_invert": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_double), ctypes.c_uint32, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_int32)],
        "igaparam_status igaparam_spline_invert(const igaparam_spline *spline, size_t n, const double *points, uint32_t samples, double *params, int32_t *found);\n\nInverts the map at `n` physical points `points` (`n × d` doubles): `params` receives the\nparametric points whose images they are (`n × d` doubles), `found` (`n` ints) 1 where the\npoint was located and 0 where it is outside the domain (or Newton's method did not converge;\n`params` is NaN there). `found` may be NULL. Newton's method starts from the nearest of\n`samples^d` samples per element (`samples` from 2 to 32; 4 is a good choice).",
    ),
    "igaparam_spline_basis_count_at": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_size_t)],
        'igaparam_status igaparam_spline_basis_count_at(const igaparam_spline *spline, const double *param, size_t *count);\n\nWrites to `*count` the number of basis functions non-zero on the element holding the\nparametric point `param` (`d` doubles in [0,1]^d): the size of the buffers of\n`igaparam_spline_basis_at`.',
    ),
    "igaparam_spline_basis_at": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_size_t), ctypes.POINTER(ctypes.c_size_t), ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double), ctypes.c_size_t],
        "igaparam_status igaparam_spline_basis_at(const igaparam_spline *spline, const double *param, size_t *count, size_t *functions, double *values, double *gradients, size_t len);\n\nThe basis functions non-zero on the element holding the parametric point `param` (`d`\ndoubles in [0,1]^d; on an element boundary the element on the upper side): `*count` receives\ntheir number `m`, `functions` their global indices (`m` values), `values` their values (`m`\ndoubles) and `gradients` their gradients with respect to the parametric coordinates\n(`m × d` doubles). The buffers hold `len` functions (`len ≥ m`, see\n`igaparam_spline_basis_count_at`); any of them may be NULL to skip it. The values sum to 1,\nand `Σ values[i] × control_point[functions[i]]` is the map's value at `param`. When the\nbuffers are too small (`IGAPARAM_STATUS_BUFFER_TOO_SMALL`) `*count` still receives `m` and\nnothing else is written.",
    ),
    "igaparam_spline_refit": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_void_p, ctypes.POINTER(RefitReport)],
        "igaparam_status igaparam_spline_refit(igaparam_spline *spline, const igaparam_domain *domain, igaparam_refit_report *report);\n\nRecomputes the control points of `spline` from the domain's current T-mesh (after\n`igaparam_domain_update`), in the spline's own space: the same basis functions, elements,\nBézier extraction and Greville points, so the basis count and element list never change.\nThe control points come by the rule of the spline's first fit (`report->rule`; a spline\nread from a file gets the first fit's choice, kept for its next refits), plus the\ncorrection an earlier untangling made, if any; the map is then certified as\n`igaparam_spline_check_validity` does with the default options (the handle keeps the result\nfor it) and, where it is not certified, untangled as `igaparam_spline_fit_domain` does. With\nthe rule fixed the control points are a linear function of the T-mesh's vertices, plus the\ncorrection (see `igaparam_refit_report`). A spline refined (`igaparam_spline_refine`) after\nits fit is fitted in the T-mesh's space and carried exactly into its own.\n\n`report` may be NULL. Errors: `IGAPARAM_STATUS_INVALID_ARGUMENT` when the domain has not\nbeen built, its boundary was replaced without `igaparam_domain_update`, its dimension is not\nthe spline's, or its T-mesh has cells the spline's elements do not refine (the domain was\nrefined after the fit, or is another domain). On error the spline is unchanged.",
    ),
    "igaparam_spline_fit_rule": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_int)],
        'igaparam_status igaparam_spline_fit_rule(const igaparam_spline *spline, igaparam_fit_rule *out);\n\nWrites to `*out` the rule the control points of `spline` come from (that of its first fit,\nwhich `igaparam_spline_refit` uses). Fails with `IGAPARAM_STATUS_INVALID_ARGUMENT` for a\nspline read from a file and never refitted (its fit is unknown).',
    ),
    "igaparam_spline_tangent": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t, ctypes.POINTER(ctypes.c_double)],
        "igaparam_status igaparam_spline_tangent(const igaparam_spline *spline, const igaparam_domain *domain, size_t vertex_size, const double *dx_boundary, size_t size, double *dp);\n\nThe tangent product of the control points: for a motion `dx_boundary` of the domain's\nboundary vertices (`vertex_size` = d × num_vertices doubles, in the order of\n`igaparam_domain_copy_vertices`; entries of inner vertices are ignored), writes to `dp`\n(`size` = d × basis_count doubles) the first-order motion of the control points of a refit\nof `spline` to the domain so moved. The T-mesh follows its boundary vertices as the\nstationary point of its optimization (implicit function theorem), and the control points\nfollow the T-mesh by the spline's fit rule, a linear map.\n\nA boundary vertex is one with a parametric coordinate 0 or 1 (see\n`igaparam_domain_copy_vertices`); it sits at its parameters' point on the boundary, so a\nhost derives `dx_boundary` from its own change of the boundary curves or surfaces (for a\nB-spline boundary, the basis functions at the vertex's parameter times the change of the\ncontrol points).\n\nNeeds: a domain built (or updated) with `stationarity_tolerance > 0` that converged and with\nno boundary vertex moved off the boundary by the seam relief (`boundary_offset` 0 is the\nsure way), and a spline in the T-mesh's own space whose last fit or refit did not untangle\n(after one that did, `igaparam_spline_refit` once more carries the untangling's correction\nas a constant). Otherwise `IGAPARAM_STATUS_INVALID_ARGUMENT` says which. The domain's\nthread count is used; the result does not depend on it.",
    ),
    "igaparam_spline_adjoint": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t, ctypes.POINTER(ctypes.c_double)],
        "igaparam_status igaparam_spline_adjoint(const igaparam_spline *spline, const igaparam_domain *domain, size_t size, const double *dj_dp, size_t vertex_size, double *dj_dboundary);\n\nThe adjoint product of the control points, the transpose of `igaparam_spline_tangent`:\ngiven `dj_dp`, the partial derivatives of a scalar J of the control points (`size` = d ×\nbasis_count doubles, in the order of `igaparam_spline_copy_control_points`), writes to\n`dj_dboundary` (`vertex_size` = d × num_vertices doubles) the total derivative of J with\nrespect to every boundary vertex of the domain's T-mesh, through the fit and the T-mesh's\noptimum (0 at inner vertices). For a B-spline boundary, the derivative with respect to a\nboundary control point is the sum over boundary vertices of their derivative times the\ncontrol point's basis function at the vertex's parameter. Same conditions as\n`igaparam_spline_tangent`; a spline fitted by quasi-interpolation is refused (its\ntranspose is not provided).",
    ),
    "igaparam_spline_tangent_controls": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t, ctypes.POINTER(ctypes.c_double)],
        "igaparam_status igaparam_spline_tangent_controls(const igaparam_spline *spline, const igaparam_domain *domain, size_t control_size, const double *dc, size_t size, double *dp);\n\nThe tangent product with respect to the boundary's own control points: for a motion `dc`\nof the control points of the domain's boundary curves or surfaces (`control_size` = d ×\n`igaparam_domain_control_count` doubles, the curves' or surfaces' control points one after\nthe other in the order the domain was made from, each in its own order), writes to `dp`\n(`size` = d × basis_count doubles) the first-order motion of the control points of a refit\nof `spline` after `igaparam_domain_update` to the boundary so moved (weights and knots\nfixed). Each boundary vertex moves by the basis values at its parameters; then as\n`igaparam_spline_tangent`, with its conditions. A corner of two curves, or an edge row of two\nsurfaces, is in two lists: a boundary vertex there follows one of them, so move both copies\nalike. Fails with `IGAPARAM_STATUS_INVALID_ARGUMENT` for a boundary of polylines or\ntriangulated faces (use `igaparam_spline_tangent`).",
    ),
    "igaparam_spline_adjoint_controls": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t, ctypes.POINTER(ctypes.c_double)],
        "igaparam_status igaparam_spline_adjoint_controls(const igaparam_spline *spline, const igaparam_domain *domain, size_t size, const double *dj_dp, size_t control_size, double *dj_dc);\n\nThe adjoint product with respect to the boundary's own control points, the transpose of\n`igaparam_spline_tangent_controls`: given `dj_dp`, the partial derivatives of a scalar J of\nthe spline's control points (`size` = d × basis_count doubles), writes to `dj_dc`\n(`control_size` = d × `igaparam_domain_control_count` doubles) the total derivative of J\nwith respect to every control point of the boundary's curves or surfaces. Same conditions\nas `igaparam_spline_tangent_controls`; not for a quasi-interpolation fit.",
    ),
    "igaparam_domain_control_count": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t)],
        "igaparam_status igaparam_domain_control_count(const igaparam_domain *domain, size_t *out);\n\nWrites to `*out` the number of control points of the built domain's boundary: those of its\ncurves (planar) or surfaces (solid) together, in the order of the sensitivities with respect\nto them (`igaparam_spline_tangent_controls`). Fails with\n`IGAPARAM_STATUS_INVALID_ARGUMENT` for a domain not built or a boundary of polylines or\ntriangulated faces.",
    ),
    "igaparam_validity_options_default": (
        ValidityOptions,
        [],
        'igaparam_validity_options igaparam_validity_options_default(void);\n\nThe default validity options.',
    ),
    "igaparam_spline_check_validity": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(ValidityOptions), ctypes.POINTER(ValidityReport), ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double), ctypes.c_size_t],
        "igaparam_status igaparam_spline_check_validity(const igaparam_spline *spline, const igaparam_validity_options *options, igaparam_validity_report *report, double *element_bounds, double *element_quality, size_t len);\n\nCertifies the sign of the Jacobian determinant on every element (lower bounds from the\nBernstein coefficients of det J_S, a polynomial of degree 5×5 in 2D and 8×8×8 in 3D per\nelement, subdividing when inconclusive) and samples the mean ratio; writes the summary to\n`*report`. `options` may be NULL for the defaults. `element_bounds` (may be NULL) receives\neach element's lower bound of det J_S and `element_quality` (may be NULL) each element's\nsmallest sampled mean ratio, `len` doubles each, at least `num_elements`: what an adaptive\nloop marks elements by. A spline from `igaparam_spline_fit_domain` or\n`igaparam_domain_fit_adaptive` (and its clones) keeps the validity its fit computed with the\ndefault options, returned without recomputing for equal options until the map changes\n(`igaparam_spline_refine`); the result is the same either way.",
    ),
}
