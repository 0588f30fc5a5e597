/* gl_shafts against the reference renderer (lmm_tracer's reference mode,
 * in process) on scenes whose medium is an atmosphere: the sky from 1 m
 * above a 6360 km planet at sunset, and the planet from 30 000 km with
 * the terminator in view; shapes casting the sun's shadows into the air
 * (testdata/atmo_casters.json, 96x72); a point light and a spot in the air
 * (testdata/atmo_lamps.json, 96x72), and seen from space (space_lamp,
 * 48x36). `ctest -R
 * atmo_reference -V` prints the errors; a failure writes the images and
 * their difference. Measured at 48x36, 256 samples per pixel for the
 * reference (its own noise included): sky 0.43%, space 0.14%; bound 1.5%.
 * The casters at 96x72: 0.69%; bound 1.5%. The space lamp: 0.15%;
 * bound 1.5% (123% before its rays were ended on the ground). The lamps: 0.013%; bound
 * 0.5%. */
#include <stdio.h>

#include "sh_test.h"
#include "test_util.h"

#define AIR                                                                  \
  "\"medium\": {\"type\": \"atmosphere\", \"center\": [0, -6360, 0],"         \
  " \"ground_radius\": 6360, \"top_radius\": 6420, \"ground_albedo\": [0.3, 0.3, 0.3]," \
  " \"rayleigh\": {\"sigma_s\": [5.802e-3, 13.558e-3, 33.1e-3], \"scale_height\": 8}," \
  " \"mie\": {\"sigma_s\": [3.996e-3, 3.996e-3, 3.996e-3],"                   \
  "  \"sigma_a\": [0.444e-3, 0.444e-3, 0.444e-3], \"scale_height\": 1.2,"     \
  "  \"phase\": {\"type\": \"cornette_shanks\", \"g\": 0.8}},"                \
  " \"ozone\": {\"sigma_a\": [0.650e-3, 1.881e-3, 0.085e-3], \"center_height\": 25, \"width\": 30}}"

static const char *sky =
    "{\"format\": \"shafts-scene\", \"version\": 1,"
    " \"camera\": {\"position\": [0, 0.001, 0], \"look_at\": [1, 0.2, 0.1],"
    "  \"fov_y_deg\": 60, \"width\": 48, \"height\": 36}, " AIR ","
    " \"lights\": [{\"type\": \"directional\", \"direction\": [-0.99939, -0.0348995, 0],"
    "  \"irradiance\": [20, 20, 20], \"angular_diameter_deg\": 2}]}";

static const char *space =
    "{\"format\": \"shafts-scene\", \"version\": 1,"
    " \"camera\": {\"position\": [30000, 1000, 0], \"look_at\": [0, -6360, 0],"
    "  \"fov_y_deg\": 28, \"width\": 48, \"height\": 36}, " AIR ","
    " \"lights\": [{\"type\": \"directional\", \"direction\": [-0.17101, -0.17365, -0.9698],"
    "  \"irradiance\": [20, 20, 20]}]}";

/* Compares scene s (freed here) with the reference at 256 spp. */
/* The planet from space with a point light on the ground in view as well
 * (the pass of gs_atmo_light.h from outside the air: the ray ends on the
 * ground's near side). */
static const char *space_lamp =
    "{\"format\": \"shafts-scene\", \"version\": 1,"
    " \"camera\": {\"position\": [30000, 1000, 0], \"look_at\": [0, -6360, 0],"
    "  \"fov_y_deg\": 28, \"width\": 48, \"height\": 36}, " AIR ","
    " \"lights\": [{\"type\": \"directional\", \"direction\": [-0.17101, -0.17365, -0.9698],"
    "  \"irradiance\": [20, 20, 20]},"
    "  {\"type\": \"point\", \"position\": [0.6, 0.08, -0.15], \"intensity\": [0.6, 0.48, 0.36]}]}";

static void compare_scene(const char *name, sh_scene *s, double bound) {
  tu_check(s != NULL, name);
  if (!s) return;
  sh_image gl = {0}, ref = {0};
  if (tu_gl(s, NULL, &gl) == SH_OK && tu_reference(s, 256, &ref) == SH_OK)
    tu_check(tu_check_close(name, &gl, &ref, bound), name);
  else
    tu_check(0, name);
  sh_image_free(&gl);
  sh_image_free(&ref);
  sh_scene_free(s);
}

static void compare(const char *name, const char *json, double bound) {
  compare_scene(name, tu_scene(json), bound);
}

int main(void) {
  compare("atmo_ref_sky", sky, 0.015);
  compare("atmo_ref_space", space, 0.015);
  compare("atmo_ref_space_lamp", space_lamp, 0.015);
  /* Shapes in the air (gs_atmo_shapes.h): pillars and a ball casting the
   * sun's shadows into the air and on the ground. */
  compare_scene("atmo_ref_casters", sh_test_load("gl_shafts/testdata/%s", "atmo_casters.json"),
                0.015);
  /* A point light and a spot in the air (gs_atmo_light.h). */
  compare_scene("atmo_ref_lamps", sh_test_load("gl_shafts/testdata/%s", "atmo_lamps.json"),
                0.005);
  return tu_failures ? 1 : 0;
}
