/* Internal to the scene parser: the parsing context (the key path being
 * read, error reports with file, line, column and key path) and typed,
 * validating readers for the members of JSON objects.
 *
 * Every reader takes the object that holds the member and the member's key.
 * A missing member is an error when `required` is set and gets the default
 * otherwise. On any error the reader fills the context's sh_error, leaves the
 * output untouched and returns the status; callers return it at once. */
#ifndef SH_PARSE_CTX_H
#define SH_PARSE_CTX_H

#include <jansson.h>
#include <stddef.h>

#include "sh_error.h"
#include "sh_json_locate.h"
#include "sh_math.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SH__PATH_MAX 16

typedef struct sh__pctx {
  const char *text; /* the whole JSON text, for locating positions */
  size_t len;
  const char *name; /* the scene's file name, for messages */
  sh_error *err;
  sh__jseg path[SH__PATH_MAX]; /* the key path of the current object */
  int depth;
} sh__pctx;

/* A closed, half-open or open interval of allowed numbers; an infinite end
 * means no limit on that side (numbers must be finite anyway). */
typedef struct sh__range {
  double lo, hi;
  int lo_open, hi_open;
} sh__range;

extern const sh__range sh__any; /* every finite number */
extern const sh__range sh__ge0; /* >= 0 */
extern const sh__range sh__gt0; /* > 0 */
/* Radiometric quantities and coefficients (intensity, irradiance,
 * emission, background, ambient, sigma_s, sigma_a): in [0, SH__QUANTITY_MAX].
 * The bound keeps every product a renderer forms in single precision
 * (GL) finite: 1e30 leaves eight orders of magnitude below float's 3.4e38,
 * while a scene scaled by 1e4 (intensity times 1e8) stays far inside. */
#define SH__QUANTITY_MAX 1e30
extern const sh__range sh__quantity;

/* Enters or leaves an object member or array element. Keys must outlive
 * their time on the path (string literals, or keys of the JSON tree). */
void sh__push_key(sh__pctx *c, const char *key);
void sh__push_index(sh__pctx *c, int index);
void sh__pop(sh__pctx *c);

/* Reports an error at the value of the current path (sh__fail), at the key
 * of its last member (sh__fail_key), or at the value of member `key` of the
 * current object (sh__fail_at). Returns `status`. */
sh_status sh__fail(sh__pctx *c, sh_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
sh_status sh__fail_key(sh__pctx *c, sh_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
sh_status sh__fail_at(sh__pctx *c, const char *key, sh_status status,
                      const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Copies an error that another module reported without a location (a
 * loader, sh_light_prepare) into the context's error, with `prefix` before
 * its message and the location of member `key` (NULL: the current value). */
sh_status sh__fail_from(sh__pctx *c, const char *key, const sh_error *inner,
                        const char *prefix);

/* Describes a JSON value for "found ..." in messages: "a string", "an
 * array of 2 elements", "the number -1". */
void sh__describe(const json_t *v, char *buf, size_t size);
/* Formats a double briefly but exactly (it reads back as the same number). */
void sh__fmt_num(double x, char *buf, size_t size);
/* Describes a range: "a number >= 0", "a number in (-1, 1)". */
void sh__describe_range(sh__range r, char *buf, size_t size);

/* The Levenshtein distance of two strings, ignoring ASCII case. */
int sh__edit_distance(const char *a, const char *b);
/* The entry of the NULL-terminated `names` closest to `word`, if it is
 * close enough to be a likely misspelling; NULL otherwise. */
const char *sh__suggest(const char *word, const char *const *names);

/* Reports `name`, the value of member `key`, as naming none of the
 * NULL-terminated `names`: "unknown KIND 'name'; did you mean '...'? THE
 * NAMES ARE: a, b", with `what_list` ("the materials are") before the list.
 * Returns SH_ERR_SCENE. */
sh_status sh__fail_unknown(sh__pctx *c, const char *key, const char *kind,
                           const char *name, const char *const *names,
                           const char *what_list);

/* Checks that every member of `obj` is one of the NULL-terminated key lists
 * in the NULL-terminated array `tables`. An unknown key is an SH_ERR_SCENE at
 * the key, with a "did you mean" suggestion or the list of allowed keys;
 * `what` names the object in that list ("a point light"). */
sh_status sh__check_keys(sh__pctx *c, json_t *obj,
                         const char *const *const *tables, const char *what);

/* Reports a value of the wrong kind at the current path: "expected
 * `expected`, found <a description of v>". */
sh_status sh__wrong(sh__pctx *c, const json_t *v, const char *expected);

/* Reports a missing required member `key` of the current object, at the
 * object, describing what it should have been. */
sh_status sh__missing(sh__pctx *c, const char *key, const char *expected);

/* The line and column of member `key` of the current object in the text
 * (of the current object when `key` is NULL); 0, 0 if not found. */
void sh__where(sh__pctx *c, const char *key, int *line, int *column);

sh_status sh__number(sh__pctx *c, json_t *obj, const char *key, int required,
                     double def, sh__range r, double *out);
/* Integers in [lo, hi]; a real with an integral value is accepted. */
sh_status sh__integer(sh__pctx *c, json_t *obj, const char *key, int required,
                      long long def, long long lo, long long hi,
                      long long *out);
/* An array of 3 numbers, each in r. */
sh_status sh__vec3(sh__pctx *c, json_t *obj, const char *key, int required,
                   sh_vec3 def, sh__range r, sh_vec3 *out);
/* As sh__vec3 with no range and no default, and the vector must not be
 * zero (a direction, an up vector, a scale). */
sh_status sh__direction(sh__pctx *c, json_t *obj, const char *key, int required,
                        sh_vec3 *out, int *present);
sh_status sh__boolean(sh__pctx *c, json_t *obj, const char *key, int required,
                      int def, int *out);
/* A string; *out points into the JSON tree (NULL when absent). */
sh_status sh__string(sh__pctx *c, json_t *obj, const char *key, int required,
                     const char **out);
/* A string from the NULL-terminated `names`; *out is its index, `def` when
 * absent. `what` names the kind in messages ("light type"). */
sh_status sh__choice(sh__pctx *c, json_t *obj, const char *key, int required,
                     const char *const *names, int def, const char *what,
                     int *out);
/* An object or array member; *out is NULL when it is absent. */
sh_status sh__object(sh__pctx *c, json_t *obj, const char *key, int required,
                     json_t **out);
sh_status sh__array(sh__pctx *c, json_t *obj, const char *key, int required,
                    json_t **out);

/* Reads members "min" and "max" of `obj` and checks min < max on every
 * axis (reported at "max"). */
sh_status sh__min_max(sh__pctx *c, json_t *obj, sh_vec3 *lo, sh_vec3 *hi);

/* True if u and v are parallel (or one is zero), relative to their size. */
int sh__parallel(sh_vec3 u, sh_vec3 v);

#ifdef __cplusplus
}
#endif
#endif
