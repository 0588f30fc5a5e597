/* Convergence: the error against the reference falls as the planes, the
 * angular sub-samples and the lattice grow, and the lattice's result tends
 * to xi evaluated per fragment (--xi exact), the limit of the sweep; a spot
 * gobo's texel sub-samples reduce the error near its apex. */
#include <stdio.h>

#include "sh_test.h"
#include "test_util.h"

/* A directional light through a window, with a shadow-casting box: with
 * sub-samples along the pattern switched off, only the planes sample it. */
static const char *WINDOW =
  "{\"format\": \"shafts-scene\", \"version\": 1,"
  " \"camera\": {\"position\": [3, 2, 3], \"look_at\": [-0.5, 0.8, 0],"
  "  \"fov_y_deg\": 55, \"width\": 80, \"height\": 60},"
  " \"medium\": {\"sigma_s\": [0.25, 0.25, 0.25], \"sigma_a\": [0.02, 0.02, 0.02],"
  "  \"bounds\": {\"min\": [-3, 0, -3], \"max\": [3, 3, 3]}},"
  " \"lights\": [{\"type\": \"directional\", \"direction\": [1, -0.7, 0.2],"
  "  \"irradiance\": [5, 4.5, 4],"
  "  \"light_map\": {\"image\": \"assets/stained_glass.png\","
  "   \"origin\": [-3, 2.6, -1], \"u\": [0, 0, 2], \"v\": [0, -1.4, 0]}}],"
  " \"materials\": {\"m\": {\"diffuse\": [0.5, 0.5, 0.5]}},"
  " \"shapes\": [{\"type\": \"box\", \"material\": \"m\", \"min\": [-0.8, 1.2, -0.4],"
  "   \"max\": [-0.4, 1.6, 0.4]}]}";

/* A spot in a hazy medium, seen by the two cameras below. */
#define SPOT_SCENE(camera)                                                   \
  "{\"format\": \"shafts-scene\", \"version\": 1,"                           \
  " \"camera\": {" camera ", \"fov_y_deg\": 50, \"width\": 80,"              \
  "  \"height\": 60},"                                                       \
  " \"medium\": {\"sigma_s\": [0.2, 0.2, 0.2],"                               \
  "  \"phase\": {\"type\": \"nishita_hazy\"},"                                \
  "  \"bounds\": {\"min\": [-4, 0, -4], \"max\": [4, 4, 4]}},"                \
  " \"lights\": [{\"type\": \"spot\", \"position\": [-1, 3, 0],"              \
  "  \"look_at\": [1, 0, 0], \"intensity\": [10, 10, 10],"                    \
  "  \"outer_angle_deg\": 30, \"inner_angle_deg\": 10}]}"

/* The spot seen from the side with its apex in view: its profile sweeps by
 * within a plane near the apex, where the angular sub-samples matter. */
static const char *SPOT =
    SPOT_SCENE("\"position\": [0, 1.5, 6], \"look_at\": [0, 1.5, 0]");

/* The same spot seen from below its apex: the lattice's convergence (right
 * at a light in view, interpolating xi cannot converge: its direction
 * term is discontinuous there). */
static const char *SPOT_BODY =
    SPOT_SCENE("\"position\": [0, 1, 5], \"look_at\": [0.5, 0.6, 0]");

/* A stage spot with a gobo of polka dots, apex in view, its edge 1 degree
 * wide (so 1-degree angular steps): near the apex a ray's part crosses
 * several texels a degree. */
static const char *GOBO =
  "{\"format\": \"shafts-scene\", \"version\": 1,"
  " \"camera\": {\"position\": [0, 2, 10.5], \"look_at\": [0, 2.2, 0],"
  "  \"fov_y_deg\": 45, \"width\": 80, \"height\": 60},"
  " \"medium\": {\"sigma_s\": [0.08, 0.08, 0.08], \"phase\": {\"type\": \"nishita_hazy\"},"
  "  \"bounds\": {\"min\": [-7, 0, -3], \"max\": [7, 6.5, 3.5]}},"
  " \"lights\": [{\"type\": \"spot\", \"position\": [-2.2, 6, -1.2],"
  "  \"look_at\": [-1.2, 0, 1.2], \"intensity\": [198, 198, 198],"
  "  \"outer_angle_deg\": 20, \"inner_angle_deg\": 19,"
  "  \"light_map\": {\"image\": \"assets/gobo_dots.png\"}}],"
  " \"materials\": {\"m\": {\"diffuse\": [0.45, 0.4, 0.35]}},"
  " \"shapes\": [{\"type\": \"box\", \"min\": [-7, -0.6, -3], \"max\": [7, 0, 3.5],"
  "   \"material\": \"m\"}]}";

/* Renders s with o and returns its error against ref (1e9 if it failed),
 * printing it after `what`. Keeps the image in *keep if keep is given
 * (caller frees), else frees it. */
