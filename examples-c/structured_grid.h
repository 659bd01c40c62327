/*
 * A structured grid of the unit square or cube as an igaparam mesh input: Q4, Q9 or H8 cells in
 * VTK node order, on a lattice of (order·nx + 1) × (order·ny + 1) [× (order·nz + 1)] nodes.
 * Header-only (static functions, valid C and C++) so that examples and tests can share it.
 */

#ifndef IGAPARAM_STRUCTURED_GRID_H
#define IGAPARAM_STRUCTURED_GRID_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "igaparam.h"

typedef struct {
  igaparam_cell_type type;
  int dimension;        /* 2 or 3 */
  size_t lattice[3];    /* nodes per direction (1 in z for quadrilaterals) */
  size_t nodes_per_cell;
  size_t num_nodes;
  size_t num_cells;
  double *xyz;          /* num_nodes × 3, node (i, j, k) at (i/(lattice[0]-1), ...) */
  int64_t *connectivity;/* num_cells × nodes_per_cell */
} structured_grid;

/* Index of lattice node (i, j, k). */
static inline size_t structured_grid_node(const structured_grid *g, size_t i, size_t j, size_t k) {
  return i + g->lattice[0] * (j + g->lattice[1] * k);
}

/* Non-zero when node `v` lies on the boundary of the square/cube. */
static inline int structured_grid_on_boundary(const structured_grid *g, size_t v) {
  size_t index[3] = {v % g->lattice[0], (v / g->lattice[0]) % g->lattice[1], v / (g->lattice[0] * g->lattice[1])};
  for (int d = 0; d < g->dimension; d++) {
    if (index[d] == 0 || index[d] == g->lattice[d] - 1) {
      return 1;
    }
  }
  return 0;
}

static inline void structured_grid_free(structured_grid *g) {
  free(g->xyz);
  free(g->connectivity);
  g->xyz = NULL;
  g->connectivity = NULL;
}

/*
 * Builds an nx × ny (× nz for H8; nz is ignored for quadrilaterals) grid of `type` cells
 * (IGAPARAM_CELL_QUAD4, _QUAD9 or _HEX8). Returns 0, or -1 for another type, a zero size or
 * an allocation failure. Release with structured_grid_free.
 */
static inline int structured_grid_init(structured_grid *g, igaparam_cell_type type, size_t nx, size_t ny, size_t nz) {
  /* Lattice offsets of a cell's nodes, in VTK order, in units of the lattice spacing. */
  static const int q4[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  static const int q9[9][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 0, 0},
                               {2, 1, 0}, {1, 2, 0}, {0, 1, 0}, {1, 1, 0}};
  static const int h8[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                               {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int(*offsets)[3];
  size_t order = 1;
  switch (type) {
    case IGAPARAM_CELL_QUAD4: offsets = q4; g->nodes_per_cell = 4; g->dimension = 2; break;
    case IGAPARAM_CELL_QUAD9: offsets = q9; g->nodes_per_cell = 9; g->dimension = 2; order = 2; break;
    case IGAPARAM_CELL_HEX8: offsets = h8; g->nodes_per_cell = 8; g->dimension = 3; break;
    default: return -1;
  }
  if (g->dimension == 2) {
    nz = 1;
  }
  if (nx == 0 || ny == 0 || nz == 0) {
    return -1;
  }
  g->type = type;
  g->lattice[0] = order * nx + 1;
  g->lattice[1] = order * ny + 1;
  g->lattice[2] = g->dimension == 3 ? order * nz + 1 : 1;
  g->num_nodes = g->lattice[0] * g->lattice[1] * g->lattice[2];
  g->num_cells = nx * ny * nz;
  g->xyz = (double *)malloc(3 * g->num_nodes * sizeof *g->xyz);
  g->connectivity = (int64_t *)malloc(g->num_cells * g->nodes_per_cell * sizeof *g->connectivity);
  if (!g->xyz || !g->connectivity) {
    structured_grid_free(g);
    return -1;
  }
  for (size_t k = 0; k < g->lattice[2]; k++) {
    for (size_t j = 0; j < g->lattice[1]; j++) {
      for (size_t i = 0; i < g->lattice[0]; i++) {
        double *p = g->xyz + 3 * structured_grid_node(g, i, j, k);
        p[0] = (double)i / (double)(g->lattice[0] - 1);
        p[1] = (double)j / (double)(g->lattice[1] - 1);
        p[2] = g->dimension == 3 ? (double)k / (double)(g->lattice[2] - 1) : 0.0;
      }
    }
  }
  int64_t *c = g->connectivity;
  for (size_t ck = 0; ck < nz; ck++) {
    for (size_t cj = 0; cj < ny; cj++) {
      for (size_t ci = 0; ci < nx; ci++) {
        for (size_t n = 0; n < g->nodes_per_cell; n++) {
          *c++ = (int64_t)structured_grid_node(g, order * ci + offsets[n][0], order * cj + offsets[n][1],
                                               order * ck + offsets[n][2]);
        }
      }
    }
  }
  return 0;
}

/* Constraint masks fixing every coordinate of the boundary nodes (caller frees). */
static inline uint8_t *structured_grid_boundary_mask(const structured_grid *g) {
  uint8_t *mask = (uint8_t *)malloc(g->num_nodes);
  if (mask) {
    const uint8_t fixed = g->dimension == 3 ? 7 : 3;
    for (size_t v = 0; v < g->num_nodes; v++) {
      mask[v] = structured_grid_on_boundary(g, v) ? fixed : 0;
    }
  }
  return mask;
}

#endif /* IGAPARAM_STRUCTURED_GRID_H */
