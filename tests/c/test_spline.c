/*
 * Tests of the spline part of the C API (include/igaparam.h) through its C ABI.
 *
 * Usage: test_spline DATA_DIR OUT_DIR, where DATA_DIR holds male_bdry.xml and puzzle3_bdry.xml
 * and OUT_DIR receives the output files. Builds the male rotor domain, fits its spline map, and
 * checks that the basis
 * queries agree with the evaluation (Σ N_i P_i = S, Σ ∇N_i P_i = J, Σ N_i = 1, N_i ≥ 0), that the
 * Bézier extraction reproduces the basis values, that inversion undoes evaluation, that the map
 * is certified valid (the validity a fit keeps being the one computed), that refinement keeps the
 * map and that the G+Smo XML round trip keeps it;
 * calls the entry points with NULL, out-of-range and non-finite arguments, checking the status,
 * the message and that a failed call leaves the handle as it was. Prints "N passed, M failed";
 * exits non-zero if any check failed. Checks the certification against a dense evaluation of
 * det J; runs the adaptive loop on the rotor; compares domain builds, fits and adaptive loops at
 * 1, 2 and 4 threads bit for bit.
 */

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dirs.h"
#include "expect.h"
#include "vtu_check.h"

/* Deterministic pseudo-random numbers in [0, 1). */
static double uniform(void) {
  static uint64_t state = 0x9e3779b97f4a7c15u;
  state = state * 6364136223846793005u + 1442695040888963407u;
  return (double)(state >> 11) / 9007199254740992.0;
}

/* Cubic Bernstein polynomials at t. */
static void bernstein3(double t, double b[4]) {
  double s = 1.0 - t;
  b[0] = s * s * s;
  b[1] = 3.0 * t * s * s;
  b[2] = 3.0 * t * t * s;
  b[3] = t * t * t;
}

#define SAMPLES 40

/* Builds the domain of a boundary file of the data directory (default options, 2 threads) and
 * fits its spline map; the domain is freed before returning. */
static igaparam_spline *fit_file(const char *name, igaparam_fit_report *report) {
  igaparam_domain *domain = NULL;
  EXPECT(igaparam_domain_new_from_file(joined(data_dir, name), &domain), IGAPARAM_STATUS_OK);
  igaparam_domain_options options = igaparam_domain_options_default();
  options.threads = 2;
  EXPECT(igaparam_domain_build(domain, &options, NULL), IGAPARAM_STATUS_OK);
  igaparam_spline *spline = NULL;
  memset(report, 0, sizeof *report);
  EXPECT(igaparam_spline_fit_domain(domain, &spline, report), IGAPARAM_STATUS_OK);
  /* The spline does not refer to the domain. */
  igaparam_domain_free(domain);
  return spline;
}

static igaparam_spline *fit_male(void) {
  igaparam_fit_report report;
  igaparam_spline *spline = fit_file("male_bdry.xml", &report);
  CHECK(spline != NULL, "fit gave no handle");
  CHECK(report.basis_count > 16 && report.element_count > 1, "fit report: %zu functions, %zu elements",
        report.basis_count, report.element_count);
  CHECK(report.residual < 1e-8, "fit residual %g", report.residual);
  /* The spline's boundary strays 8.5e-4 of the box from the curves' (their T-mesh's facets
   * up to 1.6e-3). */
  CHECK(report.boundary_distance > 0 && report.boundary_distance < 3e-3, "boundary distance %g",
        report.boundary_distance);
  return spline;
}

/* Σ N_i P_i = S and Σ ∇N_i P_i = J at random points; Σ N_i = 1; N_i ≥ 0. */
static void test_basis_agrees_with_evaluation(const igaparam_spline *s) {
  size_t nb = 0;
  EXPECT(igaparam_spline_basis_count(s, &nb), IGAPARAM_STATUS_OK);
  double *control = malloc(2 * nb * sizeof *control);
  EXPECT(igaparam_spline_copy_control_points(s, control, 2 * nb), IGAPARAM_STATUS_OK);
  double params[2 * SAMPLES], points[2 * SAMPLES], jac[4 * SAMPLES], q[SAMPLES];
  for (int i = 0; i < 2 * SAMPLES; i++) params[i] = uniform();
  params[0] = 0.0; /* a corner and a point on the upper boundary */
  params[1] = 0.0;
  params[2] = 1.0;
  params[3] = 0.5;
  EXPECT(igaparam_spline_evaluate(s, SAMPLES, params, points, jac), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_mean_ratio(s, SAMPLES, params, q), IGAPARAM_STATUS_OK);
  double worst_value = 0, worst_grad = 0, worst_sum = 0, worst_q = 0, most_negative = 0;
  for (int i = 0; i < SAMPLES; i++) {
    size_t m = 0;
    EXPECT(igaparam_spline_basis_count_at(s, params + 2 * i, &m), IGAPARAM_STATUS_OK);
    size_t *f = malloc(m * sizeof *f);
    double *v = malloc(m * sizeof *v), *g = malloc(2 * m * sizeof *g);
    size_t count = 0;
    EXPECT(igaparam_spline_basis_at(s, params + 2 * i, &count, f, v, g, m), IGAPARAM_STATUS_OK);
    CHECK(count == m, "basis_at count %zu, basis_count_at %zu", count, m);
    double x[2] = {0, 0}, j[4] = {0, 0, 0, 0}, sum = 0;
    for (size_t a = 0; a < count; a++) {
      CHECK(f[a] < nb, "function index %zu out of range", f[a]);
      sum += v[a];
      if (v[a] < most_negative) most_negative = v[a];
      for (int k = 0; k < 2; k++) {
        x[k] += v[a] * control[2 * f[a] + k];
        for (int l = 0; l < 2; l++) j[2 * k + l] += g[2 * a + l] * control[2 * f[a] + k];
      }
    }
    for (int k = 0; k < 2; k++) worst_value = fmax(worst_value, fabs(x[k] - points[2 * i + k]));
    for (int k = 0; k < 4; k++) worst_grad = fmax(worst_grad, fabs(j[k] - jac[4 * i + k]));
    worst_sum = fmax(worst_sum, fabs(sum - 1.0));
    double det = jac[4 * i] * jac[4 * i + 3] - jac[4 * i + 1] * jac[4 * i + 2];
    double frob = jac[4 * i] * jac[4 * i] + jac[4 * i + 1] * jac[4 * i + 1] +
                  jac[4 * i + 2] * jac[4 * i + 2] + jac[4 * i + 3] * jac[4 * i + 3];
    double expected = det > 0 ? 2.0 * det / frob : 0.0;
    worst_q = fmax(worst_q, fabs(expected - q[i]));
    free(f);
    free(v);
    free(g);
  }
  CHECK(worst_value < 1e-10, "Σ N_i P_i differs from S by %g", worst_value);
  CHECK(worst_grad < 1e-8, "Σ ∇N_i P_i differs from J by %g", worst_grad);
  CHECK(worst_sum < 1e-12, "Σ N_i differs from 1 by %g", worst_sum);
  CHECK(most_negative > -1e-14, "a basis value is negative: %g", most_negative);
  CHECK(worst_q < 1e-12, "mean ratio differs from 2 det J / |J|² by %g", worst_q);
  free(control);
}

