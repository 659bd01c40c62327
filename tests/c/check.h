/*
 * The counters and the failure report shared by the C tests: check_at() counts a check and
 * prints a located message when it fails; each test prints "N passed, M failed" at the end.
 */
#ifndef IGAPARAM_TEST_CHECK_H
#define IGAPARAM_TEST_CHECK_H

#include <stdarg.h>
#include <stdio.h>

static int passed, failed;

static void check_at(int ok, const char *file, int line, const char *format, ...) {
  if (ok) {
    passed++;
    return;
  }
  failed++;
  va_list args;
  va_start(args, format);
  fprintf(stderr, "FAIL %s:%d: ", file, line);
  vfprintf(stderr, format, args);
  fputc('\n', stderr);
  va_end(args);
}

#endif
