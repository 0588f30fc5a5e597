/* Internal to the scene parser: finding positions in JSON text.
 *
 * jansson keeps no source positions, so the parser, once jansson has accepted
 * the text, re-scans it to find where an offending value (or key) sits. The
 * scanner here follows a key path (object keys and array indices) through
 * the text. It also works backwards: given a byte offset where jansson
 * reported a syntax error, it tells which key path was being read there.
 *
 * Lines and columns are 1-based; columns count characters (UTF-8 code
 * points), as jansson's do. */
#ifndef SH_JSON_LOCATE_H
#define SH_JSON_LOCATE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One step of a key path: an object member when `key` is not NULL, else the
 * array element `index`. */
typedef struct sh__jseg {
  const char *key;
  int index;
} sh__jseg;

/* Finds the value at `path` (depth steps; depth 0 is the root value) in the
 * JSON text, which must be valid JSON. With `at_key` set and a path ending in
 * an object member, finds that member's key instead of its value. Writes the
 * byte offset of the value's (or key's) first character to *offset and
 * returns 1, or returns 0 if the path is not in the text. */
int sh__json_locate(const char *text, size_t len, const sh__jseg *path,
                    int depth, int at_key, size_t *offset);

/* The 1-based line and column of byte `offset` in `text`. */
void sh__json_linecol(const char *text, size_t offset, int *line, int *column);

/* The key path of a (possibly invalid or truncated) JSON text at byte
 * `offset`, such as "lights[2].intensity": the innermost member or element
 * being read there; "" at the top level. On the heap, whole (any depth,
 * keys of any length); NULL when out of memory. */
char *sh__json_path_at(const char *text, size_t len, size_t offset);

/* A key path formatted as "lights[2].intensity" (keys that are not plain
 * identifiers written as ["a key"]), on the heap; NULL when out of
 * memory. */
char *sh__json_format_path(const sh__jseg *path, int depth);

#ifdef __cplusplus
}
#endif
#endif
