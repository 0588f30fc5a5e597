#include "sh_parse_ctx.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const sh__range sh__any = {-INFINITY, INFINITY, 1, 1};
const sh__range sh__ge0 = {0.0, INFINITY, 0, 1};
const sh__range sh__gt0 = {0.0, INFINITY, 1, 1};
const sh__range sh__quantity = {0.0, SH__QUANTITY_MAX, 0, 0};

void sh__push_key(sh__pctx *c, const char *key) {
  if (c->depth < SH__PATH_MAX) {
    c->path[c->depth].key = key;
    c->path[c->depth].index = 0;
  }
  c->depth++;
}

void sh__push_index(sh__pctx *c, int index) {
  if (c->depth < SH__PATH_MAX) {
    c->path[c->depth].key = NULL;
    c->path[c->depth].index = index;
  }
  c->depth++;
}

void sh__pop(sh__pctx *c) {
  if (c->depth > 0) c->depth--;
}

/* Fills the error's location from the current path, at the key of the last
 * step if `at_key`; if the path is not in the text (it always should be),
 * falls back to the nearest enclosing value that is. */
static void locate(sh__pctx *c, int at_key) {
  sh_error *e = c->err;
  int depth = c->depth < SH__PATH_MAX ? c->depth : SH__PATH_MAX;
  size_t off = 0;
  int found = 0;
  sh_error_set_file(e, c->name);
  char *key = sh__json_format_path(c->path, depth);
  if (key) sh_error_set_key(e, "%s", key);
  free(key);
  for (int d = depth; d >= 0 && !found; d--) {
    found = sh__json_locate(
        c->text, c->len, c->path, d,
        d == depth && at_key && d > 0 && c->path[d - 1].key != NULL, &off);
  }
  if (found) sh__json_linecol(c->text, off, &e->line, &e->column);
}

void sh__where(sh__pctx *c, const char *key, int *line, int *column) {
  size_t off = 0;
  *line = *column = 0;
  if (key) sh__push_key(c, key);
  int depth = c->depth < SH__PATH_MAX ? c->depth : SH__PATH_MAX;
  if (c->text && sh__json_locate(c->text, c->len, c->path, depth, 0, &off))
    sh__json_linecol(c->text, off, line, column);
  if (key) sh__pop(c);
}

static sh_status vfail(sh__pctx *c, int at_key, sh_status status,
                       const char *fmt, va_list ap) {
  sh_error *e = c->err;
  if (!e) return status;
  sh_error_vset(e, status, fmt, ap);
  locate(c, at_key);
  return status;
}

sh_status sh__fail(sh__pctx *c, sh_status status, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vfail(c, 0, status, fmt, ap);
  va_end(ap);
  return status;
}

sh_status sh__fail_key(sh__pctx *c, sh_status status, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vfail(c, 1, status, fmt, ap);
  va_end(ap);
  return status;
}

sh_status sh__fail_at(sh__pctx *c, const char *key, sh_status status,
                      const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  sh__push_key(c, key);
  vfail(c, 0, status, fmt, ap);
  sh__pop(c);
  va_end(ap);
  return status;
}

sh_status sh__fail_from(sh__pctx *c, const char *key, const sh_error *inner,
                        const char *prefix) {
  sh_status status = inner->status != SH_OK ? inner->status : SH_ERR_SCENE;
  const char *msg =
      inner->message && inner->message[0] ? inner->message : sh_strerror(status);
  if (key) return sh__fail_at(c, key, status, "%s%s", prefix, msg);
  return sh__fail(c, status, "%s%s", prefix, msg);
}

void sh__fmt_num(double x, char *buf, size_t size) {
  snprintf(buf, size, "%.15g", x);
  if (strtod(buf, NULL) != x) snprintf(buf, size, "%.17g", x);
}

void sh__describe(const json_t *v, char *buf, size_t size) {
  char num[40];
  switch (json_typeof(v)) {
  case JSON_OBJECT: snprintf(buf, size, "an object"); break;
  case JSON_ARRAY: {
    size_t n = json_array_size(v);
    if (n == 0)
      snprintf(buf, size, "an empty array");
    else
      snprintf(buf, size, "an array of %zu element%s", n, n == 1 ? "" : "s");
    break;
  }
  case JSON_STRING: {
    const char *s = json_string_value(v);
    if (strlen(s) > 40)
      snprintf(buf, size, "the string \"%.40s...\"", s);
    else
      snprintf(buf, size, "the string \"%s\"", s);
    break;
  }
  case JSON_INTEGER:
    snprintf(buf, size, "the number %" JSON_INTEGER_FORMAT,
             json_integer_value(v));
    break;
  case JSON_REAL:
    sh__fmt_num(json_real_value(v), num, sizeof num);
    snprintf(buf, size, "the number %s", num);
    break;
  case JSON_TRUE: snprintf(buf, size, "true"); break;
  case JSON_FALSE: snprintf(buf, size, "false"); break;
  case JSON_NULL: snprintf(buf, size, "null"); break;
  }
}

