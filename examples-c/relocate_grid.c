/*
 * relocate_grid: the C API in a few calls, without any file format.
 *
 * Builds a 16 × 16 grid of biquadratic quadrilaterals (Q9) of the unit square, fixes its
 * boundary, pushes the top side down into a bump, relocates the interior nodes and prints the
 * report. Exits with 0 when every cell is valid afterwards, 1 otherwise.
 */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "igaparam.h"
#include "structured_grid.h"

/* Prints the failed call's status and message; returns 1 (the exit code). */
static int fail(const char *what, igaparam_status status) {
  char message[512];
  igaparam_last_error_message(message, sizeof message);
  fprintf(stderr, "relocate_grid: %s failed (status %d): %s\n", what, (int)status, message);
  return 1;
}

int main(void) {
  const double pi = 3.14159265358979323846;
  const double depth = 0.45; /* of the bump, in units of the side */
  structured_grid grid;
  if (structured_grid_init(&grid, IGAPARAM_CELL_QUAD9, 16, 16, 1) != 0) {
    fprintf(stderr, "relocate_grid: out of memory\n");
    return 1;
  }
  uint8_t *mask = structured_grid_boundary_mask(&grid);
  /* The new positions of the top side's nodes: y = 1 - depth·sin(πx). */
  int64_t *top = malloc(grid.lattice[0] * sizeof *top);
  double *top_xyz = malloc(3 * grid.lattice[0] * sizeof *top_xyz);
  if (!mask || !top || !top_xyz) {
    fprintf(stderr, "relocate_grid: out of memory\n");
    return 1;
  }
  for (size_t i = 0; i < grid.lattice[0]; i++) {
    top[i] = (int64_t)structured_grid_node(&grid, i, grid.lattice[1] - 1, 0);
    const double *p = grid.xyz + 3 * top[i];
    top_xyz[3 * i + 0] = p[0];
    top_xyz[3 * i + 1] = p[1] - depth * sin(pi * p[0]);
    top_xyz[3 * i + 2] = p[2];
  }

  igaparam_mesh *mesh = NULL;
  igaparam_status s;
  int code = 0;
  if ((s = igaparam_mesh_new(grid.type, grid.num_nodes, grid.xyz, grid.num_cells, grid.connectivity, &mesh)))
    code = fail("igaparam_mesh_new", s);
  else if ((s = igaparam_mesh_set_fixed(mesh, grid.num_nodes, mask)))
    code = fail("igaparam_mesh_set_fixed", s);
  else if ((s = igaparam_mesh_move_nodes(mesh, grid.lattice[0], top, top_xyz)))
    code = fail("igaparam_mesh_move_nodes", s);
  if (code == 0) {
    igaparam_relocate_options options = igaparam_relocate_options_default();
    igaparam_relocate_report r;
    if ((s = igaparam_mesh_relocate(mesh, &options, &r))) {
      code = fail("igaparam_mesh_relocate", s);
    } else {
      printf("igaparam %s: %zu Q9 cells, %zu nodes (%zu free)\n", igaparam_version(), r.cells, r.nodes,
             r.free_nodes);
      printf("invalid cells: %zu before, %zu after placement, %zu after optimization\n", r.invalid_before,
             r.invalid_after_placement, r.invalid_after);
      printf("quality: min %.4f, mean %.4f; %u sweeps (%s), %.3f s\n", r.min_quality, r.mean_quality, r.sweeps,
             r.converged ? "converged" : "not converged", r.seconds);
      if (r.invalid_after != 0) {
        fprintf(stderr, "relocate_grid: %zu cells are still invalid\n", r.invalid_after);
        code = 1;
      }
    }
  }

  igaparam_mesh_free(mesh);
  free(top_xyz);
  free(top);
  free(mask);
  structured_grid_free(&grid);
  return code;
}
