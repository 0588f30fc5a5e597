/* The reference renderer against closed forms: a Lambert plane under a point
 * light, shadows through semitransparent surfaces, and convergence of the
 * medium estimate as spp rises. */
#include <string.h>

#include "sh_camera.h"
#include "sh_parse.h"
#include "sh_reference.h"
#include "sh_rt.h"
#include "sh_test.h"
#include "shafts.h"

static sh_scene *parse(const char *json) {
  return sh_test_parse(json, "test.json");
}

static void lambert_plane(void) {
  sh_scene *s = parse(
      "{\"format\": \"shafts-scene\", \"version\": 1,"
      " \"camera\": {\"position\": [0, 3, 4], \"look_at\": [0, 0, 0],"
      "  \"fov_y_deg\": 50, \"width\": 24, \"height\": 16},"
      " \"lights\": [{\"type\": \"point\", \"position\": [0.5, 2, -0.5],"
      "  \"intensity\": [4, 8, 12]}],"
      " \"materials\": {\"floor\": {\"diffuse\": [0.5, 0.25, 0.8]}},"
      " \"shapes\": [{\"type\": \"quad\", \"material\": \"floor\","
      "  \"corner\": [-50, 0, 50], \"u\": [100, 0, 0], \"v\": [0, 0, -100]}]}");
  SH_CHECK(s != NULL);
  if (!s) return;
  sh_reference_options opt = sh_reference_defaults(s);
  sh_image img = {0};
  SH_CHECK(sh_render_reference(s, &opt, &img, NULL, NULL) == SH_OK);
  sh_camera_frame f;
  sh_camera_frame_init(&s->camera, &f);
  double worst = 0;
  for (int y = 0; y < img.height; y++)
    for (int x = 0; x < img.width; x++) {
      sh_vec3 d = sh_camera_dir(&f, x + 0.5, y + 0.5);
      double t = -f.origin.y / d.y;
      sh_vec3 p = sh_madd(f.origin, d, t), l = s->lights[0].position;
      sh_vec3 tol = sh_sub(l, p);
      double r2 = sh_dot(tol, tol), cosv = tol.y / sqrt(r2);
      double expect = 0.5 / SH_PI * 4 * cosv / r2;
      double got = img.rgb[3 * (y * img.width + x)];
      double rel = fabs(got - expect) / expect;
      if (rel > worst) worst = rel;
      SH_CHECK_NEAR(img.rgb[3 * (y * img.width + x) + 2],
                    expect * (0.8 * 12) / (0.5 * 4), 1e-5, 0);
    }
  SH_CHECK(worst < 1e-5);
  sh_image_free(&img);
  sh_scene_free(s);
}

