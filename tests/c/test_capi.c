/*
 * Tests of the C API (include/igaparam.h) through its C ABI.
 *
 * Every entry point is called with NULL handles and outputs, wrong sizes, non-finite values,
 * invalid enums and bad indices: each such call must return the documented non-OK status, set a
 * non-empty message, write no output and leave the mesh unchanged. Then relocation itself:
 * tangled Q4 and H8 grids are untangled, cancellation rolls back, the result does not depend on
 * the number of threads. Prints "N passed, M failed"; exits non-zero if any check failed.
 */

#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "igaparam.h"
#include "structured_grid.h"

/* ---------------------------------------------------------------------------------------------
 * Checks
 * ------------------------------------------------------------------------------------------- */

#include "check.h"

#define CHECK(cond) check_at((cond) != 0, __FILE__, __LINE__, "%s", #cond)
#define CHECKF(cond, ...) check_at((cond) != 0, __FILE__, __LINE__, __VA_ARGS__)
#define EXPECT_OK(call) expect_ok_at((call), __FILE__, __LINE__, #call)

/* The calling thread's last error message (truncated to 1023 bytes). */
static const char *last_message(void) {
  static char buffer[1024];
  igaparam_last_error_message(buffer, sizeof buffer);
  return buffer;
}

static void expect_ok_at(igaparam_status status, const char *file, int line, const char *call) {
  check_at(status == IGAPARAM_STATUS_OK, file, line, "%s returned %d: %s", call, (int)status,
           status == IGAPARAM_STATUS_OK ? "" : last_message());
}

/* A set of acceptable statuses. */
#define ST(status) (1u << (unsigned)(status))

/* ---------------------------------------------------------------------------------------------
 * Whether a failed call set its own message: before the call under test another failure (a
 * "primer") sets a known message; the call's message must differ from it. If it equals the
 * primer's (the call fails the same way), the call is repeated after the other primer, whose
 * message differs.
 * ------------------------------------------------------------------------------------------- */

static igaparam_mesh *primer_mesh;
static char primer_message[2][1024];

static void prime(int which) {
  size_t count;
  if (which == 0) {
    igaparam_mesh_node_count(NULL, &count);
  } else {
    igaparam_mesh_copy_positions(primer_mesh, NULL, 0);
  }
}

