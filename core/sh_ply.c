/* The PLY reader (sh_ply.h). The format: Greg Turk, "The PLY Polygon File
 * Format" (1994), as Paul Bourke's copy gives it. */
#include "sh_ply.h"

#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "sh_mesh_reader.h"

typedef enum ply_type {
  PT_NONE, PT_I8, PT_U8, PT_I16, PT_U16, PT_I32, PT_U32, PT_F32, PT_F64
} ply_type;

static const struct {
  const char *name;
  ply_type type;
} TYPES[] = {{"char", PT_I8},    {"int8", PT_I8},     {"uchar", PT_U8},
             {"uint8", PT_U8},   {"short", PT_I16},   {"int16", PT_I16},
             {"ushort", PT_U16}, {"uint16", PT_U16},  {"int", PT_I32},
             {"int32", PT_I32},  {"uint", PT_U32},    {"uint32", PT_U32},
             {"float", PT_F32},  {"float32", PT_F32}, {"double", PT_F64},
             {"float64", PT_F64}};
/* Bytes of a binary value, and the range of the integer types. */
static const size_t TYPE_SIZE[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};
static const double TYPE_MIN[] = {0, -128, 0, -32768, 0, -2147483648.0, 0, 0, 0};
static const double TYPE_MAX[] = {0, 127, 255, 32767, 65535, 2147483647.0,
                                  4294967295.0, 0, 0};

enum { ROLE_SKIP, ROLE_X, ROLE_Y, ROLE_Z, ROLE_INDICES };
enum { EL_OTHER, EL_VERTEX, EL_FACE, EL_STRIPS };
enum { FMT_ASCII, FMT_LE, FMT_BE };

typedef struct ply_prop {
  ply_type type, count_type; /* count_type != PT_NONE: a list */
  int role;
} ply_prop;

typedef struct ply_element {
  char *name;
  int kind, line, nprops;
  size_t count;
  ply_prop *props;
} ply_element;

typedef struct reader {
  sh__mesh_reader m; /* the file, the cursor, the mesh being built */
  int format, swap;
  ply_element *el;
  int nel;
} reader;

/* The error, located at a line (> 0) or, in binary data, at the cursor. */
#define fail(r, ...) sh__mesh_reader_fail(&(r)->m, __VA_ARGS__)
#define is_space sh__mesh_is_space

int sh__ply_magic(const unsigned char *head, size_t n) {
  size_t i = 0;
  while (i < n && is_space((char)head[i])) i++;
  return n - i >= 3 && (head[i] | 0x20) == 'p' && (head[i + 1] | 0x20) == 'l' &&
         (head[i + 2] | 0x20) == 'y';
}

/* ---- The header ---- */

#define MAX_TOKENS 6

typedef struct token {
  const char *s;
  size_t n;
} token;

static int tok_is(token t, const char *word) {
  return t.n == strlen(word) && !memcmp(t.s, word, t.n);
}

static ply_type type_of(token t) {
  for (size_t i = 0; i < sizeof TYPES / sizeof TYPES[0]; i++)
    if (tok_is(t, TYPES[i].name)) return TYPES[i].type;
  return PT_NONE;
}

/* Splits [s, e) into at most MAX_TOKENS tokens; returns how many there are
 * (MAX_TOKENS + 1 if more). */
static int split(const char *s, const char *e, token *t) {
  int n = 0;
  while (s < e) {
    while (s < e && is_space(*s)) s++;
    if (s == e) break;
    const char *b = s;
    while (s < e && !is_space(*s)) s++;
    if (n == MAX_TOKENS) return MAX_TOKENS + 1;
    t[n].s = b;
    t[n++].n = (size_t)(s - b);
  }
  return n;
}