static void shadow_transmittance(void) {
  sh_scene *s = parse(
      "{\"format\": \"shafts-scene\", \"version\": 1,"
      " \"camera\": {\"position\": [0, 0, 10], \"look_at\": [0, 0, 0],"
      "  \"fov_y_deg\": 40, \"width\": 4, \"height\": 4},"
      " \"materials\": {\"glass\": {\"transmit\": [0.5, 0.8, 0.1], \"ior\": 1.5},"
      "  \"wall\": {\"diffuse\": [1, 1, 1]}},"
      " \"shapes\": ["
      "  {\"type\": \"sphere\", \"material\": \"glass\", \"center\": [0, 0, 0],"
      "   \"radius\": 1},"
      "  {\"type\": \"quad\", \"material\": \"glass\", \"corner\": [-1, 5, -1],"
      "   \"u\": [2, 0, 0], \"v\": [0, 0, 2]},"
      "  {\"type\": \"box\", \"material\": \"wall\", \"min\": [5, -1, -1],"
      "   \"max\": [6, 1, 1]}]}");
  SH_CHECK(s != NULL);
  if (!s) return;
  sh_rt *rt = NULL;
  SH_CHECK(sh_rt_create(s, &rt, NULL) == SH_OK);
  /* Through the sphere: two crossings, t^2. */
  sh_vec3 v = sh_rt_visibility(rt, sh_v3(0, 0, -5), sh_v3(0, 0, 1), 10, NULL);
  SH_CHECK_NEAR(v.x, 0.25, 1e-12, 0);
  SH_CHECK_NEAR(v.y, 0.64, 1e-12, 0);
  SH_CHECK_NEAR(v.z, 0.01, 1e-12, 0);
  /* Through the quad exactly along its diagonal, where its two triangles
   * meet: one crossing. */
  sh_vec3 o = sh_v3(0, 7, 0);
  v = sh_rt_visibility(rt, o, sh_v3(0, -1, 0), 2.5, NULL);
  SH_CHECK_NEAR(v.x, 0.5, 1e-12, 0);
  /* Sphere and quad in a row: t^3. */
  v = sh_rt_visibility(rt, o, sh_v3(0, -1, 0), 20, NULL);
  SH_CHECK_NEAR(v.x, 0.125, 1e-12, 0);
  /* Opaque box. */
  v = sh_rt_visibility(rt, sh_v3(3, 0, 0), sh_v3(1, 0, 0), 10, NULL);
  SH_CHECK(sh_is_black(v));
  /* Segments that stop short of a surface see no crossing. */
  v = sh_rt_visibility(rt, sh_v3(0, 0, -5), sh_v3(0, 0, 1), 3.5, NULL);
  SH_CHECK_NEAR(v.x, 1.0, 1e-12, 0);
  /* A ray leaving a surface through the offset origin does not hit it. */
  sh_hit h;
  SH_CHECK(sh_rt_intersect(rt, sh_v3(0, 0, 5), sh_v3(0, 0, -1), 0, INFINITY,
                           &h, NULL));
  SH_CHECK_NEAR(h.t, 4.0, 1e-6, 0);
  SH_CHECK_NEAR(h.ng.z, 1.0, 1e-9, 0);
  sh_vec3 org = sh_rt_offset(rt, h.p, sh_neg(h.ng));
  SH_CHECK(sh_rt_intersect(rt, org, sh_v3(0, 0, -1), 0, INFINITY, &h, NULL));
  SH_CHECK_NEAR(h.t, 2.0, 1e-5, 0);
  SH_CHECK_NEAR(h.ng.z, -1.0, 1e-9, 0);
  sh_rt_free(rt);
  sh_scene_free(s);
}

static const char *MEDIUM_SCENE =
    "{\"format\": \"shafts-scene\", \"version\": 1,"
    " \"camera\": {\"position\": [0, 1, 6], \"look_at\": [0, 1, 0],"
    "  \"fov_y_deg\": 50, \"width\": 24, \"height\": 16},"
    " \"medium\": {\"sigma_s\": [0.2, 0.2, 0.2], \"sigma_a\": [0.05, 0.05, 0.05],"
    "  \"phase\": {\"type\": \"henyey_greenstein\", \"g\": 0.5},"
    "  \"bounds\": {\"min\": [-4, 0, -4], \"max\": [4, 4, 4]}},"
    " \"lights\": [{\"type\": \"spot\", \"position\": [0, 3.5, 0],"
    "  \"look_at\": [0, 0, 0], \"intensity\": [20, 20, 20],"
    "  \"outer_angle_deg\": 30, \"inner_angle_deg\": 20}],"
    " \"materials\": {\"m\": {\"diffuse\": [0.7, 0.7, 0.7]}},"
    " \"shapes\": [{\"type\": \"sphere\", \"material\": \"m\","
    "  \"center\": [0.3, 1.8, 0], \"radius\": 0.5},"
    "  {\"type\": \"box\", \"material\": \"m\", \"min\": [-4, -1, -4],"
    "   \"max\": [4, 0, 4]}]}";

static double rms_diff(const sh_image *a, const sh_image *b) {
  double s = 0;
  size_t n = (size_t)a->width * a->height * 3;
  for (size_t i = 0; i < n; i++) {
    double d = a->rgb[i] - b->rgb[i];
    s += d * d;
  }
  return sqrt(s / n);
}

