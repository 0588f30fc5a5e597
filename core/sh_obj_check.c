/* The check of an OBJ file's faces before assimp reads it (sh_obj_check.h). */
#include "sh_obj_check.h"

#include <stdio.h>
#include <string.h>

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