static sh_status add_property(reader *r, long line, token *t, int nt) {
  if (r->nel == 0)
    return fail(r, line, "a property comes before any element");
  ply_element *e = &r->el[r->nel - 1];
  ply_prop pr = {PT_NONE, PT_NONE, ROLE_SKIP};
  token name;
  if (nt >= 2 && tok_is(t[1], "list")) {
    if (nt != 5)
      return fail(r, line, "a list property is 'property list COUNT_TYPE TYPE NAME'");
    pr.count_type = type_of(t[2]);
    pr.type = type_of(t[3]);
    if (pr.count_type == PT_NONE || pr.count_type >= PT_F32)
      return fail(r, line, "the count type '%.*s' of a list is not an integer type",
                  (int)t[2].n, t[2].s);
    if (pr.type == PT_NONE)
      return fail(r, line, "unknown type '%.*s'", (int)t[3].n, t[3].s);
    name = t[4];
  } else {
    if (nt != 3) return fail(r, line, "a property is 'property TYPE NAME'");
    pr.type = type_of(t[1]);
    if (pr.type == PT_NONE)
      return fail(r, line, "unknown type '%.*s'", (int)t[1].n, t[1].s);
    name = t[2];
  }
  int list = pr.count_type != PT_NONE;
  if (e->kind == EL_VERTEX && !list) {
    if (tok_is(name, "x")) pr.role = ROLE_X;
    if (tok_is(name, "y")) pr.role = ROLE_Y;
    if (tok_is(name, "z")) pr.role = ROLE_Z;
  }
  if (list && pr.type < PT_F32 &&
      ((e->kind == EL_FACE && (tok_is(name, "vertex_indices") || tok_is(name, "vertex_index"))) ||
       (e->kind == EL_STRIPS && tok_is(name, "vertex_indices"))))
    pr.role = ROLE_INDICES;
  for (int i = 0; i < e->nprops; i++)
    if (pr.role != ROLE_SKIP && e->props[i].role == pr.role)
      return fail(r, line, "element '%s' has property '%.*s' twice", e->name,
                  (int)name.n, name.s);
  ply_prop *np = realloc(e->props, (size_t)(e->nprops + 1) * sizeof *np);
  if (!np) return sh_error_set(r->m.err, SH_ERR_NOMEM, "out of memory");
  e->props = np;
  e->props[e->nprops++] = pr;
  return SH_OK;
}

static sh_status add_element(reader *r, long line, token *t, int nt) {
  if (nt != 3) return fail(r, line, "an element is 'element NAME COUNT'");
  size_t count = 0;
  int whole = sh__mesh_whole(t[2].s, t[2].n, &count);
  if (whole == 0)
    return fail(r, line, "the count '%.*s' is not a whole number", (int)t[2].n, t[2].s);
  if (whole < 0)
    return fail(r, line, "the count '%.*s' is too large", (int)t[2].n, t[2].s);
  int kind = tok_is(t[1], "vertex") ? EL_VERTEX
             : tok_is(t[1], "face") ? EL_FACE
             : tok_is(t[1], "tristrips") ? EL_STRIPS
                                         : EL_OTHER;
  for (int i = 0; i < r->nel; i++)
    if (kind != EL_OTHER && r->el[i].kind == kind)
      return fail(r, line, "element '%.*s' comes twice", (int)t[1].n, t[1].s);
  ply_element *ne = realloc(r->el, (size_t)(r->nel + 1) * sizeof *ne);
  if (!ne) return sh_error_set(r->m.err, SH_ERR_NOMEM, "out of memory");
  r->el = ne;
  ply_element *e = &r->el[r->nel];
  memset(e, 0, sizeof *e);
  e->name = malloc(t[1].n + 1);
  if (!e->name) return sh_error_set(r->m.err, SH_ERR_NOMEM, "out of memory");
  memcpy(e->name, t[1].s, t[1].n);
  e->name[t[1].n] = '\0';
  e->kind = kind;
  e->count = count;
  e->line = (int)(line < INT_MAX ? line : INT_MAX);
  r->nel++;
  return SH_OK;
}

/* Parses the header; leaves r->m.p at the first byte of the data. */
static sh_status parse_header(reader *r) {
  const char *s = r->m.data;
  long line = 0;
  int have_magic = 0, have_format = 0;
  for (;;) {
    if (s >= r->m.end)
      return fail(r, line > 0 ? line : 1,
                  "the header ends at the end of the file with no 'end_header' line");
    const char *nl = memchr(s, '\n', (size_t)(r->m.end - s));
    const char *e = nl ? nl : r->m.end;
    line++;
    token t[MAX_TOKENS];
    int nt = split(s, e, t);
    s = nl ? nl + 1 : r->m.end;
    if (nt == 0) continue; /* a blank line */
    if (!have_magic) {
      if (nt != 1 || t[0].n != 3 || strncasecmp(t[0].s, "ply", 3))
        return fail(r, line, "a PLY file begins with the line 'ply'");
      have_magic = 1;
      continue;
    }
    if (tok_is(t[0], "comment") || tok_is(t[0], "obj_info")) continue;
    if (tok_is(t[0], "end_header")) {
      if (nt != 1) return fail(r, line, "'end_header' stands alone on its line");
      if (!have_format) return fail(r, line, "the header has no 'format' line");
      r->m.p = s;
      r->m.line = line + 1;
      return SH_OK;
    }
    sh_status st = SH_OK;
    if (tok_is(t[0], "format")) {
      if (have_format || r->nel) return fail(r, line, "a second or late 'format' line");
      if (nt != 3 || !tok_is(t[2], "1.0"))
        return fail(r, line, "the format line is 'format ascii|binary_little_endian|"
                             "binary_big_endian 1.0'");
      if (tok_is(t[1], "ascii")) r->format = FMT_ASCII;
      else if (tok_is(t[1], "binary_little_endian")) r->format = FMT_LE;
      else if (tok_is(t[1], "binary_big_endian")) r->format = FMT_BE;
      else return fail(r, line, "unknown format '%.*s'", (int)t[1].n, t[1].s);
      have_format = 1;
    } else if (tok_is(t[0], "element")) {
      st = add_element(r, line, t, nt);
    } else if (tok_is(t[0], "property")) {
      st = add_property(r, line, t, nt);
    } else {
      return fail(r, line, "unknown header keyword '%.*s'", (int)t[0].n, t[0].s);
    }
    if (st != SH_OK) return st;
  }
}

