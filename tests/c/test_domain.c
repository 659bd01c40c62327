/*
 * Tests of the domain part of the C API (include/igaparam.h), planar domains and solids, through its
 * C ABI.
 * Usage: test_domain DATA_DIR OUT_DIR, where DATA_DIR holds male_bdry.xml and gran_canaria.txt
 * and OUT_DIR receives the .vtu files. Builds the bundled domains and a unit square from four
 * polylines; calls every entry point with NULL, wrong sizes, non-finite values, an unbuilt domain
 * and invalid boundaries, checking the status, the message and that no output is written;
 * cancels a build through the progress callback; refuses a bad seam relief cap; reads solids
 * with per-axis scale factors (the Jacksboro block in km, a B-rep doubled). Prints
 * "N passed, M failed"; exits non-zero if any check failed.
 */

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dirs.h"
#include "expect.h"
#include "vtu_check.h"

/* A sentinel handle value: a failed constructor must leave it. */
#define UNTOUCHED ((igaparam_domain *)(uintptr_t)0x1234)

/* Four polylines of a unit square, the first being the side x = 0, each of `n` points evenly
 * spaced. `xy` has room for 4 × n × 2 doubles. */
static void unit_square(size_t n, double *xy, size_t counts[4], const double *points[4]) {
  static const double from[4][2] = {{0, 1}, {0, 0}, {1, 0}, {1, 1}};
  static const double to[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int s = 0; s < 4; s++) {
    for (size_t i = 0; i < n; i++) {
      double t = (double)i / (double)(n - 1);
      xy[(s * n + i) * 2 + 0] = from[s][0] + t * (to[s][0] - from[s][0]);
      xy[(s * n + i) * 2 + 1] = from[s][1] + t * (to[s][1] - from[s][1]);
    }
    counts[s] = n;
    points[s] = xy + s * n * 2;
  }
}

/* ---------------------------------------------------------------------------------------------
 * Construction errors
 * ------------------------------------------------------------------------------------------- */

