/* Tests of lmm_render (lmm_render.h): options set by name with their limits
 * and choices, the checks between options, each mode against the calls it
 * stands for (the reference renderer, with the light meshes hook),
 * statistics as JSON, a crop that is the same pixels as the whole image,
 * and a cancel that leaves the caller's image as it was. */
#include <jansson.h>
#include <stdlib.h>
#include <string.h>

#include "lmm_render.h"
#include "sh_camera.h"
#include "sh_parse.h"
#include "sh_reference.h"
#include "sh_test.h"

static const char *SCENE =
    "{\"format\": \"shafts-scene\", \"version\": 1,"
    " \"camera\": {\"position\": [0, 2, 5], \"look_at\": [0, 0.5, 0],"
    "  \"fov_y_deg\": 45, \"width\": 48, \"height\": 32},"
    " \"medium\": {\"sigma_s\": [0.1, 0.1, 0.1],"
    "  \"bounds\": {\"min\": [-3, -1, -3], \"max\": [3, 3, 3]}},"
    " \"lights\": [{\"type\": \"point\", \"position\": [0.5, 2.5, 0.2],"
    "  \"intensity\": [10, 10, 10]}],"
    " \"materials\": {\"m\": {\"diffuse\": [0.7, 0.7, 0.7]}},"
    " \"shapes\": [{\"type\": \"sphere\", \"material\": \"m\","
    "  \"center\": [0, 1, 0], \"radius\": 0.4},"
    "  {\"type\": \"box\", \"material\": \"m\", \"min\": [-3, -0.1, -3],"
    "   \"max\": [3, 0, 3]}],"
    " \"render\": {\"spp\": 2}}";

static void test_options(void) {
  static const struct {
    const char *key, *value, *message;
  } bad[] = {
      {"mode", "fast", "unknown value 'fast'; expected one of: reference, "
                       "whitted, lmm"},
      {"scheme", "default", "expected one of: straight, refract-trace"},
      {"spp", "0", "expected an integer from 1 to 16777216, found '0'"},
      {"spp", "2.5", "expected an integer"},
      {"mesh_step", "0", "expected a number > 0, found '0'"},
      {"mesh_step", "nan", "expected a number > 0"},
      {"area_radius", "-1", "expected a number >= 0"},
      {"local", "yes", "expected true or false"},
      {"speed", "1", "unknown option 'speed'; the options are: mode,"},
  };
  lmm_render_options o;
  sh_error err = SH_ERROR_INIT;
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
    lmm_render_options_init(&o);
    lmm_render_options before = o;
    sh_status st = lmm_render_options_set(&o, bad[i].key, bad[i].value, &err);
    int ok = st == SH_ERR_ARG && strcmp(err.path, bad[i].key) == 0 &&
             strstr(err.message, bad[i].message) &&
             memcmp(&o, &before, sizeof o) == 0;
    SH_CHECK(ok);
    if (!ok) fprintf(stderr, "%s=%s: %s\n", bad[i].key, bad[i].value,
                     err.message);
  }
  lmm_render_options_init(&o);
  SH_CHECK(lmm_render_options_set(&o, "mode", "lmm", &err) == SH_OK &&
           o.mode == LMM_MODE_LMM);
  SH_CHECK(lmm_render_options_set(&o, "scheme", "refract-both", &err) ==
               SH_OK &&
           o.scheme == LMM_SCHEME_REFRACT_BOTH);
  SH_CHECK(lmm_render_options_set(&o, "volume", "exact", &err) == SH_OK &&
           o.volume_exact == 1);
  SH_CHECK(lmm_render_options_set(&o, "refined", "true", &err) == SH_OK &&
           o.refined == 1);
  SH_CHECK(lmm_render_options_set(&o, "mesh_step", "0.25", &err) == SH_OK &&
           o.mesh_step == 0.25);
  SH_CHECK(lmm_render_options_set(&o, "seed", "4000000000", &err) == SH_OK &&
           o.seed == 4000000000LL);
  SH_CHECK(lmm_render_options_check(&o, &err) == SH_OK);
  SH_CHECK(lmm_render_options_set(&o, "mode", "whitted", &err) == SH_OK);
  SH_CHECK(lmm_render_options_check(&o, &err) == SH_ERR_ARG &&
           strstr(err.message, "refined needs mode lmm") &&
           !strcmp(err.path, "refined"));
  /* An option that would not apply is refused with its key. */
  lmm_render_options w;
  lmm_render_options_init(&w);
  SH_CHECK(lmm_render_options_set(&w, "area_samples", "4", &err) == SH_OK);
  SH_CHECK(lmm_render_options_check(&w, &err) == SH_ERR_ARG &&
           !strcmp(err.path, "area_samples") &&
           !strcmp(err.message, "area_samples needs area_radius"));
  lmm_render_options_init(&w);
  SH_CHECK(lmm_render_options_set(&w, "kl", "3", &err) == SH_OK);
  SH_CHECK(lmm_render_options_check(&w, &err) == SH_ERR_ARG &&
           !strcmp(err.path, "kl") &&
           !strcmp(err.message, "kl needs mode lmm"));
  sh_error_clear(&err);
}

