/* Live programs (gs_options.live): a renderer kept across changes of the
 * scene's values compiles no program and draws what a fresh renderer made
 * on the changed scene draws, bit for bit; live frames equal baked ones to
 * float rounding; a structural change (the phase function's type)
 * compiles and still draws right.
 *
 * The scene has a spot with a gobo (a 2D shadow map), a point light inside
 * the medium (a cube map), a directional light through a window, a sphere
 * and a floor, in a Henyey-Greenstein medium of unequal coefficients.
 * Changes go through sh_scene_update and gs_renderer_sync, as a viewport
 * makes them. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_parse.h"
#include "sh_test.h"
#include "shafts.h"
#include "test_util.h"

typedef struct params {
  double cam_pos[3];
  int width, height;
  double ball[3]; /* the sphere's translation */
  double spot_pos[3], spot_k, outer, inner, exponent;
  double point_pos[3];
  double sun_dir[3];
  double sigma_s, g;
  const char *phase;
  double box_max_y;
} params;

static const params BASE = {{2.5, 2.0, 3.0}, 64, 48, {0, 0, 0},
                            {-0.5, 3.2, 0.2}, 1.0, 28, 20, 1,
                            {1.2, 1.4, -0.5},
                            {1, -0.8, 0.3},
                            0.2, 0.3, "henyey_greenstein", 4};

/* The parts of the scene that a patch may hold, as JSON members. */
static void parts(const params *p, char *camera, char *medium, char *lights,
                  char *transforms, size_t size) {
  char phase[128];
  if (!strcmp(p->phase, "henyey_greenstein"))
    snprintf(phase, sizeof phase, "{\"type\": \"%s\", \"g\": %.17g}", p->phase, p->g);
  else
    snprintf(phase, sizeof phase, "{\"type\": \"%s\"}", p->phase);
  snprintf(camera, size,
    "\"camera\": {\"position\": [%.17g, %.17g, %.17g], \"look_at\": [0, 0.7, 0],"
    " \"fov_y_deg\": 50, \"width\": %d, \"height\": %d}",
    p->cam_pos[0], p->cam_pos[1], p->cam_pos[2], p->width, p->height);
  snprintf(medium, size,
    "\"medium\": {\"sigma_s\": [%.17g, %.17g, %.17g], \"sigma_a\": [0.02, 0.03, 0.04],"
    " \"phase\": %s, \"bounds\": {\"min\": [-3, 0, -3], \"max\": [3, %.17g, 3]}}",
    p->sigma_s, p->sigma_s, p->sigma_s, phase, p->box_max_y);
  snprintf(lights, size,
    "\"lights\": [{\"type\": \"spot\", \"position\": [%.17g, %.17g, %.17g],"
    "   \"look_at\": [0, 0, 0], \"intensity\": [%.17g, %.17g, %.17g],"
    "   \"outer_angle_deg\": %.17g, \"inner_angle_deg\": %.17g, \"exponent\": %.17g,"
    "   \"light_map\": {\"image\": \"assets/gobo_star.png\", \"up\": [0, 0, -1]}},"
    "  {\"type\": \"point\", \"position\": [%.17g, %.17g, %.17g],"
    "   \"intensity\": [3, 2.5, 2]},"
    "  {\"type\": \"directional\", \"direction\": [%.17g, %.17g, %.17g],"
    "   \"irradiance\": [1.5, 1.4, 1.3],"
    "   \"light_map\": {\"image\": \"assets/stained_glass.png\","
    "    \"origin\": [-3, 2.5, -1], \"u\": [0, 0, 2], \"v\": [0, -1.2, 0]}}]",
    p->spot_pos[0], p->spot_pos[1], p->spot_pos[2], 12 * p->spot_k, 11 * p->spot_k,
    10 * p->spot_k, p->outer, p->inner, p->exponent, p->point_pos[0], p->point_pos[1],
    p->point_pos[2], p->sun_dir[0], p->sun_dir[1], p->sun_dir[2]);
  snprintf(transforms, size, "[null, {\"translate\": [%.17g, %.17g, %.17g]}]",
           p->ball[0], p->ball[1], p->ball[2]);
}

enum { PART = 2048 };

static sh_scene *scene(const params *p) {
  char camera[PART], medium[PART], lights[PART], xf[PART], json[5 * PART];
  parts(p, camera, medium, lights, xf, PART);
  /* The sphere's transform: the second element of the transforms array. */
  char *ball = strchr(xf, '{');
  xf[strlen(xf) - 1] = '\0';
  snprintf(json, sizeof json,
    "{\"format\": \"shafts-scene\", \"version\": 1, %s,"
    " \"ambient\": [0.01, 0.01, 0.01], %s, %s,"
    " \"materials\": {\"m\": {\"diffuse\": [0.5, 0.5, 0.5], \"specular\": [0.2, 0.2, 0.2]}},"
    " \"shapes\": [{\"type\": \"quad\", \"material\": \"m\", \"corner\": [-3, 0, 3],"
    "   \"u\": [6, 0, 0], \"v\": [0, 0, -6]},"
    "  {\"type\": \"sphere\", \"material\": \"m\", \"center\": [0.2, 0.8, 0.1],"
    "   \"radius\": 0.35, \"transform\": %s}]}",
    camera, medium, lights, ball);
  return tu_scene(json);
}

