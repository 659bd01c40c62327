/*
 * relocate_vtu: relocation of a mesh read from a .vtu file, in C without VTK.
 *
 *   relocate_vtu IN.vtu OUT.vtu [THREADS]
 *
 * Reads IN (any storage VTK and meshio write: ASCII, binary, appended raw or base64, zlib
 * compressed) with its point arrays `fixed_components` and `moved`, which prescribe the
 * boundary's motion; relocates the free nodes; writes OUT (zlib-compressed binary, point data
 * `displacement`, cell data `quality`) and prints the report as one JSON object.
 */

#include <stdio.h>
#include <stdlib.h>

#include "igaparam.h"

/* Prints the failed call's status and message; returns 1 (the exit code). */
static int fail(const char *what, igaparam_status status) {
  char message[1024];
  igaparam_last_error_message(message, sizeof message);
  fprintf(stderr, "relocate_vtu: %s failed (status %d): %s\n", what, (int)status, message);
  return 1;
}

int main(int argc, char **argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: relocate_vtu IN.vtu OUT.vtu [THREADS]\n");
    return 2;
  }
  igaparam_mesh *mesh = NULL;
  igaparam_status status = igaparam_mesh_read_vtu(argv[1], &mesh);
  if (status != IGAPARAM_STATUS_OK) return fail("igaparam_mesh_read_vtu", status);
  igaparam_relocate_options options = igaparam_relocate_options_default();
  if (argc > 3) options.threads = (uint32_t)strtoul(argv[3], NULL, 10);
  igaparam_relocate_report r;
  status = igaparam_mesh_relocate(mesh, &options, &r);
  if (status != IGAPARAM_STATUS_OK) {
    igaparam_mesh_free(mesh);
    return fail("igaparam_mesh_relocate", status);
  }
  status = igaparam_mesh_write_vtu(mesh, argv[2]);
  igaparam_mesh_free(mesh);
  if (status != IGAPARAM_STATUS_OK) return fail("igaparam_mesh_write_vtu", status);
  printf("{\"cells\": %zu, \"nodes\": %zu, \"invalid_before\": %zu, \"invalid_after\": %zu, "
         "\"min_quality\": %.17g, \"mean_quality\": %.17g, \"sweeps\": %u}\n",
         r.cells, r.nodes, r.invalid_before, r.invalid_after, r.min_quality, r.mean_quality, r.sweeps);
  return r.invalid_after == 0 ? 0 : 1;
}