/* Each mode equals sh_render_reference with the same hook. */
static void test_modes(const sh_scene *s) {
  int n = 3 * s->camera.width * s->camera.height;
  float *rgb = malloc(sizeof *rgb * (size_t)n);
  lmm_render_options o;
  lmm_render_stats st;
  sh_error err = SH_ERROR_INIT;
  sh_image ref = {0};

  lmm_render_options_init(&o);
  o.threads = 2;
  SH_CHECK(lmm_render(s, &o, rgb, &st, &err) == SH_OK);
  sh_reference_options ro = sh_reference_defaults(s);
  ro.threads = 2;
  SH_CHECK(sh_render_reference(s, &ro, &ref, NULL, &err) == SH_OK);
  SH_CHECK(ref.rgb && memcmp(ref.rgb, rgb, sizeof *rgb * (size_t)n) == 0);
  SH_CHECK(st.mode == LMM_MODE_REFERENCE && st.spp == 2 && !st.has_lmm &&
           st.scheme == LMM_SCHEME_REFRACT_TRACE && st.width == 48 &&
           st.trace.camera_rays == 48 * 32 && st.seconds >= st.trace.seconds);
  sh_image_free(&ref);

  lmm_render_options_set(&o, "mode", "lmm", NULL);
  lmm_render_options_set(&o, "mesh_step", "0.1", NULL);
  SH_CHECK(lmm_render(s, &o, rgb, &st, &err) == SH_OK);
  SH_CHECK(st.has_lmm && st.mesh_step == 0.1 && st.kl == 2 &&
           st.lmm.shaded_points > 0);
  size_t len = lmm_render_stats_json(&st, NULL, 0);
  char *text = malloc(len + 1);
  SH_CHECK(lmm_render_stats_json(&st, text, len + 1) == len);
  json_t *j = json_loads(text, 0, NULL);
  SH_CHECK(j && json_real_value(json_object_get(j, "mesh_step")) == 0.1 &&
           !strcmp(json_string_value(json_object_get(j, "mode")), "lmm") &&
           json_integer_value(json_object_get(j, "camera_rays")) == 48 * 32);
  json_decref(j);
  char small[8];
  SH_CHECK(lmm_render_stats_json(&st, small, sizeof small) == len &&
           strlen(small) == 7);
  free(text);

  /* The refract-both scheme needs the lmm mode. */
  lmm_render_options_set(&o, "mode", "whitted", NULL);
  lmm_render_options_set(&o, "scheme", "refract-both", NULL);
  SH_CHECK(lmm_render(s, &o, rgb, &st, &err) == SH_ERR_ARG &&
           strstr(err.message, "needs mode lmm"));
  free(rgb);
  sh_error_clear(&err);
}

/* Cancelled from the progress callback: SH_ERR_CANCELLED, the caller's
 * image untouched. */