/* Checks what the header declares against what the file can hold, before
 * anything is allocated or looped over. */
static sh_status check_counts(reader *r) {
  size_t avail = (size_t)(r->m.end - r->m.p), need = 0;
  int vertex = -1;
  for (int i = 0; i < r->nel; i++) {
    ply_element *e = &r->el[i];
    if (e->kind == EL_VERTEX) vertex = i;
    if (e->nprops == 0 || e->count == 0) continue;
    /* At least a value and a separator per property in ASCII (the last
     * value of the file needs none), the values' bytes in binary; a list
     * holds at least its count. */
    size_t least = 0;
    for (int k = 0; k < e->nprops; k++) {
      const ply_prop *pr = &e->props[k];
      least += r->format == FMT_ASCII ? 2
               : TYPE_SIZE[pr->count_type != PT_NONE ? pr->count_type : pr->type];
    }
    size_t room = avail + (r->format == FMT_ASCII) - need; /* need <= that */
    if (e->count > room / least)
      return fail(r, e->line,
                  "element '%s' declares %zu instances of at least %zu bytes each, "
                  "more than the %zu bytes after the header hold",
                  e->name, e->count, least, avail);
    need += e->count * least;
  }
  if (vertex < 0) return fail(r, 1, "the header declares no element 'vertex'");
  ply_element *v = &r->el[vertex];
  int have[4] = {0};
  for (int k = 0; k < v->nprops; k++) have[v->props[k].role] = 1;
  if (v->count && !(have[ROLE_X] && have[ROLE_Y] && have[ROLE_Z]))
    return fail(r, v->line, "element 'vertex' lacks property x, y or z");
  return sh__mesh_reader_vertices(&r->m, v->count, v->line);
}

/* ---- The data ---- */

/* Reads one value of type t into *out (integers exactly). */
static sh_status read_value(reader *r, ply_type t, const char *what, double *out) {
  if (r->format != FMT_ASCII) {
    size_t n = TYPE_SIZE[t];
    if ((size_t)(r->m.end - r->m.p) < n)
      return fail(r, 0, "the file ends inside %s", what);
    unsigned char b[8];
    memcpy(b, r->m.p, n);
    if (r->swap)
      for (size_t i = 0; i < n / 2; i++) {
        unsigned char c = b[i];
        b[i] = b[n - 1 - i];
        b[n - 1 - i] = c;
      }
    r->m.p += n;
    switch (t) {
    case PT_I8: { int8_t x; memcpy(&x, b, 1); *out = x; break; }
    case PT_U8: *out = b[0]; break;
    case PT_I16: { int16_t x; memcpy(&x, b, 2); *out = x; break; }
    case PT_U16: { uint16_t x; memcpy(&x, b, 2); *out = x; break; }
    case PT_I32: { int32_t x; memcpy(&x, b, 4); *out = x; break; }
    case PT_U32: { uint32_t x; memcpy(&x, b, 4); *out = x; break; }
    case PT_F32: { float x; memcpy(&x, b, 4); *out = x; break; }
    default: { double x; memcpy(&x, b, 8); *out = x; break; }
    }
    return SH_OK;
  }
  while (r->m.p < r->m.end && is_space(*r->m.p))
    if (*r->m.p++ == '\n') r->m.line++;
  if (r->m.p == r->m.end) return fail(r, r->m.line, "the file ends before %s", what);
  const char *b = r->m.p;
  while (r->m.p < r->m.end && !is_space(*r->m.p)) r->m.p++;
  if (t >= PT_F32) {
    char *stop;
    *out = strtod(b, &stop); /* the data is followed by a NUL (sh_ply.h) */
    if (stop != r->m.p)
      return fail(r, r->m.line, "'%.*s' in %s is not a number", (int)(r->m.p - b), b, what);
    return SH_OK;
  }
  const char *q = b;
  int neg = q < r->m.p && *q == '-';
  if (q < r->m.p && (*q == '-' || *q == '+')) q++;
  double v = 0;
  if (q == r->m.p) return fail(r, r->m.line, "'%.*s' in %s is not a whole number", (int)(r->m.p - b), b, what);
  for (; q < r->m.p; q++) {
    if (*q < '0' || *q > '9')
      return fail(r, r->m.line, "'%.*s' in %s is not a whole number", (int)(r->m.p - b), b, what);
    v = v * 10 + (*q - '0');
    if (v > 1e10) break; /* out of every integer type's range */
  }
  *out = neg ? -v : v;
  if (*out < TYPE_MIN[t] || *out > TYPE_MAX[t])
    return fail(r, r->m.line, "'%.*s' in %s is out of its type's range", (int)(r->m.p - b), b, what);
  return SH_OK;
}

