/* Invariances of the image that hold exactly in the physics and must hold
 * to float precision in gl_shafts:
 * - scaling every length by s, the coefficients by 1/s and the point and
 *   spot intensities by s^2 leaves the image unchanged;
 * - two coincident lights render as one of their summed intensity;
 * - the image is linear in the lights' intensities. */
#include <stdio.h>
#include <string.h>

#include "sh_test.h"
#include "test_util.h"

/* A spot with a gobo and a shadow-casting ball, a directional light through
 * a window, a floor; lengths times s, coefficients over s, intensities
 * times k s^2 (irradiance times k). */
static sh_scene *scene(double s, double k) {
  char json[4096];
  double is = k * s * s;
  snprintf(json, sizeof json,
    "{\"format\": \"shafts-scene\", \"version\": 1,"
    " \"camera\": {\"position\": [%g, %g, %g], \"look_at\": [0, %g, 0],"
    "  \"fov_y_deg\": 50, \"width\": 64, \"height\": 48},"
    " \"medium\": {\"sigma_s\": [%g, %g, %g], \"sigma_a\": [%g, %g, %g],"
    "  \"phase\": {\"type\": \"henyey_greenstein\", \"g\": 0.3},"
    "  \"bounds\": {\"min\": [%g, 0, %g], \"max\": [%g, %g, %g]}},"
    " \"lights\": [{\"type\": \"spot\", \"position\": [%g, %g, %g],"
    "   \"look_at\": [0, 0, 0], \"intensity\": [%g, %g, %g],"
    "   \"outer_angle_deg\": 28, \"inner_angle_deg\": 20, \"exponent\": 1,"
    "   \"light_map\": {\"image\": \"assets/gobo_star.png\", \"up\": [0, 0, -1]}},"
    "  {\"type\": \"directional\", \"direction\": [1, -0.8, 0.3],"
    "   \"irradiance\": [%g, %g, %g],"
    "   \"light_map\": {\"image\": \"assets/stained_glass.png\","
    "    \"origin\": [%g, %g, %g], \"u\": [0, 0, %g], \"v\": [0, %g, 0]}}],"
    " \"materials\": {\"m\": {\"diffuse\": [0.5, 0.5, 0.5], \"specular\": [0.2, 0.2, 0.2]}},"
    " \"shapes\": [{\"type\": \"quad\", \"material\": \"m\", \"corner\": [%g, 0, %g],"
    "   \"u\": [%g, 0, 0], \"v\": [0, 0, %g]},"
    "  {\"type\": \"sphere\", \"material\": \"m\", \"center\": [%g, %g, %g],"
    "   \"radius\": %g}]}",
    2.5 * s, 2.0 * s, 3.0 * s, 0.7 * s,
    0.2 / s, 0.2 / s, 0.2 / s, 0.02 / s, 0.03 / s, 0.04 / s,
    -3 * s, -3 * s, 3 * s, 4 * s, 3 * s,
    -0.5 * s, 3.2 * s, 0.2 * s, 12 * is, 11 * is, 10 * is,
    1.5 * k, 1.4 * k, 1.3 * k,
    -3 * s, 2.5 * s, -1 * s, 2 * s, -1.2 * s,
    -3 * s, 3 * s, 6 * s, -6 * s, 0.2 * s, 0.8 * s, 0.1 * s, 0.35 * s);
  return tu_scene(json);
}

int main(void) {
  /* Scale invariance. */
  sh_scene *a = scene(1.0, 1.0), *b = scene(2.5, 1.0);
  SH_CHECK(a && b);
  sh_image ia = {0}, ib = {0};
  /* Not quite float precision: a fragment's sub-sample count is the ceiling
   * of a rate computed in float, which rounding can move by one between the
   * scales in a few fragments (1.1e-4 measured with the gobo sampled per
   * two texels). */
  if (a && b && tu_gl(a, NULL, &ia) == SH_OK && tu_gl(b, NULL, &ib) == SH_OK)
    SH_CHECK(tu_check_close("scale_invariance", &ib, &ia, 3e-4));
  else
    SH_CHECK(0);

  /* Linearity: intensities times 3. */
  sh_scene *c = scene(1.0, 3.0);
  sh_image ic = {0};
  SH_CHECK(c && tu_gl(c, NULL, &ic) == SH_OK);
  if (ic.rgb && ia.rgb) {
    sh_image third = {0};
    SH_CHECK(sh_image_alloc(&third, ic.width, ic.height, NULL) == SH_OK);
    for (size_t i = 0; i < (size_t)ic.width * ic.height * 3; i++)
      third.rgb[i] = ic.rgb[i] / 3.0f;
    SH_CHECK(tu_check_close("linearity", &third, &ia, 1e-5));
    sh_image_free(&third);
  }

  /* Two coincident lights, each a copy with intensity split 1 : 2, against
   * one light with the sum: the scene with k = 3 above. */
  if (c) {
    sh_light *ls = calloc(4, sizeof *ls);
    memcpy(ls, c->lights, 2 * sizeof *ls);
    memcpy(ls + 2, c->lights, 2 * sizeof *ls);
    for (int i = 0; i < 2; i++) {
      ls[i].intensity = sh_scale(ls[i].intensity, 1.0 / 3.0);
      ls[i].irradiance = sh_scale(ls[i].irradiance, 1.0 / 3.0);
      ls[i + 2].intensity = sh_scale(ls[i + 2].intensity, 2.0 / 3.0);
      ls[i + 2].irradiance = sh_scale(ls[i + 2].irradiance, 2.0 / 3.0);
    }
    /* The copies share the light maps' pixels: the scene frees its own
     * lights only. */
    sh_light *own = c->lights;
    int nown = c->nlights;
    c->lights = ls;
    c->nlights = 4;
    sh_image id = {0};
    SH_CHECK(tu_gl(c, NULL, &id) == SH_OK);
    if (id.rgb) SH_CHECK(tu_check_close("coincident_lights", &id, &ic, 1e-5));
    sh_image_free(&id);
    c->lights = own;
    c->nlights = nown;
    free(ls);
  }
  sh_image_free(&ia);
  sh_image_free(&ib);
  sh_image_free(&ic);
  sh_scene_free(a);
  sh_scene_free(b);
  sh_scene_free(c);
  SH_TEST_DONE();
}