static void init_primers(void) {
  const double xyz[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const int64_t cell[4] = {0, 1, 2, 3};
  EXPECT_OK(igaparam_mesh_new(IGAPARAM_CELL_QUAD4, 4, xyz, 1, cell, &primer_mesh));
  for (int i = 0; i < 2; i++) {
    prime(i);
    strcpy(primer_message[i], last_message());
    CHECK(primer_message[i][0] != '\0');
  }
  CHECK(strcmp(primer_message[0], primer_message[1]) != 0);
}

/* ---------------------------------------------------------------------------------------------
 * Snapshots of a mesh's positions, to check that a failed call left them as they were
 * ------------------------------------------------------------------------------------------- */

typedef struct {
  const igaparam_mesh *mesh;
  size_t len;
  double *xyz;
} snapshot;

static double *copy_positions(const igaparam_mesh *mesh, size_t *len) {
  size_t nodes = 0;
  *len = 0;
  if (igaparam_mesh_node_count(mesh, &nodes) != IGAPARAM_STATUS_OK) return NULL;
  double *xyz = malloc(3 * nodes * sizeof *xyz);
  if (xyz && igaparam_mesh_copy_positions(mesh, xyz, 3 * nodes) != IGAPARAM_STATUS_OK) {
    free(xyz);
    return NULL;
  }
  *len = 3 * nodes;
  return xyz;
}

static snapshot snapshot_take(const igaparam_mesh *mesh) {
  snapshot s = {mesh, 0, NULL};
  if (mesh) s.xyz = copy_positions(mesh, &s.len);
  return s;
}

/* Non-zero when the mesh still has the snapshot's positions; releases the snapshot. */
static int snapshot_unchanged(snapshot *s) {
  int same = 1;
  if (s->mesh) {
    size_t len;
    double *now = copy_positions(s->mesh, &len);
    same = s->xyz && now && len == s->len && memcmp(now, s->xyz, len * sizeof *now) == 0;
    free(now);
  }
  free(s->xyz);
  s->xyz = NULL;
  return same;
}

/* The message of the latest failure checked by EXPECT_FAIL (later successful calls, such as the
 * snapshot's, replace the library's message). */
static char failure_message[1024];

static void expect_failure_at(const char *file, int line, const char *call, unsigned statuses,
                              igaparam_status status, int fresh, snapshot *before) {
  const char *message = strcpy(failure_message, last_message());
  check_at(status != IGAPARAM_STATUS_OK && (statuses & ST(status)), file, line,
           "%s returned status %d, not one of the expected (mask 0x%x); message: %s", call, (int)status,
           statuses, message);
  check_at(fresh && message[0] != '\0', file, line, "%s set no message of its own (message: \"%s\")", call,
           message);
  check_at(snapshot_unchanged(before), file, line, "%s failed but changed the mesh's positions", call);
}

/*
 * Runs `call`, which must fail with a status in `statuses`, set its own non-empty message and
 * leave the positions of `watched` (a mesh, or NULL) unchanged.
 */
#define EXPECT_FAIL(statuses, watched, call)                                       \
  do {                                                                             \
    snapshot snap_ = snapshot_take(watched);                                       \
    prime(0);                                                                      \
    igaparam_status status_ = (call);                                              \
    int fresh_ = strcmp(last_message(), primer_message[0]) != 0;                   \
    if (!fresh_) {                                                                 \
      prime(1);                                                                    \
      status_ = (call);                                                            \
      fresh_ = strcmp(last_message(), primer_message[1]) != 0;                     \
    }                                                                              \
    expect_failure_at(__FILE__, __LINE__, #call, (statuses), status_, fresh_, &snap_); \
  } while (0)

/* ---------------------------------------------------------------------------------------------
 * Meshes
 * ------------------------------------------------------------------------------------------- */

static igaparam_mesh *new_grid_mesh(const structured_grid *g) {
  igaparam_mesh *mesh = NULL;
  EXPECT_OK(igaparam_mesh_new(g->type, g->num_nodes, g->xyz, g->num_cells, g->connectivity, &mesh));
  return mesh;
}

/* Builds an n × n (× n) grid of `type`, or exits. */
static void grid_init(structured_grid *g, igaparam_cell_type type, size_t n) {
  if (structured_grid_init(g, type, n, n, n) != 0) {
    fprintf(stderr, "cannot build a grid\n");
    exit(2);
  }
}

/* A mesh of grid `g` with its boundary nodes fixed. */
static igaparam_mesh *new_fixed_mesh(const structured_grid *g) {
  igaparam_mesh *mesh = new_grid_mesh(g);
  uint8_t *mask = structured_grid_boundary_mask(g);
  EXPECT_OK(igaparam_mesh_set_fixed(mesh, g->num_nodes, mask));
  free(mask);
  return mesh;
}

/* Pushes the top side (y = 1) of a 2D grid down into a bump of depth `depth`. */
static void push_top(igaparam_mesh *mesh, const structured_grid *g, double depth) {
  const double pi = 3.14159265358979323846;
  for (size_t i = 0; i < g->lattice[0]; i++) {
    int64_t v = (int64_t)structured_grid_node(g, i, g->lattice[1] - 1, 0);
    double p[3];
    memcpy(p, g->xyz + 3 * v, sizeof p);
    p[1] -= depth * sin(pi * p[0]);
    EXPECT_OK(igaparam_mesh_move_nodes(mesh, 1, &v, p));
  }
}

/* Moves every interior node by a pseudo-random offset of up to ±amplitude lattice spacings in
 * each direction (a fixed sequence, so the tests are reproducible). */
static void perturb_interior(igaparam_mesh *mesh, const structured_grid *g, double amplitude) {
  uint32_t state = 12345;
  for (size_t v = 0; v < g->num_nodes; v++) {
    if (structured_grid_on_boundary(g, v)) continue;
    double p[3];
    memcpy(p, g->xyz + 3 * v, sizeof p);
    for (int d = 0; d < g->dimension; d++) {
      state = state * 1664525u + 1013904223u;
      double r = (double)(state >> 8) / (double)(1u << 24) * 2.0 - 1.0; /* in [-1, 1) */
      p[d] += amplitude * r / (double)(g->lattice[d] - 1);
    }
    int64_t index = (int64_t)v;
    EXPECT_OK(igaparam_mesh_move_nodes(mesh, 1, &index, p));
  }
}

static size_t invalid_cells(const igaparam_mesh *mesh) {
  size_t n = (size_t)-1;
  EXPECT_OK(igaparam_mesh_invalid_cell_count(mesh, &n));
  return n;
}

/* ---------------------------------------------------------------------------------------------
 * Entry points without a mesh
 * ------------------------------------------------------------------------------------------- */

static void test_version_and_defaults(void) {
  const char *version = igaparam_version();
  char expected[64];
  snprintf(expected, sizeof expected, "%d.%d.%d", IGAPARAM_VERSION_MAJOR, IGAPARAM_VERSION_MINOR,
           IGAPARAM_VERSION_PATCH);
  CHECK(version != NULL && strcmp(version, expected) == 0);

  igaparam_relocate_options o = igaparam_relocate_options_default();
  CHECK(o.target == IGAPARAM_TARGET_INITIAL);
  CHECK(o.placement == IGAPARAM_PLACEMENT_LAPLACIAN);
  CHECK(o.optimize != 0);
  CHECK(o.max_sweeps == 100);
  CHECK(o.move_tolerance == 1e-3);
  CHECK(o.gradient_tolerance == 1e-3);
  CHECK(o.max_newton_iterations == 150);
  CHECK(o.relaxation == 1.8);
  CHECK(o.threads == 0);
  CHECK(o.progress == NULL && o.progress_user == NULL);
}

static void *fresh_thread_messages(void *unused) {
  (void)unused;
  size_t *sizes = malloc(2 * sizeof *sizes);
  sizes[0] = igaparam_last_error_message(NULL, 0); /* nothing failed on this thread yet */
  size_t count;
  igaparam_mesh_cell_count(NULL, &count);
  sizes[1] = igaparam_last_error_message(NULL, 0);
  return sizes;
}

static void test_last_error_message(void) {
  size_t count;
  CHECK(igaparam_mesh_node_count(NULL, &count) == IGAPARAM_STATUS_NULL_ARGUMENT);
  char full[1024];
  const size_t size = igaparam_last_error_message(full, sizeof full);
  CHECK(size > 1 && size <= sizeof full && strlen(full) == size - 1);
  CHECK(igaparam_last_error_message(NULL, 0) == size);
  CHECK(igaparam_last_error_message(NULL, 100) == size);

  char small[4] = {'#', '#', '#', '#'};
  CHECK(igaparam_last_error_message(small, 0) == size);
  CHECK(small[0] == '#'); /* len 0: nothing written */
  CHECK(igaparam_last_error_message(small, sizeof small) == size);
  CHECK(small[3] == '\0' && strncmp(small, full, 3) == 0); /* truncated, terminated */
  CHECK(igaparam_last_error_message(small, 1) == size && small[0] == '\0');

  /* The message belongs to the thread: a new thread starts with none, and its failures do not
   * replace this thread's message. */
  pthread_t thread;
  void *result = NULL;
  CHECK(pthread_create(&thread, NULL, fresh_thread_messages, NULL) == 0 && pthread_join(thread, &result) == 0);
  size_t *sizes = result;
  CHECK(sizes && sizes[0] == 1 && sizes[1] > 1);
  free(sizes);
  CHECK(strcmp(last_message(), full) == 0);

  /* Every call replaces the message: a successful one leaves it empty. */
  igaparam_mesh *mesh = NULL;
  const double xyz[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const int64_t cell[4] = {0, 1, 2, 3};
  CHECK(igaparam_mesh_new(IGAPARAM_CELL_QUAD4, 4, xyz, 1, cell, &mesh) == IGAPARAM_STATUS_OK);
  CHECK(igaparam_last_error_message(NULL, 0) == 1 && last_message()[0] == '\0');
  igaparam_mesh_free(mesh);
}

static void test_mesh_new(void) {
  /* One cell of every supported type is accepted and reports its dimension. */
  static const struct { igaparam_cell_type type; size_t nodes; int dimension; } types[] = {
      {IGAPARAM_CELL_QUAD4, 4, 2},  {IGAPARAM_CELL_QUAD8, 8, 2},   {IGAPARAM_CELL_QUAD9, 9, 2},
      {IGAPARAM_CELL_HEX8, 8, 3},   {IGAPARAM_CELL_HEX20, 20, 3},  {IGAPARAM_CELL_HEX27, 27, 3},
  };
  double xyz[3 * 27];
  int64_t cell[27];
  for (size_t v = 0; v < 27; v++) {
    xyz[3 * v] = (double)(v % 3);
    xyz[3 * v + 1] = (double)(v / 3 % 3);
    xyz[3 * v + 2] = (double)(v / 9);
    cell[v] = (int64_t)v;
  }
  for (size_t t = 0; t < sizeof types / sizeof types[0]; t++) {
    /* Node v at its reference coordinates (VTK order): one valid cell. */
    const int d = types[t].dimension;
    double xi[3 * 27], at[3 * 27] = {0};
    EXPECT_OK(igaparam_cell_type_copy_node_coordinates(types[t].type, IGAPARAM_ORDER_VTK, xi, 3 * 27));
    for (size_t v = 0; v < types[t].nodes; v++) {
      for (int k = 0; k < d; k++) at[3 * v + k] = xi[d * v + k];
    }
    igaparam_mesh *mesh = NULL;
    size_t nodes = 0, cells = 0, invalid = 1;
    int dimension = 0;
    EXPECT_OK(igaparam_mesh_new(types[t].type, types[t].nodes, at, 1, cell, &mesh));
    EXPECT_OK(igaparam_mesh_node_count(mesh, &nodes));
    EXPECT_OK(igaparam_mesh_cell_count(mesh, &cells));
    EXPECT_OK(igaparam_mesh_dimension(mesh, &dimension));
    EXPECT_OK(igaparam_mesh_invalid_cell_count(mesh, &invalid));
    CHECK(nodes == types[t].nodes && cells == 1 && dimension == types[t].dimension && invalid == 0);
    igaparam_mesh_free(mesh);
    /* Lattice order is no node order: every cell folded, refused with the likely cause. */
    igaparam_mesh *out = NULL;
    EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_MESH), NULL,
                igaparam_mesh_new(types[t].type, types[t].nodes, xyz, 1, cell, &out));
    CHECKF(out == NULL && strstr(failure_message, "node order") != NULL, "message: %s", failure_message);
  }

  /* Failures; *out must stay as it was. */
  igaparam_mesh *const sentinel = (igaparam_mesh *)&primer_mesh;
  igaparam_mesh *out = sentinel;
  const igaparam_cell_type q4 = IGAPARAM_CELL_QUAD4;
  EXPECT_FAIL(ST(IGAPARAM_STATUS_NULL_ARGUMENT), NULL, igaparam_mesh_new(q4, 4, xyz, 1, cell, NULL));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_NULL_ARGUMENT), NULL, igaparam_mesh_new(q4, 4, NULL, 1, cell, &out));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_NULL_ARGUMENT), NULL, igaparam_mesh_new(q4, 4, xyz, 1, NULL, &out));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_ARGUMENT), NULL, igaparam_mesh_new(7, 4, xyz, 1, cell, &out));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_ARGUMENT), NULL, igaparam_mesh_new(-1, 4, xyz, 1, cell, &out));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_ARGUMENT), NULL, igaparam_mesh_new(q4, 0, xyz, 1, cell, &out));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_ARGUMENT), NULL, igaparam_mesh_new(q4, 4, xyz, 0, cell, &out));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_ARGUMENT), NULL,
              igaparam_mesh_new(q4, (size_t)-1 / 2, xyz, 1, cell, &out)); /* num_nodes × 3 overflows */
  /* num_nodes too small for the connectivity: index 3 is out of range. */
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_MESH), NULL, igaparam_mesh_new(q4, 3, xyz, 1, cell, &out));

  int64_t bad[4] = {0, 1, 2, -1};
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_MESH), NULL, igaparam_mesh_new(q4, 4, xyz, 1, bad, &out));
  bad[3] = 4; /* == num_nodes */
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_MESH), NULL, igaparam_mesh_new(q4, 4, xyz, 1, bad, &out));
  bad[3] = 1; /* node 1 twice */
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_MESH), NULL, igaparam_mesh_new(q4, 4, xyz, 1, bad, &out));

  const double specials[2] = {NAN, INFINITY};
  for (int s = 0; s < 2; s++) {
    double copy[12];
    memcpy(copy, xyz, sizeof copy);
    copy[7] = specials[s];
    EXPECT_FAIL(ST(IGAPARAM_STATUS_NOT_FINITE), NULL, igaparam_mesh_new(q4, 4, copy, 1, cell, &out));
    copy[7] = -specials[s];
    EXPECT_FAIL(ST(IGAPARAM_STATUS_NOT_FINITE), NULL, igaparam_mesh_new(q4, 4, copy, 1, cell, &out));
  }
  CHECK(out == sentinel);

  /* Freeing NULL is a no-op: it returns, and leaves the thread's last message (that of the
   * refused NaN above) as it was. */
  char before[1024];
  snprintf(before, sizeof before, "%s", last_message());
  igaparam_mesh_free(NULL);
  CHECK(before[0] != '\0' && strcmp(before, last_message()) == 0);
}

