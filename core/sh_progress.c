#include "sh_progress.h"

#include <stdio.h>
#include <unistd.h>

void sh_progress_init(sh_progress *p, const char *label, int enabled) {
  p->label = label;
  p->start = sh_seconds();
  p->last_print = p->start;
  p->enabled = enabled && isatty(2);
  p->printed = 0;
  pthread_mutex_init(&p->lock, NULL);
}

static void draw(sh_progress *p, double frac, double now) {
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

void sh_progress_update(void *user, long done, long total) {
  sh_progress *p = user;
  if (!p->enabled || total <= 0) return;
  if (pthread_mutex_trylock(&p->lock) != 0) return;
  double now = sh_seconds();
  if (now - p->start > 1.0 && now - p->last_print > 0.1) {
    p->last_print = now;
    draw(p, (double)done / (double)total, now);
  }
  pthread_mutex_unlock(&p->lock);
}

void sh_progress_finish(sh_progress *p) {
  if (p->enabled && p->printed) fprintf(stderr, "\r%*s\r", 70, "");
  pthread_mutex_destroy(&p->lock);
}