static void test_constructor_errors(void) {
  igaparam_domain *d = UNTOUCHED;
  EXPECT(igaparam_domain_new_from_file(NULL, &d), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_domain_new_from_file(joined(data_dir, "male_bdry.xml"), NULL),
         IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_domain_new_from_file(joined(data_dir, "no_such_file.xml"), &d),
         IGAPARAM_STATUS_IO);
  EXPECT(igaparam_domain_new_from_file(joined(data_dir, "no_such_file.txt"), &d),
         IGAPARAM_STATUS_IO);
  EXPECT(igaparam_domain_new_from_file(joined(data_dir, "README.md"), &d),
         IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_domain_new_from_file("", &d), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(d == UNTOUCHED, "a failed constructor wrote its handle");

  double xy[4 * 3 * 2];
  size_t counts[4];
  const double *points[4];
  unit_square(3, xy, counts, points);
  EXPECT(igaparam_domain_new_from_polylines(NULL, points, &d), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_domain_new_from_polylines(counts, NULL, &d), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_domain_new_from_polylines(counts, points, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  const double *with_null[4] = {points[0], NULL, points[2], points[3]};
  EXPECT(igaparam_domain_new_from_polylines(counts, with_null, &d), IGAPARAM_STATUS_NULL_ARGUMENT);
  size_t too_few[4] = {3, 1, 3, 3};
  EXPECT(igaparam_domain_new_from_polylines(too_few, points, &d),
         IGAPARAM_STATUS_INVALID_ARGUMENT);

  /* NaN and infinity. */
  double saved = xy[3];
  xy[3] = NAN;
  EXPECT(igaparam_domain_new_from_polylines(counts, points, &d), IGAPARAM_STATUS_NOT_FINITE);
  xy[3] = INFINITY;
  EXPECT(igaparam_domain_new_from_polylines(counts, points, &d), IGAPARAM_STATUS_NOT_FINITE);
  xy[3] = saved;

  /* An open loop: the top side stops short of the corner (0, 1). */
  double *top_end = xy + (3 * 3 + 2) * 2;
  top_end[0] = 0.5;
  EXPECT(igaparam_domain_new_from_polylines(counts, points, &d),
         IGAPARAM_STATUS_INVALID_ARGUMENT);
  unit_square(3, xy, counts, points);

  /* A reflex corner: an L-shape cut into four polylines with the reflex vertex as a corner. */
  const double l0[] = {0, 0, 2, 0};          /* bottom */
  const double l1[] = {2, 0, 2, 1, 1, 1};    /* right, then inward to the reflex vertex (1, 1) */
  const double l2[] = {1, 1, 1, 2, 0, 2};    /* up, then left */
  const double l3[] = {0, 2, 0, 0};          /* left */
  const double *lp[4] = {l3, l0, l1, l2};
  size_t lc[4] = {2, 2, 3, 3};
  EXPECT(igaparam_domain_new_from_polylines(lc, lp, &d), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(d == UNTOUCHED, "a failed constructor wrote its handle");

  /* A loop that crosses itself: the top side dips below the bottom one and comes back. */
  const double c0[] = {0, 0, 1, 0};                /* bottom */
  const double c1[] = {1, 0, 1, 1};                /* right */
  const double c2[] = {1, 1, 0.5, -0.5, 0, 1};     /* top, through (0.5, -0.5) */
  const double c3[] = {0, 1, 0, 0};                /* left */
  const double *cp[4] = {c3, c0, c1, c2};
  size_t cc[4] = {2, 2, 2, 3};
  EXPECT(igaparam_domain_new_from_polylines(cc, cp, &d), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(strstr(message(), "crosses itself") != NULL, "crossing loop: %s", message());
  CHECK(d == UNTOUCHED, "a failed constructor wrote its handle");

  /* A zero-area loop: every point the same. */
  double flat[4 * 2 * 2] = {0};
  for (int i = 0; i < 16; i += 2) flat[i] = i / 4;
  const double *fp[4] = {flat, flat + 4, flat + 8, flat + 12};
  size_t fc[4] = {2, 2, 2, 2};
  igaparam_status s = igaparam_domain_new_from_polylines(fc, fp, &d);
  CHECK(s != IGAPARAM_STATUS_OK && message()[0] != '\0', "degenerate loop accepted");
  CHECK(d == UNTOUCHED, "a failed constructor wrote its handle");

  igaparam_domain_free(NULL);
}

/* ---------------------------------------------------------------------------------------------
 * Unit square: physical == parametric; queries before the build; option errors
 * ------------------------------------------------------------------------------------------- */

static void test_unit_square(void) {
  double xy[4 * 5 * 2];
  size_t counts[4];
  const double *points[4];
  unit_square(5, xy, counts, points);
  igaparam_domain *d = NULL;
  EXPECT(igaparam_domain_new_from_polylines(counts, points, &d), IGAPARAM_STATUS_OK);
  if (!d) return;

  /* Not built yet. */
  size_t n = 77;
  int is_built = 5;
  EXPECT(igaparam_domain_is_built(d, &is_built), IGAPARAM_STATUS_OK);
  CHECK(is_built == 0, "is_built = %d before the build", is_built);
  EXPECT(igaparam_domain_vertex_count(d, &n), IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_domain_cell_count(d, &n), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(n == 77, "a failed count wrote its output");
  double buf[8];
  uint8_t levels[2];
  EXPECT(igaparam_domain_copy_vertices(d, buf, buf, 8), IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_domain_copy_cell_quality(d, buf, 8), IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_domain_copy_cells(d, levels, buf, 2), IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_domain_write_vtu(d, joined(out_dir, "unbuilt.vtu")),
         IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_domain_vertex_count(NULL, &n), IGAPARAM_STATUS_NULL_ARGUMENT);
  /* A NULL argument is NULL_ARGUMENT also on an unbuilt domain. */
  EXPECT(igaparam_domain_write_vtu(d, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_domain_vertex_count(d, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_domain_cell_count(d, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_domain_build(NULL, NULL, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);

  /* Bad options leave the domain unbuilt and the report unwritten. */
  igaparam_domain_report report;
  memset(&report, 0xAB, sizeof report);
  igaparam_domain_report untouched = report;
  igaparam_domain_options o = igaparam_domain_options_default();
  CHECK(o.tolerance > 0 && o.min_level <= o.max_level && o.progress == NULL,
        "default options are not sensible");
  o.tolerance = NAN;
  EXPECT(igaparam_domain_build(d, &o, &report), IGAPARAM_STATUS_NOT_FINITE);
  o = igaparam_domain_options_default();
  o.tolerance = -1;
  EXPECT(igaparam_domain_build(d, &o, &report), IGAPARAM_STATUS_INVALID_ARGUMENT);
  o = igaparam_domain_options_default();
  o.max_level = 17;
  EXPECT(igaparam_domain_build(d, &o, &report), IGAPARAM_STATUS_INVALID_ARGUMENT);
  o = igaparam_domain_options_default();
  o.min_level = 5;
  o.max_level = 4;
  EXPECT(igaparam_domain_build(d, &o, &report), IGAPARAM_STATUS_INVALID_ARGUMENT);
  o = igaparam_domain_options_default();
  o.threads = 5000;
  EXPECT(igaparam_domain_build(d, &o, &report), IGAPARAM_STATUS_INVALID_ARGUMENT);
  o = igaparam_domain_options_default();
  o.boundary_offset = NAN;
  EXPECT(igaparam_domain_build(d, &o, &report), IGAPARAM_STATUS_NOT_FINITE);
  o.boundary_offset = -1e-3;
  EXPECT(igaparam_domain_build(d, &o, &report), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(memcmp(&report, &untouched, sizeof report) == 0, "a failed build wrote the report");
  EXPECT(igaparam_domain_is_built(d, &is_built), IGAPARAM_STATUS_OK);
  CHECK(is_built == 0, "a failed build left the domain built");

  /* Build: a uniform grid of the square, mapped by the identity. */
  o = igaparam_domain_options_default();
  o.min_level = 3;
  o.max_level = 3;
  EXPECT(igaparam_domain_build(d, &o, &report), IGAPARAM_STATUS_OK);
  CHECK(report.invalid_cells == 0, "square: %zu invalid cells", report.invalid_cells);
  CHECK(report.cells == 64 && report.vertices == 81, "square: %zu cells, %zu vertices",
        report.cells, report.vertices);
  CHECK(report.max_level == 3, "square: max level %u", report.max_level);
  CHECK(fabs(report.min_quality - 1) < 1e-9, "square: min quality %g", report.min_quality);
  size_t nv = 0, nc = 0;
  EXPECT(igaparam_domain_vertex_count(d, &nv), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_cell_count(d, &nc), IGAPARAM_STATUS_OK);
  CHECK(nv == report.vertices && nc == report.cells, "square: counts differ from the report");
  double *uv = malloc(2 * nv * sizeof *uv), *x = malloc(2 * nv * sizeof *x);
  EXPECT(igaparam_domain_copy_vertices(d, uv, x, 2 * nv), IGAPARAM_STATUS_OK);
  double worst = 0;
  for (size_t i = 0; i < 2 * nv; i++) worst = fmax(worst, fabs(uv[i] - x[i]));
  CHECK(worst < 1e-9, "square: physical differs from parametric by %g", worst);
  free(uv);
  free(x);
  igaparam_domain_free(d);
}

/* ---------------------------------------------------------------------------------------------
 * Bundled domains
 * ------------------------------------------------------------------------------------------- */

static int cancel_at;  /* the progress callback cancels at its cancel_at-th call */
static int calls;

static int progress(void *user, igaparam_stage stage, size_t done, size_t total) {
  (void)done;
  (void)total;
  CHECK(user == &calls, "progress: wrong user pointer");
  CHECK(stage == IGAPARAM_STAGE_OPTIMIZATION, "progress: stage %d", (int)stage);
  calls++;
  return calls >= cancel_at;
}

static void test_file(const char *name, const char *vtu) {
  igaparam_domain *d = NULL;
  EXPECT(igaparam_domain_new_from_file(joined(data_dir, name), &d), IGAPARAM_STATUS_OK);
  if (!d) return;

  igaparam_domain_report report;
  EXPECT(igaparam_domain_build(d, NULL, &report), IGAPARAM_STATUS_OK);
  CHECK(report.invalid_cells == 0, "%s: %zu invalid cells", name, report.invalid_cells);
  CHECK(report.cells > 0 && report.vertices > report.cells / 2, "%s: %zu cells, %zu vertices",
        name, report.cells, report.vertices);
  CHECK(report.min_quality > 0 && report.min_quality <= report.mean_quality &&
            report.mean_quality <= 1,
        "%s: quality min %g mean %g", name, report.min_quality, report.mean_quality);
  printf("%s: %zu cells, %zu vertices, max level %u, boundary error %.2e, quality min %.3f mean "
         "%.3f, %u sweeps, %.2f s\n",
         name, report.cells, report.vertices, report.max_level, report.boundary_error,
         report.min_quality, report.mean_quality, report.sweeps, report.seconds);

  size_t nv = 0, nc = 0;
  EXPECT(igaparam_domain_vertex_count(d, &nv), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_cell_count(d, &nc), IGAPARAM_STATUS_OK);
  CHECK(nv == report.vertices && nc == report.cells, "%s: counts differ from the report", name);

  /* Vertices. */
  double *uv = malloc(2 * nv * sizeof *uv), *x = malloc(2 * nv * sizeof *x);
  for (size_t i = 0; i < 2 * nv; i++) uv[i] = x[i] = -7;
  EXPECT(igaparam_domain_copy_vertices(d, uv, x, 2 * nv - 1), IGAPARAM_STATUS_BUFFER_TOO_SMALL);
  EXPECT(igaparam_domain_copy_vertices(d, NULL, x, 2 * nv - 1), IGAPARAM_STATUS_BUFFER_TOO_SMALL);
  CHECK(uv[0] == -7 && x[0] == -7, "%s: a failed copy wrote its output", name);
  EXPECT(igaparam_domain_copy_vertices(d, NULL, NULL, 0), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_copy_vertices(d, uv, NULL, 2 * nv), IGAPARAM_STATUS_OK);
  CHECK(x[0] == -7, "%s: a NULL-skipped output was written", name);
  EXPECT(igaparam_domain_copy_vertices(d, NULL, x, 2 * nv), IGAPARAM_STATUS_OK);
  int in_square = 1, finite = 1;
  for (size_t i = 0; i < 2 * nv; i++) {
    in_square &= uv[i] >= 0 && uv[i] <= 1;
    finite &= isfinite(x[i]) != 0;
  }
  CHECK(in_square, "%s: a parametric vertex is outside [0,1]^2", name);
  CHECK(finite, "%s: a physical vertex is not finite", name);

  /* Cells. */
  double *q = malloc(nc * sizeof *q), *bounds = malloc(4 * nc * sizeof *bounds);
  uint8_t *levels = malloc(nc);
  EXPECT(igaparam_domain_copy_cell_quality(d, q, nc - 1), IGAPARAM_STATUS_BUFFER_TOO_SMALL);
  EXPECT(igaparam_domain_copy_cell_quality(d, NULL, nc), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_domain_copy_cell_quality(d, q, nc), IGAPARAM_STATUS_OK);
  double qmin = 2;
  for (size_t c = 0; c < nc; c++) qmin = fmin(qmin, q[c]);
  CHECK(fabs(qmin - report.min_quality) < 1e-12, "%s: min quality %g, report %g", name, qmin,
        report.min_quality);
  EXPECT(igaparam_domain_copy_cells(d, levels, bounds, nc - 1), IGAPARAM_STATUS_BUFFER_TOO_SMALL);
  /* An overstated length is harmless (only the cells are written), and used to fail half-way. */
  EXPECT(igaparam_domain_copy_cells(d, levels, bounds, SIZE_MAX), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_copy_cells(d, levels, bounds, nc), IGAPARAM_STATUS_OK);
  double area = 0;
  int levels_ok = 1, bounds_ok = 1;
  for (size_t c = 0; c < nc; c++) {
    const double *b = bounds + 4 * c;
    double h = b[2] - b[0];
    levels_ok &= levels[c] <= report.max_level;
    bounds_ok &= b[0] >= 0 && b[1] >= 0 && b[2] <= 1 && b[3] <= 1 && h > 0 &&
                 fabs((b[3] - b[1]) - h) < 1e-15 && fabs(h - ldexp(1.0, -levels[c])) < 1e-15;
    area += h * h;
  }
  CHECK(levels_ok, "%s: a level is above the report's max level", name);
  CHECK(bounds_ok, "%s: a cell's bounds do not match its level", name);
  CHECK(fabs(area - 1) < 1e-12, "%s: the cells cover an area of %g", name, area);

  /* VTU output. */
  EXPECT(igaparam_domain_write_vtu(d, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_domain_write_vtu(d, joined(out_dir, "no_such_dir/x.vtu")), IGAPARAM_STATUS_IO);
  const char *path = joined(out_dir, vtu);
  remove(path);
  EXPECT(igaparam_domain_write_vtu(d, path), IGAPARAM_STATUS_OK);
  /* Read back: the counts, and the arrays the documentation names. */
  static const char *const arrays[] = {"parametric", "quality", "level"};
  check_vtu_file(path, nv, nc, arrays, 3);

  /* Cancellation leaves the earlier build: same counts, same vertices. */
  igaparam_domain_options o = igaparam_domain_options_default();
  o.progress = progress;
  o.progress_user = &calls;
  o.max_level = 4;
  calls = 0;
  cancel_at = 1;
  igaparam_domain_report r2;
  memset(&r2, 0xAB, sizeof r2);
  unsigned char untouched[sizeof r2];
  memcpy(untouched, &r2, sizeof r2);
  EXPECT(igaparam_domain_build(d, &o, &r2), IGAPARAM_STATUS_CANCELLED);
  CHECK(calls == 1, "%s: progress called %d times before cancelling", name, calls);
  CHECK(memcmp(&r2, untouched, sizeof r2) == 0, "%s: a cancelled build wrote the report", name);
  size_t nv2 = 0, nc2 = 0;
  EXPECT(igaparam_domain_vertex_count(d, &nv2), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_cell_count(d, &nc2), IGAPARAM_STATUS_OK);
  CHECK(nv2 == nv && nc2 == nc, "%s: a cancelled build changed the counts", name);
  double *x2 = malloc(2 * nv * sizeof *x2);
  EXPECT(igaparam_domain_copy_vertices(d, NULL, x2, 2 * nv), IGAPARAM_STATUS_OK);
  CHECK(memcmp(x, x2, 2 * nv * sizeof *x) == 0, "%s: a cancelled build moved vertices", name);

  /* Without cancelling, the callback sees the sweeps and the build replaces the earlier one. */
  calls = 0;
  cancel_at = 1 << 30;
  EXPECT(igaparam_domain_build(d, &o, &r2), IGAPARAM_STATUS_OK);
  CHECK(calls > 0, "%s: progress never called", name);
  CHECK(r2.max_level <= 4 && r2.cells < report.cells, "%s: max_level 4 gave %u, %zu cells", name,
        r2.max_level, r2.cells);
  EXPECT(igaparam_domain_cell_count(d, &nc2), IGAPARAM_STATUS_OK);
  CHECK(nc2 == r2.cells, "%s: the rebuild did not replace the mesh", name);

  free(x2);
  free(q);
  free(bounds);
  free(levels);
  free(uv);
  free(x);
  igaparam_domain_free(d);
}

/* The seam relief cap `boundary_offset`: refused when negative or NaN, with a message naming it
 * and the handle left as it was (counts and vertices); 0 reports no offset. */
static void test_boundary_offset(const char *name) {
  igaparam_domain *d = NULL;
  EXPECT(igaparam_domain_new_from_file(joined(data_dir, name), &d), IGAPARAM_STATUS_OK);
  if (!d) return;
  igaparam_domain_options o = igaparam_domain_options_default();
  CHECK(isfinite(o.boundary_offset) && o.boundary_offset > 0 && o.repair_rounds > 0,
        "default boundary_offset %g, repair_rounds %u", o.boundary_offset, o.repair_rounds);
  o.max_level = 6;
  o.boundary_offset = 0;
  igaparam_domain_report report;
  memset(&report, 0xAB, sizeof report);
  EXPECT(igaparam_domain_build(d, &o, &report), IGAPARAM_STATUS_OK);
  CHECK(report.boundary_offset == 0, "%s: offset 0 gave report.boundary_offset = %g", name,
        report.boundary_offset);
  size_t nv = 0, nc = 0;
  EXPECT(igaparam_domain_vertex_count(d, &nv), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_cell_count(d, &nc), IGAPARAM_STATUS_OK);
  double *x = malloc(2 * nv * sizeof *x), *x2 = malloc(2 * nv * sizeof *x2);
  EXPECT(igaparam_domain_copy_vertices(d, NULL, x, 2 * nv), IGAPARAM_STATUS_OK);

  const double bad[3] = {-1e-3, NAN, INFINITY};
  const igaparam_status want[3] = {IGAPARAM_STATUS_INVALID_ARGUMENT, IGAPARAM_STATUS_NOT_FINITE,
                                   IGAPARAM_STATUS_NOT_FINITE};
  for (int i = 0; i < 3; i++) {
    igaparam_domain_options b = o;
    b.max_level = 4; /* a different mesh, were the call to build one */
    b.boundary_offset = bad[i];
    igaparam_domain_report r2;
    memset(&r2, 0xAB, sizeof r2);
    unsigned char untouched[sizeof r2];
    memcpy(untouched, &r2, sizeof r2);
    EXPECT(igaparam_domain_build(d, &b, &r2), want[i]);
    CHECK(strstr(message(), "boundary_offset") != NULL, "%s: offset %g: message '%s' does not name it",
          name, bad[i], message());
    CHECK(memcmp(&r2, untouched, sizeof r2) == 0, "%s: a refused offset %g wrote the report", name,
          bad[i]);
    size_t nv2 = 0, nc2 = 0;
    EXPECT(igaparam_domain_vertex_count(d, &nv2), IGAPARAM_STATUS_OK);
    EXPECT(igaparam_domain_cell_count(d, &nc2), IGAPARAM_STATUS_OK);
    CHECK(nv2 == nv && nc2 == nc, "%s: a refused offset %g changed the counts", name, bad[i]);
    if (nv2 == nv) {
      EXPECT(igaparam_domain_copy_vertices(d, NULL, x2, 2 * nv), IGAPARAM_STATUS_OK);
      CHECK(memcmp(x, x2, 2 * nv * sizeof *x) == 0, "%s: a refused offset %g moved vertices", name,
            bad[i]);
    }
  }

  /* With the default cap, the offset reported stays under it. */
  o.boundary_offset = igaparam_domain_options_default().boundary_offset;
  EXPECT(igaparam_domain_build(d, &o, &report), IGAPARAM_STATUS_OK);
  CHECK(report.boundary_offset >= 0 && report.boundary_offset <= o.boundary_offset,
        "%s: boundary_offset %g above the cap %g", name, report.boundary_offset, o.boundary_offset);
  printf("%s: boundary offset %.3e with the cap %.1e\n", name, report.boundary_offset,
         o.boundary_offset);
  free(x2);
  free(x);
  igaparam_domain_free(d);
}

/* The unit cube's faces xmin ... zmax, each a 3 x 3 grid of vertices in 8 triangles. */
static void cube_faces(double xyz[6][27], uint32_t tri[6][24]) {
  for (int f = 0; f < 6; f++) {
    int k = f / 2, a = k == 0 ? 1 : 0, b = k == 2 ? 1 : 2;
    for (int j = 0; j < 3; j++)
      for (int i = 0; i < 3; i++) {
        double *p = xyz[f] + 3 * (i + 3 * j);
        p[k] = f % 2;
        p[a] = i / 2.0;
        p[b] = j / 2.0;
      }
    int t = 0;
    for (int j = 0; j < 2; j++)
      for (int i = 0; i < 2; i++) {
        uint32_t v = (uint32_t)(i + 3 * j);
        uint32_t quad[6] = {v, v + 1, v + 4, v, v + 4, v + 3};
        for (int m = 0; m < 6; m++) tri[f][t++] = quad[m];
      }
  }
}

static void test_solid(void) {
  static double xyz[6][27];
  static uint32_t tri[6][24];
  cube_faces(xyz, tri);
  size_t nv[6], nt[6];
  const double *pts[6];
  const uint32_t *tris[6];
  for (int f = 0; f < 6; f++) {
    nv[f] = 9;
    nt[f] = 8;
    pts[f] = xyz[f];
    tris[f] = tri[f];
  }
  igaparam_domain *d = UNTOUCHED;
  /* Errors: NaN, an index out of range, faces that do not share their edges, bad paths. */
  xyz[2][13] = NAN;
  EXPECT(igaparam_domain_new_solid_from_triangulations(nv, pts, nt, tris, &d),
         IGAPARAM_STATUS_NOT_FINITE);
  CHECK(strstr(message(), "ymin") != NULL, "NaN: message '%s' does not name the face", message());
  xyz[2][13] = 0;
  tri[4][5] = 9;
  EXPECT(igaparam_domain_new_solid_from_triangulations(nv, pts, nt, tris, &d),
         IGAPARAM_STATUS_INVALID_MESH);
  CHECK(strstr(message(), "zmin") != NULL, "index out of range: message '%s'", message());
  tri[4][5] = 3;
  for (int v = 0; v < 9; v++) xyz[5][3 * v + 2] = 1.25; /* zmax lifted off the sides */
  EXPECT(igaparam_domain_new_solid_from_triangulations(nv, pts, nt, tris, &d),
         IGAPARAM_STATUS_INVALID_MESH);
  for (int v = 0; v < 9; v++) xyz[5][3 * v + 2] = 1;
  EXPECT(igaparam_domain_new_solid_from_triangulations(nv, NULL, nt, tris, &d),
         IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_domain_new_solid_from_file(joined(data_dir, "no_such_file.xml"), &d),
         IGAPARAM_STATUS_IO);
  EXPECT(igaparam_domain_new_solid_from_file(joined(data_dir, "README.md"), &d),
         IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(d == UNTOUCHED, "a failed constructor wrote its handle");

  /* The unit cube gives the identity. */
  d = NULL;
  EXPECT(igaparam_domain_new_solid_from_triangulations(nv, pts, nt, tris, &d), IGAPARAM_STATUS_OK);
  if (!d) return;
  size_t dim = 0;
  EXPECT(igaparam_domain_dimension(d, &dim), IGAPARAM_STATUS_OK);
  CHECK(dim == 3, "cube: dimension %zu", dim);
  igaparam_domain_options o = igaparam_domain_options_default();
  o.min_level = 2;
  o.max_level = 2;
  igaparam_domain_report r;
  EXPECT(igaparam_domain_build(d, &o, &r), IGAPARAM_STATUS_OK);
  CHECK(r.cells == 64 && r.vertices == 125 && r.invalid_cells == 0, "cube: %zu cells, %zu vertices, %zu invalid",
        r.cells, r.vertices, r.invalid_cells);
  size_t n = r.vertices, nc = r.cells;
  double *uvw = malloc(3 * n * sizeof *uvw), *x = malloc(3 * n * sizeof *x);
  EXPECT(igaparam_domain_copy_vertices(d, uvw, x, 3 * n - 1), IGAPARAM_STATUS_BUFFER_TOO_SMALL);
  EXPECT(igaparam_domain_copy_vertices(d, uvw, x, 3 * n), IGAPARAM_STATUS_OK);
  double worst = 0;
  for (size_t i = 0; i < 3 * n; i++) worst = fmax(worst, fabs(uvw[i] - x[i]));
  CHECK(worst < 1e-9, "cube: physical differs from parametric by %g", worst);
  size_t *corners = malloc(8 * nc * sizeof *corners);
  double *bounds = malloc(6 * nc * sizeof *bounds);
  EXPECT(igaparam_domain_copy_cell_corners(d, corners, 8 * nc - 1), IGAPARAM_STATUS_BUFFER_TOO_SMALL);
  EXPECT(igaparam_domain_copy_cell_corners(d, corners, 8 * nc), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_copy_cells(d, NULL, bounds, nc), IGAPARAM_STATUS_OK);
  int corners_ok = 1;
  for (size_t c = 0; c < nc; c++) {
    const double *b = bounds + 6 * c;
    const size_t *k = corners + 8 * c;
    /* VTK order: corner 0 at the lower bound, corner 6 at the upper one. */
    corners_ok &= k[0] < n && k[6] < n;
    if (!corners_ok) break;
    for (int m = 0; m < 3; m++)
      corners_ok &= uvw[3 * k[0] + m] == b[m] && uvw[3 * k[6] + m] == b[3 + m];
  }
  CHECK(corners_ok, "cube: cell corners do not match the cell bounds");
  EXPECT(igaparam_domain_write_vtu(d, joined(out_dir, "domain_cube.vtu")), IGAPARAM_STATUS_OK);
  free(bounds);
  free(corners);
  free(uvw);
  free(x);
  igaparam_domain_free(d);

  /* The files of a solid: a G+Smo B-rep and a folder of OBJ faces. */
  const char *files[2] = {"duck3d_BRep.xml", "duck_faces"};
  for (int i = 0; i < 2; i++) {
    d = NULL;
    EXPECT(igaparam_domain_new_solid_from_file(joined(data_dir, files[i]), &d), IGAPARAM_STATUS_OK);
    dim = 0;
    EXPECT(igaparam_domain_dimension(d, &dim), IGAPARAM_STATUS_OK);
    CHECK(dim == 3, "%s: dimension %zu", files[i], dim);
    igaparam_domain_free(d);
  }
}

/* Builds `a` and `b` with options `o` and checks that `b`'s T-mesh is `a`'s with every physical
 * coordinate multiplied by `factor`, exactly. */
static void compare_scaled(igaparam_domain *a, igaparam_domain *b, double factor,
                           const igaparam_domain_options *o) {
  igaparam_domain *d[2] = {a, b};
  igaparam_domain_report r[2];
  double *uvw[2] = {NULL, NULL}, *x[2] = {NULL, NULL};
  for (int i = 0; i < 2; i++) {
    EXPECT(igaparam_domain_build(d[i], o, &r[i]), IGAPARAM_STATUS_OK);
    size_t n = r[i].vertices;
    uvw[i] = malloc(3 * n * sizeof *uvw[i]);
    x[i] = malloc(3 * n * sizeof *x[i]);
    EXPECT(igaparam_domain_copy_vertices(d[i], uvw[i], x[i], 3 * n), IGAPARAM_STATUS_OK);
  }
  printf("scaled by %g at tolerance %g, levels %u to %u: %zu cells, %zu vertices, %zu invalid, "
         "%u sweeps, %.2f s\n",
         factor, o->tolerance, o->min_level, o->max_level, r[0].cells, r[0].vertices,
         r[0].invalid_cells, r[0].sweeps, r[0].seconds);
  CHECK(r[0].invalid_cells == 0, "%zu invalid cells", r[0].invalid_cells);
  CHECK(r[1].cells == r[0].cells && r[1].vertices == r[0].vertices && r[1].sweeps == r[0].sweeps,
        "scaled by %g: %zu cells, %zu vertices, %u sweeps; unscaled %zu, %zu, %u", factor,
        r[1].cells, r[1].vertices, r[1].sweeps, r[0].cells, r[0].vertices, r[0].sweeps);
  if (r[1].vertices == r[0].vertices) {
    size_t same_uvw = 0, same_x = 0, n = 3 * r[0].vertices;
    double worst = 0;
    for (size_t k = 0; k < n; k++) {
      same_uvw += uvw[1][k] == uvw[0][k];
      same_x += x[1][k] == factor * x[0][k];
      worst = fmax(worst, fabs(x[1][k] - factor * x[0][k]));
    }
    CHECK(same_uvw == n && same_x == n,
          "scaled by %g: %zu of %zu parametric and %zu physical coordinates exact "
          "(largest difference %g)",
          factor, same_uvw, n, same_x, worst);
  }
  CHECK(r[1].min_quality == r[0].min_quality && r[1].mean_quality == r[0].mean_quality &&
            r[1].boundary_error == r[0].boundary_error,
        "scaled by %g: quality %g vs %g, boundary error %g vs %g", factor, r[1].min_quality,
        r[0].min_quality, r[1].boundary_error, r[0].boundary_error);
  for (int i = 0; i < 2; i++) {
    free(uvw[i]);
    free(x[i]);
  }
}

/* A solid read with per-axis scale factors (igaparam_domain_new_solid_from_file_scaled). */
static void test_solid_scaled(void) {
  char xml[1024], jacksboro[1024], missing[1024];
  snprintf(xml, sizeof xml, "%s", joined(data_dir, "duck3d_BRep.xml"));
  snprintf(jacksboro, sizeof jacksboro, "%s", joined(data_dir, "jacksboro_faces"));
  snprintf(missing, sizeof missing, "%s", joined(data_dir, "no_such_file.xml"));

  /* Argument errors leave the handle alone; bad factors are refused before any I/O. */
  igaparam_domain *d = UNTOUCHED;
  const double two[3] = {2, 2, 2};
  EXPECT(igaparam_domain_new_solid_from_file_scaled(NULL, two, &d), IGAPARAM_STATUS_NULL_ARGUMENT);
  CHECK(strstr(message(), "path") != NULL, "NULL path: message '%s'", message());
  EXPECT(igaparam_domain_new_solid_from_file_scaled(xml, two, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  CHECK(strstr(message(), "out") != NULL, "NULL out: message '%s'", message());
  const double bad[5][3] = {{NAN, 1, 1}, {1, 0, 1}, {1, 1, -2}, {INFINITY, 1, 1}, {1, -0.0, 1}};
  for (int i = 0; i < 5; i++) {
    EXPECT(igaparam_domain_new_solid_from_file_scaled(xml, bad[i], &d),
           IGAPARAM_STATUS_INVALID_ARGUMENT);
    CHECK(strstr(message(), "igaparam_domain_new_solid_from_file_scaled") != NULL &&
              strstr(message(), "finite and positive") != NULL,
          "bad factors %d: message '%s'", i, message());
    EXPECT(igaparam_domain_new_solid_from_file_scaled(missing, bad[i], &d),
           IGAPARAM_STATUS_INVALID_ARGUMENT);
  }
  EXPECT(igaparam_domain_new_solid_from_file_scaled(missing, two, &d), IGAPARAM_STATUS_IO);
  EXPECT(igaparam_domain_new_solid_from_file_scaled(missing, NULL, &d), IGAPARAM_STATUS_IO);
  EXPECT(igaparam_domain_new_solid_from_file_scaled(joined(data_dir, "README.md"), two, &d),
         IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(d == UNTOUCHED, "a failed constructor wrote its handle");

  /* Uniform scaling of a B-rep by 2 commutes with the whole pipeline, exactly: the same T-mesh,
   * every physical coordinate doubled (a factor 2 is exact in floating point, and every
   * tolerance is relative to the bounding box). NULL factors are the unscaled solid. */
  igaparam_domain *duck[3] = {NULL, NULL, NULL};
  EXPECT(igaparam_domain_new_solid_from_file(xml, &duck[0]), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_new_solid_from_file_scaled(xml, NULL, &duck[1]), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_new_solid_from_file_scaled(xml, two, &duck[2]), IGAPARAM_STATUS_OK);
  if (duck[0] && duck[1] && duck[2]) {
    igaparam_domain_options o = igaparam_domain_options_default();
    o.min_level = 1;
    o.max_level = 3;
    /* 3e-3: 8 cells and a few sweeps; 1e-3: every cell refined once, and the repair rounds. */
    o.tolerance = 3e-3;
    compare_scaled(duck[0], duck[1], 1.0, &o);
    compare_scaled(duck[0], duck[2], 2.0, &o);
    o.tolerance = 1e-3;
    compare_scaled(duck[0], duck[2], 2.0, &o);
  }
  for (int i = 0; i < 3; i++) igaparam_domain_free(duck[i]);

  /* The Jacksboro block (x, y in degrees/1000, z in km) with its axes in km builds without
   * invalid cells and gives a spline map certified as fitted, without untangling. */
  const double km[3] = {89273.3, 111200.0, 1.0};
  d = NULL;
  EXPECT(igaparam_domain_new_solid_from_file_scaled(jacksboro, km, &d), IGAPARAM_STATUS_OK);
  if (!d) return;
  igaparam_domain_options o = igaparam_domain_options_default();
  o.tolerance = 1e-3;
  o.max_level = 3;
  igaparam_domain_report jr;
  EXPECT(igaparam_domain_build(d, &o, &jr), IGAPARAM_STATUS_OK);
  printf("Jacksboro in km at tolerance 1e-3, max level 3: %zu cells, %zu invalid after placement, "
         "%zu invalid, min quality %g, seam offset %g\n",
         jr.cells, jr.invalid_after_placement, jr.invalid_cells, jr.min_quality, jr.boundary_offset);
  CHECK(jr.invalid_cells == 0, "Jacksboro in km: %zu invalid cells", jr.invalid_cells);
  size_t n = jr.vertices;
  double *xyz = malloc(3 * n * sizeof *xyz);
  EXPECT(igaparam_domain_copy_vertices(d, NULL, xyz, 3 * n), IGAPARAM_STATUS_OK);
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t v = 0; v < n; v++)
    for (int m = 0; m < 3; m++) {
      lo[m] = fmin(lo[m], xyz[3 * v + m]);
      hi[m] = fmax(hi[m], xyz[3 * v + m]);
    }
  free(xyz);
  /* 29.98 km by 31.88 km: the factors reached the T-mesh. */
  CHECK(fabs(hi[0] - lo[0] - 29.98) < 0.01 && fabs(hi[1] - lo[1] - 31.88) < 0.01,
        "Jacksboro in km: extent %g x %g x %g", hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  igaparam_spline *s = NULL;
  igaparam_fit_report fr;
  EXPECT(igaparam_spline_fit_domain(d, &s, &fr), IGAPARAM_STATUS_OK);
  if (s) {
    igaparam_validity_report vr;
    EXPECT(igaparam_spline_check_validity(s, NULL, &vr, NULL, NULL, 0), IGAPARAM_STATUS_OK);
    printf("Jacksboro in km, spline map: %zu functions, %zu elements, untangled %zu, certified %d, "
           "min mean ratio %g\n",
           fr.basis_count, fr.element_count, fr.untangled, (int)vr.certified_positive,
           vr.min_quality);
    CHECK(fr.untangled == 0, "Jacksboro in km: %zu control points untangled", fr.untangled);
    CHECK(vr.certified_positive == 1 && vr.uncertified == 0,
          "Jacksboro in km: %zu elements uncertified", vr.uncertified);
    igaparam_spline_free(s);
  }
  igaparam_domain_free(d);
}

/* A solid built with NULL options uses the solid defaults (tolerance 1e-3), not the planar ones. */
static void test_solid_defaults(void) {
  igaparam_domain_options planar = igaparam_domain_options_default();
  igaparam_domain_options solid = igaparam_domain_options_default_solid();
  CHECK(planar.tolerance == 1e-5 && solid.tolerance == 1e-3, "default tolerances %g, %g",
        planar.tolerance, solid.tolerance);
  CHECK(solid.max_level == planar.max_level && solid.boundary_offset == planar.boundary_offset,
        "the solid defaults differ from the planar ones in more than the tolerance");
  igaparam_domain *a = NULL, *b = NULL;
  const char *path = joined(data_dir, "duck3d_BRep.xml");
  EXPECT(igaparam_domain_new_solid_from_file(path, &a), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_new_solid_from_file(path, &b), IGAPARAM_STATUS_OK);
  if (!a || !b) return;
  igaparam_domain_report ra, rb;
  solid.threads = 2;
  EXPECT(igaparam_domain_build(a, NULL, &ra), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_build(b, &solid, &rb), IGAPARAM_STATUS_OK);
  printf("duck B-rep with the solid defaults: %zu cells, level %u, boundary error %.3e, %zu invalid\n",
         ra.cells, ra.max_level, ra.boundary_error, ra.invalid_cells);
  CHECK(ra.cells == rb.cells && ra.vertices == rb.vertices && ra.boundary_error == rb.boundary_error &&
            ra.min_quality == rb.min_quality,
        "NULL options: %zu cells, error %g; solid defaults: %zu cells, error %g", ra.cells,
        ra.boundary_error, rb.cells, rb.boundary_error);
  CHECK(ra.boundary_error <= 1e-3 && ra.invalid_cells == 0, "boundary error %g, %zu invalid",
        ra.boundary_error, ra.invalid_cells);
  igaparam_domain_free(a);
  igaparam_domain_free(b);
}

int main(int argc, char **argv) {
  if (!read_dirs(argc, argv)) return 2;
  test_constructor_errors();
  test_unit_square();
  test_solid();
  test_solid_scaled();
  test_solid_defaults();
  test_file("male_bdry.xml", "domain_male.vtu");
  test_file("gran_canaria.txt", "domain_gran_canaria.vtu");
  test_boundary_offset("gran_canaria.txt");
  printf("%d passed, %d failed\n", passed, failed);
  return failed ? 1 : 0;
}
