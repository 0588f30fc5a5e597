/* Ray queries against the scene's surfaces through Embree.
 *
 * Spheres and cylinders keep their exact form (Embree user geometry, in
 * object space under their transform); every other shape is triangles. One
 * Embree device with one error callback; three Embree scenes: all surfaces
 * (closest hits), the opaque ones (occlusion), the semitransparent ones
 * (transmittance of shadow rays). All calls on a built sh_rt are safe from
 * several threads. */
#ifndef SH_RT_H
#define SH_RT_H

#include <stdint.h>

#include "sh_error.h"
#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sh_rt sh_rt;

/* Per-thread ray counts, for statistics. */
typedef struct sh_rt_counters {
  uint64_t closest, occlusion;
} sh_rt_counters;

typedef struct sh_hit {
  double t;
  sh_vec3 p;  /* the hit point, rebuilt from the surface's own parameters */
  sh_vec3 ng; /* unit geometric normal, outwards for closed shapes */
  int shape;  /* index into the scene's shapes */
} sh_hit;

/* Builds the ray-query structures for `scene`, which must outlive them.
 * On success *out is new (caller frees with sh_rt_free). */
sh_status sh_rt_create(const sh_scene *scene, sh_rt **out, sh_error *err);
void sh_rt_free(sh_rt *rt);

/* The closest surface on o + t d (d unit) with t in (tmin, tmax). */
int sh_rt_intersect(const sh_rt *rt, sh_vec3 o, sh_vec3 d, double tmin,
                    double tmax, sh_hit *hit, sh_rt_counters *c);

/* The visibility of the segment o + t d, t in (0, tmax): 0 if an opaque
 * surface lies on it, else the product of the transmit colours of the
 * semitransparent surfaces it crosses (each crossing counted once, however
 * many coincident primitives report it). */
sh_vec3 sh_rt_visibility(const sh_rt *rt, sh_vec3 o, sh_vec3 d, double tmax,
                         sh_rt_counters *c);

/* A ray origin for leaving surface point p along a direction on the side of
 * the unit normal n (pass -n for the other side): p moved off the surface
 * by a few float ulps, so that the new ray cannot hit the surface it
 * leaves (Waechter and Binder, Ray Tracing Gems, ch. 6). */
sh_vec3 sh_rt_offset(sh_vec3 p, sh_vec3 n);

#ifdef __cplusplus
}
#endif
#endif