/* ---------------------------------------------------------------------------------------------
 * Entry points on a mesh: failures leave it (and the outputs) unchanged
 * ------------------------------------------------------------------------------------------- */

static void test_queries(igaparam_mesh *mesh, const structured_grid *g) {
  size_t nodes = 0, cells = 0, invalid = 99;
  int dimension = 0;
  EXPECT_OK(igaparam_mesh_node_count(mesh, &nodes));
  EXPECT_OK(igaparam_mesh_cell_count(mesh, &cells));
  EXPECT_OK(igaparam_mesh_dimension(mesh, &dimension));
  EXPECT_OK(igaparam_mesh_invalid_cell_count(mesh, &invalid));
  CHECK(nodes == g->num_nodes && cells == g->num_cells && dimension == g->dimension && invalid <= cells);

  size_t size_out = 777;
  int int_out = 777;
  const unsigned null = ST(IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT_FAIL(null, NULL, igaparam_mesh_node_count(NULL, &size_out));
  EXPECT_FAIL(null, mesh, igaparam_mesh_node_count(mesh, NULL));
  EXPECT_FAIL(null, NULL, igaparam_mesh_cell_count(NULL, &size_out));
  EXPECT_FAIL(null, mesh, igaparam_mesh_cell_count(mesh, NULL));
  EXPECT_FAIL(null, NULL, igaparam_mesh_dimension(NULL, &int_out));
  EXPECT_FAIL(null, mesh, igaparam_mesh_dimension(mesh, NULL));
  EXPECT_FAIL(null, NULL, igaparam_mesh_invalid_cell_count(NULL, &size_out));
  EXPECT_FAIL(null, mesh, igaparam_mesh_invalid_cell_count(mesh, NULL));
  CHECK(size_out == 777 && int_out == 777);
}

static void test_set_fixed_errors(igaparam_mesh *mesh, const structured_grid *g) {
  uint8_t *mask = calloc(g->num_nodes + 1, 1);
  const unsigned invalid = ST(IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT_FAIL(ST(IGAPARAM_STATUS_NULL_ARGUMENT), NULL, igaparam_mesh_set_fixed(NULL, g->num_nodes, mask));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_NULL_ARGUMENT), mesh, igaparam_mesh_set_fixed(mesh, g->num_nodes, NULL));
  EXPECT_FAIL(invalid, mesh, igaparam_mesh_set_fixed(mesh, g->num_nodes - 1, mask));
  EXPECT_FAIL(invalid, mesh, igaparam_mesh_set_fixed(mesh, g->num_nodes + 1, mask));
  EXPECT_FAIL(invalid, mesh, igaparam_mesh_set_fixed(mesh, 0, NULL));
  mask[g->num_nodes - 1] = 8; /* a bit beyond z; the other entries would free every node */
  EXPECT_FAIL(invalid, mesh, igaparam_mesh_set_fixed(mesh, g->num_nodes, mask));
  mask[g->num_nodes - 1] = 255;
  EXPECT_FAIL(invalid, mesh, igaparam_mesh_set_fixed(mesh, g->num_nodes, mask));
  free(mask);
}