/* The condition part of a range: "", ">= 0", "in (-1, 1)". */
static void range_condition(sh__range r, char *buf, size_t size) {
  char lo[40], hi[40];
  sh__fmt_num(r.lo, lo, sizeof lo);
  sh__fmt_num(r.hi, hi, sizeof hi);
  int has_lo = isfinite(r.lo), has_hi = isfinite(r.hi);
  if (has_lo && has_hi)
    snprintf(buf, size, "in %c%s, %s%c", r.lo_open ? '(' : '[', lo, hi,
             r.hi_open ? ')' : ']');
  else if (has_lo)
    snprintf(buf, size, "%s %s", r.lo_open ? ">" : ">=", lo);
  else if (has_hi)
    snprintf(buf, size, "%s %s", r.hi_open ? "<" : "<=", hi);
  else
    buf[0] = '\0';
}

void sh__describe_range(sh__range r, char *buf, size_t size) {
  char cond[100];
  range_condition(r, cond, sizeof cond);
  if (cond[0])
    snprintf(buf, size, "a number %s", cond);
  else
    snprintf(buf, size, "a finite number");
}

static int in_range(double x, sh__range r) {
  if (r.lo_open ? !(x > r.lo) : !(x >= r.lo)) return 0;
  if (r.hi_open ? !(x < r.hi) : !(x <= r.hi)) return 0;
  return 1;
}

static int lower(int ch) {
  return ch >= 'A' && ch <= 'Z' ? ch - 'A' + 'a' : ch;
}

int sh__edit_distance(const char *a, const char *b) {
  enum { MAXLEN = 64 };
  size_t n = strlen(a), m = strlen(b);
  int row[MAXLEN + 1];
  if (n > MAXLEN || m > MAXLEN) return INT_MAX / 2;
  for (size_t j = 0; j <= m; j++) row[j] = (int)j;
  for (size_t i = 1; i <= n; i++) {
    int diag = row[0];
    row[0] = (int)i;
    for (size_t j = 1; j <= m; j++) {
      int up = row[j];
      int cost =
          lower((unsigned char)a[i - 1]) != lower((unsigned char)b[j - 1]);
      int best = diag + cost;
      if (up + 1 < best) best = up + 1;
      if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
      row[j] = best;
      diag = up;
    }
  }
  return row[m];
}

const char *sh__suggest(const char *word, const char *const *names) {
  const char *best = NULL;
  int best_d = INT_MAX;
  int limit = strlen(word) <= 3 ? 1 : 2;
  for (int i = 0; names[i]; i++) {
    int d = sh__edit_distance(word, names[i]);
    if (d < best_d && d <= limit && d < (int)strlen(names[i])) {
      best = names[i];
      best_d = d;
    }
  }
  return best;
}

/* Writes "a, b, c" for a NULL-terminated list. */
static void join_names(const char *const *names, char *buf, size_t size) {
  size_t n = 0;
  buf[0] = '\0';
  for (int i = 0; names[i] && n < size; i++)
    n += (size_t)snprintf(buf + n, size - n, "%s%s", i ? ", " : "", names[i]);
}

sh_status sh__check_keys(sh__pctx *c, json_t *obj,
                         const char *const *const *tables, const char *what) {
  enum { MAXKEYS = 64 };
  const char *all[MAXKEYS + 1];
  int n = 0;
  for (int t = 0; tables[t]; t++)
    for (int k = 0; tables[t][k] && n < MAXKEYS; k++) all[n++] = tables[t][k];
  all[n] = NULL;
  const char *key;
  json_t *val;
  json_object_foreach(obj, key, val) {
    int known = 0;
    for (int k = 0; k < n && !known; k++) known = strcmp(key, all[k]) == 0;
    if (known) continue;
    const char *hint = sh__suggest(key, all);
    sh__push_key(c, key);
    if (hint) {
      sh__fail_key(c, SH_ERR_SCENE,
                   "unknown key '%s' in %s; did you mean '%s'?", key, what,
                   hint);
    } else {
      char list[512];
      join_names(all, list, sizeof list);
      sh__fail_key(c, SH_ERR_SCENE,
                   "unknown key '%s' in %s; the keys allowed there are: %s",
                   key, what, n ? list : "(none)");
    }
    sh__pop(c);
    return SH_ERR_SCENE;
  }
  return SH_OK;
}

