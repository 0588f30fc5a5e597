/* A minimal test harness for the *_test.c programs: checks that report the
 * file and line of a failure and keep going, and a summary exit status. */
#ifndef SH_TEST_H
#define SH_TEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int sh_test_failures = 0;
static int sh_test_checks = 0;

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

/* Call at the end of main. */
#define SH_TEST_DONE()                                                      \
  do {                                                                      \
    fprintf(stderr, "%d checks, %d failed\n", sh_test_checks,              \
            sh_test_failures);                                              \
    return sh_test_failures ? EXIT_FAILURE : EXIT_SUCCESS;                  \
  } while (0)

#endif
