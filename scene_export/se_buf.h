/* A growable text buffer with printf-style appending, for building an
 * output file in memory before it is written atomically. */
#ifndef SE_BUF_H
#define SE_BUF_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct se_buf {
  char *data; /* always NUL-terminated when non-NULL; owned */
  size_t len, cap;
  int failed; /* set once an allocation fails; later appends do nothing */
} se_buf;

/* Appends formatted text. Failures are sticky: check `failed` at the end. */
void se_buf_printf(se_buf *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Appends n bytes. */
void se_buf_append(se_buf *b, const char *s, size_t n);
/* Appends a NUL-terminated string. */
void se_buf_puts(se_buf *b, const char *s);
/* Frees the text and zeroes the buffer. */
void se_buf_free(se_buf *b);

#ifdef __cplusplus
}
#endif
#endif
