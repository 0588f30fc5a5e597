/* Tests of sh_obj_check.h through sh_mesh_load: a face of more corners
 * than SH_OBJ_MAX_CORNERS, whose triangulation in assimp takes time
 * growing as the square of its corners (fuzz/known/obj_polygon: 20001
 * corners, 5 s in the fuzzing build), is refused at once at its line,
 * also when it continues over lines or the file is not named *.obj;
 * faces up to the limit still load. */
#include "sh_mesh_test_util.h"

#include "sh_obj_check.h"

/* "v ...\n" for a triangle, then a face of n corners cycling over it,
 * with a line break continued by a backslash after every `wrap` corners
 * (0: none). */
static char *polygon(int n, int wrap) {
  size_t cap = 64 + 5 * (size_t)n;
  char *text = malloc(cap);
  if (!text) return NULL;
  size_t at = (size_t)snprintf(text, cap, "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf");
  for (int i = 0; i < n; i++) {
    at += (size_t)snprintf(text + at, cap - at, " %d", 1 + i % 3);
    if (wrap && i % wrap == wrap - 1) at += (size_t)snprintf(text + at, cap - at, " \\\n");
  }
  snprintf(text + at, cap - at, "\n");
  return text;
}

int main(void) {
  if (!sh_test_tmpdir(sh_mesh_test_dir, sizeof sh_mesh_test_dir, "sh_obj_check_test"))
    return EXIT_FAILURE;
  unsigned char buf[65536];
  size_t n = read_known("obj_polygon", buf, sizeof buf);
  SH_CHECK(n > 1);
  if (n > 1) expect_error_at("obj_polygon.obj", buf + 1, n - 1, 4, "a face of 20001 corners");

  char *text = polygon(SH_OBJ_MAX_CORNERS + 1, 0);
  SH_CHECK(text != NULL);
  if (text) expect_text_at("long.obj", text, 5, "a face of 4097 corners, more than the 4096");
  free(text);
  text = polygon(SH_OBJ_MAX_CORNERS + 1, 1000);
  if (text) expect_text_at("continued.obj", text, 5, "a face of 4097 corners");
  if (text) expect_text_at("long.mesh_data", text, 5, "a face of 4097 corners");
  free(text);
  /* At the limit: the triangle's corners cycle, so the polygon is
   * degenerate, but assimp takes it (the time is what is bounded). */
  text = polygon(SH_OBJ_MAX_CORNERS, 0);
  if (text) {
    sh_mesh m;
    sh_error err;
    sh_status s = sh_mesh_load(write_text("limit.obj", text), NULL, &m, &err);
    if (s != SH_OK) fprintf(stderr, "limit.obj: %s\n", err.message);
    SH_CHECK(s == SH_OK);
    sh_mesh_free(&m);
  }
  free(text);
  expect_tris("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 \\\n 3 4\n", 2, 4);
  SH_TEST_DONE();
}