static void test_move_nodes_errors(igaparam_mesh *mesh, const structured_grid *g) {
  const double to[6] = {0.5, 0.5, 0.0, 0.25, 0.75, 0.0};
  const int64_t n = (int64_t)g->num_nodes;
  const unsigned invalid = ST(IGAPARAM_STATUS_INVALID_ARGUMENT);
  int64_t indices[2] = {1, 2};
  EXPECT_FAIL(ST(IGAPARAM_STATUS_NULL_ARGUMENT), NULL, igaparam_mesh_move_nodes(NULL, 2, indices, to));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_NULL_ARGUMENT), mesh, igaparam_mesh_move_nodes(mesh, 2, indices, NULL));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_NULL_ARGUMENT), mesh, igaparam_mesh_move_nodes(mesh, 2, NULL, NULL));

  /* The first index is valid, the second not: nothing may move. */
  const int64_t bad_indices[] = {-1, n, n + 1000, INT64_MIN};
  for (size_t i = 0; i < sizeof bad_indices / sizeof bad_indices[0]; i++) {
    indices[1] = bad_indices[i];
    EXPECT_FAIL(invalid, mesh, igaparam_mesh_move_nodes(mesh, 2, indices, to));
  }
  /* Without indices, count may not exceed the node count. */
  double *many = calloc(3 * (g->num_nodes + 1), sizeof *many);
  EXPECT_FAIL(invalid, mesh, igaparam_mesh_move_nodes(mesh, g->num_nodes + 1, NULL, many));
  free(many);
  EXPECT_FAIL(invalid, mesh, igaparam_mesh_move_nodes(mesh, (size_t)-1 / 2, NULL, to)); /* count × 3 overflows */

  /* A non-finite value in the second position: nothing may move. */
  const double specials[3] = {NAN, INFINITY, -INFINITY};
  indices[1] = 2;
  for (int s = 0; s < 3; s++) {
    for (int d = 0; d < 3; d++) {
      double bad[6];
      memcpy(bad, to, sizeof bad);
      bad[3 + d] = specials[s];
      EXPECT_FAIL(ST(IGAPARAM_STATUS_NOT_FINITE), mesh, igaparam_mesh_move_nodes(mesh, 2, indices, bad));
      EXPECT_FAIL(ST(IGAPARAM_STATUS_NOT_FINITE), mesh, igaparam_mesh_move_nodes(mesh, 2, NULL, bad));
    }
  }

  /* Moving no node is a no-op. */
  snapshot before = snapshot_take(mesh);
  EXPECT_OK(igaparam_mesh_move_nodes(mesh, 0, NULL, NULL));
  CHECK(snapshot_unchanged(&before));
}

static void test_reset_reference_errors(void) {
  EXPECT_FAIL(ST(IGAPARAM_STATUS_NULL_ARGUMENT), NULL, igaparam_mesh_reset_reference(NULL));
}

static void test_relocate_errors(igaparam_mesh *mesh) {
  igaparam_relocate_report report, untouched;
  memset(&report, 0xA5, sizeof report);
  untouched = report;
  const igaparam_relocate_options defaults = igaparam_relocate_options_default();
  const unsigned invalid = ST(IGAPARAM_STATUS_INVALID_ARGUMENT);

  EXPECT_FAIL(ST(IGAPARAM_STATUS_NULL_ARGUMENT), NULL, igaparam_mesh_relocate(NULL, &defaults, &report));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_NULL_ARGUMENT), NULL, igaparam_mesh_relocate(NULL, NULL, NULL));

  igaparam_relocate_options o = defaults;
  o.target = 5;
  EXPECT_FAIL(invalid, mesh, igaparam_mesh_relocate(mesh, &o, &report));
  o.target = -1;
  EXPECT_FAIL(invalid, mesh, igaparam_mesh_relocate(mesh, &o, &report));
  o = defaults;
  o.placement = 9;
  EXPECT_FAIL(invalid, mesh, igaparam_mesh_relocate(mesh, &o, &report));
  o.placement = -1;
  EXPECT_FAIL(invalid, mesh, igaparam_mesh_relocate(mesh, &o, &report));
  o = defaults;
  o.move_tolerance = -1.0;
  EXPECT_FAIL(invalid, mesh, igaparam_mesh_relocate(mesh, &o, &report));
  o = defaults;
  o.gradient_tolerance = -1e-6;
  EXPECT_FAIL(invalid, mesh, igaparam_mesh_relocate(mesh, &o, &report));
  /* A NaN or infinite tolerance or relaxation is NOT_FINITE. */
  const double specials[2] = {NAN, INFINITY};
  for (int s = 0; s < 2; s++) {
    o = defaults;
    o.move_tolerance = specials[s];
    EXPECT_FAIL(ST(IGAPARAM_STATUS_NOT_FINITE), mesh, igaparam_mesh_relocate(mesh, &o, &report));
    o = defaults;
    o.gradient_tolerance = specials[s];
    EXPECT_FAIL(ST(IGAPARAM_STATUS_NOT_FINITE), mesh, igaparam_mesh_relocate(mesh, &o, &report));
  }
  /* relaxation must lie in [1, 2). */
  const double relaxations[] = {0.5, 0.999, 2.0, -1.0};
  for (size_t i = 0; i < sizeof relaxations / sizeof relaxations[0]; i++) {
    o = defaults;
    o.relaxation = relaxations[i];
    EXPECT_FAIL(invalid, mesh, igaparam_mesh_relocate(mesh, &o, &report));
  }
  o = defaults;
  o.relaxation = NAN;
  EXPECT_FAIL(ST(IGAPARAM_STATUS_NOT_FINITE), mesh, igaparam_mesh_relocate(mesh, &o, &report));
  CHECK(memcmp(&report, &untouched, sizeof report) == 0);
}