/* On every tenth element, C^e times the Bernstein values gives basis_at's values. */
static void test_extraction(const igaparam_spline *s) {
  size_t ne = 0;
  EXPECT(igaparam_spline_element_count(s, &ne), IGAPARAM_STATUS_OK);
  uint8_t *levels = malloc(ne);
  double *bounds = malloc(4 * ne * sizeof *bounds);
  EXPECT(igaparam_spline_copy_elements(s, levels, bounds, ne), IGAPARAM_STATUS_OK);
  double worst = 0;
  int index_mismatch = 0;
  for (size_t e = 0; e < ne; e += 10) {
    double *b = bounds + 4 * e;
    CHECK(fabs((b[2] - b[0]) - ldexp(1.0, -levels[e])) < 1e-15, "element %zu: side vs level", e);
    size_t m = 0;
    EXPECT(igaparam_spline_element_function_count(s, e, &m), IGAPARAM_STATUS_OK);
    size_t *f = malloc(m * sizeof *f);
    double *c = malloc(16 * m * sizeof *c);
    EXPECT(igaparam_spline_copy_element_extraction(s, e, f, m, c, 16 * m), IGAPARAM_STATUS_OK);
    double t[2] = {0.3, 0.7}, bu[4], bv[4];
    double p[2] = {b[0] + t[0] * (b[2] - b[0]), b[1] + t[1] * (b[3] - b[1])};
    bernstein3(t[0], bu);
    bernstein3(t[1], bv);
    size_t count = 0;
    size_t *g = malloc(m * sizeof *g);
    double *v = malloc(m * sizeof *v);
    EXPECT(igaparam_spline_basis_at(s, p, &count, g, v, NULL, m), IGAPARAM_STATUS_OK);
    for (size_t a = 0; a < m && a < count; a++) {
      if (g[a] != f[a]) index_mismatch++;
      double value = 0;
      for (int k = 0; k < 16; k++) value += c[16 * a + k] * bu[k % 4] * bv[k / 4];
      worst = fmax(worst, fabs(value - v[a]));
    }
    CHECK(count == m, "element %zu: %zu functions at a point, %zu in the extraction", e, count, m);
    free(f);
    free(c);
    free(g);
    free(v);
  }
  CHECK(index_mismatch == 0, "%d function indices differ between extraction and basis_at",
        index_mismatch);
  CHECK(worst < 1e-12, "extraction differs from basis values by %g", worst);
  free(levels);
  free(bounds);
}

/* Functions with an inner Greville point vanish on the boundary. */
static void test_greville(const igaparam_spline *s) {
  size_t nb = 0;
  EXPECT(igaparam_spline_basis_count(s, &nb), IGAPARAM_STATUS_OK);
  double *g = malloc(2 * nb * sizeof *g);
  EXPECT(igaparam_spline_copy_greville_points(s, g, 2 * nb), IGAPARAM_STATUS_OK);
  int on_boundary = 0, wrong = 0;
  for (size_t i = 0; i < nb; i++) {
    CHECK(g[2 * i] >= 0 && g[2 * i] <= 1 && g[2 * i + 1] >= 0 && g[2 * i + 1] <= 1,
          "Greville point %zu outside", i);
    if (g[2 * i] == 0 || g[2 * i] == 1 || g[2 * i + 1] == 0 || g[2 * i + 1] == 1) on_boundary++;
  }
  for (int i = 0; i < SAMPLES; i++) {
    double p[2] = {uniform(), uniform()};
    p[i % 2] = (i / 2) % 2 ? 1.0 : 0.0;
    size_t m = 0;
    EXPECT(igaparam_spline_basis_count_at(s, p, &m), IGAPARAM_STATUS_OK);
    size_t *f = malloc(m * sizeof *f);
    double *v = malloc(m * sizeof *v);
    EXPECT(igaparam_spline_basis_at(s, p, &m, f, v, NULL, m), IGAPARAM_STATUS_OK);
    for (size_t a = 0; a < m; a++) {
      const double *q = g + 2 * f[a];
      int inner = q[0] > 0 && q[0] < 1 && q[1] > 0 && q[1] < 1;
      if (inner && fabs(v[a]) > 1e-14) wrong++;
    }
    free(f);
    free(v);
  }
  CHECK(on_boundary > 8, "%d functions with a Greville point on the boundary", on_boundary);
  CHECK(wrong == 0, "%d inner functions do not vanish on the boundary", wrong);
  double small[1];
  EXPECT(igaparam_spline_copy_greville_points(s, small, 1), IGAPARAM_STATUS_BUFFER_TOO_SMALL);
  free(g);
}