/* Changes s to p's values with sh_scene_update; returns the SH_CHANGED_*
 * bits (0 on error). */
static unsigned update(sh_scene *s, const params *p) {
  char camera[PART], medium[PART], lights[PART], xf[PART], patch[5 * PART];
  parts(p, camera, medium, lights, xf, PART);
  snprintf(patch, sizeof patch, "{%s, %s, %s, \"transforms\": %s}", camera, medium,
           lights, xf);
  unsigned changed = 0;
  sh_error err = SH_ERROR_INIT;
  if (sh_scene_update(s, patch, "patch.json", &changed, &err) != SH_OK) {
    fprintf(stderr, "sh_scene_update: %s\n", err.message);
    return 0;
  }
  sh_error_clear(&err);
  return changed;
}

/* A fresh renderer's frame of s. */
static int fresh(const sh_scene *s, int live, sh_image *img, gs_stats *st) {
  gs_options o = gs_options_defaults(s);
  o.live = live;
  gs_renderer *r = NULL;
  sh_error err = SH_ERROR_INIT;
  if (gs_renderer_create(s, &o, &r, &err) != SH_OK) {
    fprintf(stderr, "create: %s\n", err.message);
    return 0;
  }
  int ok = tu_draw(r, s, img, st);
  gs_renderer_free(r);
  sh_error_clear(&err);
  return ok;
}

/* Changes the live renderer's scene to p's values (sh_scene_update, which
 * must report `expect` among the changes), syncs, draws, and checks that
 * nothing compiled (unless `structural`) and that the frame equals a fresh
 * live renderer's on a scene parsed with p's values. */
static void step(const char *name, gs_renderer *r, sh_scene *s, const params *p,
                 unsigned expect, int structural) {
  unsigned changed = update(s, p);
  SH_CHECK((changed & expect) == expect);
  sh_error err = SH_ERROR_INIT;
  if (gs_renderer_sync(r, changed, &err) != SH_OK) {
    fprintf(stderr, "sync: %s\n", err.message);
    SH_CHECK(0);
  }
  sh_scene *to = scene(p);
  SH_CHECK(to != NULL);
  if (!to) return;
  sh_image warm = {0}, ref = {0};
  gs_stats st, fst;
  SH_CHECK(tu_draw(r, s, &warm, &st));
  SH_CHECK(fresh(to, 1, &ref, &fst));
  fprintf(stderr, "%s: changed 0x%x, %d programs compiled, %d cached\n", name, changed,
          st.programs_compiled, st.programs_cached);
  if (structural) SH_CHECK(st.programs_compiled > 0);
  else SH_CHECK(st.programs_compiled == 0);
  if (warm.rgb && ref.rgb) SH_CHECK(tu_equal_bits(name, &warm, &ref));
  sh_image_free(&warm);
  sh_image_free(&ref);
  sh_scene_free(to);
  sh_error_clear(&err);
}

/* A fresh live frame against a fresh baked one (options o, NULL: the
 * defaults): the same shaders, the values folded by the GLSL compiler or
 * read at run time, and the general branches where live programs do not
 * specialise (a light inside the medium, the spot profile's shape). They
 * differ by float rounding (the compiler turns divisions by constants into
 * multiplications, say), which the angular sums near a spot's apex
 * amplify: measured 5.7e-7 relative RMS on this test's scene, 1.5e-4 on
 * the teapot at 80x60, where 103 of 4800 pixels differ, the largest by
 * 2e-4 of the brightest pixel's radiance (27, at the apex). Bound 5e-4. */
static void live_vs_baked(const char *name, const sh_scene *s, const gs_options *o) {
  gs_options opt = o ? *o : gs_options_defaults(s);
  sh_image img[2] = {{0}, {0}};
  for (int live = 0; live < 2; live++) {
    opt.live = live;
    SH_CHECK(tu_gl(s, &opt, &img[live]) == SH_OK);
  }
  if (img[0].rgb && img[1].rgb) {
    fprintf(stderr, "%s: relative RMS difference %.2g\n", name, tu_error(&img[1], &img[0]));
    SH_CHECK(tu_check_close(name, &img[1], &img[0], 5e-4));
  }
  sh_image_free(&img[0]);
  sh_image_free(&img[1]);
}

