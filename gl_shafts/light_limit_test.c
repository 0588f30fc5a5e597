/* The light limit (GS_MAX_LIGHTS, 256) on every path by which a scene
 * reaches a renderer, each refusal located at the key "lights": a scene of
 * 257 lights at gs_renderer_create; a patch (sh_scene_update, as the
 * Blender add-on's viewport sends) of 257 lights to a live renderer's scene
 * of 256, refused by the core, the scene and the renderer unchanged and
 * still drawing; and a live renderer's scene grown past the limit by its
 * embedding program before gs_renderer_sync, which says so with the count
 * and the limit (before, it said only that the number changed). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_parse.h"
#include "sh_test.h"
#include "shafts.h"
#include "test_util.h"

/* n point lights as a "lights" member, x moved by dx. */
static char *lights_json(int n, double dx) {
  size_t cap = (size_t)n * 120 + 64, len = 0;
  char *s = malloc(cap);
  if (!s) return NULL;
  len += (size_t)snprintf(s + len, cap - len, "\"lights\": [");
  for (int i = 0; i < n; i++)
    len += (size_t)snprintf(s + len, cap - len,
                            "%s{\"type\": \"point\", \"position\": [%g, 2, %g], "
                            "\"intensity\": [0.01, 0.01, 0.01]}",
                            i ? ", " : "", (i % 16) * 0.2 - 1.5 + dx, (i / 16) * 0.2 - 1.5);
  snprintf(s + len, cap - len, "]");
  return s;
}

static sh_scene *scene_of(int n, const char *name, sh_error *err) {
  char *lights = lights_json(n, 0);
  size_t cap = strlen(lights) + 1024;
  char *text = malloc(cap);
  sh_scene *s = NULL;
  if (lights && text) {
    snprintf(text, cap,
             "{\"format\": \"shafts-scene\", \"version\": 1,\n"
             " \"camera\": {\"position\": [0, 1, 5], \"look_at\": [0, 0, 0], "
             "\"fov_y_deg\": 45, \"width\": 8, \"height\": 6},\n"
             " %s,\n"
             " \"materials\": {\"m\": {\"diffuse\": [0.5, 0.5, 0.5]}},\n"
             " \"shapes\": [{\"type\": \"quad\", \"material\": \"m\", \"corner\": [-2, 0, 2],"
             " \"u\": [4, 0, 0], \"v\": [0, 0, -4]}]}\n",
             lights);
    if (sh_scene_parse(text, name, ".", &s, err) != SH_OK) s = NULL;
  }
  free(lights);
  free(text);
  return s;
}

/* Whether err is SH_ERR_SCENE at `file`, key "lights", saying `what`. */
static int located(const sh_error *err, sh_status st, const char *file, const char *what) {
  int ok = st == SH_ERR_SCENE && !strcmp(err->file, file) &&
           !strcmp(err->path, "lights") && strstr(err->message, what);
  if (!ok)
    fprintf(stderr, "got status %d at '%s', key '%s': %s\nwant SH_ERR_SCENE at '%s', "
            "key 'lights', saying '%s'\n", st, err->file, err->path, err->message, file, what);
  return ok;
}

int main(void) {
  sh_error err = SH_ERROR_INIT;
  sh_scene *many = scene_of(257, "many.json", &err);
  SH_CHECK(many != NULL);
  if (many) {
    gs_options o = gs_options_defaults(many);
    gs_renderer *r = NULL;
    SH_CHECK(located(&err, gs_renderer_create(many, &o, &r, &err), "many.json",
                     "257 lights: gl_shafts renders at most 256"));
    SH_CHECK(r == NULL);
    sh_scene_free(many);
  }

  sh_scene *s = scene_of(256, "live.json", &err);
  SH_CHECK(s != NULL);
  if (!s) SH_TEST_DONE();
  gs_options o = gs_options_defaults(s);
  o.live = 1;
  gs_renderer *r = NULL;
  SH_CHECK(gs_renderer_create(s, &o, &r, &err) == SH_OK);
  if (!r) {
    fprintf(stderr, "create: %s\n", err.message);
    sh_scene_free(s);
    SH_TEST_DONE();
  }
  sh_image img = {0};
  SH_CHECK(tu_draw(r, s, &img, NULL));

  /* A patch of 257 lights: refused where it is read, the scene kept. */
  char *more = lights_json(257, 0.1);
  size_t cap = strlen(more) + 4;
  char *patch = malloc(cap);
  snprintf(patch, cap, "{%s}", more);
  unsigned changed = 0;
  SH_CHECK(located(&err, sh_scene_update(s, patch, "patch.json", &changed, &err),
                   "patch.json", "the patch has 257 lights and the scene 256"));
  SH_CHECK(s->nlights == 256);
  free(more);
  free(patch);
  /* 256 moved lights: taken, synced, drawn. */
  more = lights_json(256, 0.1);
  cap = strlen(more) + 4;
  patch = malloc(cap);
  snprintf(patch, cap, "{%s}", more);
  SH_CHECK(sh_scene_update(s, patch, "patch.json", &changed, &err) == SH_OK);
  SH_CHECK(changed & SH_CHANGED_LIGHTS);
  SH_CHECK(gs_renderer_sync(r, changed, &err) == SH_OK);
  sh_image_free(&img);
  SH_CHECK(tu_draw(r, s, &img, NULL));
  free(more);
  free(patch);

  /* The embedding program grows the scene's lights past the limit (the
   * scene's struct is open to C code, sh_scene.h): sync refuses with the
   * limit, located, and draws nothing until then. */
  sh_light *grown = realloc(s->lights, 257 * sizeof *grown);
  SH_CHECK(grown != NULL);
  if (grown) {
    s->lights = grown;
    s->lights[256] = s->lights[255];
    s->lights[256].map_file = NULL;
    s->nlights = 257;
    SH_CHECK(located(&err, gs_renderer_sync(r, SH_CHANGED_LIGHTS, &err), "live.json",
                     "257 lights: gl_shafts renders at most 256"));
    s->nlights = 256;
  }
  sh_image_free(&img);
  gs_renderer_free(r);
  sh_scene_free(s);
  sh_error_clear(&err);
  SH_TEST_DONE();
}
