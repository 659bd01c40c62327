/*
 * Tests of the shape-optimization loop part of the C API (include/igaparam.h): domains from
 * B-spline/NURBS curves and surfaces given as arrays, igaparam_domain_set_boundary_* and
 * igaparam_domain_update, igaparam_spline_refit.
 * Usage: test_morph DATA_DIR OUT_DIR. Writes curves and surfaces as G+Smo XML into OUT_DIR and
 * checks that the domains made from the arrays equal those read from the files bit for bit;
 * morphs a planar domain in steps (update + refit: same basis and elements, certified); calls
 * the new entry points with NULL, wrong counts and sizes, NaN, decreasing knots, reflex corners,
 * boundaries of the other kind or orientation, an update before the build and a refit before
 * the update, checking statuses, messages and that nothing changed. Prints "N passed, M failed";
 * exits non-zero if any check failed.
 */

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dirs.h"
#include "expect.h"

/* ---------------------------------------------------------------------------------------------
 * A planar domain of four curves: a square whose top bulges by `bulge` and whose right side is
 * a quarter-circle-like NURBS arc, cubic and quadratic curves on non-uniform knots.
 * ------------------------------------------------------------------------------------------- */

typedef struct {
  double knots[4][16];
  double points[4][16];
  double weights[8];
  igaparam_curve curves[4];
} loop_data;

static void make_loop(loop_data *l, double bulge) {
  /* Side u = 0 (x = 0, upwards), cubic, 5 control points. */
  static const double k0[] = {0, 0, 0, 0, 0.4, 1, 1, 1, 1};
  static const double p0[] = {0, 0, -0.05, 0.3, 0.02, 0.5, -0.03, 0.8, 0, 1};
  /* Side v = 0 (y = 0, rightwards), quadratic, 4 control points. */
  static const double k2[] = {0, 0, 0, 0.6, 1, 1, 1};
  static const double p2[] = {0, 0, 0.4, -0.1, 0.8, 0.05, 1.2, 0};
  /* Side u = 1, rational quadratic, 3 control points: an arc bulging out. */
  static const double k1[] = {0, 0, 0, 1, 1, 1};
  static const double p1[] = {1.2, 0, 1.6, 0.55, 1.2, 1.1};
  static const double w1[] = {1, 0.8, 1};
  /* Side v = 1 (top, rightwards), cubic, 6 control points; the inner ones bulge up. */
  static const double k3[] = {0, 0, 0, 0, 0.3, 0.5, 1, 1, 1, 1};
  double p3[] = {0, 1, 0.25, 1.05, 0.5, 1.1, 0.75, 1.1, 1.0, 1.08, 1.2, 1.1};
  for (int i = 1; i < 5; i++) p3[2 * i + 1] += bulge * (i == 1 || i == 4 ? 0.5 : 1.0);
  const double *k[4] = {k0, k1, k2, k3}, *p[4] = {p0, p1, p2, p3};
  const size_t nk[4] = {9, 6, 7, 10}, np[4] = {5, 3, 4, 6};
  const uint32_t degree[4] = {3, 2, 2, 3};
  for (int c = 0; c < 4; c++) {
    memcpy(l->knots[c], k[c], nk[c] * sizeof(double));
    memcpy(l->points[c], p[c], 2 * np[c] * sizeof(double));
    l->curves[c] = (igaparam_curve){degree[c], nk[c], l->knots[c], np[c], l->points[c], NULL};
  }
  memcpy(l->weights, w1, sizeof w1);
  l->curves[1].weights = l->weights;
}

static void write_numbers(FILE *f, const double *v, size_t n) {
  for (size_t i = 0; i < n; i++) fprintf(f, "%.17g ", v[i]);
}

/* Writes the curves as a G+Smo XML file (BSpline / Nurbs geometries). */
static void write_curves(const char *path, const igaparam_curve *c, int n) {
  FILE *f = fopen(path, "w");
  if (!f) return;
  fprintf(f, "<?xml version=\"1.0\"?>\n<xml>\n");
  for (int i = 0; i < n; i++) {
    int rational = c[i].weights != NULL;
    fprintf(f, "<Geometry type=\"%s\" id=\"%d\">\n", rational ? "Nurbs" : "BSpline", i);
    fprintf(f, "<Basis type=\"%s\">", rational ? "NurbsBasis" : "BSplineBasis");
    if (rational) fprintf(f, "<Basis type=\"BSplineBasis\">");
    fprintf(f, "<KnotVector degree=\"%u\">", c[i].degree);
    write_numbers(f, c[i].knots, c[i].knot_count);
    fprintf(f, "</KnotVector>");
    if (rational) {
      fprintf(f, "</Basis><weights>");
      write_numbers(f, c[i].weights, c[i].control_point_count);
      fprintf(f, "</weights>");
    }
    fprintf(f, "</Basis>\n<coefs geoDim=\"2\">");
    write_numbers(f, c[i].control_points, 2 * c[i].control_point_count);
    fprintf(f, "</coefs>\n</Geometry>\n");
  }
  fprintf(f, "</xml>\n");
  fclose(f);
}

