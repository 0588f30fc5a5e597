#include "se_run.h"

#include <stdio.h>
#include <string.h>

#include "sh_medium.h"
#include "sh_parse.h"

/* The medium types the renderers' targets write: the others are refused,
 * located at medium.type. */
static sh_status se_medium_supported(const sh_scene *scene, const char *target,
                                     const char *who, sh_error *err) {
  const sh_medium *m = &scene->medium;
  if (!m->present) return SH_OK;
  switch (m->type) {
  case SH_MEDIUM_HOMOGENEOUS:
  case SH_MEDIUM_HEIGHT_FOG:
    return SH_OK;
  case SH_MEDIUM_ATMOSPHERE:
    if (!strcmp(target, "pov") || !strcmp(target, "blender")) return SH_OK;
    break;
  default:
    break;
  }
  sh_error_set(err, SH_ERR_SCENE,
               "%s does not write a medium of type '%s' yet; lmm_tracer renders "
               "it (docs/scene-format.md, \"Non-uniform media\")",
               who, sh_medium_type_name(m->type));
  sh_medium_locate_type(scene, err);
  return SH_ERR_SCENE;
}

const se_target *se_target_find(const char *name) {
  for (const se_target *t = se_targets; name && t->name; t++)
    if (!strcmp(t->name, name)) return t;
  return NULL;
}

sh_status se_export_scene(const sh_scene *scene, const se_target *target,
                          const se_options *opt, const char *out_path,
                          int strict, se_notes *notes, se_output *result,
                          sh_error *err) {
  if (result) memset(result, 0, sizeof *result);
  if (!scene || !target || !opt || !out_path || !notes)
    return sh_error_set(err, SH_ERR_ARG, "se_export_scene: a NULL argument");
  se_output out = {0};
  char who[64];
  snprintf(who, sizeof who, "the %s exporter", target->name);
  /* The json target writes the scene as it is; the others write
   * homogeneous media, height fog and the atmosphere (issue 12; Blender's
   * script refuses the atmosphere for EEVEE). */
  if (strcmp(target->name, "json") != 0) {
    sh_status st = se_medium_supported(scene, target->name, who, err);
    if (st != SH_OK) return st;
  }
  sh_status st = target->build(scene, opt, out_path, &out, notes, err);
  if (st == SH_OK && notes->failed) st = sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  if (st == SH_OK && strict && notes->count > 0)
    st = sh_error_set(err, SH_ERR_SCENE,
                      "the target cannot represent the scene exactly (%d approximation%s); "
                      "nothing written",
                      notes->count, notes->count == 1 ? "" : "s");
  if (st == SH_OK) st = se_output_write(&out, scene, err);
  if (result) *result = out;
  else se_output_free(&out);
  return st;
}

sh_status se_export_file(const char *scene_path, const char *target, int quality,
                         const char *out_path, sh_error *err) {
  if (!scene_path || !target || !out_path)
    return sh_error_set(err, SH_ERR_ARG, "se_export_file: a NULL argument");
  const se_target *t = se_target_find(target);
  if (!t) {
    char list[200] = "";
    size_t n = 0;
    for (const se_target *r = se_targets; r->name && n < sizeof list; r++)
      n += (size_t)snprintf(list + n, sizeof list - n, "%s%s",
                            r == se_targets ? "" : ", ", r->name);
    return sh_error_set(err, SH_ERR_ARG, "unknown export target '%s' (%s)",
                        target, list);
  }
  se_options opt = {quality ? SE_QUALITY_FINAL : SE_QUALITY_DRAFT, SE_SCALE_AUTO, 0.0};
  sh_scene *scene = NULL;
  sh_status st = sh_scene_load(scene_path, &scene, err);
  if (st != SH_OK) return st;
  se_notes notes = {0};
  st = se_export_scene(scene, t, &opt, out_path, 0, &notes, NULL, err);
  se_notes_free(&notes);
  sh_scene_free(scene);
  return st;
}