/* Turns one index list (r->m.list, n values) into triangles. */
static sh_status emit(reader *r, int kind, size_t n, long line) {
  sh__mesh_reader *m = &r->m;
  sh_status st = sh__mesh_reader_check(m, n, kind == EL_STRIPS,
                                       kind == EL_STRIPS ? "triangle strip" : "face", line);
  if (st != SH_OK) return st;
  if (kind == EL_FACE) return sh__mesh_reader_fan(m, n, line);
  size_t j = 0; /* position in the current strip */
  for (size_t i = 0; i < n && st == SH_OK; i++) {
    if (m->list[i] == -1) {
      j = 0;
      continue;
    }
    if (++j < 3) continue;
    long long a = m->list[i - 2], b = m->list[i - 1], c = m->list[i];
    st = j % 2 ? sh__mesh_reader_triangle(m, a, b, c, line)
               : sh__mesh_reader_triangle(m, b, a, c, line);
  }
  return st;
}

static sh_status read_list(reader *r, const ply_element *e, const ply_prop *pr,
                           size_t inst) {
  char what[96];
  snprintf(what, sizeof what, "a list of element instance %zu", inst);
  double c;
  sh_status st = read_value(r, pr->count_type, what, &c);
  if (st != SH_OK) return st;
  /* Errors at the count's line, or at the cursor's byte in binary data. */
  long line = r->format == FMT_ASCII ? r->m.line : 0;
  if (c < 0) return fail(r, line, "a list's count is negative");
  size_t n = (size_t)c, left = (size_t)(r->m.end - r->m.p);
  /* Each entry takes a byte at least (ASCII) or its size (binary). */
  if (n > left / (r->format == FMT_ASCII ? 1 : TYPE_SIZE[pr->type]))
    return fail(r, line,
                "a list of element '%s' counts %zu entries, more than the %zu bytes "
                "left hold", e->name, n, left);
  if (pr->role == ROLE_INDICES && (st = sh__mesh_reader_list(&r->m, n)) != SH_OK) return st;
  for (size_t i = 0; i < n; i++) {
    double v;
    if ((st = read_value(r, pr->type, what, &v)) != SH_OK) return st;
    if (pr->role == ROLE_INDICES) r->m.list[i] = (long long)v;
  }
  return pr->role == ROLE_INDICES ? emit(r, e->kind, n, line) : SH_OK;
}

static sh_status read_data(reader *r) {
  for (int i = 0; i < r->nel; i++) {
    const ply_element *e = &r->el[i];
    if (e->nprops == 0) continue;
    for (size_t k = 0; k < e->count; k++) {
      for (int j = 0; j < e->nprops; j++) {
        const ply_prop *pr = &e->props[j];
        sh_status st;
        if (pr->count_type != PT_NONE) {
          st = read_list(r, e, pr, k);
        } else {
          char what[96];
          snprintf(what, sizeof what, "element '%s' instance %zu", e->name, k);
          double v;
          st = read_value(r, pr->type, what, &v);
          if (st == SH_OK && pr->role >= ROLE_X && pr->role <= ROLE_Z)
            st = sh__mesh_reader_coord(&r->m, k, pr->role - ROLE_X, v,
                                       r->format == FMT_ASCII ? r->m.line : 0);
        }
        if (st != SH_OK) return st;
      }
    }
  }
  return SH_OK;
}

sh_status sh__ply_read(const char *path, const char *data, size_t size,
                       sh_mesh *mesh, sh_error *err) {
  reader r;
  memset(&r, 0, sizeof r);
  sh__mesh_reader_init(&r.m, path, data, size, err);
  const union { uint16_t u; unsigned char c[2]; } probe = {1};
  sh_status st = parse_header(&r);
  if (st == SH_OK) {
    r.swap = r.format == (probe.c[0] ? FMT_BE : FMT_LE);
    st = check_counts(&r);
  }
  if (st == SH_OK) st = read_data(&r);
  for (int i = 0; i < r.nel; i++) {
    free(r.el[i].name);
    free(r.el[i].props);
  }
  free(r.el);
  return sh__mesh_reader_finish(&r.m, st, mesh);
}
