/*
 * Tests of the handle rules of the C API: a handle takes one call at a time. A call on a handle
 * in use, made from the progress callback of a running call on it or from another thread, is
 * refused with IGAPARAM_STATUS_BUSY and a message naming the function; *_free of a handle in use
 * is deferred: the running call cancels and the handle is released as it returns (run under
 * AddressSanitizer or valgrind, a release under the running call is a use after free).
 * Prints "N passed, M failed"; exits non-zero if any check failed.
 */

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "igaparam.h"
#include "structured_grid.h"

#include "check.h"

static const double PI = 3.14159265358979323846;

#define CHECK(cond) check_at((cond) != 0, __FILE__, __LINE__, "%s", #cond)
#define CHECKF(cond, ...) check_at((cond) != 0, __FILE__, __LINE__, __VA_ARGS__)

static const char *last_message(void) {
  static _Thread_local char buffer[1024];
  igaparam_last_error_message(buffer, sizeof buffer);
  return buffer;
}

/* `status` is BUSY and the message names `function` and says the handle is in use. */
#define CHECK_BUSY(status, function)                                                          \
  CHECKF((status) == IGAPARAM_STATUS_BUSY && strstr(last_message(), function) &&              \
             strstr(last_message(), "in use"),                                                \
         "%s: status %d, message \"%s\"", function, (int)(status), last_message())

/* A Q4 grid of the unit square, boundary fixed, interior nodes pushed so that relocation works. */
static igaparam_mesh *new_mesh(size_t n) {
  structured_grid g;
  if (structured_grid_init(&g, IGAPARAM_CELL_QUAD4, n, n, 1) != 0) {
    return NULL;
  }
  igaparam_mesh *mesh = NULL;
  uint8_t *mask = structured_grid_boundary_mask(&g);
  if (igaparam_mesh_new(g.type, g.num_nodes, g.xyz, g.num_cells, g.connectivity, &mesh) ==
          IGAPARAM_STATUS_OK &&
      mask) {
    igaparam_mesh_set_fixed(mesh, g.num_nodes, mask);
    /* Move the top side up by a bump: the free nodes have to follow. */
    for (size_t i = 0; i < g.lattice[0]; i++) {
      int64_t v = (int64_t)structured_grid_node(&g, i, g.lattice[1] - 1, 0);
      double x = g.xyz[3 * v], p[3] = {x, 1.0 + 0.5 * sin(PI * x), 0.0};
      igaparam_mesh_move_nodes(mesh, 1, &v, p);
    }
  }
  free(mask);
  structured_grid_free(&g);
  return mesh;
}

/* ------------------------------------------------------------------------------------------ */

typedef struct {
  igaparam_mesh *mesh;
  int calls, freed;
} mesh_probe;

/* Every call on the mesh from its own relocation's callback is BUSY; the last call frees it. */
static int mesh_probe_progress(void *user, igaparam_stage stage, size_t done, size_t total) {
  (void)stage, (void)done, (void)total;
  mesh_probe *p = user;
  if (p->freed) {
    return 0; /* the relocation must cancel by itself */
  }
  p->calls++;
  size_t count = 0;
  CHECK_BUSY(igaparam_mesh_node_count(p->mesh, &count), "igaparam_mesh_node_count");
  CHECK(count == 0);
  CHECK_BUSY(igaparam_mesh_relocate(p->mesh, NULL, NULL), "igaparam_mesh_relocate");
  CHECK_BUSY(igaparam_mesh_reset_reference(p->mesh), "igaparam_mesh_reset_reference");
  double xyz[3];
  CHECK_BUSY(igaparam_mesh_copy_positions(p->mesh, xyz, 3), "igaparam_mesh_copy_positions");
  if (p->calls == 2) {
    igaparam_mesh_free(p->mesh);
    p->freed = 1;
  }
  return 0;
}

static void test_mesh_reentry(void) {
  mesh_probe probe = {new_mesh(8), 0, 0};
  CHECK(probe.mesh != NULL);
  igaparam_relocate_options o = igaparam_relocate_options_default();
  o.progress = mesh_probe_progress;
  o.progress_user = &probe;
  igaparam_relocate_report report;
  memset(&report, 0x5A, sizeof report);
  igaparam_status status = igaparam_mesh_relocate(probe.mesh, &o, &report);
  CHECKF(probe.freed, "the callback was called %d times", probe.calls);
  /* Freed during the call: the relocation stopped (and released the mesh as it returned). */
  CHECKF(status == IGAPARAM_STATUS_CANCELLED, "status %d: %s", (int)status, last_message());
}

