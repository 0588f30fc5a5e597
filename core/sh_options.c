#include "sh_options.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

sh_status sh__options_fail(sh_error *err, const char *key, const char *fmt,
                           ...) {
  va_list ap;
  va_start(ap, fmt);
  sh_error_vset(err, SH_ERR_ARG, fmt, ap);
  va_end(ap);
  sh_error_set_key(err, "%s", key);
  return SH_ERR_ARG;
}

/* "a, b, c" from a NULL-terminated list of names. */
static void join(char *buf, size_t size, const char *const *names) {
  size_t n = 0;
  buf[0] = '\0';
  for (int i = 0; names[i] && n < size; i++)
    n += (size_t)snprintf(buf + n, size - n, "%s%s", i ? ", " : "", names[i]);
}

const sh__opt *sh__options_find(const sh__opt *table, size_t n,
                                const char *key) {
  for (size_t i = 0; key && i < n; i++)
    if (!strcmp(table[i].name, key)) return &table[i];
  return NULL;
}

const char *sh__options_choice_name(const sh__opt *o, int value) {
  for (int i = 0; o->choices && o->choices[i]; i++)
    if (i + o->first == value) return o->choices[i];
  return "?";
}

/* Whether x is allowed; `unset_ok`: the "not given" value too. */
static int allowed(const sh__opt *o, double x, int unset_ok) {
  if (unset_ok && o->unset && x == o->unset_value) return 1;
  int integral = o->kind != SH__OPT_DOUBLE;
  return isfinite(x) && (o->lo_open ? x > o->lo : x >= o->lo) && x <= o->hi &&
         (!integral || x == floor(x)) &&
         (o->kind != SH__OPT_INT || fabs(x) < 2147483648.0);
}

static sh_status refuse(const sh__opt *o, const char *found, sh_error *err) {
  int integral = o->kind != SH__OPT_DOUBLE;
  char range[100] = "";
  if (integral && isfinite(o->lo) && isfinite(o->hi))
    snprintf(range, sizeof range, " from %.0f to %.0f", o->lo, o->hi);
  else if (isfinite(o->lo) && isfinite(o->hi))
    snprintf(range, sizeof range, " in %c%g, %g]", o->lo_open ? '(' : '[',
             o->lo, o->hi);
  else if (isfinite(o->lo))
    snprintf(range, sizeof range, " %s %g", o->lo_open ? ">" : ">=", o->lo);
  return sh__options_fail(err, o->name, "expected %s%s, found '%s'",
                          integral ? "an integer" : "a number", range, found);
}

static sh_status set_numbers(const sh__opt *o, void *field, const char *value,
                             sh_error *err) {
  int count = o->kind == SH__OPT_INT && o->count > 1 ? o->count : 1;
  double x[8];
  int got = 0;
  const char *p = value;
  while (got < count && got < 8) {
    char *end = NULL;
    errno = 0;
    x[got] = strtod(p, &end);
    if (end == p || errno || !allowed(o, x[got], 0))
      return refuse(o, value, err);
    got++;
    p = end;
    while (count > 1 && (*p == ' ' || *p == ',')) p++;
    if (!*p) break;
  }
  if (*p) return refuse(o, value, err);
  for (int k = 0; k < count; k++) {
    double v = x[k < got ? k : got - 1];
    if (o->kind == SH__OPT_INT)
      ((int *)field)[k] = (int)v;
    else if (o->kind == SH__OPT_LLONG)
      *(long long *)field = (long long)v;
    else
      *(double *)field = v;
  }
  return SH_OK;
}

sh_status sh__options_set(const sh__opt *table, size_t n, void *base,
                          const char *key, const char *value, sh_error *err) {
  char list[400];
  if (!base || !key || !value)
    return sh_error_set(err, SH_ERR_ARG, "options: no options, key or value");
  const sh__opt *o = sh__options_find(table, n, key);
  if (!o) {
    size_t len = 0;
    list[0] = '\0';
    for (size_t i = 0; i < n && len < sizeof list; i++)
      len += (size_t)snprintf(list + len, sizeof list - len, "%s%s",
                              i ? ", " : "", table[i].name);
    return sh__options_fail(err, key,
                            "unknown option '%s'; the options are: %s", key,
                            list);
  }
  void *field = (char *)base + o->offset;
  switch (o->kind) {
  case SH__OPT_BOOL:
    if (!strcmp(value, "1") || !strcasecmp(value, "true"))
      *(int *)field = 1;
    else if (!strcmp(value, "0") || !strcasecmp(value, "false"))
      *(int *)field = 0;
    else
      return sh__options_fail(err, key, "expected true or false, found '%s'",
                              value);
    return SH_OK;
  case SH__OPT_CHOICE:
    for (int c = 0; o->choices[c]; c++)
      if (!strcmp(o->choices[c], value)) {
        *(int *)field = c + o->first;
        return SH_OK;
      }
    join(list, sizeof list, o->choices);
    return sh__options_fail(err, key, "unknown value '%s'; expected one of: %s",
                            value, list);
  default: return set_numbers(o, field, value, err);
  }
}

sh_status sh__options_check(const sh__opt *table, size_t n, const void *base,
                            sh_error *err) {
  char found[64], list[400];
  for (size_t i = 0; i < n; i++) {
    const sh__opt *o = &table[i];
    const void *field = (const char *)base + o->offset;
    switch (o->kind) {
    case SH__OPT_BOOL: {
      int v = *(const int *)field;
      if (v != 0 && v != 1)
        return sh__options_fail(err, o->name,
                                "expected true or false, found %d", v);
      break;
    }
    case SH__OPT_CHOICE: {
      int v = *(const int *)field, ok = o->unset && v == o->unset_value;
      for (int c = 0; o->choices[c]; c++) ok |= v == c + o->first;
      if (!ok) {
        join(list, sizeof list, o->choices);
        return sh__options_fail(err, o->name,
                                "unknown value %d; expected one of: %s", v,
                                list);
      }
      break;
    }
    case SH__OPT_INT:
      for (int k = 0; k < (o->count > 1 ? o->count : 1); k++) {
        int v = ((const int *)field)[k];
        snprintf(found, sizeof found, "%d", v);
        if (!allowed(o, v, 1)) return refuse(o, found, err);
      }
      break;
    case SH__OPT_LLONG: {
      long long v = *(const long long *)field;
      snprintf(found, sizeof found, "%lld", v);
      if (!allowed(o, (double)v, 1)) return refuse(o, found, err);
      break;
    }
    case SH__OPT_DOUBLE: {
      double v = *(const double *)field;
      snprintf(found, sizeof found, "%g", v);
      if (!allowed(o, v, 1)) return refuse(o, found, err);
      break;
    }
    }
  }
  return SH_OK;
}
