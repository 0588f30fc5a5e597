#include "sh_progress.h"

#include <stdio.h>
#include <time.h>
#include <unistd.h>

double sh_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void sh_progress_init(sh_progress *p, const char *label, long total,
                      int enabled) {
  p->label = label;
  p->total = total > 0 ? total : 1;
  p->done = 0;
  p->start = sh_seconds();
  p->last_print = p->start;
  p->enabled = enabled && isatty(2);
  p->printed = 0;
  pthread_mutex_init(&p->lock, NULL);
}

static void draw(sh_progress *p, long done, double now) {
  double frac = (double)done / (double)p->total;
  double elapsed = now - p->start;
  double left = frac > 0 ? elapsed * (1.0 - frac) / frac : 0.0;
  char bar[31];
  int filled = (int)(frac * 30.0);
  for (int i = 0; i < 30; i++) bar[i] = i < filled ? '#' : '.';
  bar[30] = '\0';
  fprintf(stderr, "\r%s [%s] %5.1f%%  %.0f s left ", p->label, bar,
          100.0 * frac, left);
  fflush(stderr);
  p->printed = 1;
}

void sh_progress_add(sh_progress *p, long units) {
  long done = __atomic_add_fetch(&p->done, units, __ATOMIC_RELAXED);
  if (!p->enabled) return;
  if (pthread_mutex_trylock(&p->lock) != 0) return;
  double now = sh_seconds();
  if (now - p->start > 1.0 && now - p->last_print > 0.1) {
    p->last_print = now;
    draw(p, done, now);
  }
  pthread_mutex_unlock(&p->lock);
}

void sh_progress_finish(sh_progress *p) {
  if (p->enabled && p->printed) fprintf(stderr, "\r%*s\r", 70, "");
  pthread_mutex_destroy(&p->lock);
}