/* Without a callback the same mesh relocates, and is usable again after a refused call. */
static void test_mesh_usable_after_busy(void) {
  igaparam_mesh *mesh = new_mesh(4);
  mesh_probe probe = {mesh, 0, 1}; /* `freed` set: the callback only counts nothing */
  igaparam_relocate_options o = igaparam_relocate_options_default();
  o.progress = mesh_probe_progress;
  o.progress_user = &probe;
  CHECK(igaparam_mesh_relocate(mesh, &o, NULL) == IGAPARAM_STATUS_OK);
  size_t count = 0;
  CHECK(igaparam_mesh_node_count(mesh, &count) == IGAPARAM_STATUS_OK && count == 25);
  igaparam_mesh_free(mesh);
}

/* ------------------------------------------------------------------------------------------ */

typedef struct {
  igaparam_mesh *mesh;
  pthread_mutex_t lock;
  pthread_cond_t changed;
  int running, other_done;
  igaparam_status other_relocate, other_count;
  char other_message[1024];
} two_threads;

/* The first callback of thread A waits until thread B has tried the mesh. */
static int waiting_progress(void *user, igaparam_stage stage, size_t done, size_t total) {
  (void)stage, (void)done, (void)total;
  two_threads *t = user;
  pthread_mutex_lock(&t->lock);
  t->running = 1;
  pthread_cond_broadcast(&t->changed);
  while (!t->other_done) {
    pthread_cond_wait(&t->changed, &t->lock);
  }
  pthread_mutex_unlock(&t->lock);
  return 0;
}

static void *other_thread(void *user) {
  two_threads *t = user;
  pthread_mutex_lock(&t->lock);
  while (!t->running) {
    pthread_cond_wait(&t->changed, &t->lock);
  }
  pthread_mutex_unlock(&t->lock);
  t->other_relocate = igaparam_mesh_relocate(t->mesh, NULL, NULL);
  snprintf(t->other_message, sizeof t->other_message, "%s", last_message());
  size_t count;
  t->other_count = igaparam_mesh_node_count(t->mesh, &count);
  pthread_mutex_lock(&t->lock);
  t->other_done = 1;
  pthread_cond_broadcast(&t->changed);
  pthread_mutex_unlock(&t->lock);
  return NULL;
}

/* Two threads relocating one mesh: the second is refused (no data race), the first succeeds. */
static void test_two_threads(void) {
  two_threads t;
  memset(&t, 0, sizeof t);
  t.mesh = new_mesh(8);
  pthread_mutex_init(&t.lock, NULL);
  pthread_cond_init(&t.changed, NULL);
  pthread_t other;
  pthread_create(&other, NULL, other_thread, &t);
  igaparam_relocate_options o = igaparam_relocate_options_default();
  o.progress = waiting_progress;
  o.progress_user = &t;
  igaparam_status status = igaparam_mesh_relocate(t.mesh, &o, NULL);
  pthread_join(other, NULL);
  CHECKF(status == IGAPARAM_STATUS_OK, "status %d: %s", (int)status, last_message());
  CHECKF(t.other_relocate == IGAPARAM_STATUS_BUSY && strstr(t.other_message, "in use"),
         "the other thread's relocation: status %d, \"%s\"", (int)t.other_relocate,
         t.other_message);
  CHECK(t.other_count == IGAPARAM_STATUS_BUSY);
  size_t invalid = 99;
  CHECK(igaparam_mesh_invalid_cell_count(t.mesh, &invalid) == IGAPARAM_STATUS_OK && invalid == 0);
  igaparam_mesh_free(t.mesh);
  pthread_mutex_destroy(&t.lock);
  pthread_cond_destroy(&t.changed);
}

/* ------------------------------------------------------------------------------------------ */

/* A quadrilateral with a wavy top side: its build needs optimization sweeps. */
static igaparam_domain *new_domain(void) {
  enum { N = 33 };
  double bottom[4] = {0, 0, 1, 0}, right[4] = {1, 0, 1, 1}, left[4] = {0, 1, 0, 0}, top[2 * N];
  for (int i = 0; i < N; i++) {
    double x = 1.0 - (double)i / (N - 1);
    top[2 * i] = x;
    top[2 * i + 1] = 1.0 + 0.3 * sin(3 * PI * x);
  }
  const size_t counts[4] = {2, 2, N, 2};
  const double *points[4] = {bottom, right, top, left};
  igaparam_domain *domain = NULL;
  igaparam_status status = igaparam_domain_new_from_polylines(counts, points, &domain);
  CHECKF(status == IGAPARAM_STATUS_OK, "new domain: %d %s", (int)status, last_message());
  return domain;
}