static void test_inverse(const igaparam_spline *s) {
  double params[2 * SAMPLES], points[2 * SAMPLES], back[2 * SAMPLES];
  int found[SAMPLES];
  for (int i = 0; i < 2 * SAMPLES; i++) params[i] = 0.05 + 0.9 * uniform();
  EXPECT(igaparam_spline_evaluate(s, SAMPLES, params, points, NULL), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_invert(s, SAMPLES, points, 4, back, found), IGAPARAM_STATUS_OK);
  double worst = 0;
  int missed = 0;
  for (int i = 0; i < SAMPLES; i++) {
    if (!found[i]) missed++;
    else
      for (int k = 0; k < 2; k++) worst = fmax(worst, fabs(back[2 * i + k] - params[2 * i + k]));
  }
  CHECK(missed == 0, "%d of %d points not located", missed, SAMPLES);
  CHECK(worst < 1e-9, "inverse(S(u)) differs from u by %g", worst);
  /* A point far outside. */
  double far[2] = {1e6, 1e6}, u[2];
  int f = 1;
  EXPECT(igaparam_spline_invert(s, 1, far, 4, u, &f), IGAPARAM_STATUS_OK);
  CHECK(f == 0 && isnan(u[0]), "a point far outside was located at (%g, %g)", u[0], u[1]);
}

static void test_validity(const igaparam_spline *s) {
  size_t ne = 0;
  EXPECT(igaparam_spline_element_count(s, &ne), IGAPARAM_STATUS_OK);
  double *lower = malloc(ne * sizeof *lower), *quality = malloc(ne * sizeof *quality);
  igaparam_validity_report r;
  memset(&r, 0, sizeof r);
  EXPECT(igaparam_spline_check_validity(s, NULL, &r, lower, quality, ne), IGAPARAM_STATUS_OK);
  CHECK(r.certified_positive == 1 && r.uncertified == 0, "not certified: %zu elements",
        r.uncertified);
  CHECK(r.det_lower_bound > 0, "det lower bound %g", r.det_lower_bound);
  CHECK(r.min_quality > 0 && r.min_quality <= r.mean_quality && r.mean_quality <= 1,
        "quality min %g mean %g", r.min_quality, r.mean_quality);
  size_t total = 0;
  for (int b = 0; b < IGAPARAM_HISTOGRAM_BINS; b++) total += r.histogram[b];
  CHECK(total > 0, "empty histogram");
  double smallest = INFINITY;
  for (size_t e = 0; e < ne; e++) smallest = fmin(smallest, lower[e]);
  CHECK(smallest == r.det_lower_bound, "per-element bounds' minimum %g vs %g", smallest,
        r.det_lower_bound);
  printf("male rotor spline: %zu elements, min q %.3f, mean q %.3f, det >= %.3g, certified %d\n",
         ne, r.min_quality, r.mean_quality, r.det_lower_bound, r.certified_positive);
  free(lower);
  free(quality);
}

/* The certification against an independent dense evaluation: on every element, det J from the
 * Jacobians of igaparam_spline_evaluate at a DENSE × DENSE grid (which holds the certification's
 * 5 × 5 samples, at multiples of 1/4 of the element) is positive when the map is certified, and
 * at least the element's certified lower bound; the mean ratio recomputed at the sample points
 * is the reported per-element sampled minimum, and the dense minimum is at most it (the samples
 * are a subset of the grid, so the dense minimum can only be smaller). */
