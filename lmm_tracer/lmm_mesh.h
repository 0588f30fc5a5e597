/* The light mesh of the light meshes method (Debelov et al. 2008): a
 * uniform grid of points of step h over the scene's bounds, each holding the
 * visibility of every light from it. Values are computed on demand, the
 * first time a point is asked for, and cached in a sparse table shared by
 * all threads; the authors saw only 1-10% of the points used.
 *
 * A value is the visibility of light i from point x through the surfaces
 * that cast soft shadows: 0 or 1 in opaque scenes (stored as bits), the
 * product of the crossed `transmit` colours with semitransparent surfaces
 * (stored as RGB floats), and, in the refract-both scheme, formula 6's
 * direct term V(i, x): 1 if no surface at all is on the straight segment.
 * The refracted paths' part of formula 6 (lmm_caustic.h) is added by the
 * method (lmm_method.c), which composes the two on the same grid. */
#ifndef LMM_MESH_H
#define LMM_MESH_H

#include <stdint.h>

#include "lmm_grid.h"
#include "sh_error.h"
#include "sh_rt.h"
#include "sh_scene.h"

typedef struct lmm_mesh lmm_mesh;

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

/* Switches to the refract-both scheme's direct term: a point sees a light
 * only if no surface at all is on the segment (formula 6). Call before the
 * first lmm_mesh_values. */
void lmm_mesh_set_direct_only(lmm_mesh *mesh);

/* The mesh's grid, valid while the mesh is. */
const lmm_grid *lmm_mesh_grid(const lmm_mesh *mesh);

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