typedef struct {
  igaparam_domain *domain;
  int calls, freed;
} domain_probe;

static int domain_probe_progress(void *user, igaparam_stage stage, size_t done, size_t total) {
  (void)stage, (void)done, (void)total;
  domain_probe *p = user;
  if (p->freed) {
    return 0;
  }
  p->calls++;
  int built = -1;
  CHECK_BUSY(igaparam_domain_is_built(p->domain, &built), "igaparam_domain_is_built");
  CHECK(built == -1);
  CHECK_BUSY(igaparam_domain_build(p->domain, NULL, NULL), "igaparam_domain_build");
  igaparam_domain_free(p->domain);
  p->freed = 1;
  return 0;
}

static void test_domain_reentry(void) {
  domain_probe probe = {new_domain(), 0, 0};
  igaparam_domain_options o = igaparam_domain_options_default();
  o.min_level = 2;
  o.max_level = 4;
  o.progress = domain_probe_progress;
  o.progress_user = &probe;
  igaparam_status status = igaparam_domain_build(probe.domain, &o, NULL);
  CHECKF(probe.freed, "the callback was not called");
  CHECKF(status == IGAPARAM_STATUS_CANCELLED, "status %d: %s", (int)status, last_message());
}

/* The same rules in the domain's other long calls: from the callback of a fit, an update or the
   adaptive loop, a call on the domain is BUSY, and a release of the domain cancels the running
   call (run under AddressSanitizer and valgrind: no use after free). */
static igaparam_domain *new_built_domain(void) {
  igaparam_domain *domain = new_domain();
  igaparam_domain_options o = igaparam_domain_options_default();
  o.min_level = 2;
  o.max_level = 4;
  igaparam_status status = igaparam_domain_build(domain, &o, NULL);
  CHECKF(status == IGAPARAM_STATUS_OK, "build: %d %s", (int)status, last_message());
  return domain;
}

static void test_fit_reentry(void) {
  domain_probe probe = {new_built_domain(), 0, 0};
  igaparam_fit_options o = igaparam_fit_options_default();
  o.progress = domain_probe_progress;
  o.progress_user = &probe;
  igaparam_spline *spline = NULL;
  igaparam_status status = igaparam_spline_fit_domain_with(probe.domain, &o, &spline, NULL);
  CHECKF(probe.freed, "the fit's callback was not called");
  CHECKF(status == IGAPARAM_STATUS_CANCELLED && spline == NULL, "fit: status %d: %s",
         (int)status, last_message());
}

static void test_update_reentry(void) {
  domain_probe probe = {new_built_domain(), 0, 0};
  /* The same quadrilateral with its bottom side lowered a little. */
  enum { N = 33 };
  double bottom[4] = {0, -0.05, 1, -0.05}, right[4] = {1, -0.05, 1, 1}, left[4] = {0, 1, 0, -0.05};
  double top[2 * N];
  for (int i = 0; i < N; i++) {
    double x = 1.0 - (double)i / (N - 1);
    top[2 * i] = x;
    top[2 * i + 1] = 1.0 + 0.3 * sin(3 * PI * x);
  }
  const size_t counts[4] = {2, 2, N, 2};
  const double *points[4] = {bottom, right, top, left};
  igaparam_status status = igaparam_domain_set_boundary_polylines(probe.domain, counts, points);
  CHECKF(status == IGAPARAM_STATUS_OK, "new boundary: %d %s", (int)status, last_message());
  igaparam_domain_update_options o = igaparam_domain_update_options_default();
  o.progress = domain_probe_progress;
  o.progress_user = &probe;
  status = igaparam_domain_update(probe.domain, &o, NULL);
  CHECKF(probe.freed, "the update's callback was not called");
  CHECKF(status == IGAPARAM_STATUS_CANCELLED, "update: status %d: %s", (int)status,
         last_message());
}

static void test_adaptive_reentry(void) {
  domain_probe probe = {new_built_domain(), 0, 0};
  igaparam_adapt_options o = igaparam_adapt_options_default();
  o.target_quality = 0.99; /* refines: the callback comes before each refinement */
  o.progress = domain_probe_progress;
  o.progress_user = &probe;
  igaparam_spline *spline = NULL;
  igaparam_status status = igaparam_domain_fit_adaptive(probe.domain, &o, &spline, NULL);
  CHECKF(probe.freed, "the adaptive loop's callback was not called");
  CHECKF(status == IGAPARAM_STATUS_CANCELLED && spline == NULL, "adaptive: status %d: %s",
         (int)status, last_message());
}