/* Fills `n` doubles with a sentinel; non-zero if they all still hold it. */
static void fill_sentinel(double *values, size_t n) {
  for (size_t i = 0; i < n; i++) values[i] = -12345.5;
}
static int all_sentinel(const double *values, size_t n) {
  for (size_t i = 0; i < n; i++) {
    if (values[i] != -12345.5) return 0;
  }
  return 1;
}

/* Checks that the last message mentions `needed`, the size a too-small buffer should have had. */
static void expect_message_mentions_size(size_t needed) {
  char number[32];
  snprintf(number, sizeof number, "%zu", needed);
  CHECK(strstr(failure_message, number) != NULL);
}

static void test_copy_errors(igaparam_mesh *mesh, const structured_grid *g) {
  const size_t len = 3 * g->num_nodes;
  double *buffer = malloc((len + g->num_cells) * sizeof *buffer);
  const unsigned null = ST(IGAPARAM_STATUS_NULL_ARGUMENT), small = ST(IGAPARAM_STATUS_BUFFER_TOO_SMALL);
  fill_sentinel(buffer, len + g->num_cells);

  EXPECT_FAIL(null, NULL, igaparam_mesh_copy_positions(NULL, buffer, len));
  EXPECT_FAIL(null, mesh, igaparam_mesh_copy_positions(mesh, NULL, len));
  EXPECT_FAIL(small, mesh, igaparam_mesh_copy_positions(mesh, buffer, len - 1));
  expect_message_mentions_size(len);
  EXPECT_FAIL(small, mesh, igaparam_mesh_copy_positions(mesh, buffer, 0));
  EXPECT_FAIL(small, mesh, igaparam_mesh_copy_positions(mesh, NULL, 0));

  const igaparam_target initial = IGAPARAM_TARGET_INITIAL;
  EXPECT_FAIL(null, NULL, igaparam_mesh_copy_cell_quality(NULL, initial, buffer, g->num_cells));
  EXPECT_FAIL(null, mesh, igaparam_mesh_copy_cell_quality(mesh, initial, NULL, g->num_cells));
  EXPECT_FAIL(small, mesh, igaparam_mesh_copy_cell_quality(mesh, initial, buffer, g->num_cells - 1));
  expect_message_mentions_size(g->num_cells);
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_ARGUMENT), mesh, igaparam_mesh_copy_cell_quality(mesh, 5, buffer, g->num_cells));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_ARGUMENT), mesh, igaparam_mesh_copy_cell_quality(mesh, -1, buffer, g->num_cells));
  CHECK(all_sentinel(buffer, len + g->num_cells));

  EXPECT_FAIL(null, NULL, igaparam_mesh_copy_reference(NULL, buffer, len));
  EXPECT_FAIL(null, mesh, igaparam_mesh_copy_reference(mesh, NULL, len));
  EXPECT_FAIL(small, mesh, igaparam_mesh_copy_reference(mesh, buffer, len - 1));
  expect_message_mentions_size(len);
  CHECK(all_sentinel(buffer, len + g->num_cells));
  uint8_t *mask = malloc(g->num_nodes + 1);
  memset(mask, 0xAB, g->num_nodes + 1);
  EXPECT_FAIL(null, NULL, igaparam_mesh_copy_fixed(NULL, mask, g->num_nodes));
  EXPECT_FAIL(null, mesh, igaparam_mesh_copy_fixed(mesh, NULL, g->num_nodes));
  EXPECT_FAIL(small, mesh, igaparam_mesh_copy_fixed(mesh, mask, g->num_nodes - 1));
  expect_message_mentions_size(g->num_nodes);
  CHECK(mask[0] == 0xAB && mask[g->num_nodes - 1] == 0xAB);
  EXPECT_OK(igaparam_mesh_copy_fixed(mesh, mask, g->num_nodes + 1));
  CHECK(mask[0] <= 7 && mask[g->num_nodes] == 0xAB);
  free(mask);

  size_t per_cell = 12345;
  EXPECT_FAIL(null, NULL, igaparam_cell_type_node_count(IGAPARAM_CELL_HEX27, NULL));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_ARGUMENT), NULL, igaparam_cell_type_node_count(7, &per_cell));
  CHECK(per_cell == 12345);
  EXPECT_OK(igaparam_cell_type_node_count(IGAPARAM_CELL_HEX20, &per_cell));
  CHECK(per_cell == 20);

  /* A larger buffer than needed is fine, and only its first entries are written. */
  EXPECT_OK(igaparam_mesh_copy_positions(mesh, buffer, len + 1));
  CHECK(all_sentinel(buffer + len, g->num_cells));
  fill_sentinel(buffer, len + g->num_cells);
  EXPECT_OK(igaparam_mesh_copy_cell_quality(mesh, initial, buffer, g->num_cells + 1));
  CHECK(!all_sentinel(buffer, g->num_cells) && all_sentinel(buffer + g->num_cells, 1));
  free(buffer);
}

