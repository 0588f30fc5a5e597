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
    sh_error inner = SH_ERROR_INIT;
    if (sh__options_set(table, n, target, q->key, q->text, &inner) == SH_OK)
      continue;
    sh_error_set(err, SH_ERR_SCENE, "%s", inner.message);
    sh_error_clear(&inner);
    sh_error_set_file(err, scene->file);
    sh_error_set_key(err, "render.%s", q->key);
    if (err) {
      err->line = q->line;
      err->column = q->column;
    }
    return SH_ERR_SCENE;
  }
  return SH_OK;
}
