/* Tests of the scene parser (sh_parse.h) and the scene lifecycle
 * (sh_scene.h): a scene that uses every key of the format, defaults, every
 * shape, light and phase type, transform order, bounds, and a table of bad
 * scenes each with its status, line, column, key path and message. */
#include "sh_json_locate.h"
#include "sh_parse.h"
#include "sh_parse_ctx.h"
#include "sh_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmpdir[256];

static void path_in_tmp(char *buf, size_t size, const char *name) {
  snprintf(buf, size, "%s/%s", tmpdir, name);
}

static void write_text(const char *name, const char *text) {
  char path[512];
  path_in_tmp(path, sizeof path, name);
  FILE *f = fopen(path, "wb");
  SH_CHECK(f != NULL);
  if (!f) return;
  fwrite(text, 1, strlen(text), f);
  fclose(f);
}

static void write_image(const char *name, int w, int h) {
  sh_image img;
  sh_error err = SH_ERROR_INIT;
  char path[512];
  path_in_tmp(path, sizeof path, name);
  SH_CHECK(sh_image_alloc(&img, w, h, &err) == SH_OK);
  for (int i = 0; i < w * h * 3; i++) img.rgb[i] = (float)(i % 5) / 4.0f;
  SH_CHECK(sh_image_write(path, &img, 0.0, &err) == SH_OK);
  sh_image_free(&img);
  sh_error_clear(&err);
}

