/* Internal: renderer options by name. A renderer describes its options
 * struct with one table of rows (name, field offset, kind, limits or
 * choices, the value that means "not given"); setting from text (the
 * command lines, language bindings: lmm_render_options_set,
 * gs_options_set) and checking a filled struct (lmm_render_options_check,
 * gs_options_check) both read it, so an option has one limit and one
 * message. pbrt-v4's ParameterDictionary is the model. Errors are
 * SH_ERR_ARG with the option's name as the error's key path. Nothing here
 * prints. */
#ifndef SH_OPTIONS_H
#define SH_OPTIONS_H

#include <stddef.h>

#include "sh_error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sh__opt_kind {
  SH__OPT_INT,    /* int[count], integral values in [lo, hi] */
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
  int unset;          /* 1: a filled struct may also hold unset_value ("not
                         given", the renderer decides); text may not */
  double unset_value;
  int count;          /* INT: consecutive ints set together (a lattice's
                         NU NV: "3 4", or "3" for both); 0 means 1 */
} sh__opt;

/* The row named `key`, or NULL. */
const sh__opt *sh__options_find(const sh__opt *table, size_t n,
                                const char *key);

/* Sets the field of `base` that row `key` of the n-row table describes. */
sh_status sh__options_set(const sh__opt *table, size_t n, void *base,
                          const char *key, const char *value, sh_error *err);

/* Checks every field of a filled struct against its row. */
sh_status sh__options_check(const sh__opt *table, size_t n, const void *base,
                            sh_error *err);

/* The name of a CHOICE row's value, or "?". */
const char *sh__options_choice_name(const sh__opt *row, int value);

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
