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
  char msg[SH_ERROR_MSG_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  sh_error_set(err, SH_ERR_ARG, "%s", msg);
  if (err) snprintf(err->path, sizeof err->path, "%s", key);
  return SH_ERR_ARG;
}

/* "a, b, c" from a NULL-terminated list of n_max names at most. */
static void join(char *buf, size_t size, const char *const *names) {
  size_t n = 0;
  buf[0] = '\0';
  for (int i = 0; names[i] && n < size; i++)
    n += (size_t)snprintf(buf + n, size - n, "%s%s", i ? ", " : "", names[i]);
}

static sh_status set_number(const sh__opt *o, void *field, const char *value,
                            sh_error *err) {
  char *end = NULL;
  errno = 0;
  double x = strtod(value, &end);
  int integral = o->kind != SH__OPT_DOUBLE;
  int ok = end != value && *end == '\0' && errno == 0 && isfinite(x) &&
           (o->lo_open ? x > o->lo : x >= o->lo) && x <= o->hi &&
           (!integral || x == floor(x)) &&
           (o->kind != SH__OPT_INT || fabs(x) < 2147483648.0);
  if (!ok) {
    char range[100] = "";
    if (integral && isfinite(o->lo) && isfinite(o->hi))
      snprintf(range, sizeof range, " from %.0f to %.0f", o->lo, o->hi);
    else if (isfinite(o->lo))
      snprintf(range, sizeof range, " %s %g", o->lo_open ? ">" : ">=", o->lo);
    return sh__options_fail(err, o->name, "expected %s%s, found '%s'",
                            integral ? "an integer" : "a number", range,
                            value);
  }
  if (o->kind == SH__OPT_INT)
    *(int *)field = (int)x;
  else if (o->kind == SH__OPT_LLONG)
    *(long long *)field = (long long)x;
  else
    *(double *)field = x;
  return SH_OK;
}

sh_status sh__options_set(const sh__opt *table, size_t n, void *base,
                          const char *key, const char *value, sh_error *err) {
  char list[400];
  if (!base || !key || !value)
    return sh_error_set(err, SH_ERR_ARG, "options: no options, key or value");
  for (size_t i = 0; i < n; i++) {
    const sh__opt *o = &table[i];
    if (strcmp(o->name, key) != 0) continue;
    void *field = (char *)base + o->offset;
    switch (o->kind) {
    case SH__OPT_BOOL:
      if (!strcmp(value, "1") || !strcasecmp(value, "true"))
        *(int *)field = 1;
      else if (!strcmp(value, "0") || !strcasecmp(value, "false"))
        *(int *)field = 0;
      else
        return sh__options_fail(err, key,
                                "expected true or false, found '%s'", value);
      return SH_OK;
    case SH__OPT_CHOICE:
      for (int c = 0; o->choices[c]; c++)
        if (!strcmp(o->choices[c], value)) {
          *(int *)field = c + o->first;
          return SH_OK;
        }
      join(list, sizeof list, o->choices);
      return sh__options_fail(err, key,
                              "unknown value '%s'; expected one of: %s", value,
                              list);
    default: return set_number(o, field, value, err);
    }
  }
  size_t len = 0;
  list[0] = '\0';
  for (size_t i = 0; i < n && len < sizeof list; i++)
    len += (size_t)snprintf(list + len, sizeof list - len, "%s%s",
                            i ? ", " : "", table[i].name);
  return sh__options_fail(err, key, "unknown option '%s'; the options are: %s",
                          key, list);
}