/* A level-16 build (4^16 cells) is refused at once with LIMIT_EXCEEDED, the process alive; the
   same build with max_cells raised to what it needs gets past the check (and is cancelled from
   its callback, which the adaptation calls between its rounds). */
static int cancel_at_once(void *user, igaparam_stage stage, size_t done, size_t total) {
  (void)stage, (void)done, (void)total;
  ++*(int *)user;
  return 1;
}

static void test_cell_budget(void) {
  igaparam_domain *domain = new_domain();
  igaparam_domain_options o = igaparam_domain_options_default();
  CHECK(o.max_cells == 1000000);
  o.min_level = 16;
  o.max_level = 16;
  igaparam_domain_report report;
  memset(&report, 0x5A, sizeof report);
  igaparam_status status = igaparam_domain_build(domain, &o, &report);
  CHECKF(status == IGAPARAM_STATUS_LIMIT_EXCEEDED && strstr(last_message(), "max_cells") &&
             strstr(last_message(), "4294967296"),
         "status %d: %s", (int)status, last_message());
  CHECK(report.cells == 0x5A5A5A5A5A5A5A5Aull);
  /* Adaptation beyond the budget: a tolerance no boundary meets, a budget of 200 cells. */
  o = igaparam_domain_options_default();
  o.tolerance = 1e-300;
  o.max_level = 16;
  o.max_cells = 200;
  status = igaparam_domain_build(domain, &o, NULL);
  CHECKF(status == IGAPARAM_STATUS_LIMIT_EXCEEDED && strstr(last_message(), "adaptation"),
         "status %d: %s", (int)status, last_message());
  /* The adaptation calls the callback between its rounds: a cancel there stops it. */
  int calls = 0;
  o.max_cells = 1000000;
  o.progress = cancel_at_once;
  o.progress_user = &calls;
  status = igaparam_domain_build(domain, &o, NULL);
  CHECKF(status == IGAPARAM_STATUS_CANCELLED && calls == 1, "status %d, %d calls: %s",
         (int)status, calls, last_message());
  int built = 1;
  CHECK(igaparam_domain_is_built(domain, &built) == IGAPARAM_STATUS_OK && built == 0);
  igaparam_domain_free(domain);
}

/* The sweeps of all stages stop at max_total_sweeps: the build succeeds with the T-mesh reached
   and says so; a budget of 0 is refused and leaves the handle as it was. */
static void test_sweep_budget(void) {
  igaparam_domain *domain = new_domain();
  igaparam_domain_options o = igaparam_domain_options_default();
  CHECK(o.max_total_sweeps == IGAPARAM_DEFAULT_MAX_TOTAL_SWEEPS);
  igaparam_domain_report full, cut;
  igaparam_status status = igaparam_domain_build(domain, &o, &full);
  CHECKF(status == IGAPARAM_STATUS_OK && full.sweeps > 3 && !full.sweep_budget_exhausted,
         "status %d, %u sweeps: %s", (int)status, full.sweeps, last_message());
  o.max_total_sweeps = 3;
  status = igaparam_domain_build(domain, &o, &cut);
  CHECKF(status == IGAPARAM_STATUS_OK && cut.sweeps == 3 && cut.sweep_budget_exhausted == 1,
         "status %d, %u sweeps, exhausted %d: %s", (int)status, cut.sweeps,
         cut.sweep_budget_exhausted, last_message());
  CHECK(cut.cells == full.cells);
  size_t cells = 0;
  o.max_total_sweeps = 0;
  status = igaparam_domain_build(domain, &o, NULL);
  CHECKF(status == IGAPARAM_STATUS_INVALID_ARGUMENT && strstr(last_message(), "max_total_sweeps"),
         "status %d: %s", (int)status, last_message());
  CHECK(igaparam_domain_cell_count(domain, &cells) == IGAPARAM_STATUS_OK && cells == cut.cells);
  igaparam_domain_free(domain);
}

int main(void) {
  test_cell_budget();
  test_sweep_budget();
  test_mesh_reentry();
  test_mesh_usable_after_busy();
  test_two_threads();
  test_domain_reentry();
  test_fit_reentry();
  test_update_reentry();
  test_adaptive_reentry();
  printf("%d passed, %d failed\n", passed, failed);
  return failed ? 1 : 0;
}
