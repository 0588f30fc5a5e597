/* Text that comes from users (material names, file paths, output names)
 * and must not break, or run code in, the files the exporters write.
 *
 * The exporters avoid user strings wherever they can: POV-Ray and Blender
 * outputs refer to files the exporter itself names, and scene names appear
 * only in comments, sanitised by se_comment_text. */
#ifndef SE_TEXT_H
#define SE_TEXT_H

#include <stddef.h>

#include "se_buf.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Writes into out (room for size bytes, size >= 4) a copy of `in` that is
 * safe inside a one-line comment of any of the target languages (POV-Ray's
 * "//", the .ini's ";", Python's "#") and stays readable: printable ASCII
 * is kept, so "medium.mie.phase: POV-Ray has no cornette_shanks phase (it
 * is ...)" reads as written. What could end the comment or break the file
 * becomes '_': every control byte (line feed, carriage return, tab, DEL:
 * nothing after them reaches a parser), every byte of 128 or more (no
 * encoding to misread, no Unicode line separator) and the '*' of a "/x" or
 * "x/" pair (no block comment opened or closed). The result is cut to
 * size - 1 bytes with "..." marking a cut. */
void se_comment_text(const char *in, char *out, size_t size);

/* True if `name` (a file name without directories) is non-empty, consists
 * of letters, digits and "._+-" only, and does not start with '-' or '.':
 * the names POV-Ray's .ini files and command line take without quoting. */
int se_is_plain_file_name(const char *name);

/* Writes into out (room for size bytes) `in` with every byte that
 * se_is_plain_file_name rejects replaced by '_' (a leading '.' or '-' too),
 * cut to size - 1 bytes; "_" if `in` is empty. For the names of the side
 * files an export writes. */
void se_plain_name(const char *in, char *out, size_t size);

/* Appends `word` to b as one POSIX shell word: as it is when it holds only
 * letters, digits, "_.+-/" and does not start with '-', else in single
 * quotes with every quote written '\''. For the commands scene_export
 * prints; the shell expands nothing in it. */
void se_shell_word(se_buf *b, const char *word);

/* The last path component of `path` (a pointer into it). */
const char *se_base_name(const char *path);

/* A new string: `path` without its extension (after the last dot of the
 * last component), plus `suffix`. NULL if out of memory. */
char *se_replace_extension(const char *path, const char *suffix);

/* A new string of any length, formatted as printf does (file names are
 * never cut to a buffer's size). NULL if out of memory. */
char *se_printf_alloc(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

#ifdef __cplusplus
}
#endif
#endif
