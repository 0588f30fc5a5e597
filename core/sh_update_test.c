/* Tests of sh_scene_update (shafts.h): each kind of patch gives the scene a
 * fresh parse of the patched scene would give, with the SH_CHANGED_* bits
 * of what differs; every bad patch is refused with its status, line,
 * column, key path and message, and leaves the scene as it was. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_parse.h"
#include "sh_test.h"
#include "shafts.h"

/* The scene, with the parts a patch changes as parameters. */
#define SCENE_FMT                                                           \
  "{\"format\": \"shafts-scene\", \"version\": 1,\n"                        \
  " \"camera\": %s,\n"                                                      \
  " \"background\": %s, \"ambient\": %s,\n"                                 \
  " %s\n"                                                                   \
  " \"lights\": %s,\n"                                                      \
  " \"materials\": {\"white\": {\"diffuse\": [0.8, 0.8, 0.8]}},\n"          \
  " \"shapes\": [\n"                                                        \
  "   {\"type\": \"sphere\", \"material\": \"white\", \"center\": [0, 1, 0],\n" \
  "    \"radius\": 0.5},\n"                                                 \
  "   {\"type\": \"box\", \"material\": \"white\", \"min\": [-1, 0, -1],\n" \
  "    \"max\": [1, 0.1, 1], \"transform\": %s}]}\n"

#define CAMERA                                                              \
  "{\"position\": [0, 2, 6], \"look_at\": [0, 1, 0], \"fov_y_deg\": 40,"    \
  " \"width\": 32, \"height\": 24}"
#define LIGHTS                                                              \
  "[{\"type\": \"point\", \"position\": [1, 4, 1], \"intensity\": [20, 20, 20]},\n" \
  "  {\"type\": \"spot\", \"position\": [0, 4, 0], \"look_at\": [0, 0, 0],\n" \
  "   \"intensity\": [50, 50, 50], \"outer_angle_deg\": 30}]"
#define MEDIUM                                                              \
  "{\"sigma_s\": [0.1, 0.1, 0.1], \"bounds\": {\"min\": [-4, -1, -4],"      \
  " \"max\": [4, 4, 4]}}"
#define TRANSFORM "{\"translate\": [0, -0.5, 0]}"

typedef struct parts {
  const char *camera, *background, *ambient, *medium, *lights, *transform;
} parts;

static const parts base = {CAMERA, "[0, 0, 0]", "[0, 0, 0]", MEDIUM, LIGHTS,
                           TRANSFORM};

static sh_scene *parse(parts p) {
  char text[4096], medium[1024] = "";
  /* A patch's null medium is a scene without one. */
  if (strcmp(p.medium, "null") != 0)
    snprintf(medium, sizeof medium, "\"medium\": %s,", p.medium);
  snprintf(text, sizeof text, SCENE_FMT, p.camera, p.background, p.ambient,
           medium, p.lights, p.transform);
  sh_scene *s = NULL;
  sh_error err = SH_ERROR_INIT;
  if (sh_scene_parse(text, "scene.json", NULL, &s, &err) != SH_OK)
    fprintf(stderr, "%s: %s\n", err.path, err.message);
  SH_CHECK(s != NULL);
  sh_error_clear(&err);
  return s;
}

