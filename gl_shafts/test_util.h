/* Helpers for the gl_shafts tests: scenes from JSON text, renders by
 * gl_shafts and by the reference, and comparisons that write the images
 * and their difference to the build directory when a check fails. */
#ifndef TEST_UTIL_H
#define TEST_UTIL_H

#include "gs_render.h"
#include "sh_image.h"
#include "sh_scene.h"

/* Prints "ok: WHAT" or "FAIL: WHAT", counting failures in tu_failures. */
extern int tu_failures;
void tu_check(int cond, const char *what);

/* Parses a scene; relative files resolve against the source tree's scenes/
 * directory (SHAFTS_SOURCE_DIR). Prints the error and returns NULL on
 * failure. */
sh_scene *tu_scene(const char *json);

/* A GL context of the default backend (SHAFTS_GL_BACKEND narrows it),
 * current on the calling thread, for the tests that build programs
 * themselves; prints the backend and renderer, or the error and returns
 * NULL. Free it with gs__context_release and gs__context_free. */
struct gs__context *tu_context(void);

/* Renders with gl_shafts (opt NULL: the scene's defaults). Prints the error
 * and returns SH_OK or the failure. */
sh_status tu_gl(const sh_scene *scene, const gs_options *opt, sh_image *out);

/* The reference renderer with `spp` samples. */
sh_status tu_reference(const sh_scene *scene, int spp, sh_image *out);

/* The project's error measure (sh_image_compare, lit fraction 0.01). */
double tu_error(const sh_image *img, const sh_image *ref);

/* Checks that img is within `bound` (relative RMS) of ref, printing the
 * figure; on failure writes NAME.exr, NAME_ref.exr and NAME_diff.exr to
 * SHAFTS_BINARY_DIR (or .) and prints their paths. Returns 1 if it holds. */
int tu_check_close(const char *name, const sh_image *img, const sh_image *ref,
                   double bound);

/* Renders s with gl_shafts' defaults and with the reference at `spp`
 * samples and checks them with tu_check_close(name, ..., bound). Returns 1
 * if both render and the bound holds. */
int tu_check_reference(const char *name, const sh_scene *s, int spp, double bound);

/* Draws a kept renderer's frame of s into img (allocated here; the caller
 * frees it). Prints the error and returns 0 on failure, else 1. */
int tu_draw(gs_renderer *r, const sh_scene *s, sh_image *img, gs_stats *stats);

/* Whether a and b hold the same values bit for bit, printing how many
 * differ; on a difference writes the images as tu_check_close does. */
int tu_equal_bits(const char *name, const sh_image *a, const sh_image *b);

#endif
