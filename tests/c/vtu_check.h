/*
 * A written .vtu file read back by the C tests: check_vtu_file(path, points, cells, names, n)
 * checks that the file is whole, that its piece has `points` points and `cells` cells, and that
 * it holds the data arrays named in `names`.
 */
#ifndef IGAPARAM_TEST_VTU_CHECK_H
#define IGAPARAM_TEST_VTU_CHECK_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "expect.h"

/* The number after `key` (e.g. `NumberOfPoints="`) in `piece`, or 0 if there is none. */
static unsigned long long vtu_count(const char *piece, const char *key) {
  const char *at = piece ? strstr(piece, key) : NULL;
  return at ? strtoull(at + strlen(key), NULL, 10) : 0;
}

static void check_vtu_file(const char *path, size_t points, size_t cells, const char *const *names,
                           size_t n_names) {
  FILE *f = fopen(path, "rb");
  CHECK(f != NULL, "%s: cannot open it", path);
  if (!f) return;
  fseek(f, 0, SEEK_END);
  long size = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *text = calloc((size_t)size + 1, 1);
  size_t got = fread(text, 1, (size_t)size, f);
  fclose(f);
  const char *piece = strstr(text, "<Piece ");
  unsigned long long np = vtu_count(piece, "NumberOfPoints=\""),
                     nc = vtu_count(piece, "NumberOfCells=\"");
  CHECK(got == (size_t)size && piece && np == points && nc == cells,
        "%s: %llu points, %llu cells in the file; %zu and %zu expected", path, np, nc, points,
        cells);
  char name[128];
  for (size_t i = 0; i < n_names; i++) {
    snprintf(name, sizeof name, "Name=\"%s\"", names[i]);
    CHECK(strstr(text, name) != NULL, "%s: no %s array", path, names[i]);
  }
  CHECK(strstr(text, "</VTKFile>") != NULL, "%s: truncated", path);
  free(text);
}

#endif