/* Relocates with threads = 1 and returns the positions (caller frees). */
static double *relocated_positions(igaparam_mesh *mesh, size_t *len) {
  igaparam_relocate_options o = igaparam_relocate_options_default();
  o.threads = 1;
  igaparam_relocate_report r;
  EXPECT_OK(igaparam_mesh_relocate(mesh, &o, &r));
  return copy_positions(mesh, len);
}

/*
 * All failing calls on one mesh; then the mesh must behave exactly as a twin that never saw them
 * (same constraints, reference shape and positions): same qualities, same relocation.
 */
static void test_failed_calls_change_nothing(void) {
  structured_grid g;
  grid_init(&g, IGAPARAM_CELL_QUAD9, 4);
  igaparam_mesh *mesh = new_fixed_mesh(&g);
  igaparam_mesh *twin = new_fixed_mesh(&g);
  push_top(mesh, &g, 0.3);
  push_top(twin, &g, 0.3);

  test_queries(mesh, &g);
  test_set_fixed_errors(mesh, &g);
  test_move_nodes_errors(mesh, &g);
  test_relocate_errors(mesh);
  test_copy_errors(mesh, &g);

  for (igaparam_target t = IGAPARAM_TARGET_INITIAL; t <= IGAPARAM_TARGET_MASTER; t++) {
    double *q[2];
    q[0] = malloc(g.num_cells * sizeof(double));
    q[1] = malloc(g.num_cells * sizeof(double));
    EXPECT_OK(igaparam_mesh_copy_cell_quality(mesh, t, q[0], g.num_cells));
    EXPECT_OK(igaparam_mesh_copy_cell_quality(twin, t, q[1], g.num_cells));
    CHECK(memcmp(q[0], q[1], g.num_cells * sizeof(double)) == 0);
    free(q[0]);
    free(q[1]);
  }
  size_t len[2];
  double *x[2] = {relocated_positions(mesh, &len[0]), relocated_positions(twin, &len[1])};
  CHECK(x[0] && x[1] && len[0] == len[1] && memcmp(x[0], x[1], len[0] * sizeof(double)) == 0);
  free(x[0]);
  free(x[1]);
  igaparam_mesh_free(mesh);
  igaparam_mesh_free(twin);
  structured_grid_free(&g);
}

/* ---------------------------------------------------------------------------------------------
 * Relocation
 * ------------------------------------------------------------------------------------------- */

/* The reference shape is the target of IGAPARAM_TARGET_INITIAL: quality 1 until nodes move,
 * and 1 again after igaparam_mesh_reset_reference. */
static void test_reference_and_quality(void) {
  structured_grid g;
  grid_init(&g, IGAPARAM_CELL_QUAD4, 4);
  igaparam_mesh *mesh = new_fixed_mesh(&g);
  double q[16];
  double min_q = 2;
  EXPECT_OK(igaparam_mesh_copy_cell_quality(mesh, IGAPARAM_TARGET_INITIAL, q, 16));
  for (int c = 0; c < 16; c++) min_q = fmin(min_q, q[c]);
  CHECK(fabs(min_q - 1.0) < 1e-12);

  perturb_interior(mesh, &g, 0.2); /* moves, but no tangling */
  EXPECT_OK(igaparam_mesh_copy_cell_quality(mesh, IGAPARAM_TARGET_INITIAL, q, 16));
  min_q = 2;
  for (int c = 0; c < 16; c++) min_q = fmin(min_q, q[c]);
  CHECK(min_q > 0 && min_q < 0.999);

  EXPECT_OK(igaparam_mesh_reset_reference(mesh));
  EXPECT_OK(igaparam_mesh_copy_cell_quality(mesh, IGAPARAM_TARGET_INITIAL, q, 16));
  min_q = 2;
  for (int c = 0; c < 16; c++) min_q = fmin(min_q, q[c]);
  CHECK(fabs(min_q - 1.0) < 1e-12);

  /* An already ideal mesh does not move: relocation keeps every cell at quality ~1. */
  igaparam_relocate_report r;
  EXPECT_OK(igaparam_mesh_relocate(mesh, NULL, &r));
  CHECK(r.invalid_after == 0 && r.min_quality > 0.999);
  EXPECT_OK(igaparam_mesh_relocate(mesh, NULL, NULL)); /* report may be NULL */
  igaparam_mesh_free(mesh);
  structured_grid_free(&g);
}

/* A grid whose interior nodes are scrambled into tangled cells is untangled by the optimizer. */
static void test_untangle(igaparam_cell_type type, size_t n, igaparam_target target) {
  structured_grid g;
  grid_init(&g, type, n);
  igaparam_mesh *mesh = new_fixed_mesh(&g);
  perturb_interior(mesh, &g, 0.9);
  const size_t tangled = invalid_cells(mesh);
  CHECK(tangled > 0); /* else the test proves nothing */

  igaparam_relocate_options o = igaparam_relocate_options_default();
  o.placement = IGAPARAM_PLACEMENT_CURRENT; /* start from the tangled positions */
  o.target = target;
  igaparam_relocate_report r;
  EXPECT_OK(igaparam_mesh_relocate(mesh, &o, &r));
  CHECK(r.cells == g.num_cells && r.nodes == g.num_nodes);
  CHECK(r.invalid_before == tangled && r.invalid_after_placement == tangled);
  CHECK(r.invalid_after == 0 && invalid_cells(mesh) == 0);
  CHECK(r.min_quality > 0 && r.min_quality <= r.mean_quality && r.mean_quality <= 1.0);
  if (r.invalid_after != 0) {
    fprintf(stderr, "  untangle type %d target %d: %zu of %zu cells still invalid\n", type, target, r.invalid_after,
            r.cells);
  }
  igaparam_mesh_free(mesh);
  structured_grid_free(&g);
}

typedef struct {
  pthread_t caller;
  igaparam_stage cancel_at;   /* cancel at the first call of this stage */
  int calls, foreign_thread_calls, cancelled;
} progress_log;

static int cancelling_progress(void *user, igaparam_stage stage, size_t done, size_t total) {
  (void)done;
  (void)total;
  progress_log *log = user;
  log->calls++;
  log->foreign_thread_calls += !pthread_equal(pthread_self(), log->caller);
  if (stage == log->cancel_at) {
    log->cancelled++;
    return 1;
  }
  return 0;
}