sh_status sh__missing(sh__pctx *c, const char *key, const char *expected) {
  return sh__fail(c, SH_ERR_SCENE, "missing required key '%s' (expected %s)",
                  key, expected);
}

/* Reports a value of the wrong type or out of range: "expected X, found Y". */
static sh_status expected_found(sh__pctx *c, const char *key, const json_t *v,
                                const char *expected) {
  char found[160];
  sh__describe(v, found, sizeof found);
  return sh__fail_at(c, key, SH_ERR_SCENE, "expected %s, found %s", expected,
                     found);
}

sh_status sh__wrong(sh__pctx *c, const json_t *v, const char *expected) {
  char found[160];
  sh__describe(v, found, sizeof found);
  return sh__fail(c, SH_ERR_SCENE, "expected %s, found %s", expected, found);
}

/* What an absent key gives: the "missing required key" error when it is
 * required, SH_OK otherwise (the caller has written its default). */
static sh_status absent(sh__pctx *c, const char *key, int required,
                        const char *expected) {
  return required ? sh__missing(c, key, expected) : SH_OK;
}

/* jansson's type tests are macros; these give typed() a function. */
static int is_boolean(const json_t *v) { return json_is_boolean(v); }
static int is_string(const json_t *v) { return json_is_string(v); }
static int is_object(const json_t *v) { return json_is_object(v); }
static int is_array(const json_t *v) { return json_is_array(v); }

/* Looks up a key whose value must be of one JSON type: *out is the value,
 * NULL when the key is absent and optional; the located error when it is
 * absent and required or of another type. */
static sh_status typed(sh__pctx *c, json_t *obj, const char *key, int required,
                       const char *expected, int (*is)(const json_t *),
                       json_t **out) {
  json_t *v = json_object_get(obj, key);
  *out = NULL;
  if (!v) return absent(c, key, required, expected);
  if (!is(v)) return expected_found(c, key, v, expected);
  *out = v;
  return SH_OK;
}

sh_status sh__number(sh__pctx *c, json_t *obj, const char *key, int required,
                     double def, sh__range r, double *out) {
  char want[120];
  json_t *v = json_object_get(obj, key);
  sh__describe_range(r, want, sizeof want);
  if (!v) {
    *out = def;
    return absent(c, key, required, want);
  }
  if (!json_is_number(v)) return expected_found(c, key, v, want);
  double x = json_number_value(v);
  if (!isfinite(x) || !in_range(x, r)) return expected_found(c, key, v, want);
  *out = x;
  return SH_OK;
}

sh_status sh__integer(sh__pctx *c, json_t *obj, const char *key, int required,
                      long long def, long long lo, long long hi,
                      long long *out) {
  char want[120];
  json_t *v = json_object_get(obj, key);
  if (hi == LLONG_MAX)
    snprintf(want, sizeof want, "an integer >= %lld", lo);
  else
    snprintf(want, sizeof want, "an integer from %lld to %lld", lo, hi);
  if (!v) {
    *out = def;
    return absent(c, key, required, want);
  }
  long long x;
  if (json_is_integer(v)) {
    x = (long long)json_integer_value(v);
  } else if (json_is_real(v)) {
    double d = json_real_value(v);
    if (!isfinite(d) || d != floor(d) || fabs(d) > 9.0e15)
      return expected_found(c, key, v, want);
    x = (long long)d;
  } else {
    return expected_found(c, key, v, want);
  }
  if (x < lo || x > hi) return expected_found(c, key, v, want);
  *out = x;
  return SH_OK;
}

sh_status sh__vec3(sh__pctx *c, json_t *obj, const char *key, int required,
                   sh_vec3 def, sh__range r, sh_vec3 *out) {
  char cond[100], want[160], elem[120];
  json_t *v = json_object_get(obj, key);
  range_condition(r, cond, sizeof cond);
  if (cond[0])
    snprintf(want, sizeof want, "an array of 3 numbers %s", cond);
  else
    snprintf(want, sizeof want, "an array of 3 finite numbers");
  if (!v) {
    *out = def;
    return absent(c, key, required, want);
  }
  if (!json_is_array(v) || json_array_size(v) != 3)
    return expected_found(c, key, v, want);
  double x[3];
  sh__describe_range(r, elem, sizeof elem);
  for (int i = 0; i < 3; i++) {
    json_t *e = json_array_get(v, (size_t)i);
    if (!json_is_number(e) || !isfinite(json_number_value(e)) ||
        !in_range(json_number_value(e), r)) {
      char found[160];
      sh__describe(e, found, sizeof found);
      sh__push_key(c, key);
      sh__push_index(c, i);
      sh__fail(c, SH_ERR_SCENE, "expected %s, found %s", elem, found);
      sh__pop(c);
      sh__pop(c);
      return SH_ERR_SCENE;
    }
    x[i] = json_number_value(e);
  }
  *out = sh_v3(x[0], x[1], x[2]);
  return SH_OK;
}

