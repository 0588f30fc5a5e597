/* Refracted light paths for the refract-both scheme of the light meshes
 * method: formula 6's sum over paths through semitransparent surfaces.
 *
 * Rays leave every light towards every semitransparent shape, refract at
 * every semitransparent surface they cross (Snell's law with the material's
 * ior; total internal reflection reflects), carry the product of the
 * `transmit` colours, and stop at opaque surfaces. Once a ray has refracted,
 * each mesh point it passes within a distance rho (the mesh step) of is
 * credited with its transmittance divided by the number of rays the light
 * would send through a disc of radius rho there without the lens. A mesh
 * point's value is then the ratio of refracted irradiance to the light's
 * unobstructed irradiance: a light-collecting lens gives values above 1 at
 * its focus. */
#ifndef LMM_CAUSTIC_H
#define LMM_CAUSTIC_H

#include <stdint.h>

#include "lmm_grid.h"
#include "sh_error.h"
#include "sh_rt.h"
#include "sh_scene.h"

typedef struct lmm_caustics lmm_caustics;

/* How a caller follows and stops the pass (every field optional). When
 * *cancel becomes non-zero the pass stops within a few thousand rays:
 * SH_ERR_CANCELLED, nothing allocated. progress(progress_user, done,
 * total) reports the rays traced every few thousand, from the calling
 * thread. */
typedef struct lmm_caustics_control {
  volatile int *cancel;
  void (*progress)(void *user, long done, long total);
  void *progress_user;
} lmm_caustics_control;

/* Traces `rays` rays per light and semitransparent shape and credits the
 * points of `grid` (copied). Caller frees with lmm_caustics_free. `ctl`
 * may be NULL. */
sh_status lmm_caustics_build(const sh_scene *scene, const sh_rt *rt,
                             const lmm_grid *grid, int64_t rays,
                             const lmm_caustics_control *ctl,
                             lmm_caustics **out, sh_error *err);
void lmm_caustics_free(lmm_caustics *c);

/* The refracted visibility of light `light` at grid point (i, j, k). */
sh_vec3 lmm_caustics_at(const lmm_caustics *c, int i, int j, int k, int light);

/* As lmm_caustics_at, and writes to *pj (if not NULL and the point was
 * credited) the weighted mean of the paths' last surface points P_j: where
 * the refracted light last left a surface before reaching the point. The
 * refined variant of section 5 keeps one such point per mesh point and
 * light (the paths through a mesh point from one lens leave it close
 * together), instead of every path's. */
sh_vec3 lmm_caustics_paths(const lmm_caustics *c, int i, int j, int k,
                           int light, sh_vec3 *pj);

/* The number of grid points credited, for statistics. */
int64_t lmm_caustics_points(const lmm_caustics *c);

#endif
