/* Small file helpers shared by the tools. */
#ifndef SH_FILE_H
#define SH_FILE_H

#include <stddef.h>
#include <stdio.h>

#include "sh_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Writes `size` bytes to `path` atomically: a set of one output
 * (sh_outputs.h), staged in an unnamed temporary file in the same directory
 * and renamed over `path` once complete. On failure nothing is left behind
 * and SH_ERR_IO is returned (SH_ERR_ARG for a path that is a directory or
 * another file that is not regular). */
sh_status sh_file_write_atomic(const char *path, const void *data, size_t size,
                               sh_error *err);

/* Checks that `path` names a regular file this process can read (not a
 * directory, a device such as /dev/zero, a FIFO or a socket, which would
 * be read forever or block), before handing it to a library that reports a
 * missing file like any other failure. SH_ERR_IO, "cannot open 'PATH':
 * REASON", otherwise. Its size in bytes goes to *size when size is not
 * NULL. */
sh_status sh_file_readable(const char *path, long long *size, sh_error *err);

/* The checks every loader makes first: `fn` (the public call, named in the
 * message) was given a result `out` of out_size bytes, which is zeroed, and
 * a non-empty path naming a readable file (sh_file_readable, its size to
 * *size when size is not NULL). SH_ERR_ARG or SH_ERR_IO otherwise. */
sh_status sh__file_load_begin(const char *fn, const char *what, void *out,
                              size_t out_size, const char *path,
                              long long *size, sh_error *err);

/* Opens `path` for reading ("rb") without blocking on a FIFO (its opening
 * would wait for a writer): the caller checks with fstat that it is a
 * regular file before reading. NULL with errno on failure. */
FILE *sh_file_open_read(const char *path);

/* What a stat(2) st_mode is, for messages: "a directory", "a character
 * device", "a FIFO"... */
const char *sh_file_kind(unsigned mode);

/* The extension of `path` after its last dot, lower-cased into buf (empty
 * if there is none). */
void sh_file_extension(const char *path, char *buf, size_t size);

#ifdef __cplusplus
}
#endif
#endif
