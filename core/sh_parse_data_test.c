/* Tests of meshes from memory (sh_scene_parse_ex, shafts.h): a scene whose
 * mesh comes from arrays equals the same scene reading the mesh from an
 * OBJ file (the shape's triangles and the reference renderer's image, bit
 * for bit), and every bad mesh reference is refused with its location. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_parse.h"
#include "sh_reference.h"
#include "sh_test.h"
#include "shafts.h"

/* A scene with one mesh shape; MESH is the mesh member(s). */
#define SCENE(MESH)                                                         \
  "{\"format\": \"shafts-scene\", \"version\": 1,\n"                        \
  " \"camera\": {\"position\": [0, 2, 6], \"look_at\": [0, 0.5, 0],\n"      \
  "            \"fov_y_deg\": 40, \"width\": 24, \"height\": 16},\n"         \
  " \"medium\": {\"sigma_s\": [0.1, 0.1, 0.1],\n"                           \
  "            \"bounds\": {\"min\": [-4, -1, -4], \"max\": [4, 4, 4]}},\n"  \
  " \"lights\": [{\"type\": \"point\", \"position\": [1, 4, 1],\n"          \
  "              \"intensity\": [20, 20, 20]}],\n"                          \
  " \"materials\": {\"white\": {\"diffuse\": [0.8, 0.8, 0.8]}},\n"          \
  " \"shapes\": [{\"type\": \"mesh\", \"material\": \"white\",\n"           \
  "              \"transform\": {\"rotate_deg\": [0, 30, 0]},\n"            \
  "              " MESH "}]}\n"

static const char *source_dir(void) {
  const char *s = getenv("SHAFTS_SOURCE_DIR");
  return s ? s : "..";
}

static void render(const sh_scene *s, sh_image *img) {
  sh_reference_options opt = sh_reference_defaults(s);
  opt.spp = 2;
  opt.threads = 2;
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(sh_render_reference(s, &opt, img, NULL, &err) == SH_OK);
  sh_error_clear(&err);
}

/* The teapot from its OBJ file and from the same arrays in memory. */
static void test_equals_file(void) {
  char dir[600], obj[700];
  snprintf(dir, sizeof dir, "%s/scenes/assets", source_dir());
  snprintf(obj, sizeof obj, "%s/teapot.obj", dir);
  sh_mesh m = {0};
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(sh_mesh_load(obj, NULL, &m, &err) == SH_OK);
  if (!m.ntris) return;
  int *idx = malloc(sizeof *idx * 3 * (size_t)m.ntris);
  for (int i = 0; i < 3 * m.ntris; i++) idx[i] = (int)m.indices[i];
  sh_mesh_data md = {"teapot", m.positions, m.nverts, idx, m.ntris};
  sh_mesh_data other = {"other", m.positions, 3, idx, 1};
  sh_mesh_data both[2] = {other, md};
  sh_scene *a = NULL, *b = NULL;
  SH_CHECK(sh_scene_parse(SCENE("\"file\": \"teapot.obj\""), "a.json", dir, &a,
                          &err) == SH_OK);
  SH_CHECK(sh_scene_parse_ex(SCENE("\"data\": \"teapot\""), "b.json", NULL,
                             both, 2, &b, &err) == SH_OK);
  free(idx);
  sh_mesh_free(&m);
  if (!a || !b) {
    fprintf(stderr, "%s\n", err.message);
    sh_scene_free(a);
    sh_scene_free(b);
    return;
  }
  const sh_shape *sa = &a->shapes[0], *sb = &b->shapes[0];
  SH_CHECK(sb->file == NULL && sb->data && strcmp(sb->data, "teapot") == 0);
  SH_CHECK(sa->mesh.nverts == sb->mesh.nverts);
  SH_CHECK(sa->mesh.ntris == sb->mesh.ntris);
  SH_CHECK(memcmp(sa->mesh.positions, sb->mesh.positions,
                  sizeof(float) * 3 * (size_t)sa->mesh.nverts) == 0);
  SH_CHECK(memcmp(sa->mesh.indices, sb->mesh.indices,
                  sizeof(unsigned) * 3 * (size_t)sa->mesh.ntris) == 0);
  SH_CHECK(memcmp(&sa->xform, &sb->xform, sizeof sa->xform) == 0);
  sh_image ia = {0}, ib = {0};
  render(a, &ia);
  render(b, &ib);
  SH_CHECK(ia.rgb && ib.rgb &&
           memcmp(ia.rgb, ib.rgb, sizeof(float) * 3 * 24 * 16) == 0);
  sh_image_free(&ia);
  sh_image_free(&ib);
  sh_scene_free(a);
  sh_scene_free(b);
  sh_error_clear(&err);
}