sh_status sh__direction(sh__pctx *c, json_t *obj, const char *key, int required,
                        sh_vec3 *out, int *present) {
  sh_vec3 v;
  sh_status st = sh__vec3(c, obj, key, required, sh_v3s(0), sh__any, &v);
  if (st) return st;
  if (present) *present = json_object_get(obj, key) != NULL;
  if (!json_object_get(obj, key)) return SH_OK;
  if (sh_is_black(v))
    return sh__fail_at(c, key, SH_ERR_SCENE,
                       "expected a nonzero vector, found [0, 0, 0]");
  *out = v;
  return SH_OK;
}

sh_status sh__boolean(sh__pctx *c, json_t *obj, const char *key, int required,
                      int def, int *out) {
  json_t *v;
  sh_status st = typed(c, obj, key, required, "true or false", is_boolean, &v);
  if (st == SH_OK) *out = v ? json_is_true(v) : def;
  return st;
}

sh_status sh__string(sh__pctx *c, json_t *obj, const char *key, int required,
                     const char **out) {
  json_t *v;
  sh_status st = typed(c, obj, key, required, "a string", is_string, &v);
  if (st == SH_OK) *out = v ? json_string_value(v) : NULL;
  return st;
}

sh_status sh__choice(sh__pctx *c, json_t *obj, const char *key, int required,
                     const char *const *names, int def, const char *what,
                     int *out) {
  char list[400], want[480];
  json_t *v = json_object_get(obj, key);
  join_names(names, list, sizeof list);
  snprintf(want, sizeof want, "a %s (one of: %s)", what, list);
  if (!v) {
    *out = def;
    return absent(c, key, required, want);
  }
  if (!json_is_string(v)) return expected_found(c, key, v, want);
  const char *s = json_string_value(v);
  for (int i = 0; names[i]; i++)
    if (strcmp(s, names[i]) == 0) {
      *out = i;
      return SH_OK;
    }
  const char *hint = sh__suggest(s, names);
  if (hint)
    return sh__fail_at(c, key, SH_ERR_SCENE,
                       "unknown %s '%s'; did you mean '%s'?", what, s, hint);
  return sh__fail_at(c, key, SH_ERR_SCENE,
                     "unknown %s '%s'; expected one of: %s", what, s, list);
}

sh_status sh__object(sh__pctx *c, json_t *obj, const char *key, int required,
                     json_t **out) {
  return typed(c, obj, key, required, "an object", is_object, out);
}

sh_status sh__array(sh__pctx *c, json_t *obj, const char *key, int required,
                    json_t **out) {
  return typed(c, obj, key, required, "an array", is_array, out);
}

sh_status sh__min_max(sh__pctx *c, json_t *obj, sh_vec3 *lo, sh_vec3 *hi) {
  sh_status st;
  if ((st = sh__vec3(c, obj, "min", 1, sh_v3s(0), sh__any, lo))) return st;
  if ((st = sh__vec3(c, obj, "max", 1, sh_v3s(0), sh__any, hi))) return st;
  for (int i = 0; i < 3; i++) {
    if (sh_vget(*lo, i) < sh_vget(*hi, i)) continue;
    char a[40], b[40];
    sh__fmt_num(sh_vget(*lo, i), a, sizeof a);
    sh__fmt_num(sh_vget(*hi, i), b, sizeof b);
    return sh__fail_at(c, "max", SH_ERR_SCENE,
                       "expected max > min on every axis, found max.%c = %s "
                       "<= min.%c = %s",
                       "xyz"[i], b, "xyz"[i], a);
  }
  return SH_OK;
}

int sh__parallel(sh_vec3 u, sh_vec3 v) {
  return sh_length(sh_cross(u, v)) <= 1e-12 * sh_length(u) * sh_length(v);
}

sh_status sh__fail_unknown(sh__pctx *c, const char *key, const char *kind,
                           const char *name, const char *const *names,
                           const char *what_list) {
  char list[600], hint[200] = "";
  size_t n = 0;
  list[0] = '\0';
  for (int i = 0; names[i]; i++)
    if (n < sizeof list)
      n += (size_t)snprintf(list + n, sizeof list - n, "%s%s", i ? ", " : "",
                            names[i]);
  const char *near = sh__suggest(name, names);
  if (near) snprintf(hint, sizeof hint, "did you mean '%s'? ", near);
  return sh__fail_at(c, key, SH_ERR_SCENE, "unknown %s '%s'; %s%s: %s", kind,
                     name, hint, what_list, list);
}
