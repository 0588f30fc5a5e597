/* The OFF reader (sh_off.h). The format: Geomview's manual, "OFF Files"
 * (the header keyword's prefixes, nOFF's dimension, faces with a colour),
 * read line by line as assimp and most writers do. */
#include "sh_off.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "sh_mesh_reader.h"

int sh__off_magic(const unsigned char *head, size_t n) {
  return n >= 3 && (head[0] | 0x20) == 'o' && (head[1] | 0x20) == 'f' &&
         (head[2] | 0x20) == 'f';
}

/* The rest of the current line: [p, e), on line `line`. */
typedef struct off_line {
  const char *p, *e;
  long line;
} off_line;

/* Moves to the next line holding a token, skipping blank lines and
 * comments; 0 at the end of the file. */
static int next_line(sh__mesh_reader *r, off_line *l) {
  while (r->p < r->end) {
    const char *s = r->p, *nl = memchr(s, '\n', (size_t)(r->end - s));
    const char *e = nl ? nl : r->end, *hash = memchr(s, '#', (size_t)(e - s));
    r->p = nl ? nl + 1 : r->end;
    l->line = r->line++;
    if (hash) e = hash;
    while (s < e && sh__mesh_is_space(*s)) s++;
    if (s < e) {
      l->p = s;
      l->e = e;
      return 1;
    }
  }
  return 0;
}

/* The next token of the line into [*b, l->p); 0 if the line has no more. */
static int token(off_line *l, const char **b) {
  while (l->p < l->e && sh__mesh_is_space(*l->p)) l->p++;
  if (l->p == l->e) return 0;
  *b = l->p;
  while (l->p < l->e && !sh__mesh_is_space(*l->p)) l->p++;
  return 1;
}

/* The next token, on this line or the next ones (the header's); 0 at the
 * end of the file. */
static int token_across(sh__mesh_reader *r, off_line *l, const char **b) {
  while (!token(l, b))
    if (!next_line(r, l)) return 0;
  return 1;
}

/* The next token as a whole number; `what` names it in errors. */
static sh_status whole(sh__mesh_reader *r, off_line *l, int across, const char *what,
                       size_t *out) {
  const char *b;
  if (!(across ? token_across(r, l, &b) : token(l, &b)))
    return sh__mesh_reader_fail(r, l->line, across ? "the file ends before %s"
                                                   : "the line ends before %s", what);
  int ok = sh__mesh_whole(b, (size_t)(l->p - b), out);
  if (ok <= 0)
    return sh__mesh_reader_fail(r, l->line, "%s '%.*s' is %s", what, (int)(l->p - b), b,
                                ok ? "too large" : "not a whole number");
  return SH_OK;
}

/* The header keyword [ST][C][N][4][n]OFF in [b, e): 1 and whether it has
 * 4 and n, or 0 if it is not one. */
static int keyword(const char *b, const char *e, int *homogeneous, int *dimension) {
  int w = 0, n = 0;
  if (e - b >= 2 && b[0] == 'S' && b[1] == 'T') b += 2;
  if (b < e && *b == 'C') b++;
  if (b < e && *b == 'N') b++;
  if (b < e && *b == '4') b++, w = 1;
  if (b < e && *b == 'n') b++, n = 1;
  if (e - b != 3 || memcmp(b, "OFF", 3)) return 0;
  *homogeneous = w;
  *dimension = n;
  return 1;
}

