#include "se_blender.h"

sh_status se_blender_build(const sh_scene *scene, const se_options *opt,
                           const char *py_path, se_output *out, se_notes *notes,
                           sh_error *err) {
  (void)scene; (void)opt; (void)py_path; (void)out; (void)notes;
  return sh_error_set(err, SH_ERR_ARG, "not yet");
}
