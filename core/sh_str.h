/* Strings on the heap, for the modules that build paths and messages of any
 * length (no fixed-size buffer ever cuts a path: issue 11). */
#ifndef SH_STR_H
#define SH_STR_H

#include <stdarg.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The printf of fmt into a new heap string the caller frees, or NULL when
 * out of memory (or for a format vsnprintf refuses). */
char *sh__printf_alloc(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
char *sh__vprintf_alloc(const char *fmt, va_list ap)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 0)))
#endif
    ;

#ifdef __cplusplus
}
#endif
#endif
