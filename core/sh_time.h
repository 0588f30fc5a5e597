/* A monotonic clock for timing work (render statistics, benchmarks). */
#ifndef SH_TIME_H
#define SH_TIME_H

#ifdef __cplusplus
extern "C" {
#endif

/* Seconds on a monotonic clock (CLOCK_MONOTONIC): differences are
 * durations; the origin is arbitrary. */
double sh_seconds(void);

#ifdef __cplusplus
}
#endif
#endif
