#include "lmm_grid.h"

#include <math.h>

sh_status lmm_grid_over_scene(const sh_scene *scene, double h, lmm_grid *out,
                              sh_error *err) {
  if (!(h > 0)) return sh_error_set(err, SH_ERR_ARG, "the mesh step must be > 0");
  sh_vec3 lo, hi;
  sh_scene_bounds(scene, &lo, &hi);
  lmm_grid g;
  g.h = h;
  g.origin = sh_sub(lo, sh_v3s(h));
  for (int a = 0; a < 3; a++) {
    double ext = sh_vget(hi, a) - sh_vget(lo, a) + 2.0 * h;
    double cells = ceil(ext / h) + 1.0;
    if (!(cells <= 2e6))
      return sh_error_set(err, SH_ERR_ARG,
                          "the mesh step %g is too small for a scene %g "
                          "across: over 2 million points along an axis",
                          h, ext);
    g.n[a] = (int)cells;
  }
  *out = g;
  return SH_OK;
}

sh_vec3 lmm_grid_point(const lmm_grid *g, int i, int j, int k) {
  return sh_add(g->origin, sh_v3(i * g->h, j * g->h, k * g->h));
}

void lmm_grid_cell(const lmm_grid *g, sh_vec3 p, int ijk[3]) {
  sh_vec3 q = sh_scale(sh_sub(p, g->origin), 1.0 / g->h);
  ijk[0] = (int)floor(q.x);
  ijk[1] = (int)floor(q.y);
  ijk[2] = (int)floor(q.z);
}

int lmm_grid_contains(const lmm_grid *g, int i, int j, int k) {
  return i >= 0 && j >= 0 && k >= 0 && i < g->n[0] && j < g->n[1] &&
         k < g->n[2];
}

uint64_t lmm_grid_index(const lmm_grid *g, int i, int j, int k) {
  return (uint64_t)i +
         (uint64_t)g->n[0] * ((uint64_t)j + (uint64_t)g->n[1] * (uint64_t)k);
}

int64_t lmm_grid_points(const lmm_grid *g) {
  return (int64_t)g->n[0] * g->n[1] * g->n[2];
}

sh_vec3 lmm_grid_far_corner(const lmm_grid *g) {
  return lmm_grid_point(g, g->n[0] - 1, g->n[1] - 1, g->n[2] - 1);
}
