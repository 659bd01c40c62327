/* Uses an installed igaparam: one Q4 cell whose corners are fixed and moved, relocated.
 * Prints the library version; returns 0 on success. */
#include <stdio.h>
#include <string.h>

#include "igaparam.h"

static int fail(const char *what, igaparam_status status) {
  char message[512];
  igaparam_last_error_message(message, sizeof message);
  fprintf(stderr, "consumer: %s failed (status %d): %s\n", what, (int)status, message);
  return 1;
}

int main(void) {
  const double xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const int64_t cell[] = {0, 1, 2, 3};
  const uint8_t mask[] = {3, 3, 3, 3};
  const int64_t moved[] = {2};
  const double moved_xyz[] = {1.2, 1.1, 0};
  igaparam_mesh *mesh = NULL;
  igaparam_relocate_report report;
  igaparam_status s;
  int code = 0;

  if ((s = igaparam_mesh_new(IGAPARAM_CELL_QUAD4, 4, xyz, 1, cell, &mesh)))
    return fail("igaparam_mesh_new", s);
  if ((s = igaparam_mesh_set_fixed(mesh, 4, mask)))
    code = fail("igaparam_mesh_set_fixed", s);
  else if ((s = igaparam_mesh_move_nodes(mesh, 1, moved, moved_xyz)))
    code = fail("igaparam_mesh_move_nodes", s);
  else if ((s = igaparam_mesh_relocate(mesh, NULL, &report)))
    code = fail("igaparam_mesh_relocate", s);
  else if (report.cells != 1 || report.nodes != 4 || report.invalid_after != 0) {
    fprintf(stderr, "consumer: unexpected report: %zu cells, %zu nodes, %zu invalid\n", report.cells,
            report.nodes, report.invalid_after);
    code = 1;
  }
  igaparam_mesh_free(mesh);
  char header_version[64];
  snprintf(header_version, sizeof header_version, "%d.%d.%d", IGAPARAM_VERSION_MAJOR, IGAPARAM_VERSION_MINOR,
           IGAPARAM_VERSION_PATCH);
  if (strcmp(igaparam_version(), header_version) != 0) {
    fprintf(stderr, "consumer: library version %s, header version %s\n", igaparam_version(), header_version);
    code = 1;
  }
  printf("igaparam %s: %s\n", igaparam_version(), code == 0 ? "ok" : "FAILED");
  return code;
}