#define DENSE 17
static void test_dense_det(const igaparam_spline *s) {
  size_t ne = 0;
  EXPECT(igaparam_spline_element_count(s, &ne), IGAPARAM_STATUS_OK);
  double *lower = malloc(ne * sizeof *lower), *quality = malloc(ne * sizeof *quality);
  double *bounds = malloc(4 * ne * sizeof *bounds);
  igaparam_validity_report r;
  EXPECT(igaparam_spline_check_validity(s, NULL, &r, lower, quality, ne), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_copy_elements(s, NULL, bounds, ne), IGAPARAM_STATUS_OK);
  double uv[2 * DENSE * DENSE], jac[4 * DENSE * DENSE];
  size_t nonpositive = 0, below_bound = 0, sample_mismatch = 0;
  double dense_min_q = INFINITY, dense_min_det = INFINITY;
  for (size_t e = 0; e < ne; e++) {
    const double *b = bounds + 4 * e;
    for (int j = 0; j < DENSE; j++)
      for (int i = 0; i < DENSE; i++) {
        uv[2 * (j * DENSE + i)] = b[0] + (b[2] - b[0]) * i / (DENSE - 1);
        uv[2 * (j * DENSE + i) + 1] = b[1] + (b[3] - b[1]) * j / (DENSE - 1);
      }
    EXPECT(igaparam_spline_evaluate(s, DENSE * DENSE, uv, NULL, jac), IGAPARAM_STATUS_OK);
    double element_min_det = INFINITY, sample_min_q = INFINITY;
    for (int k = 0; k < DENSE * DENSE; k++) {
      const double *J = jac + 4 * k;
      double det = J[0] * J[3] - J[1] * J[2];
      double norm2 = J[0] * J[0] + J[1] * J[1] + J[2] * J[2] + J[3] * J[3];
      double q = det > 0 ? 2 * det / norm2 : 0;
      element_min_det = fmin(element_min_det, det);
      dense_min_q = fmin(dense_min_q, q);
      if ((k % DENSE) % 4 == 0 && (k / DENSE) % 4 == 0) sample_min_q = fmin(sample_min_q, q);
    }
    dense_min_det = fmin(dense_min_det, element_min_det);
    nonpositive += !(element_min_det > 0);
    /* A lower bound, up to the round-off of two evaluations of the same polynomial. */
    below_bound += element_min_det < lower[e] - 1e-9 * fabs(lower[e]);
    sample_mismatch += fabs(sample_min_q - quality[e]) > 1e-9;
  }
  CHECK(r.certified_positive == 1 && nonpositive == 0,
        "certified %d, but det J <= 0 at a dense sample of %zu elements", r.certified_positive,
        nonpositive);
  CHECK(below_bound == 0, "%zu elements have a dense det J under their certified lower bound",
        below_bound);
  CHECK(r.det_lower_bound <= dense_min_det * (1 + 1e-9), "lower bound %g, dense minimum %g",
        r.det_lower_bound, dense_min_det);
  CHECK(sample_mismatch == 0, "%zu elements' sampled minimum q differs from the recomputed one",
        sample_mismatch);
  CHECK(dense_min_q <= r.min_quality + 1e-12 && dense_min_q > 0,
        "dense minimum q %g, reported sampled minimum %g", dense_min_q, r.min_quality);
  printf("dense check: %zu elements x %d^2 points, det J >= %.4g (certified bound %.4g), min q %.4f "
         "(sampled %.4f)\n",
         ne, DENSE, dense_min_det, r.det_lower_bound, dense_min_q, r.min_quality);
  /* The certified lower bound of q lies under every dense value, near the sampled minimum. */
  igaparam_quality_bound_report qb;
  EXPECT(igaparam_spline_quality_bound(s, NULL, &qb), IGAPARAM_STATUS_OK);
  CHECK(qb.lower_bound <= dense_min_q && qb.lower_bound >= 0.9 * qb.sampled_min &&
            qb.sampled_min == r.min_quality && qb.element < ne,
        "quality bound %.6f, dense %.6f, sampled %.6f (validity %.6f), element %zu",
        qb.lower_bound, dense_min_q, qb.sampled_min, r.min_quality, qb.element);
  igaparam_quality_bound_options qo = igaparam_quality_bound_options_default();
  qo.gap = 1.0;
  igaparam_quality_bound_report untouched = qb;
  EXPECT(igaparam_spline_quality_bound(s, &qo, &qb), IGAPARAM_STATUS_INVALID_ARGUMENT);
  char message[512];
  igaparam_last_error_message(message, sizeof message);
  CHECK(strstr(message, "gap") && qb.lower_bound == untouched.lower_bound, "%s", message);
  EXPECT(igaparam_spline_quality_bound(s, NULL, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  printf("quality bound: %.4f <= min q <= %.4f\n", qb.lower_bound, qb.sampled_min);
  free(lower);
  free(quality);
  free(bounds);
}

/* Checks that two splines of the same number of elements have the same validity (summary and
 * per-element arrays, bit for bit) under `o` (NULL: the defaults). */
static void same_validity(const igaparam_spline *a, const igaparam_spline *b,
                          const igaparam_validity_options *o, const char *what) {
  size_t na = 0, nb = 0;
  EXPECT(igaparam_spline_element_count(a, &na), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_element_count(b, &nb), IGAPARAM_STATUS_OK);
  CHECK(na == nb && na > 0, "%s: %zu vs %zu elements", what, na, nb);
  if (na != nb || na == 0) return;
  double *bounds[2], *quality[2];
  igaparam_validity_report r[2];
  const igaparam_spline *s[2] = {a, b};
  for (int i = 0; i < 2; i++) {
    bounds[i] = malloc(na * sizeof *bounds[i]);
    quality[i] = malloc(na * sizeof *quality[i]);
    for (size_t e = 0; e < na; e++) bounds[i][e] = quality[i][e] = -7.0 - i;
    memset(&r[i], 0, sizeof r[i]);
    EXPECT(igaparam_spline_check_validity(s[i], o, &r[i], bounds[i], quality[i], na),
           IGAPARAM_STATUS_OK);
  }
  CHECK(r[0].certified_positive == r[1].certified_positive && r[0].uncertified == r[1].uncertified &&
            r[0].det_lower_bound == r[1].det_lower_bound && r[0].min_quality == r[1].min_quality &&
            r[0].mean_quality == r[1].mean_quality &&
            memcmp(r[0].histogram, r[1].histogram, sizeof r[0].histogram) == 0,
        "%s: reports differ (det >= %.17g vs %.17g, min q %.17g vs %.17g, mean q %.17g vs %.17g)",
        what, r[0].det_lower_bound, r[1].det_lower_bound, r[0].min_quality, r[1].min_quality,
        r[0].mean_quality, r[1].mean_quality);
  CHECK(memcmp(bounds[0], bounds[1], na * sizeof *bounds[0]) == 0,
        "%s: per-element det bounds differ", what);
  CHECK(memcmp(quality[0], quality[1], na * sizeof *quality[0]) == 0,
        "%s: per-element qualities differ", what);
  for (int i = 0; i < 2; i++) {
    free(bounds[i]);
    free(quality[i]);
  }
}

/* The validity a fit keeps in its handle is what a computation gives: compare the fitted spline
 * with its G+Smo XML copy (the same map, read back without a kept validity) under the default
 * options (kept by the fit) and others (computed for both), then a clone of the fit (which keeps
 * it) and, after the same refinement of both, which changes the elements, again. */
static void test_kept_validity(const igaparam_spline *s) {
  const char *xml = joined(out_dir, "male_fit.xml");
  EXPECT(igaparam_spline_write_gismo(s, xml), IGAPARAM_STATUS_OK);
  igaparam_spline *copy = NULL, *clone = NULL;
  EXPECT(igaparam_spline_read_gismo(xml, &copy), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_clone(s, &clone), IGAPARAM_STATUS_OK);
  if (!copy || !clone) return;
  same_validity(s, copy, NULL, "fit vs its XML copy");
  igaparam_validity_options other = igaparam_validity_options_default();
  other.samples = 7;
  other.max_depth = 3;
  same_validity(s, copy, &other, "fit vs its XML copy, other options");
  igaparam_validity_options defaults = igaparam_validity_options_default();
  same_validity(s, copy, &defaults, "fit vs its XML copy, default options again");
  same_validity(clone, copy, NULL, "clone vs XML copy");
  size_t marked[3] = {0, 5, 9};
  EXPECT(igaparam_spline_refine(clone, 3, marked, NULL), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_refine(copy, 3, marked, NULL), IGAPARAM_STATUS_OK);
  same_validity(clone, copy, NULL, "refined clone vs refined XML copy");
  igaparam_spline_free(clone);
  igaparam_spline_free(copy);
}

/* The largest difference between the images of `n` points under two splines. */
static double distance(const igaparam_spline *a, const igaparam_spline *b) {
  double params[2 * SAMPLES], pa[2 * SAMPLES], pb[2 * SAMPLES];
  for (int i = 0; i < 2 * SAMPLES; i++) params[i] = uniform();
  EXPECT(igaparam_spline_evaluate(a, SAMPLES, params, pa, NULL), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_evaluate(b, SAMPLES, params, pb, NULL), IGAPARAM_STATUS_OK);
  double worst = 0;
  for (int i = 0; i < 2 * SAMPLES; i++) worst = fmax(worst, fabs(pa[i] - pb[i]));
  return worst;
}

static void test_refine_and_files(const igaparam_spline *s) {
  igaparam_spline *r = NULL;
  EXPECT(igaparam_spline_clone(s, &r), IGAPARAM_STATUS_OK);
  size_t before = 0, after = 0;
  EXPECT(igaparam_spline_basis_count(r, &before), IGAPARAM_STATUS_OK);
  size_t marked[2] = {0, 3};
  igaparam_fit_report report;
  EXPECT(igaparam_spline_refine(r, 2, marked, &report), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_basis_count(r, &after), IGAPARAM_STATUS_OK);
  CHECK(after > before && report.basis_count == after, "refinement: %zu -> %zu functions", before,
        after);
  CHECK(distance(s, r) < 1e-9, "local refinement changed the map by %g", distance(s, r));
  EXPECT(igaparam_spline_refine(r, 0, NULL, NULL), IGAPARAM_STATUS_OK);
  CHECK(distance(s, r) < 1e-9, "uniform refinement changed the map by %g", distance(s, r));
  EXPECT(igaparam_spline_basis_count(r, &after), IGAPARAM_STATUS_OK);

  const char *xml = joined(out_dir, "male_spline.xml");
  EXPECT(igaparam_spline_write_gismo(r, xml), IGAPARAM_STATUS_OK);
  igaparam_spline *back = NULL;
  EXPECT(igaparam_spline_read_gismo(xml, &back), IGAPARAM_STATUS_OK);
  size_t nb = 0;
  EXPECT(igaparam_spline_basis_count(back, &nb), IGAPARAM_STATUS_OK);
  CHECK(nb == after, "read back %zu functions, wrote %zu", nb, after);
  CHECK(distance(r, back) < 1e-12, "XML round trip changed the map by %g", distance(r, back));
  size_t d = 0;
  EXPECT(igaparam_spline_dimension(back, &d), IGAPARAM_STATUS_OK);
  CHECK(d == 2, "dimension %zu", d);
  EXPECT(igaparam_spline_write_vtu(s, joined(out_dir, "male_spline.vtu"), 4), IGAPARAM_STATUS_OK);
  size_t ne = 0;
  EXPECT(igaparam_spline_element_count(s, &ne), IGAPARAM_STATUS_OK);
  /* 4 x 4 quads on a 5 x 5 grid of points per element. */
  static const char *const arrays[] = {"quality", "det", "level", "element"};
  check_vtu_file(joined(out_dir, "male_spline.vtu"), 25 * ne, 16 * ne, arrays, 4);
  igaparam_spline_free(back);
  igaparam_spline_free(r);
}

static void test_errors(igaparam_spline *s) {
  size_t n = 7, nb = 0, ne = 0;
  EXPECT(igaparam_spline_basis_count(s, &nb), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_element_count(s, &ne), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_spline_basis_count(NULL, &n), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_spline_basis_count(s, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);

  /* Unbuilt domain; NULL domain. The out handle stays untouched. */
  igaparam_domain *domain = NULL;
  EXPECT(igaparam_domain_new_from_file(joined(data_dir, "male_bdry.xml"), &domain),
         IGAPARAM_STATUS_OK);
  igaparam_spline *untouched = (igaparam_spline *)(uintptr_t)0x1234;
  EXPECT(igaparam_spline_fit_domain(domain, &untouched, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_spline_fit_domain(NULL, &untouched, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_spline_fit_domain(domain, NULL, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  CHECK(untouched == (igaparam_spline *)(uintptr_t)0x1234, "a failed fit wrote the handle");
  igaparam_domain_free(domain);

  /* Parameters outside [0,1]^2, not finite; outputs not written. */
  double bad[2] = {0.5, 1.5}, nan2[2] = {0.5, NAN}, out[2] = {-7, -7};
  EXPECT(igaparam_spline_evaluate(s, 1, bad, out, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_spline_evaluate(s, 1, nan2, out, NULL), IGAPARAM_STATUS_NOT_FINITE);
  EXPECT(igaparam_spline_evaluate(s, 1, NULL, out, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_spline_evaluate(s, SIZE_MAX, bad, out, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(out[0] == -7 && out[1] == -7, "a failed evaluation wrote its output");
  EXPECT(igaparam_spline_mean_ratio(s, 1, bad, out), IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_spline_basis_count_at(s, bad, &n), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(strncmp(message(), "igaparam_spline_basis_count_at:", 31) == 0,
        "the message names another function: %s", message());
  EXPECT(igaparam_spline_invert(s, 1, nan2, 4, out, NULL), IGAPARAM_STATUS_NOT_FINITE);
  EXPECT(igaparam_spline_invert(s, 1, bad, 1, out, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_spline_invert(s, 1, bad, 4, NULL, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);

  /* Buffers too small; element out of range. */
  double small[1];
  EXPECT(igaparam_spline_copy_control_points(s, small, 1), IGAPARAM_STATUS_BUFFER_TOO_SMALL);
  double p[2] = {0.5, 0.5};
  size_t f[1] = {SIZE_MAX}, m_at = 0;
  EXPECT(igaparam_spline_basis_count_at(s, p, &m_at), IGAPARAM_STATUS_OK);
  n = 0;
  EXPECT(igaparam_spline_basis_at(s, p, &n, f, NULL, NULL, 1), IGAPARAM_STATUS_BUFFER_TOO_SMALL);
  CHECK(n == m_at && f[0] == SIZE_MAX, "too small: count %zu (needed %zu), functions written",
        n, m_at);
  /* An overstated length is harmless: only the functions needed are written. */
  double *vg = malloc(3 * m_at * sizeof(double));
  EXPECT(igaparam_spline_basis_at(s, p, &n, NULL, vg, vg + m_at, SIZE_MAX), IGAPARAM_STATUS_OK);
  free(vg);
  EXPECT(igaparam_spline_element_function_count(s, ne, &n), IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_spline_copy_elements(s, NULL, small, 0), IGAPARAM_STATUS_BUFFER_TOO_SMALL);

  /* A failed refinement leaves the spline as it was. */
  size_t marked[1] = {ne};
  EXPECT(igaparam_spline_refine(s, 1, marked, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_spline_refine(s, 1, NULL, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  /* An element marked twice is refused, naming the caller's positions (not a cell index). */
  size_t twice[3] = {1, 0, 1};
  EXPECT(igaparam_spline_refine(s, 3, twice, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  CHECK(strstr(message(), "elements[2] = 1 repeats elements[0]") != NULL, "repeated element: %s",
        message());
  size_t still = 0;
  EXPECT(igaparam_spline_basis_count(s, &still), IGAPARAM_STATUS_OK);
  CHECK(still == nb, "a failed refinement changed the basis: %zu -> %zu", nb, still);

  igaparam_validity_options vo = igaparam_validity_options_default();
  vo.samples = 1;
  igaparam_validity_report vr;
  EXPECT(igaparam_spline_check_validity(s, &vo, &vr, NULL, NULL, 0),
         IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_spline_check_validity(s, NULL, NULL, NULL, NULL, 0),
         IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_spline_write_vtu(s, joined(out_dir, "x.vtu"), 0), IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_spline_write_gismo(s, "/nonexistent-dir/x.xml"), IGAPARAM_STATUS_IO);
  EXPECT(igaparam_spline_write_gismo(s, ""), IGAPARAM_STATUS_INVALID_ARGUMENT);

  /* Reading: missing file, a file that holds no THB spline (a format error, as for every reader). */
  igaparam_spline *r = (igaparam_spline *)(uintptr_t)0x1234;
  EXPECT(igaparam_spline_read_gismo(joined(out_dir, "missing.xml"), &r), IGAPARAM_STATUS_IO);
  EXPECT(igaparam_spline_read_gismo(joined(data_dir, "male_bdry.xml"), &r), IGAPARAM_STATUS_IO);
  CHECK(r == (igaparam_spline *)(uintptr_t)0x1234, "a failed read wrote the handle");
  igaparam_spline_free(NULL);
}

static int cancel(void *user, igaparam_stage stage, size_t done, size_t total) {
  (void)done;
  (void)total;
  *(int *)user += stage == IGAPARAM_STAGE_ADAPTATION;
  return 1;
}

/* The adaptive loop on the rotor, whose first (smoothed) spline map has min q_S 0.34 < 0.4. */
static void test_adapt(void) {
  igaparam_domain *domain = NULL;
  EXPECT(igaparam_domain_new_from_file(joined(data_dir, "rotor_bdry.xml"), &domain),
         IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_build(domain, NULL, NULL), IGAPARAM_STATUS_OK);
  size_t cells = 0, after = 0;
  EXPECT(igaparam_domain_cell_count(domain, &cells), IGAPARAM_STATUS_OK);

  /* Cancelled at the first refinement: the domain is unchanged, no handle written. */
  igaparam_adapt_options options = igaparam_adapt_options_default();
  options.target_quality = 0.4;
  int calls = 0;
  options.progress = cancel;
  options.progress_user = &calls;
  igaparam_spline *s = (igaparam_spline *)(uintptr_t)0x1234;
  EXPECT(igaparam_domain_fit_adaptive(domain, &options, &s, NULL), IGAPARAM_STATUS_CANCELLED);
  EXPECT(igaparam_domain_cell_count(domain, &after), IGAPARAM_STATUS_OK);
  CHECK(calls == 1 && after == cells && s == (igaparam_spline *)(uintptr_t)0x1234,
        "cancellation: %d calls, %zu -> %zu cells", calls, cells, after);

  options = igaparam_adapt_options_default();
  options.target_quality = 2.0;
  EXPECT(igaparam_domain_fit_adaptive(domain, &options, &s, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  options.target_quality = NAN;
  EXPECT(igaparam_domain_fit_adaptive(domain, &options, &s, NULL), IGAPARAM_STATUS_NOT_FINITE);
  EXPECT(igaparam_domain_fit_adaptive(domain, NULL, NULL, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);

  igaparam_adapt_report r;
  memset(&r, 0, sizeof r);
  s = NULL;
  options = igaparam_adapt_options_default();
  options.target_quality = 0.4;
  EXPECT(igaparam_domain_fit_adaptive(domain, &options, &s, &r), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_cell_count(domain, &after), IGAPARAM_STATUS_OK);
  CHECK(r.reached == 1 && r.certified_positive == 1 && r.min_quality >= 0.4,
        "adaptation: reached %d, certified %d, min q %g", r.reached, r.certified_positive,
        r.min_quality);
  CHECK(r.rounds >= 1 && r.refined_cells > 0 && after > cells && r.elements == after,
        "adaptation: %u rounds, %zu refined, %zu -> %zu cells, %zu elements", r.rounds,
        r.refined_cells, cells, after, r.elements);
  igaparam_validity_report v;
  EXPECT(igaparam_spline_check_validity(s, NULL, &v, NULL, NULL, 0), IGAPARAM_STATUS_OK);
  CHECK(v.certified_positive == 1 && v.min_quality == r.min_quality,
        "the spline returned: certified %d, min q %g", v.certified_positive, v.min_quality);
  printf("rotor adaptation: %u rounds, %zu -> %zu cells, min q %.3f, mean q %.3f\n", r.rounds,
         cells, after, r.min_quality, r.mean_quality);
  /* The validity the adaptive fit keeps is that of its map, read back from XML. */
  const char *xml = joined(out_dir, "rotor_adapted.xml");
  EXPECT(igaparam_spline_write_gismo(s, xml), IGAPARAM_STATUS_OK);
  igaparam_spline *copy = NULL;
  EXPECT(igaparam_spline_read_gismo(xml, &copy), IGAPARAM_STATUS_OK);
  if (copy) same_validity(s, copy, NULL, "adaptive fit vs its XML copy");
  igaparam_spline_free(copy);
  igaparam_spline_free(s);

  /* Unbuilt domain. */
  igaparam_domain *fresh = NULL;
  EXPECT(igaparam_domain_new_from_file(joined(data_dir, "puzzle3_bdry.xml"), &fresh),
         IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_fit_adaptive(fresh, NULL, &s, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  igaparam_domain_free(fresh);
  igaparam_domain_free(domain);
}

/* Gran Canaria: the fitted map folds next to the kinked coastline; the fit untangles its inner
 * control points, keeps the boundary, and the map is certified. */
static void test_untangled_fit(void) {
  igaparam_fit_report report;
  igaparam_spline *spline = fit_file("gran_canaria.txt", &report);
  if (!spline) return;
  CHECK(report.untangled > 0, "untangled %zu control points", report.untangled);
  CHECK(report.boundary_offset == 0.0, "boundary moved by %g", report.boundary_offset);
  igaparam_validity_report v;
  EXPECT(igaparam_spline_check_validity(spline, NULL, &v, NULL, NULL, 0), IGAPARAM_STATUS_OK);
  CHECK(v.certified_positive && v.uncertified == 0, "%zu uncertified elements", v.uncertified);
  igaparam_spline_free(spline);
}

/* Progress calls of a fit by stage; cancels at the first call of stage `stop` (-1: never). */
typedef struct {
  int calls[7];
  int stop;
  size_t last_done[7];
  int ordered;
} fit_calls;

static int count_fit(void *user, igaparam_stage stage, size_t done, size_t total) {
  fit_calls *c = (fit_calls *)user;
  if ((int)stage < 0 || (int)stage > 6 || done > total) {
    c->ordered = 0;
    return 1;
  }
  if (c->calls[stage] > 0 && done < c->last_done[stage]) c->ordered = 0;
  c->calls[stage] += 1;
  c->last_done[stage] = done;
  return (int)stage == c->stop;
}

/* Fits `domain` with `options` and returns its control points (malloc'ed, `*n` of them). */
static double *fitted_points(const igaparam_domain *domain, const igaparam_fit_options *options,
                             size_t *n) {
  igaparam_spline *s = NULL;
  *n = 0;
  if (options)
    EXPECT(igaparam_spline_fit_domain_with(domain, options, &s, NULL), IGAPARAM_STATUS_OK);
  else
    EXPECT(igaparam_spline_fit_domain(domain, &s, NULL), IGAPARAM_STATUS_OK);
  if (!s) return NULL;
  EXPECT(igaparam_spline_basis_count(s, n), IGAPARAM_STATUS_OK);
  double *p = malloc(2 * *n * sizeof *p);
  EXPECT(igaparam_spline_copy_control_points(s, p, 2 * *n), IGAPARAM_STATUS_OK);
  igaparam_spline_free(s);
  return p;
}

static int same_points(const double *a, size_t na, const double *b, size_t nb) {
  return a && b && na == nb && memcmp(a, b, 2 * na * sizeof *a) == 0;
}

/* igaparam_spline_fit_domain_with on Gran Canaria (its fit is untangled): the defaults give the
 * plain fit, threads do not change it, progress sees the fit, untangling and smoothing stages
 * and cancels at each, options are checked, nothing is written on failure. */
static void test_fit_with(void) {
  igaparam_domain *domain = NULL;
  EXPECT(igaparam_domain_new_from_file(joined(data_dir, "gran_canaria.txt"), &domain),
         IGAPARAM_STATUS_OK);
  igaparam_spline *untouched = (igaparam_spline *)(uintptr_t)0x1234, *s = untouched;
  EXPECT(igaparam_spline_fit_domain_with(domain, NULL, &s, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_domain_build(domain, NULL, NULL), IGAPARAM_STATUS_OK);
  size_t n0, n1, n2, n3;
  double *plain = fitted_points(domain, NULL, &n0);
  igaparam_fit_options options = igaparam_fit_options_default();
  double *defaults = fitted_points(domain, &options, &n1);
  options.threads = 1;
  double *one = fitted_points(domain, &options, &n2);
  options.threads = 2;
  fit_calls calls = {{0}, -1, {0}, 1};
  options.progress = count_fit;
  options.progress_user = &calls;
  double *two = fitted_points(domain, &options, &n3);
  CHECK(same_points(plain, n0, defaults, n1), "the default options change the fit");
  CHECK(same_points(one, n2, two, n3) && same_points(plain, n0, one, n2),
        "1 and 2 threads differ");
  CHECK(calls.calls[IGAPARAM_STAGE_FIT] == 5 && calls.calls[IGAPARAM_STAGE_UNTANGLING] > 0 &&
            calls.calls[IGAPARAM_STAGE_SMOOTHING] > 0 && calls.ordered,
        "progress: %d fit, %d untangling, %d smoothing calls, ordered %d",
        calls.calls[IGAPARAM_STAGE_FIT], calls.calls[IGAPARAM_STAGE_UNTANGLING],
        calls.calls[IGAPARAM_STAGE_SMOOTHING], calls.ordered);
  free(plain);
  free(defaults);
  free(one);
  free(two);

  igaparam_stage stops[3] = {IGAPARAM_STAGE_FIT, IGAPARAM_STAGE_UNTANGLING,
                             IGAPARAM_STAGE_SMOOTHING};
  for (int i = 0; i < 3; ++i) {
    fit_calls stop = {{0}, (int)stops[i], {0}, 1};
    options.progress_user = &stop;
    igaparam_fit_report report = {0};
    report.basis_count = 77;
    EXPECT(igaparam_spline_fit_domain_with(domain, &options, &s, &report),
           IGAPARAM_STATUS_CANCELLED);
    CHECK(s == untouched && report.basis_count == 77 && stop.calls[stops[i]] == 1,
          "cancel at stage %d wrote its outputs", (int)stops[i]);
  }

  igaparam_fit_options bad = igaparam_fit_options_default();
  bad.validity.samples = 1;
  EXPECT(igaparam_spline_fit_domain_with(domain, &bad, &s, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  bad = igaparam_fit_options_default();
  bad.choice = 9;
  EXPECT(igaparam_spline_fit_domain_with(domain, &bad, &s, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  bad = igaparam_fit_options_default();
  bad.boundary_offset = NAN;
  EXPECT(igaparam_spline_fit_domain_with(domain, &bad, &s, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  bad = igaparam_fit_options_default();
  bad.threads = 5000;
  EXPECT(igaparam_spline_fit_domain_with(domain, &bad, &s, NULL), IGAPARAM_STATUS_INVALID_ARGUMENT);
  EXPECT(igaparam_spline_fit_domain_with(domain, NULL, NULL, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  EXPECT(igaparam_spline_fit_domain_with(NULL, NULL, &s, NULL), IGAPARAM_STATUS_NULL_ARGUMENT);
  CHECK(s == untouched, "a failed fit wrote the handle");

  /* Untangling off: the folded fit is returned uncertified. */
  options = igaparam_fit_options_default();
  options.untangle_rounds = 0;
  s = NULL;
  EXPECT(igaparam_spline_fit_domain_with(domain, &options, &s, NULL), IGAPARAM_STATUS_OK);
  igaparam_validity_report v;
  EXPECT(igaparam_spline_check_validity(s, NULL, &v, NULL, NULL, 0), IGAPARAM_STATUS_OK);
  CHECK(!v.certified_positive && v.uncertified > 0, "untangling off: %zu uncertified",
        v.uncertified);
  igaparam_spline_free(s);
  igaparam_domain_free(domain);
}

/* One run of the rotor at `threads` threads: the built T-mesh's physical vertices, the checked
 * fit's control points, then the adaptive loop's control points and report. */
typedef struct {
  double *vertices, *fitted, *adapted;
  size_t nv, nf, na;
  igaparam_domain_report built;
  igaparam_adapt_report adapt;
} thread_run;

static double *control_points(const igaparam_spline *s, size_t *n) {
  *n = 0;
  EXPECT(igaparam_spline_basis_count(s, n), IGAPARAM_STATUS_OK);
  double *p = malloc(2 * *n * sizeof *p + 1);
  EXPECT(igaparam_spline_copy_control_points(s, p, 2 * *n), IGAPARAM_STATUS_OK);
  return p;
}

static thread_run run_rotor(uint32_t threads) {
  thread_run run;
  memset(&run, 0, sizeof run);
  igaparam_domain *domain = NULL;
  EXPECT(igaparam_domain_new_from_file(joined(data_dir, "rotor_bdry.xml"), &domain), IGAPARAM_STATUS_OK);
  if (!domain) return run;
  igaparam_domain_options o = igaparam_domain_options_default();
  o.threads = threads;
  EXPECT(igaparam_domain_build(domain, &o, &run.built), IGAPARAM_STATUS_OK);
  EXPECT(igaparam_domain_vertex_count(domain, &run.nv), IGAPARAM_STATUS_OK);
  run.vertices = malloc(2 * run.nv * sizeof *run.vertices + 1);
  EXPECT(igaparam_domain_copy_vertices(domain, NULL, run.vertices, 2 * run.nv), IGAPARAM_STATUS_OK);
  igaparam_fit_options f = igaparam_fit_options_default();
  f.threads = threads;
  igaparam_spline *s = NULL;
  EXPECT(igaparam_spline_fit_domain_with(domain, &f, &s, NULL), IGAPARAM_STATUS_OK);
  if (s) run.fitted = control_points(s, &run.nf);
  igaparam_spline_free(s);
  igaparam_adapt_options a = igaparam_adapt_options_default();
  a.target_quality = 0.4;
  a.threads = threads;
  s = NULL;
  EXPECT(igaparam_domain_fit_adaptive(domain, &a, &s, &run.adapt), IGAPARAM_STATUS_OK);
  if (s) run.adapted = control_points(s, &run.na);
  igaparam_spline_free(s);
  igaparam_domain_free(domain);
  return run;
}

/* The domain build, the fit and the adaptive loop give the same bits at 1, 2 and 4 threads
 * (4 is capped to the machine's cores). */
static void test_threads(void) {
  const uint32_t threads[3] = {1, 2, 4};
  thread_run runs[3];
  for (int i = 0; i < 3; i++) runs[i] = run_rotor(threads[i]);
  CHECK(runs[0].adapt.rounds >= 1 && runs[0].adapt.reached, "the rotor's loop did not refine");
  for (int i = 1; i < 3; i++) {
    thread_run *a = &runs[0], *b = &runs[i];
    CHECK(same_points(a->vertices, a->nv, b->vertices, b->nv), "%u threads: other T-mesh vertices",
          threads[i]);
    CHECK(a->built.cells == b->built.cells && a->built.sweeps == b->built.sweeps &&
              a->built.min_quality == b->built.min_quality &&
              a->built.boundary_error == b->built.boundary_error,
          "%u threads: another build report", threads[i]);
    CHECK(same_points(a->fitted, a->nf, b->fitted, b->nf), "%u threads: another fit", threads[i]);
    CHECK(same_points(a->adapted, a->na, b->adapted, b->na), "%u threads: another adapted map",
          threads[i]);
    CHECK(a->adapt.rounds == b->adapt.rounds && a->adapt.refined_cells == b->adapt.refined_cells &&
              a->adapt.min_quality == b->adapt.min_quality &&
              a->adapt.mean_quality == b->adapt.mean_quality && a->adapt.untangled == b->adapt.untangled,
          "%u threads: another adapt report", threads[i]);
  }
  for (int i = 0; i < 3; i++) {
    free(runs[i].vertices);
    free(runs[i].fitted);
    free(runs[i].adapted);
  }
}

int main(int argc, char **argv) {
  if (!read_dirs(argc, argv)) return 2;
  igaparam_spline *s = fit_male();
  if (s) {
    test_basis_agrees_with_evaluation(s);
    test_extraction(s);
    test_greville(s);
    test_inverse(s);
    test_validity(s);
    test_dense_det(s);
    test_kept_validity(s);
    test_refine_and_files(s);
    test_errors(s);
    igaparam_spline_free(s);
  }
  test_adapt();
  test_untangled_fit();
  test_fit_with();
  test_threads();
  printf("%d passed, %d failed\n", passed, failed);
  return failed == 0 ? 0 : 1;
}
