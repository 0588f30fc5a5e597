#include "sh_render_params.h"

#include <stdio.h>
#include <string.h>

const sh_render_param *sh__render_param(const sh_scene *scene,
                                        const char *key) {
  for (int i = 0; scene && i < scene->render.nparams; i++)
    if (!strcmp(scene->render.params[i].key, key))
      return &scene->render.params[i];
  return NULL;
}

sh_status sh__render_params_apply(const sh_scene *scene, const sh__opt *table,
                                  size_t n, void *target,
                                  const char *const *keys, sh_error *err) {
  for (int k = 0; keys[k]; k++) {
    const sh_render_param *q = sh__render_param(scene, keys[k]);
    if (!q) continue;
    sh_error inner;
    if (sh__options_set(table, n, target, q->key, q->text, &inner) == SH_OK)
      continue;
    sh_error_set(err, SH_ERR_SCENE, "%s", inner.message);
    if (err) {
      snprintf(err->file, sizeof err->file, "%s",
               scene->file ? scene->file : "");
      err->line = q->line;
      err->column = q->column;
      snprintf(err->path, sizeof err->path, "render.%s", q->key);
    }
    return SH_ERR_SCENE;
  }
  return SH_OK;
}
