/* gl_shafts' options and statistics by name, for command lines and
 * language bindings that should not mirror gs_options and gs_stats
 * (gs_render.h): options on the heap set from text, the frame's
 * statistics as JSON. The Python module (shafts.py) uses these. */
#ifndef GS_NAMED_H
#define GS_NAMED_H

#include <stddef.h>

#include "gs_render.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The options the scene's render keys give (planes, lattice,
 * light_map_res, shadow_map_res, xi, jitter) over the built-in defaults,
 * each checked against the table gs_options_set reads: a bad one is
 * SH_ERR_SCENE at its file, line and column, key path "render.KEY". */
sh_status gs_options_from_scene(const sh_scene *scene, gs_options *opt,
                                sh_error *err);

/* gs_options_defaults(scene) on the heap (NULL if out of memory); free
 * with gs_options_free. */
gs_options *gs_options_new(const sh_scene *scene);
void gs_options_free(gs_options *opt);

/* Sets the field named `key` (a gs_options field: "planes", "lattice_u",
 * "lattice_v", "lattice" (both: "NU NV", or one N), "light_map_res", "shadow_map_res", "xi" (lattice | exact),
 * "jitter", "sub_angle_deg", "sub_texels", "backend" (auto | egl |
 * osmesa), "live"; booleans take 0/1/true/false) from text. The value must
 * pass gs_options_check; else SH_ERR_ARG with the key as the error's key
 * path, and the options are unchanged. */
sh_status gs_options_set(gs_options *opt, const char *key, const char *value,
                         sh_error *err);

/* The names an option takes (NULL-terminated: "xi", "backend"), or NULL
 * for a number; and the name of one of its values ("?" if none). */
const char *const *gs_option_choices(const char *key);
const char *gs_option_name(const char *key, int value);

/* The size of a gs_stats, for a binding's buffer. */
size_t gs_stats_size(void);

/* Writes the frame statistics as a JSON object (the gs_stats field names)
 * into buf, as lmm_render_stats_json does: returns the whole text's
 * length, writes at most size bytes with the terminator. */
size_t gs_stats_json(const gs_stats *stats, char *buf, size_t size);

#ifdef __cplusplus
}
#endif
#endif
