/* Internal: a renderer takes its keys of the scene's `render` object
 * (sh_render_param, kept by the parser with their places) through its own
 * option table (sh_options.h), so a key such as render.lattice has the one
 * limit the renderer's command-line option and bindings have, and a bad
 * value is reported at its file, line and column. */
#ifndef SH_RENDER_PARAMS_H
#define SH_RENDER_PARAMS_H

#include "sh_options.h"
#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The scene's render key `key`, or NULL if the scene does not give it. */
const sh_render_param *sh__render_param(const sh_scene *scene,
                                        const char *key);

/* Sets, for every render key of the scene listed in `keys` (NULL-
 * terminated: the renderer's own), the option of the same name in
 * `target` (sh__options_set). A value the table refuses is SH_ERR_SCENE
 * with the scene's file, the value's line and column, the key path
 * "render.KEY" and the table's message. */
sh_status sh__render_params_apply(const sh_scene *scene, const sh__opt *table,
                                  size_t n, void *target,
                                  const char *const *keys, sh_error *err);

#ifdef __cplusplus
}
#endif
#endif
