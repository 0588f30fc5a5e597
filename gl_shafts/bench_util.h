/* What the gl_shafts benchmarks (bench.c, live_bench.c) share: the
 * process's CPU time, a comparison for sorting times, and callgrind's
 * instrumentation macros, empty where valgrind's header is missing. Under
 * valgrind --tool=callgrind --instr-atstart=no only the code between
 * CALLGRIND_START_INSTRUMENTATION and CALLGRIND_STOP_INSTRUMENTATION is
 * measured (instruction counts are immune to other load). */
#ifndef BENCH_UTIL_H
#define BENCH_UTIL_H

#if defined(__has_include)
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#endif
#endif
#ifndef CALLGRIND_START_INSTRUMENTATION
#define CALLGRIND_START_INSTRUMENTATION
#define CALLGRIND_STOP_INSTRUMENTATION
#endif

/* CPU time of the process, all threads (llvmpipe's too), in seconds. */
double bench_cpu_seconds(void);

/* qsort's comparison of doubles, ascending. */
int bench_cmp_double(const void *a, const void *b);

#endif