/* Cancelling from the progress callback returns CANCELLED, writes no report and changes nothing. */
static void test_cancellation(igaparam_stage stage) {
  structured_grid g;
  grid_init(&g, IGAPARAM_CELL_QUAD4, 6);
  igaparam_mesh *mesh = new_fixed_mesh(&g);
  perturb_interior(mesh, &g, 0.9);
  progress_log log = {pthread_self(), stage, 0, 0, 0};
  igaparam_relocate_options o = igaparam_relocate_options_default();
  o.placement = IGAPARAM_PLACEMENT_CURRENT;
  o.threads = 2;
  o.progress = cancelling_progress;
  o.progress_user = &log;
  igaparam_relocate_report report, untouched;
  memset(&report, 0x5A, sizeof report);
  untouched = report;
  EXPECT_FAIL(ST(IGAPARAM_STATUS_CANCELLED), mesh, igaparam_mesh_relocate(mesh, &o, &report));
  CHECK(log.cancelled >= 1 && log.foreign_thread_calls == 0);
  CHECK(memcmp(&report, &untouched, sizeof report) == 0);
  igaparam_mesh_free(mesh);
  structured_grid_free(&g);
}

/* The result does not depend on the number of threads (bit for bit). */
static void test_threads_agree(igaparam_cell_type type, size_t n) {
  structured_grid g;
  grid_init(&g, type, n);
  double *x[2] = {NULL, NULL};
  size_t len[2] = {0, 0};
  igaparam_relocate_report r[2];
  for (int run = 0; run < 2; run++) {
    igaparam_mesh *mesh = new_fixed_mesh(&g);
    if (g.dimension == 2) {
      push_top(mesh, &g, 0.4);
    } else {
      perturb_interior(mesh, &g, 0.9);
    }
    igaparam_relocate_options o = igaparam_relocate_options_default();
    o.placement = g.dimension == 2 ? IGAPARAM_PLACEMENT_LAPLACIAN : IGAPARAM_PLACEMENT_CURRENT;
    o.threads = (uint32_t)(run + 1);
    EXPECT_OK(igaparam_mesh_relocate(mesh, &o, &r[run]));
    x[run] = copy_positions(mesh, &len[run]);
    igaparam_mesh_free(mesh);
  }
  structured_grid_free(&g);
  CHECK(x[0] && x[1] && len[0] == len[1] && memcmp(x[0], x[1], len[0] * sizeof(double)) == 0);
  CHECK(r[0].sweeps == r[1].sweeps && r[0].invalid_after == r[1].invalid_after &&
        r[0].min_quality == r[1].min_quality);
  free(x[0]);
  free(x[1]);
}

/* ---------------------------------------------------------------------------------------------
 * Node orders and .vtu files
 * ------------------------------------------------------------------------------------------- */

/* A 2 × 2 × 2 grid of H27 cells made in Gmsh's order is the grid made in VTK's order; its
 * connectivity comes back in either order; a .vtu written in every storage reads back alike. */
static void test_orders_and_files(void) {
  /* H27 cells on the lattice of a 4 × 4 × 4 H8 grid: cell (a, b, c) covers nodes 2a..2a+2, ... */
  double xi[27 * 3];
  EXPECT_OK(igaparam_cell_type_copy_node_coordinates(IGAPARAM_CELL_HEX27, IGAPARAM_ORDER_GMSH, xi, 27 * 3));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_BUFFER_TOO_SMALL), NULL,
              igaparam_cell_type_copy_node_coordinates(IGAPARAM_CELL_HEX27, IGAPARAM_ORDER_GMSH, xi, 80));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_ARGUMENT), NULL,
              igaparam_cell_type_copy_node_coordinates(IGAPARAM_CELL_HEX27, 2, xi, 81));
  structured_grid lattice;
  if (structured_grid_init(&lattice, IGAPARAM_CELL_HEX8, 4, 4, 4) != 0) {
    CHECKF(0, "out of memory");
    return;
  }
  int64_t gmsh[8 * 27];
  for (size_t c = 0; c < 8; c++) {
    for (size_t n = 0; n < 27; n++) {
      size_t i = 2 * (c % 2) + (size_t)(xi[3 * n] + 1), j = 2 * (c / 2 % 2) + (size_t)(xi[3 * n + 1] + 1),
             k = 2 * (c / 4) + (size_t)(xi[3 * n + 2] + 1);
      gmsh[27 * c + n] = (int64_t)structured_grid_node(&lattice, i, j, k);
    }
  }
  igaparam_mesh *mesh = NULL, *wrong = NULL;
  EXPECT_OK(igaparam_mesh_new_ordered(IGAPARAM_CELL_HEX27, IGAPARAM_ORDER_GMSH, lattice.num_nodes, lattice.xyz, 8,
                                      gmsh, &mesh));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_MESH), NULL,
              igaparam_mesh_new(IGAPARAM_CELL_HEX27, lattice.num_nodes, lattice.xyz, 8, gmsh, &wrong));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_ARGUMENT), NULL,
              igaparam_mesh_new_ordered(IGAPARAM_CELL_HEX27, 5, lattice.num_nodes, lattice.xyz, 8, gmsh, &wrong));
  CHECKF(wrong == NULL, "a failed call wrote its output");
  igaparam_node_order order = -1;
  EXPECT_OK(igaparam_mesh_order(mesh, &order));
  CHECKF(order == IGAPARAM_ORDER_GMSH, "order %d", order);
  int64_t back[8 * 27], vtk[8 * 27];
  EXPECT_OK(igaparam_mesh_copy_connectivity(mesh, IGAPARAM_ORDER_GMSH, back, 8 * 27));
  CHECKF(memcmp(back, gmsh, sizeof back) == 0, "the connectivity did not come back as given");
  EXPECT_OK(igaparam_mesh_copy_connectivity(mesh, IGAPARAM_ORDER_VTK, vtk, 8 * 27));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_BUFFER_TOO_SMALL), mesh, igaparam_mesh_copy_connectivity(mesh, 0, vtk, 8 * 27 - 1));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_ARGUMENT), mesh, igaparam_mesh_copy_connectivity(mesh, 9, vtk, 8 * 27));
  igaparam_mesh *twin = NULL;
  EXPECT_OK(igaparam_mesh_new(IGAPARAM_CELL_HEX27, lattice.num_nodes, lattice.xyz, 8, vtk, &twin));
  size_t invalid = 1;
  EXPECT_OK(igaparam_mesh_invalid_cell_count(twin, &invalid));
  CHECKF(invalid == 0, "%zu invalid cells", invalid);

  /* .vtu round trips; bad paths and formats. */
  static const igaparam_vtu_format formats[] = {
      IGAPARAM_VTU_DEFAULT, IGAPARAM_VTU_ASCII, IGAPARAM_VTU_BINARY, IGAPARAM_VTU_APPENDED,
      IGAPARAM_VTU_APPENDED | IGAPARAM_VTU_ZLIB, IGAPARAM_VTU_APPENDED_BASE64 | IGAPARAM_VTU_ZLIB};
  const char *path = "test_capi_mesh.vtu";
  size_t len = 0;
  double *expected = copy_positions(mesh, &len);
  for (size_t f = 0; f < sizeof formats / sizeof formats[0]; f++) {
    EXPECT_OK(igaparam_mesh_write_vtu_format(mesh, path, formats[f]));
    igaparam_mesh *read = NULL;
    EXPECT_OK(igaparam_mesh_read_vtu(path, &read));
    size_t read_len = 0;
    double *got = copy_positions(read, &read_len);
    CHECKF(got && expected && read_len == len && memcmp(got, expected, len * sizeof *got) == 0,
           "format %d: positions differ", formats[f]);
    EXPECT_OK(igaparam_mesh_copy_connectivity(read, IGAPARAM_ORDER_VTK, back, 8 * 27));
    CHECKF(memcmp(back, vtk, sizeof back) == 0, "format %d: connectivity differs", formats[f]);
    free(got);
    igaparam_mesh_free(read);
  }
  free(expected);
  EXPECT_OK(igaparam_mesh_write_vtu(mesh, path));
  igaparam_mesh *out = NULL;
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_ARGUMENT), mesh,
              igaparam_mesh_write_vtu_format(mesh, path, IGAPARAM_VTU_ASCII | IGAPARAM_VTU_ZLIB));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_ARGUMENT), mesh, igaparam_mesh_write_vtu_format(mesh, path, 4));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_IO), mesh, igaparam_mesh_write_vtu(mesh, "no_such_dir/x.vtu"));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_NULL_ARGUMENT), mesh, igaparam_mesh_write_vtu(mesh, NULL));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_NULL_ARGUMENT), NULL, igaparam_mesh_write_vtu(NULL, path));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_IO), NULL, igaparam_mesh_read_vtu("no_such_file.vtu", &out));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_NULL_ARGUMENT), NULL, igaparam_mesh_read_vtu(path, NULL));
  EXPECT_FAIL(ST(IGAPARAM_STATUS_INVALID_ARGUMENT), NULL, igaparam_mesh_read_vtu("", &out));
  FILE *f = fopen(path, "w");
  if (f) {
    fputs("<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece", f);
    fclose(f);
  }
  EXPECT_FAIL(ST(IGAPARAM_STATUS_IO), NULL, igaparam_mesh_read_vtu(path, &out));
  CHECKF(out == NULL, "a failed read wrote its output");
  igaparam_cell_type type = 0;
  EXPECT_OK(igaparam_mesh_cell_type(mesh, &type));
  CHECKF(type == IGAPARAM_CELL_HEX27, "cell type %d", type);
  remove(path);
  igaparam_mesh_free(twin);
  igaparam_mesh_free(mesh);
  structured_grid_free(&lattice);
}

