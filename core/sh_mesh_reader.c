/* What the core's own mesh readers share (sh_mesh_reader.h). */
#include "sh_mesh_reader.h"
#include "sh_str.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void sh__mesh_reader_init(sh__mesh_reader *r, const char *path,
                          const char *data, size_t size, sh_error *err) {
  memset(r, 0, sizeof *r);
  r->path = path;
  r->data = r->p = data;
  r->end = data + size;
  r->line = 1;
  r->err = err;
}

sh_status sh__mesh_reader_fail(sh__mesh_reader *r, long line, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  char *what = sh__vprintf_alloc(fmt, ap);
  va_end(ap);
  if (line > 0)
    sh_error_set(r->err, SH_ERR_MESH, "cannot load mesh '%s': line %ld: %s",
                 r->path, line, what ? what : "out of memory");
  else
    sh_error_set(r->err, SH_ERR_MESH, "cannot load mesh '%s': byte %zu: %s",
                 r->path, (size_t)(r->p - r->data), what ? what : "out of memory");
  free(what);
  sh_error_set_file(r->err, r->path);
  if (r->err)
    r->err->line = line > 0 ? (int)(line < INT_MAX ? line : INT_MAX) : 0;
  return SH_ERR_MESH;
}

int sh__mesh_is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

int sh__mesh_whole(const char *s, size_t n, size_t *out) {
  size_t v = 0;
  if (n == 0) return 0;
  for (size_t i = 0; i < n; i++)
    if (s[i] < '0' || s[i] > '9') return 0;
  for (size_t i = 0; i < n; i++) {
    if (v > (SIZE_MAX - 9) / 10) return -1;
    v = v * 10 + (size_t)(s[i] - '0');
  }
  *out = v;
  return 1;
}

sh_status sh__mesh_reader_vertices(sh__mesh_reader *r, size_t n, long line) {
  if (n > (size_t)INT_MAX / 3)
    return sh__mesh_reader_fail(r, line, "too many vertices (%zu)", n);
  r->nverts = n;
  r->pos = calloc(n ? 3 * n : 1, sizeof *r->pos);
  return r->pos ? SH_OK : sh_error_set(r->err, SH_ERR_NOMEM, "out of memory");
}

sh_status sh__mesh_reader_coord(sh__mesh_reader *r, size_t k, int axis, double v,
                                long line) {
  float f = (float)v;
  if (!isfinite(f))
    return sh__mesh_reader_fail(r, line,
                                "vertex %zu is not a finite number (NaN, infinite or "
                                "beyond single precision's 3.4e38)", k);
  r->pos[3 * k + (size_t)axis] = f;
  return SH_OK;
}

sh_status sh__mesh_reader_list(sh__mesh_reader *r, size_t n) {
  if (n <= r->list_cap) return SH_OK;
  long long *nl = realloc(r->list, n * sizeof *nl);
  if (!nl) return sh_error_set(r->err, SH_ERR_NOMEM, "out of memory");
  r->list = nl;
  r->list_cap = n;
  return SH_OK;
}

sh_status sh__mesh_reader_check(sh__mesh_reader *r, size_t n, int restart,
                                const char *what, long line) {
  for (size_t i = 0; i < n; i++) {
    long long x = r->list[i];
    if (restart && x == -1) continue;
    if (x < 0 || (unsigned long long)x >= r->nverts)
      return sh__mesh_reader_fail(r, line, "a %s refers to vertex %lld of %zu (counted from 0)",
                                  what, x, r->nverts);
  }
  return SH_OK;
}

sh_status sh__mesh_reader_triangle(sh__mesh_reader *r, long long a, long long b,
                                   long long c, long line) {
  if (a == b || b == c || a == c) return SH_OK; /* degenerate */
  if (r->ntris == r->cap) {
    size_t cap = r->cap ? 2 * r->cap : 256;
    if (cap > (size_t)INT_MAX / 3) return sh__mesh_reader_fail(r, line, "too many triangles");
    unsigned *nt = realloc(r->tris, cap * 3 * sizeof *nt);
    if (!nt) return sh_error_set(r->err, SH_ERR_NOMEM, "out of memory");
    r->tris = nt;
    r->cap = cap;
  }
  unsigned *t = r->tris + 3 * r->ntris++;
  t[0] = (unsigned)a, t[1] = (unsigned)b, t[2] = (unsigned)c;
  return SH_OK;
}

sh_status sh__mesh_reader_fan(sh__mesh_reader *r, size_t n, long line) {
  sh_status st = SH_OK;
  for (size_t k = 1; k + 1 < n && st == SH_OK; k++)
    st = sh__mesh_reader_triangle(r, r->list[0], r->list[k], r->list[k + 1], line);
  return st;
}

sh_status sh__mesh_reader_finish(sh__mesh_reader *r, sh_status st, sh_mesh *mesh) {
  free(r->list);
  r->list = NULL;
  memset(mesh, 0, sizeof *mesh);
  if (st == SH_OK && r->ntris == 0)
    st = sh_error_set(r->err, SH_ERR_MESH, "cannot load mesh '%s': it has no triangles",
                      r->path);
  if (st != SH_OK) {
    free(r->pos);
    free(r->tris);
    r->pos = NULL;
    r->tris = NULL;
    return st;
  }
  mesh->nverts = (int)r->nverts;
  mesh->ntris = (int)r->ntris;
  mesh->positions = r->pos;
  mesh->indices = r->tris;
  return SH_OK;
}