static void stop(void *user, long done, long total) {
  (void)done;
  (void)total;
  *(volatile int *)user = 1;
}

static void test_cancel(const sh_scene *s) {
  int n = 3 * s->camera.width * s->camera.height;
  float *rgb = calloc((size_t)n, sizeof *rgb);
  volatile int cancel = 0;
  lmm_render_options *o = lmm_render_options_new();
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(lmm_render_stats_size() == sizeof(lmm_render_stats));
  lmm_render_options_set(o, "mode", "lmm", NULL);
  lmm_render_options_set_callbacks(o, stop, (void *)&cancel, &cancel);
  SH_CHECK(lmm_render(s, o, rgb, NULL, &err) == SH_ERR_CANCELLED);
  int zero = 1;
  for (int i = 0; i < n; i++) zero &= rgb[i] == 0;
  SH_CHECK(zero);
  lmm_render_options_free(o);
  free(rgb);
  sh_error_clear(&err);
}

/* A crop is the same region of the whole image to the bit, in every mode
 * (the sphere lights of whitted and the light mesh's hook included), and
 * one outside the image is refused before any work. */
static void test_crop(const sh_scene *s) {
  const sh_crop crop = {7, 5, 31, 26};
  int w = s->camera.width, h = s->camera.height;
  int cw = crop.x1 - crop.x0, ch = crop.y1 - crop.y0;
  float *full = malloc(sizeof *full * 3 * (size_t)w * h);
  float *part = malloc(sizeof *part * 3 * (size_t)cw * ch);
  sh_error err = SH_ERROR_INIT;
  for (int mode = 0; mode < 3 && full && part; mode++) {
    lmm_render_options o;
    lmm_render_stats st;
    lmm_render_options_init(&o);
    o.mode = (lmm_mode)mode;
    if (o.mode == LMM_MODE_WHITTED) o.area_radius = 0.2;
    o.threads = 1;
    SH_CHECK(lmm_render(s, &o, full, NULL, &err) == SH_OK);
    o.threads = 2;
    o.crop = crop;
    SH_CHECK(lmm_render(s, &o, part, &st, &err) == SH_OK);
    SH_CHECK(st.width == cw && st.height == ch && st.trace.camera_rays == (uint64_t)cw * ch);
    int same = 1;
    for (int y = 0; y < ch; y++)
      same &= !memcmp(part + 3 * (size_t)y * cw,
                      full + 3 * ((size_t)(y + crop.y0) * w + crop.x0),
                      sizeof *part * 3 * (size_t)cw);
    SH_CHECK(same);
    if (!same) fprintf(stderr, "mode %d: the crop differs\n", mode);
  }
  static const struct {
    sh_crop crop;
    const char *message;
  } bad[] = {
      {{0, 0, 49, 32}, "x1 = 49 is beyond the image's width 48"},
      {{0, 0, 48, 33}, "y1 = 33 is beyond the image's height 32"},
      {{10, 0, 10, 32}, "x1 must be greater than x0"},
      {{0, 5, 48, 4}, "y1 must be greater than y0"},
      {{-1, 0, 48, 32}, "x0 is negative"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof *bad && part; i++) {
    lmm_render_options o;
    lmm_render_options_init(&o);
    o.crop = bad[i].crop;
    int ok = lmm_render(s, &o, part, NULL, &err) == SH_ERR_ARG &&
             !strcmp(err.path, "crop") && strstr(err.message, bad[i].message);
    SH_CHECK(ok);
    if (!ok) fprintf(stderr, "bad crop %zu: %s\n", i, err.message);
  }
  free(full);
  free(part);
  sh_error_clear(&err);
}

int main(void) {
  sh_scene *s = NULL;
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(sh_scene_parse(SCENE, "t.json", NULL, &s, &err) == SH_OK);
  test_options();
  if (s) {
    test_modes(s);
    test_crop(s);
    test_cancel(s);
  }
  sh_scene_free(s);
  sh_error_clear(&err);
  SH_TEST_DONE();
}
