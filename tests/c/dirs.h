/*
 * The directories of the C tests run as `test_<name> DATA_DIR OUT_DIR`: read_dirs() takes them
 * from the command line, joined() makes the path of a file in one of them.
 */
#ifndef IGAPARAM_TEST_DIRS_H
#define IGAPARAM_TEST_DIRS_H

#include <stdio.h>

static char data_dir[512], out_dir[512];

/* `dir`/`name`, in one of two static buffers used in turn (two paths may be in use at once). */
static const char *joined(const char *dir, const char *name) {
  static char buf[2][1024];
  static int which;
  which ^= 1;
  snprintf(buf[which], sizeof buf[which], "%s/%s", dir, name);
  return buf[which];
}

/* Reads DATA_DIR and OUT_DIR; prints the usage and returns 0 when they are not given. */
static int read_dirs(int argc, char **argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: %s DATA_DIR OUT_DIR\n", argv[0]);
    return 0;
  }
  snprintf(data_dir, sizeof data_dir, "%s", argv[1]);
  snprintf(out_dir, sizeof out_dir, "%s", argv[2]);
  return 1;
}

#endif
