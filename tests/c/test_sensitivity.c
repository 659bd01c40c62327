/*
 * Tests of the shape-optimization loop API through the C ABI: warm-started relocation
 * (IGAPARAM_PLACEMENT_INCREMENTAL), the Newton stage (stationarity_tolerance, gradient_norm),
 * and the sensitivity products igaparam_mesh_adjoint / igaparam_mesh_tangent: their refusals
 * (NULLs, sizes, NaN, no stationary point, a move since), their duality, and their agreement with
 * central differences of full relocations. Prints "N passed, M failed"; exits non-zero if any
 * check failed.
 */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "igaparam.h"
#include "structured_grid.h"

#include "expect.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* A Q9 grid whose top side is pushed down by a bump of height `h`, the boundary prescribed. */
static igaparam_mesh *bumped_grid(structured_grid *g, double h) {
  igaparam_mesh *mesh = NULL;
  EXPECT(structured_grid_init(g, IGAPARAM_CELL_QUAD9, 6, 6, 1) == 0 ? IGAPARAM_STATUS_OK
                                                                     : IGAPARAM_STATUS_INTERNAL,
         IGAPARAM_STATUS_OK);
  EXPECT(igaparam_mesh_new(g->type, g->num_nodes, g->xyz, g->num_cells, g->connectivity, &mesh),
         IGAPARAM_STATUS_OK);
  uint8_t *mask = calloc(g->num_nodes, 1);
  double *moved = malloc(3 * g->num_nodes * sizeof *moved);
  memcpy(moved, g->xyz, 3 * g->num_nodes * sizeof *moved);
  for (size_t v = 0; v < g->num_nodes; v++) {
    if (structured_grid_on_boundary(g, v)) {
      mask[v] = 3;
      if (moved[3 * v + 1] == 1.0) {
        moved[3 * v + 1] -= h * sin(M_PI * moved[3 * v]);
      }
    }
  }
  EXPECT(igaparam_mesh_set_fixed(mesh, g->num_nodes, mask), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_mesh_move_nodes(mesh, g->num_nodes, NULL, moved), IGAPARAM_STATUS_OK);
  free(mask);
  free(moved);
  return mesh;
}

static igaparam_relocate_options tight_options(void) {
  igaparam_relocate_options o = igaparam_relocate_options_default();
  o.threads = 2;
  o.stationarity_tolerance = 1e-12;
  return o;
}

static double dot(const double *a, const double *b, size_t n) {
  double s = 0;
  for (size_t i = 0; i < n; i++) s += a[i] * b[i];
  return s;
}