/* The physical vertices of a built domain (malloc'ed, *n vertices of d coordinates). */
static double *vertices(const igaparam_domain *d, size_t dim, size_t *n) {
  *n = 0;
  if (igaparam_domain_vertex_count(d, n) != IGAPARAM_STATUS_OK) return NULL;
  double *x = malloc(dim * *n * sizeof *x);
  if (igaparam_domain_copy_vertices(d, NULL, x, dim * *n) != IGAPARAM_STATUS_OK) {
    free(x);
    return NULL;
  }
  return x;
}

/* Both domains build with `o` and give the same vertices, bit for bit. */
static void same_domains(igaparam_domain *a, igaparam_domain *b, size_t dim,
                         const igaparam_domain_options *o, const char *what) {
  EXPECT(igaparam_domain_build(a, o, NULL), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_build(b, o, NULL), IGAPARAM_STATUS_OK);
  size_t na = 0, nb = 0;
  double *xa = vertices(a, dim, &na), *xb = vertices(b, dim, &nb);
  CHECK(xa && xb && na == nb && na > 0 && memcmp(xa, xb, dim * na * sizeof *xa) == 0,
        "%s: the domain from arrays differs from the one from the file (%zu, %zu vertices)",
        what, na, nb);
  free(xa);
  free(xb);
}

static void test_curves_equal_their_file(void) {
  loop_data l;
  make_loop(&l, 0.1);
  const char *path = joined(out_dir, "loop.xml");
  write_curves(path, l.curves, 4);
  igaparam_domain *from_arrays = NULL, *from_file = NULL;
  EXPECT(igaparam_domain_new_from_curves(4, l.curves, &from_arrays), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_new_from_file(path, &from_file), IGAPARAM_STATUS_OK);
  if (from_arrays && from_file) {
    igaparam_domain_options o = igaparam_domain_options_default();
    o.threads = 2;
    same_domains(from_arrays, from_file, 2, &o, "four curves");
  }
  igaparam_domain_free(from_arrays);
  igaparam_domain_free(from_file);
}

/* ---------------------------------------------------------------------------------------------
 * A solid of six biquadratic surfaces: a box mapped by a smooth function, each face's 3 × 3
 * control points the images of its half-grid, so that the faces share their edges exactly.
 * ------------------------------------------------------------------------------------------- */

typedef struct {
  double knots[6];
  double points[6][27];
  igaparam_surface surfaces[6];
} box_data;

static void box_map(const double p[3], double scale, double out[3]) {
  out[0] = 2 * p[0] + 0.3 * p[2];
  out[1] = p[1] + 0.1 * p[0] * p[2];
  out[2] = p[2] * (1 + 0.2 * p[0] * p[1]) * scale;
}

/* Face f (x = 0, x = 1, y = 0, ...) with its two in-plane axes (a, b) in increasing order. */
static void make_box(box_data *b, double top) {
  static const double knots[6] = {0, 0, 0, 1, 1, 1};
  memcpy(b->knots, knots, sizeof knots);
  for (int f = 0; f < 6; f++) {
    int axis = f / 2, ia = axis == 0 ? 1 : 0, ib = axis == 2 ? 1 : 2;
    for (int j = 0; j < 3; j++)
      for (int i = 0; i < 3; i++) {
        double p[3];
        p[axis] = f % 2;
        p[ia] = i / 2.0;
        p[ib] = j / 2.0;
        box_map(p, p[2] == 1 ? top : 1, &b->points[f][3 * (i + 3 * j)]);
      }
    b->surfaces[f] = (igaparam_surface){2, 2, 6, b->knots, 6, b->knots, 3, 3, b->points[f], NULL};
  }
}

