/* The scene of the precision tests (issue 11, "precision at extreme
 * ratios"): testdata/far_camera.json, a spot in fog over a floor with a
 * ball that shadows the shaft, seen by a camera `distance` units away whose
 * field of view keeps the framing (2.4 units of height at the spot's
 * axis), every length times `scale`, the coefficients over it and the
 * spot's intensity times its square (so the image stays the same), and
 * the whole moved by `offset`. The file itself is the case at 5000 units,
 * scale 1, offset 0. */
#ifndef SH_TEST_EXTREMES_H
#define SH_TEST_EXTREMES_H

#include <math.h>
#include <stdio.h>

#include "sh_math.h"
#include "sh_parse.h"


static inline sh_scene *sh_test_far_camera(double distance, double scale,
                                           sh_vec3 offset, int width,
                                           int height) {
  /* The half height framed at the spot's axis: 5000 units away at 0.055
   * degrees. */
  double half = 5000.0 * tan(0.0275 * SH_PI / 180.0);
  double k = scale, fov = 2.0 * atan(half / distance) * 180.0 / SH_PI;
#define SH__P(a, b, c) k *(a) + offset.x, k *(b) + offset.y, k *(c) + offset.z
  char json[4096];
  snprintf(json, sizeof json,
      "{\"format\": \"shafts-scene\", \"version\": 1,"
      " \"camera\": {\"position\": [%.17g, %.17g, %.17g],"
      "  \"look_at\": [%.17g, %.17g, %.17g], \"fov_y_deg\": %.17g,"
      "  \"width\": %d, \"height\": %d},"
      " \"medium\": {\"sigma_s\": [%.17g, %.17g, %.17g],"
      "  \"sigma_a\": [%.17g, %.17g, %.17g],"
      "  \"phase\": {\"type\": \"henyey_greenstein\", \"g\": 0.3},"
      "  \"bounds\": {\"min\": [%.17g, %.17g, %.17g],"
      "   \"max\": [%.17g, %.17g, %.17g]}},"
      " \"lights\": [{\"type\": \"spot\", \"position\": [%.17g, %.17g, %.17g],"
      "  \"direction\": [0, -1, 0], \"intensity\": [%.17g, %.17g, %.17g],"
      "  \"outer_angle_deg\": 30, \"inner_angle_deg\": 20, \"exponent\": 1}],"
      " \"materials\": {\"floor\": {\"diffuse\": [0.3, 0.3, 0.3]},"
      "  \"black\": {\"diffuse\": [0, 0, 0]}},"
      " \"shapes\": [{\"type\": \"quad\", \"material\": \"floor\","
      "  \"corner\": [%.17g, %.17g, %.17g], \"u\": [%.17g, 0, 0],"
      "  \"v\": [0, 0, %.17g]},"
      "  {\"type\": \"sphere\", \"material\": \"black\","
      "   \"center\": [%.17g, %.17g, %.17g], \"radius\": %.17g}]}",
      SH__P(0, 1.5, distance), SH__P(0, 1.5, 0), fov, width, height,
      0.3 / k, 0.3 / k, 0.3 / k, 0.03 / k, 0.03 / k, 0.03 / k,
      SH__P(-2, 0, -2), SH__P(2, 4, 2), SH__P(0, 3.8, 0),
      10 * k * k, 10 * k * k, 10 * k * k,
      SH__P(-2, 0, 2), 4 * k, -4 * k, SH__P(0.35, 2.4, 0.1), 0.35 * k);
#undef SH__P
  sh_error err = SH_ERROR_INIT;
  sh_scene *s = NULL;
  if (sh_scene_parse(json, "far_camera.json", ".", &s, &err) != SH_OK)
    fprintf(stderr, "far_camera.json: %s\n", err.message);
  sh_error_clear(&err);
  return s;
}

#endif