static void convergence(void) {
  sh_scene *s = parse(MEDIUM_SCENE);
  SH_CHECK(s != NULL);
  if (!s) return;
  sh_reference_options opt = sh_reference_defaults(s);
  opt.spp = 256;
  sh_image ref = {0}, img = {0};
  SH_CHECK(sh_render_reference(s, &opt, &ref, NULL, NULL) == SH_OK);
  double prev = INFINITY;
  for (int spp = 1; spp <= 16; spp *= 4) {
    opt.spp = spp;
    opt.seed = 7; /* independent of the reference's stream */
    SH_CHECK(sh_render_reference(s, &opt, &img, NULL, NULL) == SH_OK);
    double e = rms_diff(&img, &ref);
    fprintf(stderr, "spp %3d: rms error %.3g\n", spp, e);
    SH_CHECK(e < prev);
    prev = e;
    sh_image_free(&img);
  }
  /* Same command, same image, whatever the thread count. */
  opt.spp = 4;
  opt.threads = 1;
  sh_image one = {0}, two = {0};
  sh_render_reference(s, &opt, &one, NULL, NULL);
  opt.threads = 3;
  sh_render_reference(s, &opt, &two, NULL, NULL);
  SH_CHECK(memcmp(one.rgb, two.rgb, sizeof(float) * 3 * one.width * one.height) == 0);
  sh_image_free(&one);
  sh_image_free(&two);
  sh_image_free(&ref);
  sh_scene_free(s);
}

/* The progress callback: counts calls, keeps the largest `done`, and asks
 * the render to stop once `stop_at` tiles are done (0: never). */
typedef struct watch {
  long calls, done, total, stop_at;
  volatile int cancel;
} watch;

static void on_progress(void *user, long done, long total) {
  watch *w = user;
  __atomic_add_fetch(&w->calls, 1, __ATOMIC_RELAXED);
  long seen = __atomic_load_n(&w->done, __ATOMIC_RELAXED);
  while (done > seen && !__atomic_compare_exchange_n(&w->done, &seen, done, 0,
                                                     __ATOMIC_RELAXED,
                                                     __ATOMIC_RELAXED)) {
  }
  w->total = total;
  if (w->stop_at && done >= w->stop_at) w->cancel = 1;
}

/* Progress is reported through the caller's callback, once per tile; a
 * cancelled render returns SH_ERR_CANCELLED and no image. */
static void progress_and_cancel(void) {
  sh_scene *s = parse(MEDIUM_SCENE);
  SH_CHECK(s != NULL);
  if (!s) return;
  SH_CHECK(sh_scene_update(s,
                           "{\"camera\": {\"position\": [0, 1, 6], "
                           "\"look_at\": [0, 1, 0], \"fov_y_deg\": 50, "
                           "\"width\": 96, \"height\": 64}}",
                           "patch", NULL, NULL) == SH_OK);
  int tiles = ((s->camera.width + 15) / 16) * ((s->camera.height + 15) / 16);
  sh_reference_options opt = sh_reference_defaults(s);
  SH_CHECK(opt.progress == NULL && opt.cancel == NULL);
  opt.threads = 2;
  opt.spp = 2;
  watch w = {0};
  opt.progress = on_progress;
  opt.progress_user = &w;
  sh_image img = {0};
  SH_CHECK(sh_render_reference(s, &opt, &img, NULL, NULL) == SH_OK);
  SH_CHECK(w.calls == tiles && w.done == tiles && w.total == tiles);
  sh_image_free(&img);
  if (tiles > 2) {
    watch c = {0};
    c.stop_at = 1;
    opt.progress_user = &c;
    opt.cancel = &c.cancel;
    sh_error err = SH_ERROR_INIT;
    img.rgb = (float *)1;
    SH_CHECK(sh_render_reference(s, &opt, &img, NULL, &err) ==
             SH_ERR_CANCELLED);
    SH_CHECK(err.status == SH_ERR_CANCELLED && img.rgb == NULL);
    SH_CHECK(c.calls < tiles);
    sh_error_clear(&err);
  }
  sh_scene_free(s);
}

int main(void) {
  lambert_plane();
  shadow_transmittance();
  convergence();
  progress_and_cancel();
  SH_TEST_DONE();
}
