#include "test_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gs_context.h"
#include "sh_compare.h"
#include "sh_parse.h"
#include "sh_reference.h"
#include "sh_str.h"

/* Prints the whole error and clears it. */
static void report(const char *what, sh_error *err) {
  char *text = sh_error_text(err);
  fprintf(stderr, "%s: %s\n", what, text ? text : err->message);
  free(text);
  sh_error_clear(err);
}

int tu_failures;

void tu_check(int cond, const char *what) {
  printf("%s: %s\n", cond ? "ok" : "FAIL", what);
  if (!cond) tu_failures++;
}

sh_scene *tu_scene(const char *json) {
  const char *src = getenv("SHAFTS_SOURCE_DIR");
  char *dir = sh__printf_alloc("%s/scenes", src ? src : "../..");
  sh_scene *s = NULL;
  sh_error err = SH_ERROR_INIT;
  if (dir && sh_scene_parse(json, "test.json", dir, &s, &err) != SH_OK)
    report("parsing a test scene", &err);
  free(dir);
  return s;
}

sh_status tu_gl(const sh_scene *scene, const gs_options *opt, sh_image *out) {
  gs_options o = opt ? *opt : gs_options_defaults(scene);
  sh_error err = SH_ERROR_INIT;
  sh_status st = gs_render(scene, &o, out, NULL, &err);
  if (st != SH_OK) report("gl_shafts", &err);
  return st;
}

sh_status tu_reference(const sh_scene *scene, int spp, sh_image *out) {
  sh_reference_options o = sh_reference_defaults(scene);
  o.spp = spp;
  sh_error err = SH_ERROR_INIT;
  sh_status st = sh_render_reference(scene, &o, out, NULL, &err);
  if (st != SH_OK) report("reference", &err);
  return st;
}

double tu_error(const sh_image *img, const sh_image *ref) {
  sh_image_error e;
  if (sh_image_compare(img, ref, 0.01, &e, NULL, NULL) != SH_OK) return 1e9;
  return e.rel_rms;
}

int tu_check_close(const char *name, const sh_image *img, const sh_image *ref,
                   double bound) {
  double e = tu_error(img, ref);
  fprintf(stderr, "%-40s error %7.3f %% (bound %.2f %%)\n", name, 100 * e, 100 * bound);
  if (e <= bound) return 1;
  const char *dir = getenv("SHAFTS_BINARY_DIR");
  char path[1024];
  sh_image_error ie;
  sh_image diff = {0};
  sh_image_compare(img, ref, 0.01, &ie, &diff, NULL);
  const sh_image *imgs[3] = {img, ref, &diff};
  const char *suffix[3] = {"", "_ref", "_diff"};
  for (int i = 0; i < 3; i++) {
    snprintf(path, sizeof path, "%s/gl_shafts_%s%s.exr", dir ? dir : ".", name, suffix[i]);
    if (imgs[i]->rgb && sh_image_write(path, imgs[i], 0, NULL) == SH_OK)
      fprintf(stderr, "  wrote %s\n", path);
  }
  sh_image_free(&diff);
  return 0;
}

int tu_check_reference(const char *name, const sh_scene *s, int spp, double bound) {
  sh_image gl = {0}, ref = {0};
  int ok = tu_reference(s, spp, &ref) == SH_OK && tu_gl(s, NULL, &gl) == SH_OK &&
           tu_check_close(name, &gl, &ref, bound);
  sh_image_free(&gl);
  sh_image_free(&ref);
  return ok;
}

gs__context *tu_context(void) {
  gs__context *ctx = NULL;
  sh_error err = SH_ERROR_INIT;
  if (gs__context_create(GS_BACKEND_AUTO, &ctx, &err) != SH_OK) {
    printf("FAIL: no GL context: %s\n", err.message);
    sh_error_clear(&err);
    return NULL;
  }
  printf("backend %s, %s\n", gs__context_backend_name(ctx), gs__context_renderer(ctx));
  return ctx;
}

int tu_draw(gs_renderer *r, const sh_scene *s, sh_image *img, gs_stats *stats) {
  sh_error err = SH_ERROR_INIT;
  if (sh_image_alloc(img, s->camera.width, s->camera.height, NULL) != SH_OK) return 0;
  if (gs_renderer_draw(r, img->rgb, stats, &err) != SH_OK) {
    fprintf(stderr, "draw: %s\n", err.message);
    sh_error_clear(&err);
    return 0;
  }
  return 1;
}

int tu_equal_bits(const char *name, const sh_image *a, const sh_image *b) {
  size_t n = (size_t)a->width * a->height * 3, diff = 0;
  for (size_t i = 0; i < n; i++) diff += a->rgb[i] != b->rgb[i];
  fprintf(stderr, "%-40s %zu of %zu values differ\n", name, diff, n);
  if (diff) tu_check_close(name, a, b, 0.0); /* writes the images */
  return diff == 0;
}
