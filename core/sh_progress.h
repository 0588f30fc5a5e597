/* The command-line tools' progress bar: percentage and time left on
 * stderr, shown only when enabled, stderr is a terminal, and the work has
 * run for over a second. It is a progress callback of the library
 * (sh_reference_options.progress): the library itself never prints.
 * Part of the tools' static library (shafts_cli), not of libshafts.so. */
#ifndef SH_PROGRESS_H
#define SH_PROGRESS_H

#include <pthread.h>

#include "sh_time.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sh_progress {
  const char *label;
  double start, last_print;
  int enabled, printed;
  pthread_mutex_t lock;
} sh_progress;

/* Starts a bar labelled `label`. `enabled` = 0 silences it (--quiet); it is
 * also silent when stderr is not a terminal. */
void sh_progress_init(sh_progress *p, const char *label, int enabled);

/* The callback: `user` is the sh_progress. Redraws at most ten times a
 * second; safe to call from several threads at once. */
void sh_progress_update(void *user, long done, long total);

/* Ends the bar (clears its line). */
void sh_progress_finish(sh_progress *p);

#ifdef __cplusplus
}
#endif
#endif