static int same_vec(sh_vec3 a, sh_vec3 b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

/* Everything a patch may change, compared exactly. */
static int same_scene(const sh_scene *a, const sh_scene *b) {
  const sh_camera *ca = &a->camera, *cb = &b->camera;
  int same = same_vec(ca->position, cb->position) &&
             same_vec(ca->look_at, cb->look_at) && same_vec(ca->up, cb->up) &&
             ca->fov_y_deg == cb->fov_y_deg && ca->width == cb->width &&
             ca->height == cb->height &&
             same_vec(a->background, b->background) &&
             same_vec(a->ambient, b->ambient) &&
             a->medium.present == b->medium.present &&
             a->nlights == b->nlights && a->nshapes == b->nshapes;
  if (same && a->medium.present)
    same = same_vec(a->medium.sigma_s, b->medium.sigma_s) &&
           same_vec(a->medium.sigma_t, b->medium.sigma_t) &&
           a->medium.phase.type == b->medium.phase.type &&
           a->medium.phase.g == b->medium.phase.g &&
           same_vec(a->medium.bmin, b->medium.bmin) &&
           same_vec(a->medium.bmax, b->medium.bmax);
  for (int i = 0; same && i < a->nlights; i++) {
    const sh_light *la = &a->lights[i], *lb = &b->lights[i];
    same = la->type == lb->type && same_vec(la->position, lb->position) &&
           same_vec(la->direction, lb->direction) &&
           same_vec(la->intensity, lb->intensity) &&
           same_vec(la->irradiance, lb->irradiance) &&
           la->outer_deg == lb->outer_deg && la->inner_deg == lb->inner_deg &&
           la->cos_outer == lb->cos_outer && la->cos_inner == lb->cos_inner &&
           la->exponent == lb->exponent &&
           la->soft_shadows == lb->soft_shadows;
  }
  for (int i = 0; same && i < a->nshapes; i++)
    same = memcmp(&a->shapes[i].xform, &b->shapes[i].xform,
                  sizeof(sh_mat4)) == 0 &&
           memcmp(&a->shapes[i].inv, &b->shapes[i].inv, sizeof(sh_mat4)) == 0;
  return same;
}

/* Applies `patch` to the base scene and compares it with a parse of
 * `expect`; checks the changed bits. */
static void check_update(const char *patch, parts expect, unsigned bits) {
  sh_scene *s = parse(base), *want = parse(expect);
  unsigned changed = 999;
  sh_error err = SH_ERROR_INIT;
  if (!s || !want) goto out;
  sh_status st = sh_scene_update(s, patch, "patch.json", &changed, &err);
  SH_CHECK(st == SH_OK);
  if (st) fprintf(stderr, "%s: %s: %s\n", patch, err.path, err.message);
  SH_CHECK(changed == bits);
  if (changed != bits)
    fprintf(stderr, "%s: changed %u, expected %u\n", patch, changed, bits);
  SH_CHECK(same_scene(s, want));
out:
  sh_scene_free(s);
  sh_scene_free(want);
  sh_error_clear(&err);
}

static void test_updates(void) {
  parts p = base;
  p.camera = "{\"position\": [1, 2, 6], \"look_at\": [0, 1, 0], "
             "\"up\": [0, 1, 0.1], \"fov_y_deg\": 30, \"width\": 32, "
             "\"height\": 24}";
  char patch[2048];
  snprintf(patch, sizeof patch, "{\"camera\": %s}", p.camera);
  check_update(patch, p, SH_CHANGED_CAMERA);
  p.camera = "{\"position\": [0, 2, 6], \"look_at\": [0, 1, 0], "
             "\"fov_y_deg\": 40, \"width\": 64, \"height\": 24}";
  snprintf(patch, sizeof patch, "{\"camera\": %s}", p.camera);
  check_update(patch, p, SH_CHANGED_CAMERA | SH_CHANGED_SIZE);
  /* The same camera changes nothing. */
  check_update("{\"camera\": " CAMERA "}", base, 0);

  p = base;
  p.lights =
      "[{\"type\": \"point\", \"position\": [2, 4, 1], \"intensity\": [5, 6, "
      "7], \"soft_shadows\": false},\n"
      " {\"type\": \"spot\", \"position\": [0, 3, 0], \"direction\": [0, -1, "
      "0.2], \"intensity\": [9, 9, 9], \"outer_angle_deg\": 45, "
      "\"inner_angle_deg\": 10, \"exponent\": 1}]";
  snprintf(patch, sizeof patch, "{\"lights\": %s}", p.lights);
  check_update(patch, p, SH_CHANGED_LIGHTS);

  p = base;
  p.medium = "{\"sigma_s\": [0.2, 0.1, 0.1], \"sigma_a\": [0.01, 0, 0], "
             "\"phase\": {\"type\": \"henyey_greenstein\", \"g\": 0.5}, "
             "\"bounds\": {\"min\": [-4, -1, -4], \"max\": [4, 5, 4]}}";
  snprintf(patch, sizeof patch, "{\"medium\": %s}", p.medium);
  check_update(patch, p, SH_CHANGED_MEDIUM);
  p.medium = "null";
  check_update("{\"medium\": null}", p, SH_CHANGED_MEDIUM);

  p = base;
  p.background = "[0.1, 0.2, 0.3]";
  p.ambient = "[0.01, 0.01, 0.01]";
  check_update("{\"background\": [0.1, 0.2, 0.3], "
               "\"ambient\": [0.01, 0.01, 0.01]}",
               p, SH_CHANGED_ENVIRONMENT);

  p = base;
  p.transform = "{\"translate\": [0, -1, 0], \"rotate_deg\": [0, 45, 0], "
                "\"scale\": 2}";
  snprintf(patch, sizeof patch, "{\"transforms\": [null, %s]}", p.transform);
  check_update(patch, p, SH_CHANGED_SHAPES);
  check_update("{\"transforms\": [null, " TRANSFORM "]}", base, 0);

  /* All at once. */
  p.camera = "{\"position\": [1, 2, 6], \"look_at\": [0, 1, 0], "
             "\"fov_y_deg\": 40, \"width\": 32, \"height\": 24}";
  p.medium = "null";
  snprintf(patch, sizeof patch,
           "{\"transforms\": [null, %s], \"camera\": %s, \"medium\": null}",
           p.transform, p.camera);
  check_update(patch, p,
               SH_CHANGED_SHAPES | SH_CHANGED_CAMERA | SH_CHANGED_MEDIUM);
}

/* A spot's light map without an up of its own takes the camera's up: a
 * patched camera turns it as a fresh parse would. */
static void test_map_follows_camera_up(void) {
  static const char *fmt =
      "{\"format\": \"shafts-scene\", \"version\": 1,\n"
      " \"camera\": {\"position\": [0, 1, 6], \"look_at\": [0, 0, 0],"
      " \"up\": %s, \"fov_y_deg\": 40, \"width\": 16, \"height\": 16},\n"
      " \"lights\": [{\"type\": \"spot\", \"position\": [0, 3, 0],"
      " \"direction\": [0, -1, 0.3], \"intensity\": [1, 1, 1],"
      " \"outer_angle_deg\": 30, \"light_map\": {\"image\": "
      "\"gobo_star.png\"}}]}";
  const char *src = getenv("SHAFTS_SOURCE_DIR");
  char dir[600], text[2048];
  snprintf(dir, sizeof dir, "%s/scenes/assets", src ? src : "..");
  sh_scene *s = NULL, *want = NULL;
  sh_error err = SH_ERROR_INIT;
  snprintf(text, sizeof text, fmt, "[0, 1, 0]");
  SH_CHECK(sh_scene_parse(text, "a.json", dir, &s, &err) == SH_OK);
  snprintf(text, sizeof text, fmt, "[1, 1, 0]");
  SH_CHECK(sh_scene_parse(text, "b.json", dir, &want, &err) == SH_OK);
  if (s && want) {
    unsigned changed = 0;
    SH_CHECK(sh_scene_update(s,
                             "{\"camera\": {\"position\": [0, 1, 6], "
                             "\"look_at\": [0, 0, 0], \"up\": [1, 1, 0], "
                             "\"fov_y_deg\": 40, \"width\": 16, "
                             "\"height\": 16}}",
                             "p.json", &changed, &err) == SH_OK);
    SH_CHECK(changed == (SH_CHANGED_CAMERA | SH_CHANGED_LIGHTS));
    /* Equal but for the rounding of normalizing the unit axis again. */
    const sh_light *a = &s->lights[0], *b = &want->lights[0];
    SH_CHECK_NEAR(a->map_up.x, b->map_up.x, 0, 1e-15);
    SH_CHECK_NEAR(a->map_up.y, b->map_up.y, 0, 1e-15);
    SH_CHECK_NEAR(a->map_up.z, b->map_up.z, 0, 1e-15);
    SH_CHECK_NEAR(a->map_right.x, b->map_right.x, 0, 1e-15);
    SH_CHECK_NEAR(a->map_right.y, b->map_right.y, 0, 1e-15);
    SH_CHECK_NEAR(a->map_right.z, b->map_right.z, 0, 1e-15);
    SH_CHECK(!same_vec(s->lights[0].map_up, sh_v3(0, 0, 0)));
  }
  sh_scene_free(s);
  sh_scene_free(want);
  sh_error_clear(&err);
}

typedef struct bad_case {
  const char *patch;
  sh_status status;
  int line, column;
  const char *path, *message;
} bad_case;

static void test_bad(void) {
  static const bad_case cases[] = {
      {"{\"camera\": ", SH_ERR_SYNTAX, 1, 11, "camera", "invalid JSON"},
      {"[1]", SH_ERR_SCENE, 1, 1, "", "expected an object (a scene patch)"},
      {"{\"camra\": {}}", SH_ERR_SCENE, 1, 2, "camra",
       "did you mean 'camera'"},
      {"{\"render\": {}}", SH_ERR_SCENE, 1, 2, "render", "unknown key"},
      {"{\"camera\": {\"position\": [0, 2, 6], \"look_at\": [0, 1, 0],\n"
       "            \"fov_y_deg\": 200, \"width\": 32, \"height\": 24}}",
       SH_ERR_SCENE, 2, 26, "camera.fov_y_deg", "in [1e-06, 180)"},
      {"{\"camera\": {\"position\": [0, 2, 6], \"look_at\": [0, 1, 0]}}",
       SH_ERR_SCENE, 1, 12, "camera", "missing required key 'fov_y_deg'"},
      {"{\"lights\": []}", SH_ERR_SCENE, 1, 12, "lights",
       "the patch has 0 lights and the scene 2"},
      {"{\"lights\": [{\"type\": \"point\", \"position\": [1, 4, 1],\n"
       "  \"intensity\": [20, 20, 20]},\n"
       " {\"type\": \"point\", \"position\": [0, 4, 0],\n"
       "  \"intensity\": [50, 50, 50]}]}",
       SH_ERR_SCENE, 3, 11, "lights[1].type",
       "light 1 is a spot light in the scene and a point light in the patch"},
      {"{\"lights\": [{\"type\": \"point\", \"position\": [1, 4, 1],\n"
       "  \"intensity\": [20, -1, 20]},\n"
       " {\"type\": \"spot\", \"position\": [0, 4, 0], \"look_at\": [0, 0, 0],\n"
       "  \"intensity\": [50, 50, 50], \"outer_angle_deg\": 30}]}",
       SH_ERR_SCENE, 2, 21, "lights[0].intensity[1]", "in [0, 1e+30]"},
      {"{\"lights\": {}}", SH_ERR_SCENE, 1, 12, "lights", "expected an array"},
      {"{\"medium\": {\"sigma_s\": [0.1, -0.1, 0.1],\n"
       " \"bounds\": {\"min\": [-4, -1, -4], \"max\": [4, 4, 4]}}}",
       SH_ERR_SCENE, 1, 30, "medium.sigma_s[1]", "in [0, 1e+30]"},
      {"{\"background\": \"black\"}", SH_ERR_SCENE, 1, 16, "background",
       "expected an array of 3 numbers"},
      {"{\"transforms\": [null]}", SH_ERR_SCENE, 1, 16, "transforms",
       "expected 2 elements (one transform or null per shape), found 1"},
      {"{\"transforms\": [3, null]}", SH_ERR_SCENE, 1, 17, "transforms[0]",
       "expected an object (a transform)"},
      {"{\"transforms\": [null, {\"scale\": [1, 0, 1]}]}", SH_ERR_SCENE, 1, 33,
       "transforms[1].scale", "nonzero scale"},
      {"{\"transforms\": [null, {\"translat\": [1, 0, 1]}]}", SH_ERR_SCENE, 1,
       24, "transforms[1].translat", "did you mean 'translate'"},
      /* Valid members before a bad one: nothing is applied. */
      {"{\"camera\": {\"position\": [5, 2, 6], \"look_at\": [0, 1, 0],\n"
       " \"fov_y_deg\": 40, \"width\": 64, \"height\": 24},\n"
       " \"lights\": [{\"type\": \"point\", \"position\": [1, 4, 1],\n"
       "  \"intensity\": [1, 1, 1]},\n"
       " {\"type\": \"spot\", \"position\": [0, 4, 0], \"look_at\": [0, 0, 0],\n"
       "  \"intensity\": [5, 5, 5], \"outer_angle_deg\": 30}],\n"
       " \"medium\": null, \"background\": [1, 1, 1],\n"
       " \"transforms\": [null, {\"matrix\": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,"
       " 0, 0, 0, 0, 2]}]}",
       SH_ERR_SCENE, 8, 34, "transforms[1].matrix",
       "expected the last row (elements 12 to 15) to be 0, 0, 0, 1"},
  };
  sh_scene *s = parse(base), *orig = parse(base);
  if (!s || !orig) return;
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    const bad_case *k = &cases[i];
    unsigned changed = 999;
    sh_error err = SH_ERROR_INIT;
    sh_status st = sh_scene_update(s, k->patch, "patch.json", &changed, &err);
    char what[40];
    snprintf(what, sizeof what, "case %zu", i);
    SH_CHECK(sh_test_error_is(what, st, &err, k->status, k->line, k->column,
                              k->path, k->message) &&
             strcmp(err.file, "patch.json") == 0 && changed == 0);
    SH_CHECK(same_scene(s, orig));
    sh_error_clear(&err);
  }
  sh_scene_free(s);
  sh_scene_free(orig);
}

