/* A minimal test harness for the *_test.c programs: checks that report the
 * file and line of a failure and keep going, and a summary exit status. */
#ifndef SH_TEST_H
#define SH_TEST_H

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_error.h"
#include "sh_parse.h"
#include "sh_str.h"

/* Unused in a test that only borrows the helpers below. */
#if defined(__GNUC__)
#define SH_TEST__UNUSED __attribute__((unused))
#else
#define SH_TEST__UNUSED
#endif
static int sh_test_failures SH_TEST__UNUSED = 0;
static int sh_test_checks SH_TEST__UNUSED = 0;

#define SH_CHECK(cond)                                                      \
  do {                                                                      \
    sh_test_checks++;                                                       \
    if (!(cond)) {                                                          \
      sh_test_failures++;                                                   \
      fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__,      \
              #cond);                                                       \
    }                                                                       \
  } while (0)

/* |a - b| <= tol_abs + tol_rel * |b| */
#define SH_CHECK_NEAR(a, b, tol_rel, tol_abs)                               \
  do {                                                                      \
    double sh__a = (a), sh__b = (b);                                        \
    sh_test_checks++;                                                       \
    if (!(fabs(sh__a - sh__b) <= (tol_abs) + (tol_rel)*fabs(sh__b))) {      \
      sh_test_failures++;                                                   \
      fprintf(stderr, "%s:%d: %s = %.9g, expected %s = %.9g\n", __FILE__,   \
              __LINE__, #a, sh__a, #b, sh__b);                              \
    }                                                                       \
  } while (0)

/* Whether a call that returned `got` and filled `err` failed as expected:
 * with `status`, at `line`:`column` (0 for none), key path `path`, and a
 * message containing `message`. Prints what it got otherwise, under the
 * name `what`. */
static inline int sh_test_error_is(const char *what, sh_status got,
                                   const sh_error *err, sh_status status,
                                   int line, int column, const char *path,
                                   const char *message) {
  int ok = got == status && err->status == status && err->line == line &&
           err->column == column && strcmp(err->path, path) == 0 &&
           strstr(err->message, message) != NULL;
  if (!ok)
    fprintf(stderr,
            "%s: got status %d at %d:%d '%s': %s\n  expected %d at %d:%d "
            "'%s' with \"%s\"\n",
            what, (int)got, err->line, err->column, err->path, err->message,
            (int)status, line, column, path, message);
  return ok;
}

/* Parses the scene text `json` as if read from the file `name` in the
 * current directory. Returns the scene, or NULL after printing the located
 * error. */
static inline sh_scene *sh_test_parse(const char *json, const char *name) {
  sh_error err = SH_ERROR_INIT;
  sh_scene *s = NULL;
  if (sh_scene_parse(json, name, ".", &s, &err) != SH_OK) {
    char *text = sh_error_text(&err);
    fprintf(stderr, "parse failed: %s\n", text ? text : err.message);
    free(text);
  }
  sh_error_clear(&err);
  return s;
}

/* Loads the scene file at a path in the source tree ($SHAFTS_SOURCE_DIR,
 * else ../.., the tree seen from a test's build directory), given as a
 * printf format: sh_test_load("scenes/%s.json", name). Returns the scene,
 * or NULL after printing the located error. */
static inline sh_scene *sh_test_load(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
static inline sh_scene *sh_test_load(const char *fmt, ...) {
  const char *src = getenv("SHAFTS_SOURCE_DIR");
  va_list ap;
  va_start(ap, fmt);
  char *rel = sh__vprintf_alloc(fmt, ap);
  va_end(ap);
  char *path = rel ? sh__printf_alloc("%s/%s", src ? src : "../..", rel) : NULL;
  sh_scene *s = NULL;
  sh_error err = SH_ERROR_INIT;
  if (!path) {
    fprintf(stderr, "out of memory\n");
  } else if (sh_scene_load(path, &s, &err) != SH_OK) {
    char *text = sh_error_text(&err);
    fprintf(stderr, "%s\n", text ? text : err.message);
    free(text);
  }
  sh_error_clear(&err);
  free(rel);
  free(path);
  return s;
}

/* Makes a fresh directory for a test's files, `$TMPDIR/<name>.XXXXXX`
 * (/tmp without TMPDIR), and writes its path into `dir`. Returns 0 and
 * prints why when it cannot; the caller's main then exits with failure. */
static inline int sh_test_tmpdir(char *dir, size_t size, const char *name) {
  const char *base = getenv("TMPDIR");
  snprintf(dir, size, "%s/%s.XXXXXX", base && *base ? base : "/tmp", name);
  if (!mkdtemp(dir)) {
    perror("mkdtemp");
    return 0;
  }
  return 1;
}

/* Call at the end of main. */
#define SH_TEST_DONE()                                                      \
  do {                                                                      \
    fprintf(stderr, "%d checks, %d failed\n", sh_test_checks,              \
            sh_test_failures);                                              \
    return sh_test_failures ? EXIT_FAILURE : EXIT_SUCCESS;                  \
  } while (0)

#endif
