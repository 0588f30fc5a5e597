/* The grid: it covers the scene's bounds with a step of margin, and a
 * point's cell, index and position agree with each other. */
#include "lmm_grid.h"

#include "sh_parse.h"
#include "sh_test.h"

static const char *scene_text =
    "{\"format\": \"shafts-scene\", \"version\": 1,"
    " \"camera\": {\"position\": [0, 1, 5], \"look_at\": [0, 1, 0],"
    "  \"fov_y_deg\": 40, \"width\": 8, \"height\": 6},"
    " \"lights\": [{\"type\": \"point\", \"position\": [0, 4, 0],"
    "  \"intensity\": [1, 1, 1]}],"
    " \"materials\": {\"m\": {\"diffuse\": [0.5, 0.5, 0.5]}},"
    " \"shapes\": [{\"type\": \"box\", \"min\": [-1, 0, -2], \"max\": [3, 1, 2],"
    "  \"material\": \"m\"}]}";

int main(void) {
  sh_scene *s = NULL;
  sh_error err = SH_ERROR_INIT;
  if (sh_scene_parse(scene_text, "grid.json", ".", &s, &err) != SH_OK) {
    fprintf(stderr, "%s\n", err.message);
    SH_CHECK(!"scene parses");
    SH_TEST_DONE();
  }
  lmm_grid g;
  SH_CHECK(lmm_grid_over_scene(s, 0.25, &g, NULL) == SH_OK);
  sh_vec3 lo, hi;
  sh_scene_bounds(s, &lo, &hi);
  sh_vec3 far = lmm_grid_far_corner(&g);
  for (int a = 0; a < 3; a++) {
    SH_CHECK(sh_vget(g.origin, a) <= sh_vget(lo, a) - 0.25 + 1e-12);
    SH_CHECK(sh_vget(far, a) >= sh_vget(hi, a) + 0.25 - 1e-12);
  }
  SH_CHECK(lmm_grid_points(&g) == (int64_t)g.n[0] * g.n[1] * g.n[2]);
  /* A point lies in its own cell, and the indices are one to one. */
  int ijk[3];
  sh_vec3 p = lmm_grid_point(&g, 3, 5, 7);
  lmm_grid_cell(&g, sh_add(p, sh_v3s(0.1)), ijk);
  SH_CHECK(ijk[0] == 3 && ijk[1] == 5 && ijk[2] == 7);
  SH_CHECK(lmm_grid_index(&g, 3, 5, 7) ==
           3 + (uint64_t)g.n[0] * (5 + (uint64_t)g.n[1] * 7));
  SH_CHECK(lmm_grid_contains(&g, 0, 0, 0));
  SH_CHECK(!lmm_grid_contains(&g, -1, 0, 0));
  SH_CHECK(!lmm_grid_contains(&g, g.n[0], 0, 0));
  /* Bad steps are refused with a message. */
  SH_CHECK(lmm_grid_over_scene(s, 0.0, &g, &err) == SH_ERR_ARG);
  SH_CHECK(lmm_grid_over_scene(s, 1e-9, &g, &err) == SH_ERR_ARG);
  sh_scene_free(s);
  sh_error_clear(&err);
  SH_TEST_DONE();
}