int main(void) {
  sh_scene *s = scene(&BASE);
  SH_CHECK(s != NULL);
  if (!s) SH_TEST_DONE();

  sh_image live = {0};
  gs_stats st;
  SH_CHECK(fresh(s, 1, &live, &st));
  live_vs_baked("live_vs_baked", s, NULL);
  gs_options lattice = gs_options_defaults(s);
  lattice.xi = GS_XI_LATTICE;
  lattice.jitter = 1;
  live_vs_baked("live_vs_baked_lattice_jitter", s, &lattice);
  const char *src = getenv("SHAFTS_SOURCE_DIR");
  char path[1024];
  snprintf(path, sizeof path, "%s/scenes/teapot_spot.json", src ? src : "../..");
  sh_scene *teapot = NULL;
  sh_error lerr = SH_ERROR_INIT;
  SH_CHECK(sh_scene_load(path, &teapot, &lerr) == SH_OK);
  if (teapot) {
    teapot->camera.width = 80;
    teapot->camera.height = 60;
    live_vs_baked("live_vs_baked_teapot", teapot, NULL);
  }
  sh_scene_free(teapot);

  gs_options o = gs_options_defaults(s);
  o.live = 1;
  gs_renderer *r = NULL;
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(gs_renderer_create(s, &o, &r, &err) == SH_OK);
  if (r) {
    sh_image first = {0}, again = {0};
    gs_stats a, b;
    SH_CHECK(tu_draw(r, s, &first, &a) && tu_draw(r, s, &again, &b));
    fprintf(stderr, "first frame: %d programs compiled; warm: %d\n", a.programs_compiled,
            b.programs_compiled);
    SH_CHECK(a.programs_compiled > 0 && a.programs_compiled == a.programs_cached);
    SH_CHECK(b.programs_compiled == 0 && b.programs_cached == a.programs_cached);
    if (first.rgb && again.rgb && live.rgb) {
      SH_CHECK(tu_equal_bits("warm_frame", &again, &first));
      SH_CHECK(tu_equal_bits("first_frame_vs_fresh", &first, &live));
    }
    sh_image_free(&first);
    sh_image_free(&again);

    params p = BASE;
    p.spot_pos[0] += 0.01;
    step("spot_moved_by_0.01", r, s, &p, SH_CHANGED_LIGHTS, 0);
    p.spot_pos[1] -= 0.6;
    p.spot_pos[2] += 0.4;
    step("spot_moved", r, s, &p, SH_CHANGED_LIGHTS, 0);
    p.spot_k *= 1.01;
    step("spot_intensity_plus_1pc", r, s, &p, SH_CHANGED_LIGHTS, 0);
    p.outer = 32;
    p.inner = 32;
    step("spot_hard_edge", r, s, &p, SH_CHANGED_LIGHTS, 0);
    p.inner = 12;
    step("spot_cone_widened", r, s, &p, SH_CHANGED_LIGHTS, 0);
    /* The cosine exponent's class (0, 1, other) and a light's being inside
     * the medium's box are switches that values flip: the first flip
     * builds the other variant, later ones find it cached. */
    p.exponent = 2.5;
    step("spot_exponent_2.5", r, s, &p, SH_CHANGED_LIGHTS, 1);
    p.exponent = 1;
    step("spot_exponent_back_to_1", r, s, &p, SH_CHANGED_LIGHTS, 0);
    p.exponent = 3.5;
    step("spot_exponent_3.5", r, s, &p, SH_CHANGED_LIGHTS, 0);
    p.point_pos[0] = -1.5;
    p.point_pos[1] = 5; /* out of the medium's box */
    step("point_light_leaves_the_medium", r, s, &p, SH_CHANGED_LIGHTS, 1);
    p.point_pos[1] = 1.5;
    step("point_light_back_in_the_medium", r, s, &p, SH_CHANGED_LIGHTS, 0);
    p.point_pos[1] = 5.5;
    step("point_light_out_again", r, s, &p, SH_CHANGED_LIGHTS, 0);
    p.sun_dir[0] = 0.8;
    p.sun_dir[2] = 0.5;
    step("sun_turned", r, s, &p, SH_CHANGED_LIGHTS, 0);
    p.cam_pos[0] += 0.01;
    step("camera_moved_by_0.01", r, s, &p, SH_CHANGED_CAMERA, 0);
    p.cam_pos[0] = -2.0;
    p.cam_pos[1] = 1.2;
    step("camera_moved", r, s, &p, SH_CHANGED_CAMERA, 0);
    p.width = 80;
    p.height = 40;
    step("image_resized", r, s, &p, SH_CHANGED_CAMERA | SH_CHANGED_SIZE, 0);
    p.ball[0] = 0.5;
    p.ball[2] = -0.3;
    step("sphere_moved", r, s, &p, SH_CHANGED_SHAPES, 0);
    p.sigma_s = 0.35;
    p.g = 0.6;
    p.box_max_y = 3.5;
    step("medium_coefficients_g_box", r, s, &p, SH_CHANGED_MEDIUM, 0);
    p.sigma_s = 3.0; /* optically thick slabs */
    step("medium_dense", r, s, &p, SH_CHANGED_MEDIUM, 0);
    p.phase = "rayleigh";
    step("phase_type_changed", r, s, &p, SH_CHANGED_MEDIUM, 1);
    gs_renderer_free(r);
  }
  sh_image_free(&live);
  sh_scene_free(s);
  sh_error_clear(&err);
  sh_error_clear(&lerr);
  SH_TEST_DONE();
}
