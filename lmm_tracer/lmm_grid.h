/* The light mesh's grid: the points origin + h (i, j, k) for 0 <= i < n[0],
 * 0 <= j < n[1], 0 <= k < n[2], covering a scene's bounds with one step of
 * margin on every side. It is plain data, shared by the mesh of cached
 * visibility values (lmm_mesh.h) and the refracted-path deposits
 * (lmm_caustic.h); the method (lmm_method.h) composes the two. */
#ifndef LMM_GRID_H
#define LMM_GRID_H

#include <stdint.h>

#include "sh_error.h"
#include "sh_math.h"
#include "sh_scene.h"

typedef struct lmm_grid {
  sh_vec3 origin; /* the point (0, 0, 0), world space */
  double h;       /* the step, scene units, > 0 */
  int n[3];       /* points along each axis, >= 1 */
} lmm_grid;

/* The grid of step h over the scene's bounds (sh_scene_bounds) widened by
 * h. SH_ERR_ARG if h is not > 0 or an axis would need over 2 million
 * points. */
sh_status lmm_grid_over_scene(const sh_scene *scene, double h, lmm_grid *out,
                              sh_error *err);

/* The grid point (i, j, k) in world space. */
sh_vec3 lmm_grid_point(const lmm_grid *g, int i, int j, int k);

/* The grid cell containing p: the index of its lowest corner (it may lie
 * outside the grid). */
void lmm_grid_cell(const lmm_grid *g, sh_vec3 p, int ijk[3]);

/* 1 if (i, j, k) is a point of the grid. */
int lmm_grid_contains(const lmm_grid *g, int i, int j, int k);

/* The linear index of point (i, j, k), i fastest; the point must be in the
 * grid. */
uint64_t lmm_grid_index(const lmm_grid *g, int i, int j, int k);

/* The number of points. */
int64_t lmm_grid_points(const lmm_grid *g);

/* The corner of the grid opposite the origin: the point n - 1. */
sh_vec3 lmm_grid_far_corner(const lmm_grid *g);

#endif
