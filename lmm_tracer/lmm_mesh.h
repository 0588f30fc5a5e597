/* The light mesh of the light meshes method (Debelov et al. 2008): a
 * uniform grid of points of step h over the scene's bounds, each holding the
 * visibility of every light from it. Values are computed on demand, the
 * first time a point is asked for, and cached in a sparse table shared by
 * all threads; the authors saw only 1-10% of the points used.
 *
 * A value is the visibility of light i from point x through the surfaces
 * that cast soft shadows: 0 or 1 in opaque scenes (stored as bits), the
 * product of the crossed `transmit` colours with semitransparent surfaces
 * (stored as RGB floats), and, in the refract-both scheme, formula 6:
 * V(i, x) (no surface at all on the straight segment) plus the refracted
 * paths' transmittance deposited at x (lmm_caustic.h). */
#ifndef LMM_MESH_H
#define LMM_MESH_H

#include <stdint.h>

#include "sh_error.h"
#include "sh_rt.h"
#include "sh_scene.h"

typedef struct lmm_mesh lmm_mesh;
typedef struct lmm_caustics lmm_caustics;

typedef struct lmm_mesh_stats {
  int64_t points_total;    /* grid points over the scene's bounds */
  int64_t points_computed; /* points whose values were computed and cached */
  int64_t points_uncached; /* computed again: table full or a race */
  int bits;                /* 1 if values are stored as bits */
} lmm_mesh_stats;

/* Creates the mesh of step h over the scene's bounds. `capacity_log2`
 * sizes the point table (0: default 2^21 slots). Caller frees with
 * lmm_mesh_free; the scene and rt must outlive the mesh. */
sh_status lmm_mesh_create(const sh_scene *scene, const sh_rt *rt, double h,
                          int capacity_log2, lmm_mesh **out, sh_error *err);
void lmm_mesh_free(lmm_mesh *mesh);

/* Switches to the refract-both scheme: the direct term becomes "no surface
 * at all on the segment", and with `add_paths` the refracted paths of
 * `caustics` are added to it (formula 6); without, the values hold the
 * direct term only (the refined variant reads the paths itself). Call
 * before the first lmm_mesh_values; `caustics` must outlive the mesh. */
void lmm_mesh_set_caustics(lmm_mesh *mesh, const lmm_caustics *caustics,
                           int add_paths);

/* The grid: its first point, and its number of points along each axis. */
void lmm_mesh_grid(const lmm_mesh *mesh, sh_vec3 *origin, int n[3]);

double lmm_mesh_step(const lmm_mesh *mesh);
/* The grid point (i, j, k) in world space. */
sh_vec3 lmm_mesh_point(const lmm_mesh *mesh, int i, int j, int k);
/* The grid cell containing p: the index of its lowest corner (may lie
 * outside the grid). */
void lmm_mesh_cell(const lmm_mesh *mesh, sh_vec3 p, int ijk[3]);
/* 1 if (i, j, k) is a point of the grid. */
int lmm_mesh_contains(const lmm_mesh *mesh, int i, int j, int k);

/* Writes the visibility of every light from point (i, j, k), which must be
 * in the grid, into vis[0 .. nlights-1], computing it on first use. Safe
 * from several threads. */
void lmm_mesh_values(lmm_mesh *mesh, int i, int j, int k, sh_vec3 *vis,
                     sh_rt_counters *c);

/* In opaque scenes (bit storage): writes the light mask of point (i, j, k)
 * into words[0 .. (nlights + 63) / 64 - 1], bit l set if light l is
 * visible, computing it on first use. Returns 0 (and writes nothing) if the
 * mesh stores floats. */
int lmm_mesh_bits(lmm_mesh *mesh, int i, int j, int k, uint64_t *words,
                  sh_rt_counters *c);

void lmm_mesh_get_stats(const lmm_mesh *mesh, lmm_mesh_stats *stats);

#endif