/* Refusals: each leaves the outputs unwritten. */
static void test_refusals(void) {
  structured_grid g;
  igaparam_mesh *mesh = bumped_grid(&g, 0.2);
  size_t n = 3 * g.num_nodes;
  double *w = calloc(n, sizeof *w), *out = malloc(n * sizeof *out);
  for (size_t i = 0; i < n; i++) out[i] = 42.0;
  EXPECT(igaparam_mesh_adjoint(mesh, n, w, out), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(strstr(message(), "no relocation") != NULL, "message: %s", message());
  igaparam_relocate_options plain = igaparam_relocate_options_default();
  EXPECT(igaparam_mesh_relocate(mesh, &plain, NULL), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_mesh_tangent(mesh, n, w, out), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(strstr(message(), "stationarity_tolerance") != NULL, "message: %s", message());
  igaparam_relocate_options o = tight_options();
  igaparam_relocate_report report;
  EXPECT(igaparam_mesh_relocate(mesh, &o, &report), IGAPARAM_STATUS_OK);
  CHECK(report.gradient_norm <= 1e-12 && report.converged == 1, "gradient %g", report.gradient_norm);
  EXPECT(igaparam_mesh_adjoint(NULL, n, w, out), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_mesh_adjoint(mesh, n, NULL, out), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_mesh_tangent(mesh, n, w, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_mesh_tangent(mesh, n - 3, w, out), IGAPARAM_STATUS_INVALID_ARGUMENT);
  w[5] = NAN;
  EXPECT(igaparam_mesh_adjoint(mesh, n, w, out), IGAPARAM_STATUS_NOT_FINITE);
  w[5] = INFINITY;
  EXPECT(igaparam_mesh_tangent(mesh, n, w, out), IGAPARAM_STATUS_NOT_FINITE);
  w[5] = 0;
  o.stationarity_tolerance = -1;
  EXPECT(igaparam_mesh_relocate(mesh, &o, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  o = tight_options();
  o.method = 7;
  EXPECT(igaparam_mesh_relocate(mesh, &o, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  o = tight_options();
  o.placement = 9;
  EXPECT(igaparam_mesh_relocate(mesh, &o, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  int untouched = 1;
  for (size_t i = 0; i < n; i++) untouched &= out[i] == 42.0;
  CHECK(untouched, "a refused product wrote its output");
  /* A failed relocation keeps the sensitivities of the last one. */
  EXPECT(igaparam_mesh_tangent(mesh, n, w, out), IGAPARAM_STATUS_OK);
  /* A move invalidates them. */
  double *xyz = malloc(n * sizeof *xyz);
  EXPECT(igaparam_mesh_copy_positions(mesh, xyz, n), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_mesh_move_nodes(mesh, 1, NULL, xyz), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_mesh_adjoint(mesh, n, w, out), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(strstr(message(), "moved") != NULL, "message: %s", message());
  free(xyz);
  free(w);
  free(out);
  igaparam_mesh_free(mesh);
  structured_grid_free(&g);
}

/* The prescribed coordinates of `mesh` moved by t·v, relocated warm; positions into `x`. */
static void relocated_after(igaparam_mesh *base, const structured_grid *g, const double *v, double t,
                            double *x) {
  size_t n = 3 * g->num_nodes;
  igaparam_mesh *mesh = NULL;
  double *xyz = malloc(n * sizeof *xyz), *ref = malloc(n * sizeof *ref);
  uint8_t *mask = malloc(g->num_nodes);
  EXPECT(igaparam_mesh_copy_reference(base, ref, n), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_mesh_copy_positions(base, xyz, n), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_mesh_copy_fixed(base, mask, g->num_nodes), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_mesh_new(g->type, g->num_nodes, ref, g->num_cells, g->connectivity, &mesh),
         IGAPARAM_STATUS_OK);
  EXPECT(igaparam_mesh_set_fixed(mesh, g->num_nodes, mask), IGAPARAM_STATUS_OK);
  for (size_t i = 0; i < n; i++) xyz[i] += t * v[i];
  EXPECT(igaparam_mesh_move_nodes(mesh, g->num_nodes, NULL, xyz), IGAPARAM_STATUS_OK);
  igaparam_relocate_options o = tight_options();
  EXPECT(igaparam_mesh_relocate(mesh, &o, NULL), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_mesh_copy_positions(mesh, x, n), IGAPARAM_STATUS_OK);
  igaparam_mesh_free(mesh);
  free(xyz);
  free(ref);
  free(mask);
}

/* Duality to round-off, and central differences of full relocations. */
static void test_products(void) {
  structured_grid g;
  igaparam_mesh *mesh = bumped_grid(&g, 0.2);
  size_t n = 3 * g.num_nodes;
  igaparam_relocate_options o = tight_options();
  EXPECT(igaparam_mesh_relocate(mesh, &o, NULL), IGAPARAM_STATUS_OK);
  double *w = malloc(n * sizeof *w), *v = calloc(n, sizeof *v);
  double *a = malloc(n * sizeof *a), *t = malloc(n * sizeof *t);
  uint8_t *mask = malloc(g.num_nodes);
  EXPECT(igaparam_mesh_copy_fixed(mesh, mask, g.num_nodes), IGAPARAM_STATUS_OK);
  unsigned seed = 7;
  for (size_t i = 0; i < n; i++) {
    seed = seed * 1103515245u + 12345u;
    w[i] = (double)(seed >> 8) / (1u << 24) - 0.5;
    if (i % 3 < 2 && (mask[i / 3] & (1u << (i % 3)))) v[i] = sin(0.37 * (double)i);
  }
  EXPECT(igaparam_mesh_adjoint(mesh, n, w, a), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_mesh_tangent(mesh, n, v, t), IGAPARAM_STATUS_OK);
  double wt = dot(w, t, n), av = dot(a, v, n);
  CHECK(fabs(wt - av) <= 1e-10 * fabs(wt), "duality: %.17g vs %.17g", wt, av);
  /* In place: the input array may be the output array. */
  double *inplace = malloc(n * sizeof *inplace);
  memcpy(inplace, w, n * sizeof *inplace);
  EXPECT(igaparam_mesh_adjoint(mesh, n, inplace, inplace), IGAPARAM_STATUS_OK);
  CHECK(memcmp(inplace, a, n * sizeof *a) == 0, "in-place adjoint differs");
  const double h = 1e-5;
  double *plus = malloc(n * sizeof *plus), *minus = malloc(n * sizeof *minus);
  relocated_after(mesh, &g, v, h, plus);
  relocated_after(mesh, &g, v, -h, minus);
  double fd = (dot(w, plus, n) - dot(w, minus, n)) / (2 * h);
  CHECK(fabs(fd - av) <= 1e-6 * fabs(av), "adjoint %.12g vs central differences %.12g", av, fd);
  free(w);
  free(v);
  free(a);
  free(t);
  free(mask);
  free(inplace);
  free(plus);
  free(minus);
  igaparam_mesh_free(mesh);
  structured_grid_free(&g);
}

/* A loop that deepens the bump in ten steps, relocating warm: every step valid, each step's
 * result close to a cold relocation of the same boundary. */
static void test_warm_loop(void) {
  structured_grid g;
  igaparam_mesh *mesh = bumped_grid(&g, 0.0);
  size_t n = 3 * g.num_nodes;
  double *xyz = malloc(n * sizeof *xyz), *cold_x = malloc(n * sizeof *cold_x);
  igaparam_relocate_options o = tight_options();
  o.placement = IGAPARAM_PLACEMENT_INCREMENTAL;
  for (int step = 1; step <= 10; step++) {
    structured_grid cold_grid;
    igaparam_mesh *cold = bumped_grid(&cold_grid, 0.04 * step);
    /* The warm mesh's boundary: that of the cold one. */
    EXPECT(igaparam_mesh_copy_positions(cold, xyz, n), IGAPARAM_STATUS_OK);
    uint8_t *mask = malloc(g.num_nodes);
    EXPECT(igaparam_mesh_copy_fixed(cold, mask, g.num_nodes), IGAPARAM_STATUS_OK);
    for (size_t v = 0; v < g.num_nodes; v++) {
      const int64_t index = (int64_t)v;
      if (mask[v]) EXPECT(igaparam_mesh_move_nodes(mesh, 1, &index, xyz + 3 * v), IGAPARAM_STATUS_OK);
    }
    free(mask);
    igaparam_relocate_report warm, reference;
    EXPECT(igaparam_mesh_relocate(mesh, &o, &warm), IGAPARAM_STATUS_OK);
    igaparam_relocate_options cold_options = tight_options();
    EXPECT(igaparam_mesh_relocate(cold, &cold_options, &reference), IGAPARAM_STATUS_OK);
    CHECK(warm.invalid_after == 0 && warm.gradient_norm <= 1e-12, "step %d: %zu invalid", step,
          warm.invalid_after);
    EXPECT(igaparam_mesh_copy_positions(mesh, xyz, n), IGAPARAM_STATUS_OK);
    EXPECT(igaparam_mesh_copy_positions(cold, cold_x, n), IGAPARAM_STATUS_OK);
    double gap = 0;
    for (size_t i = 0; i < n; i++) gap = fmax(gap, fabs(xyz[i] - cold_x[i]));
    CHECK(gap < 1e-8, "step %d: warm and cold optima differ by %g", step, gap);
    igaparam_mesh_free(cold);
    structured_grid_free(&cold_grid);
  }
  free(xyz);
  free(cold_x);
  igaparam_mesh_free(mesh);
  structured_grid_free(&g);
}

int main(void) {
  test_refusals();
  test_products();
  test_warm_loop();
  printf("%d passed, %d failed\n", passed, failed);
  return failed == 0 ? 0 : 1;
}