/* The header, up to and with the counts' line. */
static sh_status header(sh__mesh_reader *r, off_line *l, int *ndim, int *homogeneous,
                        size_t *nf) {
  const char *b;
  *ndim = 3;
  *homogeneous = 0;
  if (!next_line(r, l)) return sh__mesh_reader_fail(r, 1, "the file is empty");
  const char *first = l->p;
  token(l, &b);
  int dimension = 0;
  if (keyword(b, l->p, homogeneous, &dimension)) {
    const char *save = l->p;
    if (token(l, &b) && l->p - b == 6 && !memcmp(b, "BINARY", 6))
      return sh__mesh_reader_fail(r, l->line, "binary OFF files are not read (only text)");
    l->p = save;
  } else if (*b >= '0' && *b <= '9') {
    l->p = first; /* no keyword (it is optional): the counts come first */
  } else {
    return sh__mesh_reader_fail(r, l->line,
                                "'%.*s' is neither an OFF keyword ([ST][C][N][4][n]OFF) "
                                "nor a vertex count", (int)(l->p - b), b);
  }
  size_t n;
  sh_status st;
  if (dimension) {
    if ((st = whole(r, l, 1, "the dimension", &n)) != SH_OK) return st;
    if (n < 1 || n > 3)
      return sh__mesh_reader_fail(r, l->line, "the dimension is %zu; 1, 2 or 3 are read", n);
    *ndim = (int)n;
  }
  size_t nv;
  if ((st = whole(r, l, 1, "the vertex count", &nv)) != SH_OK ||
      (st = whole(r, l, 0, "the face count", nf)) != SH_OK)
    return st;
  /* Each vertex and each face takes a line of one byte at least and its
   * line end (the last line may have none). */
  size_t left = (size_t)(r->end - r->p), lines = left / 2 + 1;
  if (nv > lines || *nf > lines - nv)
    return sh__mesh_reader_fail(r, l->line,
                                "the header declares %zu vertices and %zu faces, more "
                                "lines than the %zu bytes after it hold", nv, *nf, left);
  return sh__mesh_reader_vertices(r, nv, l->line);
}

static sh_status vertices(sh__mesh_reader *r, off_line *l, int ndim, int homogeneous) {
  for (size_t k = 0; k < r->nverts; k++) {
    if (!next_line(r, l))
      return sh__mesh_reader_fail(r, l->line, "the file ends after %zu of its %zu vertices",
                                  k, r->nverts);
    double x[4] = {0, 0, 0, 1};
    int nx = ndim + homogeneous;
    for (int i = 0; i < nx; i++) {
      const char *b;
      char *stop;
      if (!token(l, &b))
        return sh__mesh_reader_fail(r, l->line, "vertex %zu has %d coordinates, not %d", k,
                                    i, nx);
      x[i == ndim ? 3 : i] = strtod(b, &stop); /* the data ends with a NUL */
      if (stop != l->p)
        return sh__mesh_reader_fail(r, l->line, "'%.*s' in vertex %zu is not a number",
                                    (int)(l->p - b), b, k);
    }
    for (int i = 0; i < 3; i++) {
      sh_status st = sh__mesh_reader_coord(r, k, i, x[i] / x[3], l->line);
      if (st != SH_OK) return st;
    }
  }
  return SH_OK;
}

static sh_status faces(sh__mesh_reader *r, off_line *l, size_t nf) {
  for (size_t f = 0; f < nf; f++) {
    if (!next_line(r, l))
      return sh__mesh_reader_fail(r, l->line, "the file ends after %zu of its %zu faces", f,
                                  nf);
    size_t n;
    sh_status st = whole(r, l, 0, "a face's corner count", &n);
    if (st != SH_OK) return st;
    /* Each index takes two bytes of the line at least. */
    if (n > (size_t)(l->e - l->p) / 2)
      return sh__mesh_reader_fail(r, l->line, "a face counts %zu corners, more than its "
                                  "line holds", n);
    if ((st = sh__mesh_reader_list(r, n)) != SH_OK) return st;
    for (size_t i = 0; i < n; i++) {
      size_t x;
      if ((st = whole(r, l, 0, "a face's vertex index", &x)) != SH_OK) return st;
      r->list[i] = x < (size_t)LLONG_MAX ? (long long)x : LLONG_MAX;
    }
    if ((st = sh__mesh_reader_check(r, n, 0, "face", l->line)) != SH_OK ||
        (st = sh__mesh_reader_fan(r, n, l->line)) != SH_OK)
      return st;
  }
  return SH_OK;
}

sh_status sh__off_read(const char *path, const char *data, size_t size,
                       sh_mesh *mesh, sh_error *err) {
  sh__mesh_reader r;
  sh__mesh_reader_init(&r, path, data, size, err);
  off_line l = {data, data, 1};
  int ndim = 3, homogeneous = 0;
  size_t nf = 0;
  sh_status st = header(&r, &l, &ndim, &homogeneous, &nf);
  if (st == SH_OK) st = vertices(&r, &l, ndim, homogeneous);
  if (st == SH_OK) st = faces(&r, &l, nf);
  return sh__mesh_reader_finish(&r, st, mesh);
}