static void write_surfaces(const char *path, const igaparam_surface *s) {
  FILE *f = fopen(path, "w");
  if (!f) return;
  fprintf(f, "<?xml version=\"1.0\"?>\n<xml>\n");
  for (int i = 0; i < 6; i++) {
    fprintf(f, "<Geometry type=\"TensorBSpline2\" id=\"%d\"><Basis type=\"TensorBSplineBasis2\">", i);
    fprintf(f, "<Basis type=\"BSplineBasis\" index=\"0\"><KnotVector degree=\"%u\">", s[i].degree_u);
    write_numbers(f, s[i].knots_u, s[i].knot_count_u);
    fprintf(f, "</KnotVector></Basis><Basis type=\"BSplineBasis\" index=\"1\"><KnotVector degree=\"%u\">",
            s[i].degree_v);
    write_numbers(f, s[i].knots_v, s[i].knot_count_v);
    fprintf(f, "</KnotVector></Basis></Basis>\n<coefs geoDim=\"3\">");
    write_numbers(f, s[i].control_points, 3 * s[i].control_point_count_u * s[i].control_point_count_v);
    fprintf(f, "</coefs></Geometry>\n");
  }
  fprintf(f, "</xml>\n");
  fclose(f);
}

static igaparam_domain_options coarse_solid(void) {
  igaparam_domain_options o = igaparam_domain_options_default_solid();
  o.tolerance = 1e-2;
  o.max_level = 3;
  o.threads = 2;
  return o;
}

static void test_surfaces_equal_their_file(void) {
  box_data b;
  make_box(&b, 1.0);
  const char *path = joined(out_dir, "box.xml");
  write_surfaces(path, b.surfaces);
  igaparam_domain *from_arrays = NULL, *from_file = NULL;
  EXPECT(igaparam_domain_new_solid_from_surfaces(6, b.surfaces, &from_arrays), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_new_solid_from_file(path, &from_file), IGAPARAM_STATUS_OK);
  if (from_arrays && from_file) {
    igaparam_domain_options o = coarse_solid();
    same_domains(from_arrays, from_file, 3, &o, "six surfaces");
  }
  igaparam_domain_free(from_arrays);
  igaparam_domain_free(from_file);
}

/* ---------------------------------------------------------------------------------------------
 * Bad arrays
 * ------------------------------------------------------------------------------------------- */

#define UNTOUCHED ((igaparam_domain *)(uintptr_t)0x1234)

/* The curve constructor refuses the arrays with `want` and leaves `*out`. */
static void refused(const igaparam_curve *curves, size_t count, igaparam_status want,
                    const char *what) {
  igaparam_domain *d = UNTOUCHED;
  igaparam_status got = igaparam_domain_new_from_curves(count, curves, &d);
  CHECK(got == want && message()[0] != '\0' && d == UNTOUCHED,
        "%s: status %d (%s), expected %d", what, (int)got, message(), (int)want);
}