static double error_of(sh_scene *s, const gs_options *o, const sh_image *ref,
                       const char *what, sh_image *keep) {
  sh_image img = {0};
  SH_CHECK(tu_gl(s, o, &img) == SH_OK);
  double e = img.rgb ? tu_error(&img, ref) : 1e9;
  fprintf(stderr, "%s: error %.3f %%\n", what, 100 * e);
  if (keep)
    *keep = img;
  else
    sh_image_free(&img);
  return e;
}

int main(void) {
  char name[64];
  /* Planes (directional light, no sub-samples): 4 to 32. */
  sh_scene *s = tu_scene(WINDOW);
  SH_CHECK(s != NULL);
  sh_image ref = {0};
  if (s && tu_reference(s, 256, &ref) == SH_OK) {
    double prev = 1e9;
    for (int planes = 4; planes <= 32; planes *= 2) {
      gs_options o = gs_options_defaults(s);
      o.planes = planes;
      o.sub_texels = 1e6;
      sh_image img = {0};
      SH_CHECK(tu_gl(s, &o, &img) == SH_OK);
      double e = img.rgb ? tu_error(&img, &ref) : 1e9;
      fprintf(stderr, "window, %2d planes: error %.3f %%\n", planes, 100 * e);
      SH_CHECK(e < prev);
      prev = e;
      snprintf(name, sizeof name, "window_%d_planes", planes);
      if (planes == 32) SH_CHECK(tu_check_close(name, &img, &ref, 0.15));
      sh_image_free(&img);
    }
    /* The sub-samples along the pattern do what more planes do. */
    prev = 1e9;
    for (double t = 16; t >= 1; t /= 4) {
      gs_options o = gs_options_defaults(s);
      o.planes = 4;
      o.sub_texels = t;
      sh_image img = {0};
      snprintf(name, sizeof name, "window, 4 planes, %4.1f texels a sample", t);
      double e = error_of(s, &o, &ref, name, &img);
      SH_CHECK(e < prev);
      prev = e;
      if (t == 1 && img.rgb)
        SH_CHECK(tu_check_close("window_4_planes_subsampled", &img, &ref, 0.06));
      sh_image_free(&img);
    }
  }
  sh_image_free(&ref);
  sh_scene_free(s);

  /* Angular sub-samples (spot, 4 planes): 16 to 1 degrees. */
  s = tu_scene(SPOT);
  SH_CHECK(s != NULL);
  sh_image exact = {0};
  if (s && tu_reference(s, 256, &ref) == SH_OK) {
    double prev = 1e9;
    for (double a = 16; a >= 1; a /= 4) {
      gs_options o = gs_options_defaults(s);
      o.planes = 4;
      o.sub_angle_deg = a;
      sh_image img = {0};
      snprintf(name, sizeof name, "spot, sub-angle %4.1f degrees", a);
      double e = error_of(s, &o, &ref, name, &img);
      /* Down to the reference's own noise (0.03 %). */
      SH_CHECK(e < prev || e < 0.001);
      prev = e;
      if (a == 1) {
        SH_CHECK(tu_check_close("spot_sub_angle_1", &img, &ref, 0.002));
        exact = img;
      } else {
        sh_image_free(&img);
      }
    }
  }
  sh_image_free(&exact);
  sh_image_free(&ref);
  sh_scene_free(s);

  /* A gobo's texels sub-sample the part of a ray near the apex: without
   * them (one texel-rate sample per 1e6 texels) the angular steps alone
   * skip the dots. */
  s = tu_scene(GOBO);
  SH_CHECK(s != NULL);
  if (s && tu_reference(s, 256, &ref) == SH_OK) {
    gs_options o = gs_options_defaults(s);
    o.planes = 4;
    o.sub_texels = 1e6;
    double coarse = error_of(s, &o, &ref, "gobo, no texel sub-samples", NULL);
    o.sub_texels = 1;
    double fine = error_of(s, &o, &ref, "gobo, a sample per texel", NULL);
    SH_CHECK(fine < 0.5 * coarse);
  }
  sh_image_free(&ref);
  sh_scene_free(s);

  /* The lattice tends to xi exact as it grows. */
  s = tu_scene(SPOT_BODY);
  SH_CHECK(s != NULL);
  gs_options o = s ? gs_options_defaults(s) : (gs_options){0};
  o.planes = 4;
  o.sub_angle_deg = 1;
  if (s && tu_gl(s, &o, &exact) == SH_OK) {
    double prev = 1e9;
    for (int n = 6; n <= 48; n *= 2) {
      o.xi = GS_XI_LATTICE;
      o.lattice_u = o.lattice_v = n;
      sh_image img = {0};
      SH_CHECK(tu_gl(s, &o, &img) == SH_OK);
      double e = img.rgb ? tu_error(&img, &exact) : 1e9;
      fprintf(stderr, "spot, lattice %2dx%-2d: %.3f %% from xi exact\n", n, n, 100 * e);
      SH_CHECK(e < prev);
      prev = e;
      if (n == 48) SH_CHECK(tu_check_close("lattice_48", &img, &exact, 0.05));
      sh_image_free(&img);
    }
  }
  sh_image_free(&exact);
  sh_image_free(&ref);
  sh_scene_free(s);
  SH_TEST_DONE();
}
