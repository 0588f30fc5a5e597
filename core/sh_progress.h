/* Progress reporting for long work: a bar with percentage and time left on
 * stderr, shown only when enabled, stderr is a terminal, and the work has
 * run for over a second. Safe to call from several threads. */
#ifndef SH_PROGRESS_H
#define SH_PROGRESS_H

#include <pthread.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sh_progress {
  const char *label;
  long total;
  long done; /* updated atomically */
  double start, last_print;
  int enabled, printed;
  pthread_mutex_t lock;
} sh_progress;

/* Starts a report of `total` units. `enabled` = 0 silences it (--quiet);
 * it is also silent when stderr is not a terminal. */
void sh_progress_init(sh_progress *p, const char *label, long total,
                      int enabled);
/* Adds `units` finished units and redraws at most ten times a second. */
void sh_progress_add(sh_progress *p, long units);
/* Ends the report (clears the bar's line). */
void sh_progress_finish(sh_progress *p);

/* Seconds on a monotonic clock. */
double sh_seconds(void);

#ifdef __cplusplus
}
#endif
#endif