/* An atmosphere by patch: set, unchanged when the same, changed when only
 * its ozone changes (the patch compares every key of the kind). */
#define ATMO_PATCH(width)                                                    \
  "{\"medium\": {\"type\": \"atmosphere\", \"center\": [0, -6360, 0], "       \
  "\"ground_radius\": 6360, \"top_radius\": 6420, \"rayleigh\": "            \
  "{\"sigma_s\": [5.802e-3, 13.558e-3, 33.1e-3], \"scale_height\": 8}, "      \
  "\"ozone\": {\"sigma_a\": [0.650e-3, 1.881e-3, 0.085e-3], "                \
  "\"center_height\": 25, \"width\": " width "}}}"

static void test_atmosphere_patch(void) {
  sh_scene *s = parse(base);
  sh_error err = SH_ERROR_INIT;
  unsigned changed = 999;
  if (!s) return;
  SH_CHECK(sh_scene_update(s, ATMO_PATCH("30"), "p.json", &changed, &err) == SH_OK);
  SH_CHECK(changed == SH_CHANGED_MEDIUM);
  SH_CHECK(s->medium.type == SH_MEDIUM_ATMOSPHERE && s->medium.atmo.top_radius == 6420);
  SH_CHECK(sh_scene_update(s, ATMO_PATCH("30"), "p.json", &changed, &err) == SH_OK);
  SH_CHECK(changed == 0);
  SH_CHECK(sh_scene_update(s, ATMO_PATCH("20"), "p.json", &changed, &err) == SH_OK);
  SH_CHECK(changed == SH_CHANGED_MEDIUM);
  SH_CHECK(s->medium.atmo.ozone_width == 20);
  sh_scene_free(s);
  sh_error_clear(&err);
}

int main(void) {
  test_atmosphere_patch();
  test_updates();
  test_map_follows_camera_up();
  test_bad();
  SH_TEST_DONE();
}