/* A free node moved by igaparam_mesh_move_nodes is where the relocation starts only with
 * IGAPARAM_PLACEMENT_CURRENT: the Laplacian placement computes every free coordinate from the
 * prescribed motion (here none, so the free node goes back to its reference position), as the
 * header says. */
static void test_moved_free_node(void) {
  structured_grid g;
  grid_init(&g, IGAPARAM_CELL_QUAD4, 2);
  igaparam_mesh *mesh = new_fixed_mesh(&g);
  int64_t centre = (int64_t)structured_grid_node(&g, 1, 1, 0);
  CHECK(!structured_grid_on_boundary(&g, (size_t)centre));
  const double *reference = g.xyz + 3 * centre;
  double moved[3] = {reference[0] + 0.1, reference[1] - 0.05, reference[2]};
  igaparam_relocate_options options = igaparam_relocate_options_default();
  options.optimize = 0;
  const igaparam_placement placements[2] = {IGAPARAM_PLACEMENT_LAPLACIAN,
                                            IGAPARAM_PLACEMENT_CURRENT};
  const double *expected[2] = {reference, moved};
  for (int k = 0; k < 2; k++) {
    EXPECT_OK(igaparam_mesh_move_nodes(mesh, 1, &centre, moved));
    options.placement = placements[k];
    EXPECT_OK(igaparam_mesh_relocate(mesh, &options, NULL));
    size_t len = 0;
    double *xyz = copy_positions(mesh, &len);
    const double *p = xyz + 3 * centre;
    CHECKF(fabs(p[0] - expected[k][0]) < 1e-12 && fabs(p[1] - expected[k][1]) < 1e-12,
          "placement %d: the moved free node is at (%g, %g), expected (%g, %g)", (int)placements[k],
          p[0], p[1], expected[k][0], expected[k][1]);
    free(xyz);
  }
  igaparam_mesh_free(mesh);
  structured_grid_free(&g);
}

int main(void) {
  printf("igaparam %s\n", igaparam_version());
  init_primers();

  test_version_and_defaults();
  test_last_error_message();
  test_mesh_new();
  test_reset_reference_errors();
  test_failed_calls_change_nothing();
  test_reference_and_quality();
  test_untangle(IGAPARAM_CELL_QUAD4, 6, IGAPARAM_TARGET_INITIAL);
  test_untangle(IGAPARAM_CELL_QUAD4, 6, IGAPARAM_TARGET_MASTER);
  test_untangle(IGAPARAM_CELL_HEX8, 3, IGAPARAM_TARGET_INITIAL);
  test_cancellation(IGAPARAM_STAGE_PLACEMENT);
  test_cancellation(IGAPARAM_STAGE_OPTIMIZATION);
  test_threads_agree(IGAPARAM_CELL_QUAD9, 12);
  test_threads_agree(IGAPARAM_CELL_HEX8, 4);
  test_orders_and_files();
  test_moved_free_node();

  igaparam_mesh_free(primer_mesh);
  printf("%d passed, %d failed\n", passed, failed);
  return failed == 0 ? 0 : 1;
}
