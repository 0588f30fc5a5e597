/* Internal: renderer options set by name from text, for the command lines
 * and language bindings (lmm_render_options_set, gs_options_set). A
 * renderer describes its options struct with a table of rows (name, field
 * offset, kind, limits or choices); sh__options_set parses a value for the
 * row of that name, checks it and stores it. Errors are SH_ERR_ARG with
 * the option's name as the error's key path. */
#ifndef SH_OPTIONS_H
#define SH_OPTIONS_H

#include <stddef.h>

#include "sh_error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sh__opt_kind {
  SH__OPT_INT,    /* int, integral values in [lo, hi] */
  SH__OPT_LLONG,  /* long long, integral values in [lo, hi] */
  SH__OPT_DOUBLE, /* double in [lo, hi] ((lo, hi] if lo_open) */
  SH__OPT_BOOL,   /* int 0/1 from "0", "1", "false", "true" */
  SH__OPT_CHOICE  /* int: the index in `choices` plus `first` */
} sh__opt_kind;

typedef struct sh__opt {
  const char *name;
  size_t offset; /* of the field in the options struct */
  sh__opt_kind kind;
  double lo, hi;
  int lo_open;
  const char *const *choices; /* NULL-terminated */
  int first;
} sh__opt;

/* Sets the field of `base` that row `key` of the n-row table describes. */
sh_status sh__options_set(const sh__opt *table, size_t n, void *base,
                          const char *key, const char *value, sh_error *err);

/* An SH_ERR_ARG whose key path is `key`. */
sh_status sh__options_fail(sh_error *err, const char *key, const char *fmt,
                           ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#ifdef __cplusplus
}
#endif
#endif