static void test_bad_curves(void) {
  loop_data l;
  make_loop(&l, 0);
  igaparam_domain *d = UNTOUCHED;
  EXPECT(igaparam_domain_new_from_curves(4, NULL, &d), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_domain_new_from_curves(4, l.curves, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  refused(l.curves, 3, IGAPARAM_STATUS_INVALID_ARGUMENT, "three curves");
  CHECK(strstr(message(), "4") != NULL, "three curves: %s", message());
  igaparam_curve c[4];
  memcpy(c, l.curves, sizeof c);
  c[2].knots = NULL;
  refused(c, 4, IGAPARAM_STATUS_NULL_ARGUMENT, "NULL knots");
  memcpy(c, l.curves, sizeof c);
  c[2].knot_count = 6;
  refused(c, 4, IGAPARAM_STATUS_INVALID_ARGUMENT, "a knot too few");
  CHECK(strstr(message(), "curves[2]") != NULL, "the message names the curve: %s", message());
  memcpy(c, l.curves, sizeof c);
  c[2].degree = 0;
  refused(c, 4, IGAPARAM_STATUS_INVALID_ARGUMENT, "degree 0");
  l.knots[3][5] = 0.1; /* after 0.5: decreasing */
  refused(l.curves, 4, IGAPARAM_STATUS_INVALID_ARGUMENT, "decreasing knots");
  CHECK(strstr(message(), "non-decreasing") != NULL, "decreasing knots: %s", message());
  make_loop(&l, 0);
  l.knots[0][4] = NAN;
  refused(l.curves, 4, IGAPARAM_STATUS_NOT_FINITE, "a NaN knot");
  make_loop(&l, 0);
  l.points[2][3] = NAN;
  refused(l.curves, 4, IGAPARAM_STATUS_NOT_FINITE, "a NaN control point");
  make_loop(&l, 0);
  l.weights[1] = INFINITY;
  refused(l.curves, 4, IGAPARAM_STATUS_NOT_FINITE, "an infinite weight");
  l.weights[1] = -0.5;
  refused(l.curves, 4, IGAPARAM_STATUS_INVALID_ARGUMENT, "a negative weight");
  make_loop(&l, 0);
  l.points[2][6] = 1.0; /* the bottom curve stops short of the corner (1.2, 0) */
  refused(l.curves, 4, IGAPARAM_STATUS_INVALID_ARGUMENT, "an open loop");
  make_loop(&l, 0);
  l.points[2][2] = -0.3; /* the bottom curve leaves (0, 0) backwards: a reflex corner */
  l.points[2][3] = -0.3;
  refused(l.curves, 4, IGAPARAM_STATUS_INVALID_ARGUMENT, "a reflex corner");
  CHECK(strstr(message(), "convex") != NULL, "reflex corner: %s", message());

  box_data b;
  make_box(&b, 1.0);
  d = UNTOUCHED;
  EXPECT(igaparam_domain_new_solid_from_surfaces(5, b.surfaces, &d), IGAPARAM_STATUS_INVALID_ARGUMENT);
  b.points[4][13] = NAN;
  EXPECT(igaparam_domain_new_solid_from_surfaces(6, b.surfaces, &d), IGAPARAM_STATUS_NOT_FINITE);
  make_box(&b, 1.0);
  b.surfaces[3].control_point_count_v = 2;
  EXPECT(igaparam_domain_new_solid_from_surfaces(6, b.surfaces, &d), IGAPARAM_STATUS_INVALID_ARGUMENT);
  make_box(&b, 1.0);
  for (int i = 0; i < 27; i++) b.points[5][i] *= 1.01; /* no longer on its neighbours' edges */
  EXPECT(igaparam_domain_new_solid_from_surfaces(6, b.surfaces, &d), IGAPARAM_STATUS_INVALID_MESH);
  CHECK(d == UNTOUCHED, "a failed constructor wrote its handle");
}

/* ---------------------------------------------------------------------------------------------
 * The loop: set_boundary + update + refit
 * ------------------------------------------------------------------------------------------- */

static double *control_points(const igaparam_spline *s, size_t *n) {
  igaparam_spline_basis_count(s, n);
  double *p = malloc(2 * *n * sizeof *p);
  igaparam_spline_copy_control_points(s, p, 2 * *n);
  return p;
}

static double *element_bounds(const igaparam_spline *s, size_t *n) {
  igaparam_spline_element_count(s, n);
  double *b = malloc(4 * *n * sizeof *b);
  igaparam_spline_copy_elements(s, NULL, b, *n);
  return b;
}

static void test_loop(void) {
  loop_data l;
  make_loop(&l, 0);
  igaparam_domain *d = NULL;
  EXPECT(igaparam_domain_new_from_curves(4, l.curves, &d), IGAPARAM_STATUS_OK);
  if (!d) return;
  EXPECT(igaparam_domain_update(d, NULL, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(strstr(message(), "build") != NULL, "update before build: %s", message());
  igaparam_domain_options o = igaparam_domain_options_default();
  o.threads = 2;
  igaparam_domain_report built;
  EXPECT(igaparam_domain_build(d, &o, &built), IGAPARAM_STATUS_OK);
  igaparam_spline *s = NULL;
  igaparam_fit_report fit;
  EXPECT(igaparam_spline_fit_domain(d, &s, &fit), IGAPARAM_STATUS_OK);
  if (!s) {
    igaparam_domain_free(d);
    return;
  }
  igaparam_fit_rule rule = (igaparam_fit_rule)99;
  EXPECT(igaparam_spline_fit_rule(s, &rule), IGAPARAM_STATUS_OK);
  CHECK(rule == (fit.quasi_interpolation ? IGAPARAM_FIT_QUASI_INTERPOLATION
                 : fit.least_squares   ? IGAPARAM_FIT_LEAST_SQUARES
                                       : IGAPARAM_FIT_INTERPOLATION),
        "the fit rule %d does not match the fit report", (int)rule);
  size_t nb = 0, ne = 0, n;
  double *bounds = element_bounds(s, &ne);
  igaparam_spline_basis_count(s, &nb);

  igaparam_domain_update_options u = igaparam_domain_update_options_default();
  u.threads = 2;
  const int steps = 5;
  for (int step = 1; step <= steps; step++) {
    make_loop(&l, 0.1 * step / steps);
    EXPECT(igaparam_domain_set_boundary_curves(d, 4, l.curves), IGAPARAM_STATUS_OK);
    if (step == 1) {
      /* A refit before the update is refused and changes nothing. */
      size_t np;
      double *before = control_points(s, &np);
      igaparam_refit_report r;
      EXPECT(igaparam_spline_refit(s, d, &r), IGAPARAM_STATUS_INVALID_ARGUMENT);
      CHECK(strstr(message(), "igaparam_domain_update") != NULL, "refit: %s", message());
      double *after = control_points(s, &np);
      CHECK(memcmp(before, after, 2 * np * sizeof *before) == 0, "a failed refit changed the spline");
      free(before);
      free(after);
      igaparam_spline *stale = NULL;
      EXPECT(igaparam_spline_fit_domain(d, &stale, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
    }
    igaparam_domain_update_report ur;
    EXPECT(igaparam_domain_update(d, &u, &ur), IGAPARAM_STATUS_OK);
    CHECK(ur.domain.invalid_cells == 0 && ur.domain.cells == built.cells && ur.refined_cells == 0,
          "step %d: %zu invalid of %zu cells", step, ur.domain.invalid_cells, ur.domain.cells);
    CHECK(ur.boundary_motion > 0 && ur.steps >= 1, "step %d: motion %g", step, ur.boundary_motion);
    igaparam_refit_report rr;
    EXPECT(igaparam_spline_refit(s, d, &rr), IGAPARAM_STATUS_OK);
    CHECK(rr.rule == rule && rr.certified_positive && rr.fit.basis_count == nb &&
              rr.fit.element_count == ne,
          "step %d: rule %d, certified %d, %zu functions, %zu elements", step, (int)rr.rule,
          rr.certified_positive, rr.fit.basis_count, rr.fit.element_count);
    double *now = element_bounds(s, &n);
    CHECK(n == ne && memcmp(now, bounds, 4 * ne * sizeof *now) == 0, "step %d: elements changed",
          step);
    free(now);
    igaparam_validity_report v;
    EXPECT(igaparam_spline_check_validity(s, NULL, &v, NULL, NULL, 0), IGAPARAM_STATUS_OK);
    CHECK(v.certified_positive && fabs(v.min_quality - rr.min_quality) < 1e-15,
          "step %d: validity %d, q %g vs %g", step, v.certified_positive, v.min_quality,
          rr.min_quality);
  }
  free(bounds);

  /* The other kind, or a file that does not exist: refused, the domain unchanged. */
  size_t nv;
  double *before = vertices(d, 2, &nv);
  box_data b;
  make_box(&b, 1.0);
  EXPECT(igaparam_domain_set_boundary_surfaces(d, 6, b.surfaces), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(strstr(message(), "planar") != NULL, "surfaces for a planar domain: %s", message());
  EXPECT(igaparam_domain_set_boundary_from_file_scaled(d, joined(data_dir, "male_bdry.xml"), NULL),
         IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_domain_set_boundary_from_file(d, joined(data_dir, "no_such_file.xml")),
         IGAPARAM_STATUS_IO);
  make_loop(&l, 0.5);
  l.points[3][5] = NAN;
  EXPECT(igaparam_domain_set_boundary_curves(d, 4, l.curves), IGAPARAM_STATUS_NOT_FINITE);
  EXPECT(igaparam_domain_set_boundary_curves(d, 2, l.curves), IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_domain_set_boundary_curves(NULL, 4, l.curves), IGAPARAM_STATUS_NULL_ARGUMENT);
  u.threads = 5000;
  EXPECT(igaparam_domain_update(d, &u, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  /* Nothing was replaced: the update moves nothing. */
  igaparam_domain_update_report ur;
  EXPECT(igaparam_domain_update(d, NULL, &ur), IGAPARAM_STATUS_OK);
  CHECK(ur.boundary_motion == 0, "a refused boundary was kept (motion %g)", ur.boundary_motion);
  double *after = vertices(d, 2, &n);
  double moved = 0;
  for (size_t i = 0; before && after && i < 2 * nv; i++) moved = fmax(moved, fabs(after[i] - before[i]));
  CHECK(n == nv && moved < 1e-2, "the domain moved by %g", moved);
  free(before);
  free(after);

  /* A 3D spline does not refit to a planar domain. */
  igaparam_domain *box = NULL;
  EXPECT(igaparam_domain_new_solid_from_surfaces(6, b.surfaces, &box), IGAPARAM_STATUS_OK);
  igaparam_domain_options co = coarse_solid();
  igaparam_spline *s3 = NULL;
  EXPECT(igaparam_domain_build(box, &co, NULL), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_fit_domain(box, &s3, NULL), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_refit(s3, d, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_spline_refit(NULL, d, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_spline_refit(s, NULL, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  igaparam_spline_free(s3);
  igaparam_domain_free(box);
  igaparam_spline_free(s);
  igaparam_domain_free(d);
}

/* The spline of a file has no fit rule until its first refit chooses one. */
static void test_read_spline_refit(void) {
  loop_data l;
  make_loop(&l, 0);
  igaparam_domain *d = NULL;
  EXPECT(igaparam_domain_new_from_curves(4, l.curves, &d), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_build(d, NULL, NULL), IGAPARAM_STATUS_OK);
  igaparam_spline *s = NULL, *read = NULL;
  EXPECT(igaparam_spline_fit_domain(d, &s, NULL), IGAPARAM_STATUS_OK);
  const char *path = joined(out_dir, "loop_spline.xml");
  EXPECT(igaparam_spline_write_gismo(s, path), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_read_gismo(path, &read), IGAPARAM_STATUS_OK);
  igaparam_fit_rule rule, first;
  EXPECT(igaparam_spline_fit_rule(read, &rule), IGAPARAM_STATUS_INVALID_ARGUMENT);
  igaparam_refit_report r;
  EXPECT(igaparam_spline_refit(read, d, &r), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_fit_rule(read, &rule), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_fit_rule(s, &first), IGAPARAM_STATUS_OK);
  CHECK(rule == first && r.rule == first && r.certified_positive,
        "the refit of the read spline chose rule %d, the fit %d", (int)rule, (int)first);
  igaparam_spline_free(read);
  igaparam_spline_free(s);
  igaparam_domain_free(d);
}

/* A solid: a mirrored boundary (the faces x = 0 and x = 1 swapped) is refused; the top rises. */
static void test_solid_update(void) {
  box_data b;
  make_box(&b, 1.0);
  igaparam_domain *d = NULL;
  EXPECT(igaparam_domain_new_solid_from_surfaces(6, b.surfaces, &d), IGAPARAM_STATUS_OK);
  igaparam_domain_options o = coarse_solid();
  EXPECT(igaparam_domain_build(d, &o, NULL), IGAPARAM_STATUS_OK);
  igaparam_surface mirrored[6];
  memcpy(mirrored, b.surfaces, sizeof mirrored);
  mirrored[0] = b.surfaces[1];
  mirrored[1] = b.surfaces[0];
  EXPECT(igaparam_domain_set_boundary_surfaces(d, 6, mirrored), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(strstr(message(), "oriented") != NULL, "mirrored: %s", message());
  EXPECT(igaparam_domain_set_boundary_curves(d, 4, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  box_data taller;
  make_box(&taller, 1.1);
  EXPECT(igaparam_domain_set_boundary_surfaces(d, 6, taller.surfaces), IGAPARAM_STATUS_OK);
  igaparam_domain_update_report r;
  EXPECT(igaparam_domain_update(d, NULL, &r), IGAPARAM_STATUS_OK);
  CHECK(r.domain.invalid_cells == 0 && r.boundary_motion > 0.01,
        "solid update: %zu invalid, motion %g", r.domain.invalid_cells, r.boundary_motion);
  igaparam_domain_free(d);
}

/* Cancelling an update leaves the domain as it was. */
static int cancel(void *user, igaparam_stage stage, size_t done, size_t total) {
  (void)stage, (void)done, (void)total;
  ++*(int *)user;
  return 1;
}

static void test_cancel(void) {
  loop_data l;
  make_loop(&l, 0);
  igaparam_domain *d = NULL;
  EXPECT(igaparam_domain_new_from_curves(4, l.curves, &d), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_build(d, NULL, NULL), IGAPARAM_STATUS_OK);
  size_t n, m;
  double *before = vertices(d, 2, &n);
  make_loop(&l, 0.2);
  EXPECT(igaparam_domain_set_boundary_curves(d, 4, l.curves), IGAPARAM_STATUS_OK);
  int calls = 0;
  igaparam_domain_update_options u = igaparam_domain_update_options_default();
  u.progress = cancel;
  u.progress_user = &calls;
  igaparam_domain_update_report r;
  memset(&r, 0xAB, sizeof r);
  unsigned char untouched[sizeof r];
  memcpy(untouched, &r, sizeof r);
  EXPECT(igaparam_domain_update(d, &u, &r), IGAPARAM_STATUS_CANCELLED);
  CHECK(calls == 1 && memcmp(&r, untouched, sizeof r) == 0, "cancel: %d calls", calls);
  double *after = vertices(d, 2, &m);
  CHECK(before && after && n == m && memcmp(before, after, 2 * n * sizeof *before) == 0,
        "a cancelled update moved the T-mesh");
  free(before);
  free(after);
  igaparam_domain_free(d);
}

/* ---------------------------------------------------------------------------------------------
 * Sensitivities of the control points (igaparam_spline_tangent / igaparam_spline_adjoint):
 * the tangent against central differences of update + refit as the top bulges, the adjoint as
 * its transpose, and bad arguments.
 * ------------------------------------------------------------------------------------------- */

/* The domain moved onto the loop of `bulge`, the spline refitted: vertices and control points. */
static void moved(igaparam_domain *d, igaparam_spline *s, double bulge, double **x, double **p) {
  loop_data l;
  make_loop(&l, bulge);
  size_t n;
  EXPECT(igaparam_domain_set_boundary_curves(d, 4, l.curves), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_update(d, NULL, NULL), IGAPARAM_STATUS_OK);
  igaparam_refit_report r;
  EXPECT(igaparam_spline_refit(s, d, &r), IGAPARAM_STATUS_OK);
  CHECK(r.fit.untangled == 0, "the refit at bulge %g untangled", bulge);
  *x = vertices(d, 2, &n);
  *p = control_points(s, &n);
}

static double largest(const double *v, size_t n) {
  double m = 0;
  for (size_t i = 0; i < n; i++) m = fabs(v[i]) > m ? fabs(v[i]) : m;
  return m;
}

static void test_sensitivities(void) {
  loop_data l;
  make_loop(&l, 0);
  igaparam_domain *d = NULL;
  EXPECT(igaparam_domain_new_from_curves(4, l.curves, &d), IGAPARAM_STATUS_OK);
  igaparam_domain_options o = igaparam_domain_options_default();
  o.threads = 2;
  o.boundary_offset = 0;
  o.stationarity_tolerance = 1e-12;
  igaparam_domain_report built;
  EXPECT(igaparam_domain_build(d, &o, &built), IGAPARAM_STATUS_OK);
  CHECK(built.invalid_cells == 0 && built.gradient_norm <= 1e-12 && built.newton_iterations > 0,
        "polished build: %zu invalid, gradient %g", built.invalid_cells, built.gradient_norm);
  igaparam_spline *s = NULL;
  igaparam_fit_report fit;
  EXPECT(igaparam_spline_fit_domain(d, &s, &fit), IGAPARAM_STATUS_OK);
  if (!s) {
    igaparam_domain_free(d);
    return;
  }
  if (fit.untangled) EXPECT(igaparam_spline_refit(s, d, NULL), IGAPARAM_STATUS_OK);
  size_t nv, nb;
  free(vertices(d, 2, &nv));
  free(control_points(s, &nb));
  const double h = 1e-4;
  double *xp, *pp, *xm, *pm, *x0, *p0;
  moved(d, s, h, &xp, &pp);
  moved(d, s, -h, &xm, &pm);
  moved(d, s, 0, &x0, &p0);
  double *dx = malloc(2 * nv * sizeof *dx), *g = calloc(2 * nv, sizeof *g);
  double *fd = malloc(2 * nb * sizeof *fd), *dp = malloc(2 * nb * sizeof *dp);
  double *w = malloc(2 * nb * sizeof *w);
  for (size_t i = 0; i < 2 * nv; i++) dx[i] = (xp[i] - xm[i]) / (2 * h);
  for (size_t i = 0; i < 2 * nb; i++) fd[i] = (pp[i] - pm[i]) / (2 * h), w[i] = cos((double)i);
  EXPECT(igaparam_spline_tangent(s, d, 2 * nv, dx, 2 * nb, dp), IGAPARAM_STATUS_OK);
  double error = 0, wdp = 0, gdx = 0;
  for (size_t i = 0; i < 2 * nb; i++) error = fmax(error, fabs(dp[i] - fd[i]));
  CHECK(largest(fd, 2 * nb) > 0 && error <= 1e-6 * largest(fd, 2 * nb),
        "tangent vs finite differences: %.3e of %.3e", error, largest(fd, 2 * nb));
  /* A bad size fails before the output is written. */
  EXPECT(igaparam_spline_adjoint(s, d, 2 * nb - 1, w, 2 * nv, g), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(strstr(message(), "dj_dp") != NULL && largest(g, 2 * nv) == 0, "bad size: %s", message());
  EXPECT(igaparam_spline_adjoint(s, d, 2 * nb, w, 2 * nv, g), IGAPARAM_STATUS_OK);
  for (size_t i = 0; i < 2 * nb; i++) wdp += w[i] * dp[i];
  for (size_t i = 0; i < 2 * nv; i++) gdx += g[i] * dx[i];
  CHECK(fabs(wdp - gdx) <= 1e-9 * fmax(fabs(wdp), fabs(gdx)), "w.dp %.15e, adjoint.dx %.15e", wdp,
        gdx);
  /* With respect to the curves' control points: the bulge raises the inner control points
   * of the top curve (the fourth given), in y, by 0.5, 1, 1, 0.5 per unit. */
  size_t nc = 0;
  EXPECT(igaparam_domain_control_count(d, &nc), IGAPARAM_STATUS_OK);
  CHECK(nc == 5 + 3 + 4 + 6, "%zu control points", nc);
  double *dc = calloc(2 * nc, sizeof *dc), *gc = malloc(2 * nc * sizeof *gc);
  const size_t top = 5 + 3 + 4;
  for (int i = 1; i < 5; i++) dc[2 * (top + i) + 1] = (i == 1 || i == 4) ? 0.5 : 1.0;
  EXPECT(igaparam_spline_tangent_controls(s, d, 2 * nc, dc, 2 * nb, dp), IGAPARAM_STATUS_OK);
  error = 0;
  for (size_t i = 0; i < 2 * nb; i++) error = fmax(error, fabs(dp[i] - fd[i]));
  CHECK(error <= 1e-6 * largest(fd, 2 * nb), "controls tangent vs finite differences: %.3e", error);
  EXPECT(igaparam_spline_adjoint_controls(s, d, 2 * nb, w, 2 * nc, gc), IGAPARAM_STATUS_OK);
  double gdc = 0, wdpc = 0;
  for (size_t i = 0; i < 2 * nb; i++) wdpc += w[i] * dp[i];
  for (size_t i = 0; i < 2 * nc; i++) gdc += gc[i] * dc[i];
  CHECK(fabs(wdpc - gdc) <= 1e-9 * fmax(fabs(wdpc), fabs(gdc)), "w.dp %.15e, adjoint.dc %.15e", wdpc,
        gdc);
  EXPECT(igaparam_spline_adjoint_controls(s, d, 2 * nb, w, 2 * nc - 2, gc),
         IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(strstr(message(), "dj_dc") != NULL, "bad size: %s", message());
  free(dc);
  free(gc);
  EXPECT(igaparam_spline_adjoint(NULL, d, 2 * nb, w, 2 * nv, g), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_spline_tangent(s, NULL, 2 * nv, dx, 2 * nb, dp), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_spline_tangent(s, d, 2 * nv, NULL, 2 * nb, dp), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_spline_tangent(s, d, 2 * nv, dx, 2 * nb, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  /* Without the polish there is nothing to differentiate. */
  o.stationarity_tolerance = 0;
  EXPECT(igaparam_domain_build(d, &o, NULL), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_tangent(s, d, 2 * nv, dx, 2 * nb, dp), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(strstr(message(), "stationarity_tolerance") != NULL, "unpolished: %s", message());
  double *ptrs[] = {xp, pp, xm, pm, x0, p0, dx, g, fd, dp, w};
  for (size_t i = 0; i < sizeof ptrs / sizeof *ptrs; i++) free(ptrs[i]);
  igaparam_spline_free(s);
  igaparam_domain_free(d);
}

int main(int argc, char **argv) {
  if (!read_dirs(argc, argv)) return 2;
  test_curves_equal_their_file();
  test_surfaces_equal_their_file();
  test_bad_curves();
  test_loop();
  test_read_spline_refit();
  test_solid_update();
  test_cancel();
  test_sensitivities();
  printf("%d passed, %d failed\n", passed, failed);
  return failed != 0;
}
