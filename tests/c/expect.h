/*
 * Status checks shared by the C tests: EXPECT(call, status) checks that a call returned the
 * status wanted, with a non-empty message from igaparam_last_error_message unless it is OK.
 */
#ifndef IGAPARAM_TEST_EXPECT_H
#define IGAPARAM_TEST_EXPECT_H

#include <stdio.h>

#include "igaparam.h"

#include "check.h"

#define CHECK(cond, ...) check_at((cond), __FILE__, __LINE__, __VA_ARGS__)

/* The message of the calling thread's latest call. */
static const char *message(void) {
  static char buf[1024];
  igaparam_last_error_message(buf, sizeof buf);
  return buf;
}

/* The call returned `want`, and a non-empty message unless `want` is OK. */
static void expect_at(igaparam_status got, igaparam_status want, const char *what, const char *file,
                      int line) {
  const char *m = message();
  if (want == IGAPARAM_STATUS_OK) {
    check_at(got == want, file, line, "%s: status %d, expected OK (%s)", what, (int)got, m);
  } else {
    check_at(got == want && m[0] != '\0', file, line,
             "%s: status %d (message \"%s\"), expected %d with a message", what, (int)got, m,
             (int)want);
  }
}

#define EXPECT(call, want) expect_at((call), (want), #call, __FILE__, __LINE__)

#endif
