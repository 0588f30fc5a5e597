#include "se_run.h"

#include <string.h>

#include "se_blender.h"
#include "se_json.h"
#include "se_pov.h"
#include "sh_parse.h"

sh_status se_export_scene(const sh_scene *scene, se_target target, const se_options *opt,
                          const char *out_path, int strict, se_notes *notes,
                          sh_error *err) {
  se_output out = {0};
  sh_status st;
  if (target == SE_TARGET_POV) st = se_pov_build(scene, opt, out_path, &out, notes, err);
  else if (target == SE_TARGET_BLENDER)
    st = se_blender_build(scene, opt, out_path, &out, notes, err);
  else st = se_json_build(scene, out_path, &out, err);
  if (st == SH_OK && notes->failed) st = sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  if (st == SH_OK && strict && notes->count > 0)
    st = sh_error_set(err, SH_ERR_SCENE,
                      "the target cannot represent the scene exactly (%d approximation%s); "
                      "nothing written",
                      notes->count, notes->count == 1 ? "" : "s");
  if (st == SH_OK) st = se_output_write(&out, err);
  se_output_free(&out);
  return st;
}

sh_status se_export_file(const char *scene_path, const char *target, int quality,
                         const char *out_path, sh_error *err) {
  if (!scene_path || !target || !out_path)
    return sh_error_set(err, SH_ERR_ARG, "se_export_file: a NULL argument");
  se_target t;
  if (!strcmp(target, "pov")) t = SE_TARGET_POV;
  else if (!strcmp(target, "blender")) t = SE_TARGET_BLENDER;
  else if (!strcmp(target, "json")) t = SE_TARGET_JSON;
  else
    return sh_error_set(err, SH_ERR_ARG, "unknown export target '%s' (pov, blender or json)",
                        target);
  se_options opt = {quality ? SE_QUALITY_FINAL : SE_QUALITY_DRAFT};
  sh_scene *scene = NULL;
  sh_status st = sh_scene_load(scene_path, &scene, err);
  if (st != SH_OK) return st;
  se_notes notes = {0};
  st = se_export_scene(scene, t, &opt, out_path, 0, &notes, err);
  se_notes_free(&notes);
  sh_scene_free(scene);
  return st;
}