typedef struct bad_case {
  const char *mesh; /* the shape's mesh member(s) */
  int which;        /* the mesh array to pass: see test_bad */
  sh_status status;
  int column;       /* on line 11 of SCENE */
  const char *path, *message;
} bad_case;

static void test_bad(void) {
  static const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  static const float nan_pos[] = {0, 0, 0, 1, 0, 0, 0, 1.0f / 0.0f, 0};
  static const int tri[] = {0, 1, 2}, far[] = {0, 1, 3}, neg[] = {0, -1, 2};
  const sh_mesh_data sets[][2] = {
      {{"tri", pos, 3, tri, 1}, {"quad", pos, 3, tri, 1}},
      {{"tri", nan_pos, 3, tri, 1}, {"x", pos, 3, tri, 1}},
      {{"tri", pos, 3, far, 1}, {"x", pos, 3, tri, 1}},
      {{"tri", pos, 3, neg, 1}, {"x", pos, 3, tri, 1}},
      {{"tri", pos, 3, tri, 0}, {"x", pos, 3, tri, 1}},
      {{"tri", pos, 3, tri, 1}, {"tri", pos, 3, tri, 1}},
  };
  static const bad_case cases[] = {
      {"\"data\": \"trx\"", 0, SH_ERR_SCENE, 23, "shapes[0].data",
       "unknown mesh 'trx'; did you mean 'tri'? the meshes in memory are: "
       "tri, quad"},
      {"\"data\": \"tri\", \"file\": \"a.obj\"", 0, SH_ERR_SCENE, 15,
       "shapes[0].data", "either file or data, not both"},
      {"\"data\": 3", 0, SH_ERR_SCENE, 23, "shapes[0].data",
       "expected a string"},
      {"\"data\": \"tri\"", 1, SH_ERR_SCENE, 23, "shapes[0].data",
       "non-finite position: coordinate 1 of vertex 2"},
      {"\"data\": \"tri\"", 2, SH_ERR_SCENE, 23, "shapes[0].data",
       "triangle 0 refers to vertex 3, and there are 3 vertices"},
      {"\"data\": \"tri\"", 3, SH_ERR_SCENE, 23, "shapes[0].data",
       "triangle 0 refers to vertex -1"},
      {"\"data\": \"tri\"", 4, SH_ERR_SCENE, 23, "shapes[0].data",
       "has no triangles"},
      {"\"data\": \"tri\"", 5, SH_ERR_ARG, 0, "", "two meshes are named 'tri'"},
      {"\"data\": \"tri\"", -1, SH_ERR_SCENE, 23, "shapes[0].data",
       "no meshes were passed in memory"},
  };
  char text[2048];
  const char *fmt = SCENE("%s");
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    const bad_case *k = &cases[i];
    snprintf(text, sizeof text, fmt, k->mesh);
    sh_scene *s = (sh_scene *)1;
    sh_error err = SH_ERROR_INIT;
    sh_status st = sh_scene_parse_ex(text, "bad.json", NULL,
                                     k->which < 0 ? NULL : sets[k->which],
                                     k->which < 0 ? 0 : 2, &s, &err);
    char what[40];
    snprintf(what, sizeof what, "case %zu", i);
    SH_CHECK(s == NULL &&
             sh_test_error_is(what, st, &err, k->status, k->column ? 11 : 0,
                              k->column, k->path, k->message));
    sh_error_clear(&err);
  }
}

int main(void) {
  SH_CHECK(strcmp(sh_version(), "") != 0 && strchr(sh_version(), '.'));
  test_equals_file();
  test_bad();
  SH_TEST_DONE();
}