/* The files the scenes refer to. */
static void write_fixtures(void) {
  write_text("tet.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                        "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  write_text("garbage.obj", "this is not a mesh\n\x01\x02\n");
  write_text("empty.png", "");
  write_text("text.png", "this is not an image");
  write_image("map.png", 4, 2);
  write_image("hf.png", 3, 3);
  write_image("row.png", 3, 1);
}

static sh_scene *load_text(const char *name, const char *text, sh_error *err) {
  char path[512];
  sh_scene *s = (sh_scene *)1;
  write_text(name, text);
  path_in_tmp(path, sizeof path, name);
  sh_status st = sh_scene_load(path, &s, err);
  if (st != SH_OK) {
    char buf[2048];
    sh_error_format(err, buf, sizeof buf);
    fprintf(stderr, "%s\n", buf);
    SH_CHECK(s == NULL);
    return NULL;
  }
  return s;
}

static void check_vec(sh_vec3 a, double x, double y, double z) {
  SH_CHECK_NEAR(a.x, x, 1e-12, 1e-12);
  SH_CHECK_NEAR(a.y, y, 1e-12, 1e-12);
  SH_CHECK_NEAR(a.z, z, 1e-12, 1e-12);
}

static const char *full_scene =
    "{\n"
    "  \"format\": \"shafts-scene\", \"version\": 1,\n"
    "  \"camera\": {\"position\": [0, 1, 5], \"look_at\": [0, 1, 0],\n"
    "             \"up\": [0, 2, 0], \"fov_y_deg\": 45, \"width\": 64,\n"
    "             \"height\": 48},\n"
    "  \"background\": [0.1, 0.2, 0.3], \"ambient\": [0.01, 0.02, 0.03],\n"
    "  \"medium\": {\"sigma_s\": [0.1, 0.2, 0.3], \"sigma_a\": [0.01, 0, "
    "0.02],\n"
    "             \"phase\": {\"type\": \"henyey_greenstein\", \"g\": 0.7},\n"
    "             \"bounds\": {\"min\": [-5, 0, -5], \"max\": [5, 4, 5]}},\n"
    "  \"lights\": [\n"
    "    {\"type\": \"point\", \"position\": [1, 3, 0], \"intensity\": [10, "
    "11, 12]},\n"
    "    {\"type\": \"spot\", \"position\": [0, 3.5, 0], \"look_at\": [0, 0, "
    "0],\n"
    "     \"intensity\": [50, 40, 30], \"outer_angle_deg\": 30},\n"
    "    {\"type\": \"spot\", \"position\": [2, 3, 0], \"direction\": [0, -2, "
    "0],\n"
    "     \"intensity\": [5, 5, 5], \"outer_angle_deg\": 40,\n"
    "     \"inner_angle_deg\": 20, \"exponent\": 1.5,\n"
    "     \"light_map\": {\"image\": \"map.png\", \"up\": [0, 0, -1]}},\n"
    "    {\"type\": \"directional\", \"direction\": [0, -1, 0],\n"
    "     \"irradiance\": [2, 2, 2]},\n"
    "    {\"type\": \"directional\", \"direction\": [0, -1, -1],\n"
    "     \"irradiance\": [1, 2, 3],\n"
    "     \"light_map\": {\"image\": \"map.png\", \"origin\": [-1, 3, -1],\n"
    "                   \"u\": [2, 0, 0], \"v\": [0, 0, 2]}},\n"
    "    {\"type\": \"spot\", \"position\": [0, 3, 0], \"direction\": [1, 0, "
    "0],\n"
    "     \"intensity\": [1, 1, 1], \"outer_angle_deg\": 120}\n"
    "  ],\n"
    "  \"materials\": {\n"
    "    \"white\": {\"diffuse\": [0.8, 0.8, 0.8]},\n"
    "    \"glass\": {\"diffuse\": [0, 0, 0], \"specular\": [0.5, 0.5, 0.5],\n"
    "              \"shininess\": 64, \"reflect\": [0.1, 0.1, 0.1],\n"
    "              \"transmit\": [0.9, 0.8, 0.7], \"ior\": 1.5,\n"
    "              \"emission\": [0, 0, 0.5]}\n"
    "  },\n"
    "  \"shapes\": [\n"
    "    {\"type\": \"sphere\", \"material\": \"glass\", \"center\": [0, 1, "
    "0],\n"
    "     \"radius\": 0.5},\n"
    "    {\"type\": \"box\", \"material\": \"white\", \"min\": [-1, -1, -1],\n"
    "     \"max\": [1, 1, 1], \"transform\": {\"translate\": [1, 2, 3],\n"
    "     \"rotate_deg\": [90, 90, 0], \"scale\": [2, 3, 4]}},\n"
    "    {\"type\": \"cylinder\", \"material\": \"white\", \"base\": [0, 0, "
    "0],\n"
    "     \"top\": [0, 2, 0], \"radius\": 0.25, \"caps\": false,\n"
    "     \"transform\": {\"scale\": 2}},\n"
    "    {\"type\": \"quad\", \"material\": \"white\", \"corner\": [-5, 0, "
    "-5],\n"
    "     \"u\": [10, 0, 0], \"v\": [0, 0, 10], \"transform\": {\"matrix\":\n"
    "     [1, 0, 0, 1,  0, 1, 0, 2,  0, 0, 1, 3,  0, 0, 0, 1]}},\n"
    "    {\"type\": \"mesh\", \"material\": \"white\", \"file\": "
    "\"tet.obj\"},\n"
    "    {\"type\": \"heightfield\", \"material\": \"white\", \"image\": "
    "\"hf.png\",\n"
    "     \"min\": [-2, 0, -2], \"max\": [2, 0.5, 2]},\n"
    "    {\"type\": \"cylinder\", \"material\": \"white\", \"base\": [0, 0, "
    "0],\n"
    "     \"top\": [1, 0, 0], \"radius\": 1}\n"
    "  ],\n"
    "  \"render\": {\"spp\": 4, \"max_depth\": 3, \"seed\": 4000000000,\n"
    "             \"exposure\": -1.5}\n"
    "}\n";

static int ends_with(const char *s, const char *tail) {
  size_t a = strlen(s), b = strlen(tail);
  return a >= b && strcmp(s + a - b, tail) == 0;
}

static void test_full_scene(void) {
  sh_error err = SH_ERROR_INIT;
  sh_scene *s = load_text("full.json", full_scene, &err);
  SH_CHECK(s != NULL);
  if (!s) return;
  SH_CHECK(ends_with(s->file, "/full.json"));
  check_vec(s->camera.position, 0, 1, 5);
  check_vec(s->camera.look_at, 0, 1, 0);
  check_vec(s->camera.up, 0, 2, 0);
  SH_CHECK(s->camera.fov_y_deg == 45);
  SH_CHECK(s->camera.width == 64 && s->camera.height == 48);
  check_vec(s->background, 0.1, 0.2, 0.3);
  check_vec(s->ambient, 0.01, 0.02, 0.03);

  const sh_medium *m = &s->medium;
  SH_CHECK(m->present);
  check_vec(m->sigma_s, 0.1, 0.2, 0.3);
  check_vec(m->sigma_a, 0.01, 0, 0.02);
  check_vec(m->sigma_t, 0.11, 0.2, 0.32);
  SH_CHECK(m->phase.type == SH_PHASE_HENYEY_GREENSTEIN);
  SH_CHECK(m->phase.g == 0.7);
  check_vec(m->bmin, -5, 0, -5);
  check_vec(m->bmax, 5, 4, 5);

  SH_CHECK(s->nlights == 6);
  if (s->nlights == 6) {
    const sh_light *l = s->lights;
    SH_CHECK(l[0].type == SH_LIGHT_POINT);
    check_vec(l[0].position, 1, 3, 0);
    check_vec(l[0].intensity, 10, 11, 12);
    SH_CHECK(!l[0].has_map);
    /* A spot aimed with look_at: defaults inner = outer, exponent 0. */
    SH_CHECK(l[1].type == SH_LIGHT_SPOT);
    check_vec(l[1].direction, 0, -1, 0);
    SH_CHECK(l[1].outer_deg == 30 && l[1].inner_deg == 30);
    SH_CHECK(l[1].exponent == 0);
    SH_CHECK_NEAR(l[1].cos_outer, cos(30 * SH_PI / 180), 0, 1e-15);
    SH_CHECK(l[1].cos_inner == l[1].cos_outer);
    SH_CHECK(!l[1].has_map && l[1].map_file == NULL);
    /* A spot with every key, its map oriented by the given up. */
    SH_CHECK(l[2].type == SH_LIGHT_SPOT);
    check_vec(l[2].direction, 0, -1, 0);
    SH_CHECK(l[2].outer_deg == 40 && l[2].inner_deg == 20);
    SH_CHECK(l[2].exponent == 1.5);
    SH_CHECK(l[2].has_map);
    SH_CHECK(l[2].map_file && ends_with(l[2].map_file, "/map.png"));
    SH_CHECK(l[2].map.width == 4 && l[2].map.height == 2);
    check_vec(l[2].map_up, 0, 0, -1);
    check_vec(l[2].map_right, 1, 0, 0);
    SH_CHECK_NEAR(l[2].tan_outer, tan(40 * SH_PI / 180), 0, 1e-15);
    SH_CHECK(l[3].type == SH_LIGHT_DIRECTIONAL);
    check_vec(l[3].direction, 0, -1, 0);
    check_vec(l[3].irradiance, 2, 2, 2);
    SH_CHECK(!l[3].has_map);
    SH_CHECK(l[4].type == SH_LIGHT_DIRECTIONAL && l[4].has_map);
    check_vec(l[4].direction, 0, -sqrt(0.5), -sqrt(0.5));
    check_vec(l[4].map_origin, -1, 3, -1);
    check_vec(l[4].map_u, 2, 0, 0);
    check_vec(l[4].map_v, 0, 0, 2);
    check_vec(l[4].map_normal, 0, -1, 0);
    SH_CHECK(l[4].map.width == 4);
    /* A wide spot without a map may exceed 90 degrees. */
    SH_CHECK(l[5].outer_deg == 120 && !l[5].has_map);
  }

  SH_CHECK(s->nmaterials == 2);
  if (s->nmaterials == 2) {
    const sh_material *w = &s->materials[0], *g = &s->materials[1];
    SH_CHECK(strcmp(w->name, "white") == 0);
    check_vec(w->diffuse, 0.8, 0.8, 0.8);
    check_vec(w->specular, 0, 0, 0);
    SH_CHECK(w->shininess == 32 && w->ior == 1);
    check_vec(w->transmit, 0, 0, 0);
    SH_CHECK(strcmp(g->name, "glass") == 0);
    check_vec(g->specular, 0.5, 0.5, 0.5);
    SH_CHECK(g->shininess == 64 && g->ior == 1.5);
    check_vec(g->reflect, 0.1, 0.1, 0.1);
    check_vec(g->transmit, 0.9, 0.8, 0.7);
    check_vec(g->emission, 0, 0, 0.5);
  }
  SH_CHECK(sh_scene_has_semitransparent(s));

  SH_CHECK(s->nshapes == 7);
  if (s->nshapes == 7) {
    const sh_shape *sh = s->shapes;
    SH_CHECK(sh[0].type == SH_SHAPE_SPHERE && sh[0].material == 1);
    check_vec(sh[0].center, 0, 1, 0);
    SH_CHECK(sh[0].radius == 0.5);
    for (int i = 0; i < 4; i++)
      for (int j = 0; j < 4; j++)
        SH_CHECK(sh[0].xform.m[i][j] == (i == j) &&
                 sh[0].inv.m[i][j] == (i == j));

    /* Scale, then rotate about X, then Y, then translate. */
    SH_CHECK(sh[1].type == SH_SHAPE_BOX && sh[1].material == 0);
    check_vec(sh[1].bmin, -1, -1, -1);
    check_vec(sh[1].bmax, 1, 1, 1);
    check_vec(sh_xform_point(&sh[1].xform, sh_v3(0, 0, 0)), 1, 2, 3);
    check_vec(sh_xform_point(&sh[1].xform, sh_v3(1, 0, 0)), 1, 2, 1);
    check_vec(sh_xform_point(&sh[1].xform, sh_v3(0, 1, 0)), 4, 2, 3);
    check_vec(sh_xform_point(&sh[1].xform, sh_v3(0, 0, 1)), 1, -2, 3);
    check_vec(sh_xform_point(&sh[1].inv, sh_v3(4, 2, 3)), 0, 1, 0);
    sh_mat4 id = sh_mat4_mul(sh[1].inv, sh[1].xform);
    for (int i = 0; i < 4; i++)
      for (int j = 0; j < 4; j++) SH_CHECK_NEAR(id.m[i][j], i == j, 0, 1e-12);

    SH_CHECK(sh[2].type == SH_SHAPE_CYLINDER && !sh[2].caps);
    check_vec(sh[2].top, 0, 2, 0);
    SH_CHECK(sh[2].radius == 0.25);
    check_vec(sh_xform_point(&sh[2].xform, sh_v3(1, 1, 1)), 2, 2, 2);
    check_vec(sh_xform_point(&sh[2].inv, sh_v3(1, 1, 1)), 0.5, 0.5, 0.5);

    SH_CHECK(sh[3].type == SH_SHAPE_QUAD);
    check_vec(sh[3].corner, -5, 0, -5);
    check_vec(sh[3].u, 10, 0, 0);
    check_vec(sh[3].v, 0, 0, 10);
    check_vec(sh_xform_point(&sh[3].xform, sh_v3(1, 1, 1)), 2, 3, 4);
    check_vec(sh_xform_point(&sh[3].inv, sh_v3(1, 2, 3)), 0, 0, 0);

    SH_CHECK(sh[4].type == SH_SHAPE_MESH && sh[4].mesh.ntris == 4);
    SH_CHECK(sh[4].file && ends_with(sh[4].file, "/tet.obj"));

    SH_CHECK(sh[5].type == SH_SHAPE_HEIGHTFIELD);
    SH_CHECK(sh[5].mesh.nverts == 9 && sh[5].mesh.ntris == 8);
    SH_CHECK(sh[5].file && ends_with(sh[5].file, "/hf.png"));
    check_vec(sh[5].bmax, 2, 0.5, 2);

    SH_CHECK(sh[6].type == SH_SHAPE_CYLINDER && sh[6].caps);
  }

  SH_CHECK(s->render.spp == 4 && s->render.max_depth == 3);
  SH_CHECK(s->render.seed == 4000000000u);
  SH_CHECK(s->render.exposure == -1.5);
  sh_scene_free(s);
  sh_error_clear(&err);
}

#define MINIMAL_HEAD                                                           \
  "{\"format\": \"shafts-scene\", \"version\": 1,\n"                           \
  "\"camera\": {\"position\": [0, 0, 5], \"look_at\": [0, 0, 0], "             \
  "\"fov_y_deg\": 40, \"width\": 8, \"height\": 6}"

/* The renderers' render keys are kept as given, with their places, for the
 * renderer to check (gl_shafts' and lmm_tracer's tests check the refusals). */
static void test_render_params(void) {
  sh_error err = SH_ERROR_INIT;
  sh_scene *s = NULL;
  SH_CHECK(sh_scene_parse(MINIMAL_HEAD ",\n\"render\": {\"spp\": 4, "
                          "\"lattice\": [20, 1], \"xi\": \"exakt\"}}",
                          "mem.json", NULL, &s, &err) == SH_OK);
  if (!s) return;
  SH_CHECK(s->render.spp == 4 && s->render.nparams == 2);
  if (s->render.nparams == 2) {
    const sh_render_param *q = &s->render.params[0];
    SH_CHECK(!strcmp(q->key, "lattice") && !strcmp(q->text, "20 1") &&
             !strcmp(q->json, "[20,1]") && q->line == 3 && q->column == 33);
    q = &s->render.params[1];
    SH_CHECK(!strcmp(q->key, "xi") && !strcmp(q->text, "exakt"));
  }
  sh_scene_free(s);
  sh_error_clear(&err);
}

static void test_defaults(void) {
  sh_error err = SH_ERROR_INIT;
  sh_scene *s = NULL;
  SH_CHECK(sh_scene_parse(MINIMAL_HEAD "}", "mem.json", NULL, &s, &err) ==
           SH_OK);
  SH_CHECK(s != NULL);
  if (!s) return;
  SH_CHECK(strcmp(s->file, "mem.json") == 0);
  SH_CHECK(s->render.nparams == 0 && s->render.spp == 16);
  check_vec(s->camera.up, 0, 1, 0);
  check_vec(s->background, 0, 0, 0);
  check_vec(s->ambient, 0, 0, 0);
  SH_CHECK(!s->medium.present);
  SH_CHECK(s->nlights == 0 && s->lights == NULL);
  SH_CHECK(s->nmaterials == 0 && s->nshapes == 0);
  SH_CHECK(s->render.spp == 16 && s->render.max_depth == 5);
  SH_CHECK(s->render.seed == 0 && s->render.exposure == 0);
  SH_CHECK(!sh_scene_has_semitransparent(s));
  sh_vec3 lo, hi;
  sh_scene_bounds(s, &lo, &hi);
  check_vec(lo, 0, 0, 0);
  check_vec(hi, 0, 0, 0);
  sh_scene_free(s);
  sh_scene_free(NULL);

  /* Medium defaults: no absorption, isotropic phase. Empty lists are fine;
   * a real number with an integral value is an integer. */
  s = NULL;
  SH_CHECK(sh_scene_parse(MINIMAL_HEAD
                          ", \"medium\": {\"sigma_s\": [1, 2, 3], \"bounds\": "
                          "{\"min\": [0, 0, 0], \"max\": [1, 1, 1]}},"
                          "\"lights\": [], \"shapes\": [], \"materials\": {},"
                          "\"render\": {\"spp\": 8.0}}",
                          "mem.json", NULL, &s, &err) == SH_OK);
  if (s) {
    SH_CHECK(s->medium.present);
    SH_CHECK(s->medium.phase.type == SH_PHASE_ISOTROPIC);
    check_vec(s->medium.sigma_a, 0, 0, 0);
    check_vec(s->medium.sigma_t, 1, 2, 3);
    SH_CHECK(s->render.spp == 8);
  }
  sh_scene_free(s);
  sh_error_clear(&err);
}

static void test_phase_types(void) {
  static const char *types[] = {"isotropic", "nishita_hazy", "nishita_murky",
                                "rayleigh"};
  static const sh_phase_type want[] = {
      SH_PHASE_ISOTROPIC, SH_PHASE_NISHITA_HAZY, SH_PHASE_NISHITA_MURKY,
      SH_PHASE_RAYLEIGH};
  for (int i = 0; i < 4; i++) {
    char text[1024];
    sh_error err = SH_ERROR_INIT;
    sh_scene *s = NULL;
    snprintf(text, sizeof text,
             MINIMAL_HEAD ", \"medium\": {\"sigma_s\": [1, 1, 1], \"phase\": "
                          "{\"type\": \"%s\"}, \"bounds\": {\"min\": [0, 0, "
                          "0], \"max\": [1, 1, 1]}}}",
             types[i]);
    SH_CHECK(sh_scene_parse(text, "phase.json", NULL, &s, &err) == SH_OK);
    if (s) {
      SH_CHECK(s->medium.phase.type == want[i]);
      SH_CHECK(s->medium.phase.g == 0);
    }
    sh_scene_free(s);
    sh_error_clear(&err);
  }
}

static void test_bounds(void) {
  sh_error err = SH_ERROR_INIT;
  sh_scene *s = NULL;
  SH_CHECK(sh_scene_parse(
               MINIMAL_HEAD
               ", \"medium\": {\"sigma_s\": [1, 1, 1], \"bounds\": {\"min\": "
               "[-1, -1, -1], \"max\": [1, 1, 1]}},"
               "\"lights\": [{\"type\": \"point\", \"position\": [0, 5, 0], "
               "\"intensity\": [1, 1, 1]}, {\"type\": \"directional\", "
               "\"direction\": [0, -1, 0], \"irradiance\": [1, 1, 1]}],"
               "\"materials\": {\"m\": {}},"
               "\"shapes\": [{\"type\": \"sphere\", \"material\": \"m\", "
               "\"center\": [0, 0, 0], \"radius\": 1, \"transform\": "
               "{\"translate\": [10, 0, 0], \"scale\": 2}}]}",
               "b.json", NULL, &s, &err) == SH_OK);
  if (s) {
    sh_vec3 lo, hi;
    sh_scene_bounds(s, &lo, &hi);
    check_vec(lo, -1, -2, -2);
    check_vec(hi, 12, 5, 2);
  }
  sh_scene_free(s);

  /* A cylinder along Y reaches its radius across X and Z only; a quad its
   * four corners; a rotated box its rotated corners. */
  s = NULL;
  SH_CHECK(sh_scene_parse(
               MINIMAL_HEAD
               ", \"materials\": {\"m\": {}}, \"shapes\": ["
               "{\"type\": \"cylinder\", \"material\": \"m\", \"base\": [0, "
               "0, 0], \"top\": [0, 2, 0], \"radius\": 0.5},"
               "{\"type\": \"quad\", \"material\": \"m\", \"corner\": [3, 0, "
               "0], \"u\": [1, 0, 0], \"v\": [0, 0, -1]},"
               "{\"type\": \"box\", \"material\": \"m\", \"min\": [-1, -1, "
               "-1], \"max\": [1, 1, 1], \"transform\": {\"rotate_deg\": [0, "
               "0, 45], \"translate\": [-5, 0, 0]}}]}",
               "c.json", NULL, &s, &err) == SH_OK);
  if (s) {
    sh_vec3 lo, hi;
    sh_scene_bounds(s, &lo, &hi);
    check_vec(lo, -5 - sqrt(2), -sqrt(2), -1);
    check_vec(hi, 4, 2, 1);
  }
  sh_scene_free(s);
  sh_error_clear(&err);
}

/* An atmosphere with every key (Bruneton 2017 in km), and the defaults
 * and derived values of one with Rayleigh alone. */
static void test_atmosphere(void) {
  sh_error err = SH_ERROR_INIT;
  sh_scene *s = NULL;
  SH_CHECK(sh_scene_parse(
               MINIMAL_HEAD ",\n\"medium\": {\"type\": \"atmosphere\", "
               "\"center\": [1, -6360, 2], \"ground_radius\": 6360, "
               "\"top_radius\": 6420, \"ground_albedo\": [0.3, 0.2, 0.1], "
               "\"rayleigh\": {\"sigma_s\": [5.802e-3, 13.558e-3, 33.1e-3], "
               "\"scale_height\": 8}, \"mie\": {\"sigma_s\": [3.996e-3, "
               "3.996e-3, 3.996e-3], \"sigma_a\": [0.444e-3, 0.444e-3, "
               "0.444e-3], \"scale_height\": 1.2, \"phase\": {\"type\": "
               "\"cornette_shanks\", \"g\": 0.8}}, \"ozone\": {\"sigma_a\": "
               "[0.650e-3, 1.881e-3, 0.085e-3], \"center_height\": 25, "
               "\"width\": 30}}}",
               "atmo.json", NULL, &s, &err) == SH_OK);
  if (s) {
    const sh_medium *m = &s->medium;
    const sh_atmosphere *a = &m->atmo;
    SH_CHECK(m->present && m->type == SH_MEDIUM_ATMOSPHERE);
    SH_CHECK(a->center.x == 1 && a->center.y == -6360 && a->center.z == 2);
    SH_CHECK(a->ground_radius == 6360 && a->top_radius == 6420);
    SH_CHECK(a->ground_albedo.x == 0.3 && a->ground_albedo.z == 0.1);
    SH_CHECK(a->rayleigh_sigma_s.z == 33.1e-3 && a->rayleigh_H == 8);
    SH_CHECK(a->has_mie && a->mie_H == 1.2 && a->mie_sigma_a.y == 0.444e-3);
    SH_CHECK(a->mie_phase.type == SH_PHASE_CORNETTE_SHANKS && a->mie_phase.g == 0.8);
    SH_CHECK(a->has_ozone && a->ozone_height == 25 && a->ozone_width == 30);
    SH_CHECK(a->ozone_sigma_a.y == 1.881e-3);
    /* Derived: the box around the top sphere, the largest coefficients. */
    SH_CHECK(m->bmin.x == 1 - 6420 && m->bmax.y == -6360 + 6420);
    SH_CHECK_NEAR(m->sigma_t.x, 5.802e-3 + 3.996e-3 + 0.444e-3 + 0.650e-3,
                  1e-15, 0);
    SH_CHECK(m->phase.type == SH_PHASE_RAYLEIGH);
    sh_scene_free(s);
  }
  s = NULL;
  SH_CHECK(sh_scene_parse(
               MINIMAL_HEAD ",\n\"medium\": {\"type\": \"atmosphere\", "
               "\"center\": [0, 0, 0], \"ground_radius\": 1, "
               "\"top_radius\": 1.5, \"rayleigh\": {\"sigma_s\": [1, 2, 3], "
               "\"scale_height\": 0.1}}}",
               "atmo2.json", NULL, &s, &err) == SH_OK);
  if (s) {
    const sh_atmosphere *a = &s->medium.atmo;
    SH_CHECK(!a->has_mie && !a->has_ozone);
    SH_CHECK(a->ground_albedo.x == 0.1 && a->ground_albedo.y == 0.1);
    SH_CHECK(s->medium.sigma_t.z == 3);
    sh_scene_free(s);
  }
  sh_error_clear(&err);
}

/* A bad scene, what the parser must say about it, and where. */
typedef struct bad_case {
  const char *text;
  sh_status status;
  int line, column;
  const char *path;
  const char *message; /* a substring of the message */
} bad_case;

/* The camera is on line 2, so the case's own text starts on line 3. */
#define HEAD MINIMAL_HEAD ",\n"

static const bad_case bad_cases[] = {
    /* JSON syntax: jansson's position, and the key path read there. */
    {HEAD "\"lights\": [}\n", SH_ERR_SYNTAX, 3, 12, "lights[0]",
     "invalid JSON"},
    {HEAD "\"lights\": [{\"type\": \"point\",", SH_ERR_SYNTAX, 3, 28,
     "lights[0]", "end of file"},
    {"", SH_ERR_SYNTAX, 1, 1, "", "invalid JSON"},
    {HEAD "\"ambient\": [0, 0, 0], \"ambient\": [0, 0, 0]}", SH_ERR_SYNTAX, 3,
     31, "ambient", "duplicate object key"},
    /* Numbers that do not fit a double. */
    {HEAD "\"ambient\": [0, 1e999, 0]}", SH_ERR_SCENE, 3, 16, "ambient[1]",
     "expected a finite number, found 1e999"},
    {HEAD "\"ambient\": [0, -1e999, 0]}", SH_ERR_SCENE, 3, 16, "ambient[1]",
     "finite"},
    {HEAD "\"render\": {\"seed\": 99999999999999999999}}", SH_ERR_SCENE, 3, 20,
     "render.seed", "too large"},
    /* Types. */
    {HEAD "\"background\": \"black\"}", SH_ERR_SCENE, 3, 15, "background",
     "expected an array of 3 numbers in [0, 1e+30], found the string \"black\""},
    {HEAD "\"background\": [1, 1]}", SH_ERR_SCENE, 3, 15, "background",
     "found an array of 2 elements"},
    {HEAD "\"lights\": {}}", SH_ERR_SCENE, 3, 11, "lights",
     "expected an array, found an object"},
    {HEAD "\"lights\": [3]}", SH_ERR_SCENE, 3, 12, "lights[0]",
     "expected an object (a light), found the number 3"},
    {"[1, 2]", SH_ERR_SCENE, 1, 1, "", "expected an object"},
    {HEAD "\"render\": {\"spp\": 1.5}}", SH_ERR_SCENE, 3, 19, "render.spp",
     "expected an integer from 1 to 2147483647, found the number 1.5"},
    {HEAD "\"shapes\": [{\"type\": \"cylinder\", \"material\": \"m\", "
          "\"base\": [0, 0, 0], \"top\": [0, 1, 0], \"radius\": 1, "
          "\"caps\": 1}], \"materials\": {\"m\": {}}}",
     SH_ERR_SCENE, 3, 108, "shapes[0].caps", "expected true or false"},
    /* Unknown keys. */
    {"{\"format\": \"shafts-scene\", \"version\": 1,\n"
     "\"camera\": {\"positon\": [0, 0, 5], \"look_at\": [0, 0, 0], "
     "\"fov_y_deg\": 40, \"width\": 8, \"height\": 6}}",
     SH_ERR_SCENE, 2, 12, "camera.positon",
     "unknown key 'positon' in the camera; did you mean 'position'?"},
    {HEAD "\"shadows\": true}", SH_ERR_SCENE, 3, 1, "shadows",
     "the keys allowed there are: format, version"},
    {HEAD "\"lights\": [{\"type\": \"point\", \"position\": [0, 0, 0], "
          "\"intensity\": [1, 1, 1], \"irradiance\": [1, 1, 1]}]}",
     SH_ERR_SCENE, 3, 77, "lights[0].irradiance",
     "unknown key 'irradiance' in a point light"},
    /* The sun's disk: directional lights only, at most 10 degrees. */
    {HEAD "\"lights\": [{\"type\": \"directional\", \"direction\": [0, -1, "
          "0], \"irradiance\": [1, 1, 1], \"angular_diameter_deg\": 11}]}",
     SH_ERR_SCENE, 3, 110, "lights[0].angular_diameter_deg",
     "expected a number in [0, 10], found the number 11"},
    {HEAD "\"lights\": [{\"type\": \"directional\", \"direction\": [0, -1, "
          "0], \"irradiance\": [1, 1, 1], \"angular_diameter_deg\": -1}]}",
     SH_ERR_SCENE, 3, 110, "lights[0].angular_diameter_deg",
     "expected a number in [0, 10], found the number -1"},
    {HEAD "\"lights\": [{\"type\": \"point\", \"position\": [0, 0, 0], "
          "\"intensity\": [1, 1, 1], \"angular_diameter_deg\": 1}]}",
     SH_ERR_SCENE, 3, 77, "lights[0].angular_diameter_deg",
     "unknown key 'angular_diameter_deg' in a point light"},
    {HEAD "\"lights\": [{\"type\": \"spto\"}]}", SH_ERR_SCENE, 3, 21,
     "lights[0].type", "unknown light type 'spto'; did you mean 'spot'?"},
    {HEAD "\"medium\": {\"sigma_s\": [1, 1, 1], \"phase\": {\"type\": "
          "\"isotropic\", \"g\": 0.5}, \"bounds\": {\"min\": [0, 0, 0], "
          "\"max\": [1, 1, 1]}}}",
     SH_ERR_SCENE, 3, 65, "medium.phase.g",
     "unknown key 'g' in a phase function of type 'isotropic'"},
    /* Medium types: each accepts only its own keys. */
    {HEAD "\"medium\": {\"sigma_s\": [1, 1, 1], \"scale_height\": 2, "
          "\"bounds\": {\"min\": [0, 0, 0], \"max\": [1, 1, 1]}}}",
     SH_ERR_SCENE, 3, 34, "medium.scale_height",
     "unknown key 'scale_height' in a homogeneous medium"},
    {HEAD "\"medium\": {\"type\": \"height_fog\", \"sigma_s\": [1, 1, 1], "
          "\"bounds\": {\"min\": [0, 0, 0], \"max\": [1, 1, 1]}}}",
     SH_ERR_SCENE, 3, 11, "medium", "scale_height"},
    {HEAD "\"medium\": {\"type\": \"height_fog\", \"scale_height\": 0, "
          "\"sigma_s\": [1, 1, 1], \"bounds\": {\"min\": [0, 0, 0], "
          "\"max\": [1, 1, 1]}}}",
     SH_ERR_SCENE, 3, 50, "medium.scale_height", "found the number 0"},
    {HEAD "\"medium\": {\"type\": \"height_fog\", \"scale_height\": 1, "
          "\"center\": [0, 0, 0], \"sigma_s\": [1, 1, 1], \"bounds\": "
          "{\"min\": [0, 0, 0], \"max\": [1, 1, 1]}}}",
     SH_ERR_SCENE, 3, 53, "medium.center",
     "unknown key 'center' in a medium of type 'height_fog'"},
    {HEAD "\"medium\": {\"sigma_s\": [1, 1, 1], \"phase\": {\"type\": "
          "\"cornette_shanks\"}, \"bounds\": {\"min\": [0, 0, 0], "
          "\"max\": [1, 1, 1]}}}",
     SH_ERR_SCENE, 3, 43, "medium.phase", "missing required key 'g'"},
#define ATMO_HEAD HEAD "\"medium\": {\"type\": \"atmosphere\", \"center\": [0, -6360, 0],\n"
    {ATMO_HEAD "\"ground_radius\": 6360, \"top_radius\": 6300, \"rayleigh\": "
               "{\"sigma_s\": [1, 1, 1], \"scale_height\": 8}}}",
     SH_ERR_SCENE, 4, 38, "medium.top_radius",
     "expected top_radius > ground_radius (6360), found 6300"},
    {ATMO_HEAD "\"ground_radius\": 6360, \"top_radius\": 6420}}", SH_ERR_SCENE,
     3, 11, "medium", "missing required key 'rayleigh'"},
    {ATMO_HEAD "\"ground_radius\": 6360, \"top_radius\": 6420, \"sigma_s\": [1, 1, 1]}}",
     SH_ERR_SCENE, 4, 44, "medium.sigma_s",
     "unknown key 'sigma_s' in a medium of type 'atmosphere'"},
    {ATMO_HEAD "\"ground_radius\": 6360, \"top_radius\": 6420, \"rayleigh\": "
               "{\"sigma_s\": [1, 1, 1], \"scale_height\": -8}}}",
     SH_ERR_SCENE, 4, 95, "medium.rayleigh.scale_height", "found the number -8"},
    {ATMO_HEAD "\"ground_radius\": 6360, \"top_radius\": 6420, \"rayleigh\": "
               "{\"sigma_s\": [1, 1, 1], \"scale_height\": 8},\n\"mie\": "
               "{\"sigma_s\": [1, 1, 1], \"scale_height\": 1.2}}}",
     SH_ERR_SCENE, 5, 8, "medium.mie", "missing required key 'phase'"},
    {ATMO_HEAD "\"ground_radius\": 6360, \"top_radius\": 6420, \"rayleigh\": "
               "{\"sigma_s\": [1, 1, 1], \"scale_height\": 8},\n\"mie\": "
               "{\"sigma_s\": [1, 1, 1], \"scale_height\": 1.2, \"g\": 0.8}}}",
     SH_ERR_SCENE, 5, 52, "medium.mie.g",
     "unknown key 'g' in the atmosphere's mie"},
    {ATMO_HEAD "\"ground_radius\": 6360, \"top_radius\": 6420, \"rayleigh\": "
               "{\"sigma_s\": [1, 1, 1], \"scale_height\": 8},\n\"ozone\": "
               "{\"sigma_a\": [1, 1, 1], \"center_height\": 25, \"width\": 0}}}",
     SH_ERR_SCENE, 5, 63, "medium.ozone.width", "found the number 0"},
    {ATMO_HEAD "\"ground_radius\": 6360, \"top_radius\": 6420, \"rayleigh\": "
               "{\"sigma_s\": [1, 1, 1], \"scale_height\": 8}, \"bounds\": {}}}",
     SH_ERR_SCENE, 4, 99, "medium.bounds",
     "unknown key 'bounds' in a medium of type 'atmosphere'"},
    {HEAD "\"medium\": {\"type\": \"heigth_fog\", \"sigma_s\": [1, 1, 1]}}",
     SH_ERR_SCENE, 3, 20, "medium.type",
     "unknown medium type 'heigth_fog'; did you mean 'height_fog'?"},
    /* Ranges. */
    {HEAD "\"medium\": {\"sigma_s\": [0.1, -0.5, 0], \"bounds\": {\"min\": "
          "[0, 0, 0], \"max\": [1, 1, 1]}}}",
     SH_ERR_SCENE, 3, 29, "medium.sigma_s[1]",
     "expected a number in [0, 1e+30], found the number -0.5"},
    {HEAD "\"medium\": {\"sigma_s\": [1, 1, 1], \"phase\": {\"type\": "
          "\"henyey_greenstein\", \"g\": 1}, \"bounds\": {\"min\": [0, 0, "
          "0], \"max\": [1, 1, 1]}}}",
     SH_ERR_SCENE, 3, 78, "medium.phase.g",
     "expected a number in (-1, 1), found the number 1"},
    {HEAD "\"medium\": {\"sigma_s\": [1, 1, 1], \"phase\": {\"type\": "
          "\"henyey_greenstein\", \"g\": -1.5}, \"bounds\": {\"min\": [0, 0, "
          "0], \"max\": [1, 1, 1]}}}",
     SH_ERR_SCENE, 3, 78, "medium.phase.g", "found the number -1.5"},
    {HEAD "\"medium\": {\"sigma_s\": [1, 1, 1], \"phase\": {\"type\": "
          "\"henyey_greenstein\"}, \"bounds\": {\"min\": [0, 0, 0], "
          "\"max\": [1, 1, 1]}}}",
     SH_ERR_SCENE, 3, 43, "medium.phase",
     "missing required key 'g' (expected a number in (-1, 1))"},
    {HEAD "\"medium\": {\"sigma_s\": [1, 1, 1]}}", SH_ERR_SCENE, 3, 11,
     "medium", "missing required key 'bounds'"},
    {HEAD "\"medium\": {\"sigma_s\": [1, 1, 1], \"bounds\": {\"min\": [0, 0, "
          "0], \"max\": [1, 0, 1]}}}",
     SH_ERR_SCENE, 3, 70, "medium.bounds.max",
     "expected max > min on every axis, found max.y = 0 <= min.y = 0"},
    {HEAD "\"lights\": [{\"type\": \"spot\", \"position\": [0, 0, 0], "
          "\"direction\": [0, -1, 0], \"intensity\": [1, 1, 1], "
          "\"outer_angle_deg\": 30, \"inner_angle_deg\": 40}]}",
     SH_ERR_SCENE, 3, 143, "lights[0].inner_angle_deg",
     "expected inner_angle_deg <= outer_angle_deg (30), found 40"},
    {HEAD "\"lights\": [{\"type\": \"spot\", \"position\": [0, 0, 0], "
          "\"direction\": [0, -1, 0], \"intensity\": [1, 1, 1], "
          "\"outer_angle_deg\": 100, \"light_map\": {\"image\": "
          "\"map.png\"}}]}",
     SH_ERR_SCENE, 3, 120, "lights[0].outer_angle_deg",
     "a spot light with a light_map needs outer_angle_deg < 90, found 100"},
    {HEAD "\"lights\": [{\"type\": \"point\", \"position\": [0, 0, 0], "
          "\"intensity\": [1, -1, 1]}]}",
     SH_ERR_SCENE, 3, 70, "lights[0].intensity[1]", "expected a number in [0, 1e+30]"},
    {"{\"format\": \"shafts-scene\", \"version\": 1,\n"
     "\"camera\": {\"position\": [0, 0, 5], \"look_at\": [0, 0, 0], "
     "\"fov_y_deg\": 180, \"width\": 8, \"height\": 6}}",
     SH_ERR_SCENE, 2, 70, "camera.fov_y_deg",
     "expected a number in [1e-06, 180), found the number 180"},
    {"{\"format\": \"shafts-scene\", \"version\": 1,\n"
     "\"camera\": {\"position\": [0, 0, 5], \"look_at\": [0, 0, 0], "
     "\"fov_y_deg\": 40, \"width\": 0, \"height\": 6}}",
     SH_ERR_SCENE, 2, 83, "camera.width",
     "expected an integer from 1 to 65536, found the number 0"},
    {"{\"format\": \"shafts-scene\", \"version\": 1,\n"
     "\"camera\": {\"position\": [0, 5, 0], \"look_at\": [0, 0, 0], "
     "\"fov_y_deg\": 40, \"width\": 8, \"height\": 6}}",
     SH_ERR_SCENE, 2, 11, "camera", "parallel to the default up"},
    {"{\"format\": \"shafts-scene\", \"version\": 1,\n"
     "\"camera\": {\"position\": [0, 0, 5], \"look_at\": [0, 0, 5], "
     "\"fov_y_deg\": 40, \"width\": 8, \"height\": 6}}",
     SH_ERR_SCENE, 2, 46, "camera.look_at", "look_at equals position"},
    /* Structure. */
    {"{\"format\": \"shafts-scene\", \"version\": 1}", SH_ERR_SCENE, 1, 1, "",
     "missing required key 'camera' (expected an object)"},
    {"{\"format\": \"shafts\", \"version\": 1}", SH_ERR_SCENE, 1, 12, "format",
     "expected \"shafts-scene\", found \"shafts\""},
    {"{\"format\": \"shafts-scene\", \"version\": 2}", SH_ERR_SCENE, 1, 39,
     "version", "unsupported scene format version 2"},
    {"{\"version\": 1, \"camera\": {}}", SH_ERR_SCENE, 1, 1, "",
     "missing required key 'format'"},
    {HEAD "\"lights\": [{\"type\": \"spot\", \"position\": [0, 0, 0], "
          "\"direction\": [0, -1, 0], \"look_at\": [0, 0, 0], "
          "\"intensity\": [1, 1, 1], \"outer_angle_deg\": 30}]}",
     SH_ERR_SCENE, 3, 77, "lights[0].look_at",
     "either direction or look_at, not both"},
    {HEAD "\"lights\": [{\"type\": \"spot\", \"position\": [0, 0, 0], "
          "\"intensity\": [1, 1, 1], \"outer_angle_deg\": 30}]}",
     SH_ERR_SCENE, 3, 12, "lights[0]",
     "missing required key 'direction' or 'look_at'"},
    {HEAD "\"lights\": [{\"type\": \"directional\", \"direction\": [0, 0, "
          "0], \"irradiance\": [1, 1, 1]}]}",
     SH_ERR_SCENE, 3, 49, "lights[0].direction", "expected a nonzero vector"},
    {HEAD "\"lights\": [{\"type\": \"directional\", \"direction\": [0, -1, "
          "0], \"irradiance\": [1, 1, 1], \"light_map\": {\"image\": "
          "\"map.png\", \"u\": [1, 0, 0], \"v\": [0, 0, 1]}}]}",
     SH_ERR_SCENE, 3, 99, "lights[0].light_map",
     "missing required key 'origin'"},
    {HEAD "\"lights\": [{\"type\": \"directional\", \"direction\": [1, 0, "
          "0], \"irradiance\": [1, 1, 1], \"light_map\": {\"image\": "
          "\"map.png\", \"origin\": [0, 0, 0], \"u\": [1, 0, 0], \"v\": [0, "
          "0, 1]}}]}",
     SH_ERR_SCENE, 3, 98, "lights[0].light_map", "parallel to the light map"},
    {HEAD "\"lights\": [{\"type\": \"directional\", \"direction\": [0, -1, "
          "0], \"irradiance\": [1, 1, 1], \"light_map\": {\"image\": "
          "\"map.png\", \"origin\": [0, 0, 0], \"u\": [1, 0, 0], \"v\": [2, "
          "0, 0]}}]}",
     SH_ERR_SCENE, 3, 162, "lights[0].light_map.v", "u and v are parallel"},
    /* Shapes, materials and transforms. */
    {HEAD "\"materials\": {\"white\": {}, \"glass\": {}}, \"shapes\": "
          "[{\"type\": \"sphere\", \"material\": \"whte\", \"center\": [0, 0, "
          "0], \"radius\": 1}]}",
     SH_ERR_SCENE, 3, 84, "shapes[0].material",
     "unknown material 'whte'; did you mean 'white'? the materials are: "
     "white, glass"},
    {HEAD "\"shapes\": [{\"type\": \"sphere\", \"material\": \"m\", "
          "\"center\": [0, 0, 0], \"radius\": 1}]}",
     SH_ERR_SCENE, 3, 43, "shapes[0].material",
     "unknown material 'm'; the scene defines no materials"},
    {HEAD "\"materials\": {\"m\": {\"ior\": 0}}}", SH_ERR_SCENE, 3, 28,
     "materials.m.ior", "expected a number > 0, found the number 0"},
    {HEAD "\"materials\": {\"m\": {\"shininess\": -1}}}", SH_ERR_SCENE, 3, 34,
     "materials.m.shininess", "expected a number >= 0"},
    {HEAD "\"materials\": {\"m\": {}}, \"shapes\": [{\"type\": \"box\", "
          "\"material\": \"m\", \"min\": [0, 0, 0], \"max\": [1, 1, 0]}]}",
     SH_ERR_SCENE, 3, 94, "shapes[0].max",
     "expected max > min on every axis, found max.z = 0 <= min.z = 0"},
    {HEAD "\"materials\": {\"m\": {}}, \"shapes\": [{\"type\": \"sphere\", "
          "\"material\": \"m\", \"center\": [0, 0, 0], \"radius\": 0}]}",
     SH_ERR_SCENE, 3, 103, "shapes[0].radius", "expected a number > 0"},
    {HEAD "\"materials\": {\"m\": {}}, \"shapes\": [{\"type\": \"sphere\", "
          "\"material\": \"m\", \"center\": [0, 0, 0]}]}",
     SH_ERR_SCENE, 3, 36, "shapes[0]", "missing required key 'radius'"},
    {HEAD "\"materials\": {\"m\": {}}, \"shapes\": [{\"type\": \"cylinder\", "
          "\"material\": \"m\", \"base\": [0, 1, 0], \"top\": [0, 1, 0], "
          "\"radius\": 1}]}",
     SH_ERR_SCENE, 3, 100, "shapes[0].top", "top equals base"},
    {HEAD "\"materials\": {\"m\": {}}, \"shapes\": [{\"type\": \"quad\", "
          "\"material\": \"m\", \"corner\": [0, 0, 0], \"u\": [1, 1, 0], "
          "\"v\": [2, 2, 0]}]}",
     SH_ERR_SCENE, 3, 112, "shapes[0].v", "u and v are parallel"},
    {HEAD "\"materials\": {\"m\": {}}, \"shapes\": [{\"type\": \"sphere\", "
          "\"material\": \"m\", \"center\": [0, 0, 0], \"radius\": 1, "
          "\"transform\": {\"scale\": [1, 0, 1]}}]}",
     SH_ERR_SCENE, 3, 129, "shapes[0].transform.scale",
     "expected nonzero scale factors"},
    {HEAD "\"materials\": {\"m\": {}}, \"shapes\": [{\"type\": \"sphere\", "
          "\"material\": \"m\", \"center\": [0, 0, 0], \"radius\": 1, "
          "\"transform\": {\"translate\": [1, 0, 0], \"matrix\": []}}]}",
     SH_ERR_SCENE, 3, 120, "shapes[0].transform.translate",
     "'matrix' cannot be combined with translate"},
    {HEAD "\"materials\": {\"m\": {}}, \"shapes\": [{\"type\": \"sphere\", "
          "\"material\": \"m\", \"center\": [0, 0, 0], \"radius\": 1, "
          "\"transform\": {\"matrix\": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, "
          "0, 0, 1, 1]}}]}",
     SH_ERR_SCENE, 3, 130, "shapes[0].transform.matrix",
     "expected the last row (elements 12 to 15) to be 0, 0, 0, 1, found 0, "
     "0, 1, 1"},
    {HEAD "\"materials\": {\"m\": {}}, \"shapes\": [{\"type\": \"sphere\", "
          "\"material\": \"m\", \"center\": [0, 0, 0], \"radius\": 1, "
          "\"transform\": {\"matrix\": [1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, "
          "0, 0, 0, 1]}}]}",
     SH_ERR_SCENE, 3, 130, "shapes[0].transform.matrix",
     "the matrix is singular"},
    {HEAD "\"materials\": {\"m\": {}}, \"shapes\": [{\"type\": \"sphere\", "
          "\"material\": \"m\", \"center\": [0, 0, 0], \"radius\": 1, "
          "\"transform\": {\"matrix\": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, "
          "0, 0, 0]}}]}",
     SH_ERR_SCENE, 3, 130, "shapes[0].transform.matrix",
     "expected an array of 16 finite numbers (row-major), found an array of "
     "15 elements"},
    /* Files. */
    {HEAD "\"materials\": {\"m\": {}}, \"shapes\": [{\"type\": \"mesh\", "
          "\"material\": \"m\", \"file\": \"nope.obj\"}]}",
     SH_ERR_IO, 3, 78, "shapes[0].file",
     "cannot open the mesh file 'nope.obj' (resolved to '"},
    {HEAD "\"materials\": {\"m\": {}}, \"shapes\": [{\"type\": \"mesh\", "
          "\"material\": \"m\", \"file\": \"garbage.obj\"}]}",
     SH_ERR_MESH, 3, 78, "shapes[0].file", "cannot load mesh '"},
    {HEAD "\"materials\": {\"m\": {}}, \"shapes\": [{\"type\": \"mesh\", "
          "\"material\": \"m\", \"file\": \"\"}]}",
     SH_ERR_SCENE, 3, 78, "shapes[0].file",
     "expected a file name, found an empty string"},
    {HEAD "\"lights\": [{\"type\": \"spot\", \"position\": [0, 0, 0], "
          "\"direction\": [0, -1, 0], \"intensity\": [1, 1, 1], "
          "\"outer_angle_deg\": 30, \"light_map\": {\"image\": "
          "\"nope.png\"}}]}",
     SH_ERR_IO, 3, 147, "lights[0].light_map.image",
     "cannot open the image 'nope.png'"},
    {HEAD "\"lights\": [{\"type\": \"spot\", \"position\": [0, 0, 0], "
          "\"direction\": [0, -1, 0], \"intensity\": [1, 1, 1], "
          "\"outer_angle_deg\": 30, \"light_map\": {\"image\": "
          "\"empty.png\"}}]}",
     SH_ERR_IMAGE, 3, 147, "lights[0].light_map.image", "is an empty file"},
    {HEAD "\"lights\": [{\"type\": \"spot\", \"position\": [0, 0, 0], "
          "\"direction\": [0, -1, 0], \"intensity\": [1, 1, 1], "
          "\"outer_angle_deg\": 30, \"light_map\": {\"image\": "
          "\"text.png\"}}]}",
     SH_ERR_IMAGE, 3, 147, "lights[0].light_map.image",
     "cannot read the image '"},
    {HEAD "\"materials\": {\"m\": {}}, \"shapes\": [{\"type\": "
          "\"heightfield\", \"material\": \"m\", \"image\": \"row.png\", "
          "\"min\": [0, 0, 0], \"max\": [1, 1, 1]}]}",
     SH_ERR_IMAGE, 3, 86, "shapes[0].image",
     "a heightfield image needs at least 2 x 2 pixels, found 3 x 1"},
    {HEAD "\"materials\": {\"m\": {}}, \"shapes\": [{\"type\": "
          "\"heightfield\", \"material\": \"m\", \"image\": \"hf.png\", "
          "\"min\": [0, 0, 0], \"max\": [0, 1, 1]}]}",
     SH_ERR_SCENE, 3, 121, "shapes[0].max", "found max.x = 0 <= min.x = 0"},
    {HEAD "\"render\": {\"max_depth\": -1}}", SH_ERR_SCENE, 3, 25,
     "render.max_depth", "expected an integer from 0 to 100"},
    {HEAD "\"render\": {\"spp\": 0}}", SH_ERR_SCENE, 3, 19, "render.spp",
     "expected an integer from 1 to 2147483647, found the number 0"},
    {HEAD "\"render\": {\"exposure\": \"high\"}}", SH_ERR_SCENE, 3, 24,
     "render.exposure", "expected a finite number, found the string"},
    {HEAD "\"lights\": [{\"type\": \"point\", \"position\": [0, 0, 0], "
          "\"intensity\": [1, 1, 1], \"soft_shadow\": false}]}",
     SH_ERR_SCENE, 3, 77, "lights[0].soft_shadow",
     "did you mean 'soft_shadows'"},
};

/* Prints the line of `text` that an error points at, with a caret. */
static void show_position(const char *text, int line, int column) {
  const char *p = text;
  for (int l = 1; l < line && p; l++) {
    p = strchr(p, '\n');
    if (p) p++;
  }
  if (!p) return;
  const char *e = strchr(p, '\n');
  int n = e ? (int)(e - p) : (int)strlen(p);
  fprintf(stderr, "  %.*s\n  %*s^\n", n, p, column > 0 ? column - 1 : 0, "");
}

static void test_bad_cases(void) {
  int n = (int)(sizeof bad_cases / sizeof bad_cases[0]);
  for (int i = 0; i < n; i++) {
    const bad_case *b = &bad_cases[i];
    char name[64], path[512], formatted[2048], prefix[700];
    sh_error err = SH_ERROR_INIT;
    sh_scene *s = (sh_scene *)1;
    snprintf(name, sizeof name, "bad%02d.json", i);
    write_text(name, b->text);
    path_in_tmp(path, sizeof path, name);
    sh_status st = sh_scene_load(path, &s, &err);
    sh_error_format(&err, formatted, sizeof formatted);
    int ok = s == NULL && strcmp(err.file, path) == 0 &&
             sh_test_error_is(name, st, &err, b->status, b->line, b->column,
                              b->path, b->message);
    if (b->path[0])
      snprintf(prefix, sizeof prefix, "%s:%d:%d: %s: ", path, b->line,
               b->column, b->path);
    else
      snprintf(prefix, sizeof prefix, "%s:%d:%d: ", path, b->line, b->column);
    ok = ok && strncmp(formatted, prefix, strlen(prefix)) == 0;
    SH_CHECK(ok);
    if (!ok) {
      fprintf(stderr, "%s: %s\n", name, formatted);
      show_position(b->text, err.line, err.column);
    }
    sh_error_clear(&err);
  }
}

static void test_io_errors(void) {
  sh_error err = SH_ERROR_INIT;
  sh_scene *s = (sh_scene *)1;
  char path[512];
  path_in_tmp(path, sizeof path, "does-not-exist.json");
  SH_CHECK(sh_scene_load(path, &s, &err) == SH_ERR_IO);
  SH_CHECK(s == NULL);
  SH_CHECK(strcmp(err.file, path) == 0 && err.line == 0);
  SH_CHECK(strstr(err.message, "No such file") != NULL);
  /* A directory is not a scene file. */
  s = (sh_scene *)1;
  SH_CHECK(sh_scene_load(tmpdir, &s, &err) == SH_ERR_IO && s == NULL);
  /* Bad arguments. */
  SH_CHECK(sh_scene_parse(NULL, "x", NULL, &s, &err) == SH_ERR_ARG);
  SH_CHECK(sh_scene_load(path, NULL, NULL) == SH_ERR_ARG);
  /* A NULL error report is allowed. */
  SH_CHECK(sh_scene_parse("{", "x", NULL, &s, NULL) == SH_ERR_SYNTAX);
  SH_CHECK(s == NULL);
  sh_error_clear(&err);
}

/* Files that are not regular would be read forever (/dev/zero), block (a
 * FIFO) or exhaust memory (a scene beyond SH_SCENE_MAX_BYTES): refused
 * with a clear message before a byte is read (issue 11, kind 7). */
static void test_not_regular(void) {
  sh_error err = SH_ERROR_INIT;
  sh_scene *s = NULL;
  SH_CHECK(sh_scene_load("/dev/zero", &s, &err) == SH_ERR_IO && s == NULL);
  SH_CHECK(strstr(err.message, "a character device, not a regular file"));
  char fifo[512], big[512];
  path_in_tmp(fifo, sizeof fifo, "fifo.json");
  SH_CHECK(mkfifo(fifo, 0600) == 0);
  SH_CHECK(sh_scene_load(fifo, &s, &err) == SH_ERR_IO && s == NULL);
  SH_CHECK(strstr(err.message, "a FIFO, not a regular file"));
  /* A FIFO named as a mesh or as a light map, inside the scene's tree. */
  const char *uses[] = {
      MINIMAL_HEAD ", \"materials\": {\"m\": {}}, \"shapes\": [{\"type\": "
                   "\"mesh\", \"material\": \"m\", \"file\": \"fifo.json\"}]}",
      MINIMAL_HEAD ", \"lights\": [{\"type\": \"spot\", \"position\": [0, 1, "
                   "0], \"direction\": [0, -1, 0], \"intensity\": [1, 1, 1], "
                   "\"outer_angle_deg\": 30, \"light_map\": {\"image\": "
                   "\"fifo.json\"}}]}"};
  for (int i = 0; i < 2; i++) {
    sh_status st = sh_scene_parse(uses[i], "in-memory", tmpdir, &s, &err);
    SH_CHECK(st == SH_ERR_IO);
    if (st != SH_ERR_IO) fprintf(stderr, "  use %d: %d %s\n", i, st, err.message);
    SH_CHECK(s == NULL && strstr(err.message, "is a FIFO, not a regular file"));
    SH_CHECK(err.line > 0);
  }
  unlink(fifo);
  /* One byte beyond the limit (a sparse file: no disk is used). */
  path_in_tmp(big, sizeof big, "big.json");
  FILE *f = fopen(big, "w");
  SH_CHECK(f && ftruncate(fileno(f), (off_t)SH_SCENE_MAX_BYTES + 1) == 0);
  if (f) fclose(f);
  SH_CHECK(sh_scene_load(big, &s, &err) == SH_ERR_SCENE && s == NULL);
  SH_CHECK(strstr(err.message, "more than the 64 MiB a scene may have"));
  SH_CHECK(strcmp(err.file, big) == 0);
  unlink(big);
  sh_error_clear(&err);
}

/* sh_scene_parse resolves names against base_dir, and reports `name`. */
static void test_parse_base_dir(void) {
  sh_error err = SH_ERROR_INIT;
  sh_scene *s = NULL;
  const char *text =
      MINIMAL_HEAD ", \"materials\": {\"m\": {}}, \"shapes\": [{\"type\": "
                   "\"mesh\", \"material\": \"m\", \"file\": \"tet.obj\"}]}";
  SH_CHECK(sh_scene_parse(text, "in-memory", tmpdir, &s, &err) == SH_OK);
  if (s) {
    char want[512];
    path_in_tmp(want, sizeof want, "tet.obj");
    SH_CHECK(strcmp(s->shapes[0].file, want) == 0);
    SH_CHECK(s->shapes[0].mesh.ntris == 4);
  }
  sh_scene_free(s);
  s = NULL;
  SH_CHECK(sh_scene_parse(text, "in-memory", "/nonexistent-dir", &s, &err) ==
           SH_ERR_IO);
  SH_CHECK(strcmp(err.file, "in-memory") == 0);
  SH_CHECK(strstr(err.message, "/nonexistent-dir/tet.obj") != NULL);
  sh_error_clear(&err);
}

/* A minimal scene with one mesh shape whose file is `file`, into text. */
static void mesh_scene(char *text, size_t size, const char *file) {
  snprintf(text, size,
           MINIMAL_HEAD ", \"materials\": {\"m\": {}}, \"shapes\": "
                        "[{\"type\": \"mesh\", \"material\": \"m\", "
                        "\"file\": \"%s\"}]}",
           file);
}

/* Files named relatively must stay in the scene's directory tree, however
 * the name is spelt: "..", "./..", "a/../..", doubled slashes and links
 * that point out are refused with a located error (issue 11). */
static void test_confined_names(void) {
  char sub[300], link[320], target[300];
  path_in_tmp(sub, sizeof sub, "sub");
  SH_CHECK(mkdir(sub, 0700) == 0);
  path_in_tmp(target, sizeof target, "tet.obj");
  snprintf(link, sizeof link, "%s/link.obj", sub);
  SH_CHECK(symlink(target, link) == 0);
  const char *names[] = {"../tet.obj", "./../tet.obj", "x/../../tet.obj",
                         "..//tet.obj", "link.obj"};
  for (int i = 0; i < 5; i++) {
    char text[512];
    mesh_scene(text, sizeof text, names[i]);
    sh_scene *s = NULL;
    sh_error err = SH_ERROR_INIT;
    sh_status st = sh_scene_parse(text, "in-memory", sub, &s, &err);
    /* "x/../../tet.obj" names a directory x that does not exist: it is
     * outside the tree all the same (its ".." taken by name), and said so
     * before the OS would say that x is missing. */
    SH_CHECK(st == SH_ERR_SCENE);
    SH_CHECK(s == NULL);
    SH_CHECK(strstr(err.message, "outside the scene's directory") != NULL);
    SH_CHECK(strcmp(err.path, "shapes[0].file") == 0 && err.line > 0);
    sh_scene_free(s);
    /* From the parent directory the same file is inside the tree (but
     * "sub/x/../../tet.obj" passes through the missing x: the OS refuses
     * it). */
    if (i < 4) {
      char name[64];
      snprintf(name, sizeof name, "sub/%s", names[i]);
      mesh_scene(text, sizeof text, name);
      st = sh_scene_parse(text, "in-memory", tmpdir, &s, &err);
      SH_CHECK(st == (i == 2 ? SH_ERR_IO : SH_OK));
      sh_scene_free(s);
    }
    sh_error_clear(&err);
  }
  /* A name outside the tree is refused as outside whether or not the file
   * exists: a missing "../x.obj" was reported as a missing file, which
   * sent the user looking for it rather than moving it into the tree. A
   * missing file inside the tree is still missing (SH_ERR_IO). */
  const char *missing[] = {"../missing.obj", "../nodir/missing.obj",
                           "x/../../missing.obj", "./..//missing.obj",
                           "missing.obj", "nodir/../missing.obj"};
  for (int i = 0; i < 6; i++) {
    for (int map = 0; map < 2; map++) {
      char text[512];
      if (map)
        snprintf(text, sizeof text,
                 MINIMAL_HEAD ", \"lights\": [{\"type\": \"spot\", "
                 "\"position\": [0, 2, 0], \"direction\": [0, -1, 0], "
                 "\"intensity\": [1, 1, 1], \"outer_angle_deg\": 20, "
                 "\"light_map\": {\"image\": \"%s\"}}]}",
                 missing[i]);
      else
        mesh_scene(text, sizeof text, missing[i]);
      sh_scene *s = NULL;
      sh_error err = SH_ERROR_INIT;
      sh_status st = sh_scene_parse(text, "in-memory", sub, &s, &err);
      SH_CHECK(s == NULL);
      if (i < 4) {
        SH_CHECK(st == SH_ERR_SCENE);
        SH_CHECK(strstr(err.message, "outside the scene's directory") != NULL);
        char want[320];
        path_in_tmp(want, sizeof want, i == 1 ? "nodir/missing.obj" : "missing.obj");
        SH_CHECK(strstr(err.message, want) != NULL); /* where it resolves */
      } else {
        SH_CHECK(st == SH_ERR_IO);
        SH_CHECK(strstr(err.message, "cannot open the") != NULL);
      }
      SH_CHECK(strstr(err.path, map ? "light_map.image" : "shapes[0].file") != NULL);
      sh_scene_free(s);
      sh_error_clear(&err);
    }
  }
  unlink(link);
  rmdir(sub);
  /* An absolute name in a scene file is refused, whatever it names, even
   * a file in the scene's own directory; text passed in may use one. */
  char scene[512], text[1024];
  path_in_tmp(scene, sizeof scene, "absolute.json");
  snprintf(text, sizeof text,
           MINIMAL_HEAD ", \"materials\": {\"m\": {}}, \"shapes\": "
                        "[{\"type\": \"mesh\", \"material\": \"m\", "
                        "\"file\": \"%s\"}]}",
           target);
  FILE *f = fopen(scene, "w");
  if (f) {
    fputs(text, f);
    fclose(f);
  }
  sh_scene *s = NULL;
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(sh_scene_load(scene, &s, &err) == SH_ERR_SCENE && s == NULL);
  SH_CHECK(strstr(err.message, "is absolute") != NULL);
  SH_CHECK(strcmp(err.path, "shapes[0].file") == 0 && err.line > 0);
  SH_CHECK(sh_scene_parse(text, "in-memory", tmpdir, &s, &err) == SH_OK);
  sh_scene_free(s);
  unlink(scene);
  sh_error_clear(&err);
}

/* Light-map and heightfield texels must be finite and non-negative: NaN,
 * infinities and negative values are located errors naming the texel
 * (issue 11, non-finite input). */
static void test_bad_texels(void) {
  const float bad[] = {NAN, INFINITY, -INFINITY, -0.5f};
  for (int i = 0; i < 4; i++) {
    sh_image img;
    sh_error err = SH_ERROR_INIT;
    SH_CHECK(sh_image_alloc(&img, 3, 2, &err) == SH_OK);
    for (int k = 0; k < 18; k++) img.rgb[k] = 0.5f;
    img.rgb[3 * (1 * 3 + 2) + 1] = bad[i]; /* texel (2, 1), channel G */
    char path[512];
    path_in_tmp(path, sizeof path, "badmap.exr");
    SH_CHECK(sh_image_write(path, &img, 0.0, &err) == SH_OK);
    sh_image_free(&img);
    for (int hf = 0; hf < 2; hf++) {
      const char *text =
          hf ? MINIMAL_HEAD ", \"materials\": {\"m\": {}}, \"shapes\": "
               "[{\"type\": \"heightfield\", \"material\": \"m\", "
               "\"image\": \"badmap.exr\", \"min\": [0, 0, 0], "
               "\"max\": [1, 1, 1]}]}"
             : MINIMAL_HEAD ", \"lights\": [{\"type\": \"spot\", "
               "\"position\": [0, 2, 0], \"direction\": [0, -1, 0], "
               "\"intensity\": [1, 1, 1], \"outer_angle_deg\": 20, "
               "\"light_map\": {\"image\": \"badmap.exr\"}}]}";
      sh_scene *s = NULL;
      SH_CHECK(sh_scene_parse(text, "mem.json", tmpdir, &s, &err) ==
               SH_ERR_IMAGE);
      SH_CHECK(s == NULL);
      SH_CHECK(strstr(err.message, "texel (2, 1), channel G") != NULL);
      SH_CHECK(strstr(err.path, "image") != NULL && err.line > 0);
    }
    unlink(path);
    sh_error_clear(&err);
  }
}

/* The locator on its own: escaped keys, multi-byte characters, nesting. */
static void test_locator(void) {
  const char *text = "{\"\\u00e9t\\u00e9\": 1, \"a\\\"b\": {\"x\": [10, [20, "
                     "{\"y\": 30}]]},\n \"\xc3\xa9\": \"z\", \"k\": 2}";
  size_t len = strlen(text), off = 0;
  int line, col;
  sh__jseg p1[] = {{"a\"b", 0}, {"x", 0}, {NULL, 1}, {NULL, 1}, {"y", 0}};
  SH_CHECK(sh__json_locate(text, len, p1, 5, 0, &off));
  SH_CHECK(strncmp(text + off, "30}", 3) == 0);
  SH_CHECK(sh__json_locate(text, len, p1, 5, 1, &off));
  SH_CHECK(strncmp(text + off, "\"y\"", 3) == 0);
  sh__jseg p2[] = {{"\xc3\xa9t\xc3\xa9", 0}};
  SH_CHECK(sh__json_locate(text, len, p2, 1, 0, &off));
  SH_CHECK(strncmp(text + off, "1,", 2) == 0);
  sh__jseg p3[] = {{"k", 0}};
  SH_CHECK(sh__json_locate(text, len, p3, 1, 0, &off));
  sh__json_linecol(text, off, &line, &col);
  SH_CHECK(line == 2 && col == 17); /* the é counts as one column */
  sh__jseg p4[] = {{"missing", 0}};
  SH_CHECK(!sh__json_locate(text, len, p4, 1, 0, &off));
  sh__jseg p5[] = {{"a\"b", 0}, {"x", 0}, {NULL, 5}};
  SH_CHECK(!sh__json_locate(text, len, p5, 3, 0, &off));

  char *buf = sh__json_format_path(p1, 5);
  SH_CHECK(buf && strcmp(buf, "[\"a\"b\"].x[1][1].y") == 0);
  free(buf);
  const char *trunc = "{\"lights\": [{\"type\": \"spot\"}, {\"position\": [1, ";
  buf = sh__json_path_at(trunc, strlen(trunc), strlen(trunc));
  SH_CHECK(buf && strcmp(buf, "lights[1].position[1]") == 0);
  free(buf);
  /* Keys of any length and any depth, escapes decoded (the path was cut
   * at 256 characters, keys at 64 and depth at 32). */
  size_t nkey = 300, ndeep = 50;
  char *deep = malloc(nkey + 16 + 2 * ndeep + 8);
  size_t at = 0;
  deep[at++] = '{';
  deep[at++] = '"';
  for (size_t i = 0; i < nkey; i++) deep[at++] = (char)('a' + i % 26);
  memcpy(deep + at, "\\u00e9\": ", 10);
  at += 10;
  for (size_t i = 0; i < ndeep; i++) deep[at++] = '[';
  deep[at] = '\0';
  buf = sh__json_path_at(deep, at, at);
  SH_CHECK(buf && strlen(buf) == nkey + 6 + 3 * ndeep &&
           !strncmp(buf, "[\"abc", 5) && strstr(buf, "n\xc3\xa9\"][0][0]") &&
           !strcmp(buf + strlen(buf) - 3, "[0]"));
  if (buf) printf("a key path of %zu characters\n", strlen(buf));
  free(buf);
  free(deep);

  SH_CHECK(sh__edit_distance("positon", "position") == 1);
  SH_CHECK(sh__edit_distance("Position", "position") == 0);
  SH_CHECK(sh__edit_distance("", "abc") == 3);
  static const char *const names[] = {"spot", "point", "directional", NULL};
  SH_CHECK(sh__suggest("spto", names) &&
           !strcmp(sh__suggest("spto", names), "spot"));
  SH_CHECK(sh__suggest("area", names) == NULL);
}

static void remove_tmpdir(void) {
  static const char *files[] = {"tet.obj",  "garbage.obj", "empty.png",
                                "text.png", "map.png",     "hf.png",
                                "row.png",  "full.json"};
  char path[512];
  for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
    path_in_tmp(path, sizeof path, files[i]);
    unlink(path);
  }
  for (size_t i = 0; i < sizeof bad_cases / sizeof bad_cases[0]; i++) {
    char name[64];
    snprintf(name, sizeof name, "bad%02d.json", (int)i);
    path_in_tmp(path, sizeof path, name);
    unlink(path);
  }
  rmdir(tmpdir);
}

int main(void) {
  test_atmosphere();
  if (!sh_test_tmpdir(tmpdir, sizeof tmpdir, "sh_parse_test"))
    return EXIT_FAILURE;
  write_fixtures();
  test_full_scene();
  test_defaults();
  test_render_params();
  test_phase_types();
  test_bounds();
  test_bad_cases();
  test_io_errors();
  test_not_regular();
  test_parse_base_dir();
  test_confined_names();
  test_bad_texels();
  test_locator();
  remove_tmpdir();
  SH_TEST_DONE();
}
