/* Estimators of single scattering along a ray segment inside the medium:
 * the light each light scatters towards the ray's origin,
 *   integral over [t0, t1] of sigma_s p(alpha) V(t) E_light(t) Tr(t0, t) dt,
 * with V the visibility through the scene's surfaces and E_light including
 * the light's own transmittance through the medium. */
#ifndef SH_INSCATTER_H
#define SH_INSCATTER_H

#include "sh_rng.h"
#include "sh_rt.h"
#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Estimates one light's in-scattered radiance along o + t d (d unit) for t
 * in [t0, t1], a span inside the medium's bounds, with n stratified
 * samples. `rt` may be NULL for an unoccluded scene; `hook`, if given with
 * a volume function, provides the visibility instead (worker `thread`).
 * *samples, if given, is increased by the samples taken. */
sh_vec3 sh_inscatter_light(const sh_scene *scene, const sh_rt *rt,
                           const sh_shadow_hook *hook, int thread,
                           const sh_light *light, sh_vec3 o, sh_vec3 d,
                           double t0, double t1, int n, sh_rng *rng,
                           sh_rt_counters *c, uint64_t *samples);

/* The sub-span of [t0, t1] inside a spot light's cone (its front nappe,
 * which is convex). Returns 0 if the ray misses the cone there. For point
 * and directional lights it returns [t0, t1]. */
int sh_light_clip(const sh_light *light, sh_vec3 o, sh_vec3 d, double t0,
                  double t1, double *a, double *b);

#ifdef __cplusplus
}
#endif
#endif
