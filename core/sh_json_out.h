/* Internal: writing statistics as JSON text (the tools' --stats files and
 * the bindings' stats dictionaries share the format): integral numbers as
 * JSON integers, others as reals with 10 significant digits, two-space
 * indents. */
#ifndef SH_JSON_OUT_H
#define SH_JSON_OUT_H

#include <jansson.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Sets member `key` of `o` to the number v. */
void sh__json_num(json_t *o, const char *key, double v);

/* The text of `o` (NULL: none), which it releases (json_decref). */
char *sh__json_dumps(json_t *o);

/* Writes the text of `o` into buf (size bytes, NUL-terminated, cut short
 * if too small; buf may be NULL with size 0) and releases `o`. Returns the
 * length of the whole text, as snprintf does; 0 if out of memory. */
size_t sh__json_dump_to(json_t *o, char *buf, size_t size);

#ifdef __cplusplus
}
#endif
#endif
