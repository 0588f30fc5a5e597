/* The check of an OBJ file's faces before assimp reads it (sh_obj_check.h). */
#include "sh_obj_check.h"

#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "sh_mesh_reader.h"

sh_status sh__obj_check(const char *path, const char *data, size_t size,
                        sh_error *err) {
  const char *p = data, *end = data + size;
  long line = 1;
  while (p < end) {
    long first = line; /* the line a logical line starts on */
    size_t tokens = 0;
    int face = 0, in_token = 0;
    /* One logical line: tokens up to a line end not after a backslash. */
    for (; p < end; p++) {
      char c = *p;
      if (c == '\n') {
        line++;
        const char *q = p;
        while (q > data && (q[-1] == '\r')) q--;
        if (q > data && q[-1] == '\\') continue; /* continued */
        p++;
        break;
      }
      int blank = sh__mesh_is_space(c) || c == '\\';
      if (!blank && !in_token) {
        tokens++;
        if (tokens == 1) face = c == 'f' && (p + 1 == end || sh__mesh_is_space(p[1]));
      }
      in_token = !blank;
    }
    if (face && tokens - 1 > SH_OBJ_MAX_CORNERS) {
      sh_error_set(err, SH_ERR_MESH,
                   "cannot load mesh '%s': line %ld: a face of %zu corners, more than the "
                   "%d whose triangulation is bounded (its time grows as the square of "
                   "the corners)", path, first, tokens - 1, SH_OBJ_MAX_CORNERS);
      sh_error_set_file(err, path);
      if (err) err->line = (int)first;
      return SH_ERR_MESH;
    }
  }
  return SH_OK;
}

/* Whether the statement at `s` (of `n` bytes to its line's end) is `word`:
 * its first character as given (assimp dispatches on it), the rest in any
 * case (assimp compares them so). */
static int mtl_is(const char *s, size_t n, const char *word) {
  size_t k = strlen(word);
  return n >= k && s[0] == word[0] && strncasecmp(s + 1, word + 1, k - 1) == 0;
}

/* assimp's line ends (ObjTools.h's IsLineEnd). */
static int mtl_line_end(char c) { return c == '\n' || c == '\r' || c == '\f' || c == '\0'; }

sh_status sh__mtl_check(const char *mesh, const char *path, const char *data,
                        size_t size, sh_error *err) {
  const char *p = data, *end = data + size;
  const unsigned char *u = (const unsigned char *)data;
  /* assimp's TextFileToBuffer drops a UTF-8 byte-order mark, and swaps or
   * converts (with faults) text after a UTF-16 or UTF-32 one. */
  if (size >= 3 && u[0] == 0xEF && u[1] == 0xBB && u[2] == 0xBF) {
    p += 3;
  } else if (size >= 2 && ((u[0] == 0xFE && u[1] == 0xFF) || (u[0] == 0xFF && u[1] == 0xFE) ||
                           (size >= 4 && !u[0] && !u[1] && u[2] == 0xFE && u[3] == 0xFF))) {
    sh_error_set(err, SH_ERR_MESH,
                 "cannot load mesh '%s': its material library '%s' is UTF-16 or UTF-32 "
                 "(a byte-order mark), which assimp 5.2 converts with faults: save it as "
                 "UTF-8 or ASCII", mesh, path);
    sh_error_set_file(err, path);
    if (err) err->line = 1;
    return SH_ERR_MESH;
  }
  long line = 1;
  while (p < end) {
    while (p < end && (*p == ' ' || *p == '\t')) p++;
    const char *e = p;
    while (e < end && !mtl_line_end(*e)) e++;
    size_t n = (size_t)(e - p);
    if (n >= 2 && (p[0] == 'n' || p[0] == 'N') && p[1] == 'e') return SH_OK; /* newmtl */
    if (n && (p[0] == 'a' || mtl_is(p, n, "map_") || mtl_is(p, n, "bump") ||
              mtl_is(p, n, "disp") || mtl_is(p, n, "norm") || mtl_is(p, n, "Norm"))) {
      /* Its keyword, if it is short printable ASCII. */
      size_t k = 0;
      while (k < n && k < 17 && p[k] > ' ' && p[k] < 127) k++;
      int show = k < 17 && (k == n || p[k] == ' ' || p[k] == '\t');
      sh_error_set(err, SH_ERR_MESH,
                   "cannot load mesh '%s': its material library '%s', line %ld: %s%s%.*s%s "
                   "before the library's first newmtl (it belongs to a material, and "
                   "assimp's reader would write it to none): move it below the newmtl of "
                   "its material, or delete it",
                   mesh, path, line,
                   p[0] == 'a' ? "an 'a' statement (anisotropy)" : "a texture map",
                   show ? " ('" : "", show ? (int)k : 0, p, show ? "')" : "");
      sh_error_set_file(err, path);
      if (err) err->line = (int)line;
      return SH_ERR_MESH;
    }
    if (e == end) break;
    if (*e == '\n') line++;
    p = e + 1;
  }
  return SH_OK;
}
