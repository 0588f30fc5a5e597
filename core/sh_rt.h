/* Ray queries against the scene's surfaces through Embree.
 *
 * Spheres and cylinders keep their exact form (Embree user geometry, in
 * object space under their transform); every other shape is triangles. One
 * Embree device with one error callback and one Embree scene, in which
 * every shape carries its class (below) as geometry mask, so that a query
 * can look at some classes only. All calls on a built sh_rt are safe from
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

/* Shape classes: opaque or semitransparent (a non-black transmit), and
 * whether the material casts soft shadows in the light meshes method. */
enum {
  SH_RT_OPAQUE_SOFT = 1u,
  SH_RT_OPAQUE_HARD = 2u,
  SH_RT_SEMI_SOFT = 4u,
  SH_RT_SEMI_HARD = 8u,
  SH_RT_OPAQUE = SH_RT_OPAQUE_SOFT | SH_RT_OPAQUE_HARD,
  SH_RT_SEMI = SH_RT_SEMI_SOFT | SH_RT_SEMI_HARD,
  SH_RT_SOFT = SH_RT_OPAQUE_SOFT | SH_RT_SEMI_SOFT,
  SH_RT_HARD = SH_RT_OPAQUE_HARD | SH_RT_SEMI_HARD,
  SH_RT_ALL = 15u
};

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

/* A replacement for the hard-shadow visibility of lights, for methods that
 * compute it otherwise (the light meshes method, area-light sampling).
 * Either function may be NULL, and either may return 0 to fall back to
 * shadow rays for that point. `thread` is the worker's index, in
 * [0, threads). */
typedef struct sh_shadow_hook {
  /* Fills vis[0 .. nlights-1] with the visibility of every light from the
   * surface point p with unit normal n (facing the viewer) on shape
   * `shape`. The tracer still skips lights behind the surface. */
  int (*surface)(void *user, int thread, sh_vec3 p, sh_vec3 n, int shape,
                 sh_vec3 *vis, sh_rt_counters *c);
  /* The visibility of light `light` from point x in the medium. */
  int (*volume)(void *user, int thread, sh_vec3 x, int light, sh_vec3 *vis,
                sh_rt_counters *c);
  void *user;
} sh_shadow_hook;

/* As sh_rt_visibility, counting only the surfaces of the given classes. */
sh_vec3 sh_rt_visibility_of(const sh_rt *rt, sh_vec3 o, sh_vec3 d, double tmax,
                            unsigned classes, sh_rt_counters *c);

/* 1 if any surface of the given classes lies on o + t d, t in (0, tmax). */
int sh_rt_occluded(const sh_rt *rt, sh_vec3 o, sh_vec3 d, double tmax,
                   unsigned classes, sh_rt_counters *c);

/* Closest hits of n rays at once through Embree's stream interface
 * (rtcIntersect1M), faster for coherent rays such as a row of camera rays.
 * Writes each ray's hit distance (INFINITY for a miss) to t[i] and its
 * shape (-1 for a miss) to shape[i]. */
void sh_rt_intersect_stream(const sh_rt *rt, int n, const sh_vec3 *o,
                            const sh_vec3 *d, double *t, int *shape,
                            int coherent, sh_rt_counters *c);

/* Occlusion of n segments at once (rtcOccluded1M) against the surfaces of
 * the given classes: occluded[i] = 1 if something lies on segment i. */
void sh_rt_occluded_stream(const sh_rt *rt, int n, const sh_vec3 *o,
                           const sh_vec3 *d, const double *tmax,
                           unsigned classes, int coherent, unsigned char *occluded,
                           sh_rt_counters *c);

/* The union of the classes of the scene's shapes. */
unsigned sh_rt_classes(const sh_rt *rt);

/* A ray origin for leaving surface point p along a direction on the side of
 * the unit normal n (pass -n for the other side): p moved off the surface
 * by a few float ulps of the frame Embree sees (centred on the shapes and
 * scaled to their size, so the offset is the same fraction of the scene
 * wherever it sits and however large it is), so that the new ray cannot
 * hit the surface it leaves (Waechter and Binder, Ray Tracing Gems,
 * ch. 6). */
sh_vec3 sh_rt_offset(const sh_rt *rt, sh_vec3 p, sh_vec3 n);

/* The end of the ray o + t d's free part before `hit` (found by
 * sh_rt_intersect on that ray): the largest t whose point lies on the
 * ray's side of the hit surface by at least sh_rt_offset's distance. The
 * hit's own t comes from Embree's single-precision distance and may lie
 * beyond the surface, so that a point sampled at it (a medium's in-scatter
 * at the segment's end) is on the far side, inside a closed shape, and its
 * shadow ray reaches a light the surface should hide. The distance is
 * measured along the normal to the hit point's tangent plane, so a
 * grazing ray loses at most a sliver that close to the surface. Never
 * below 0. */
double sh_rt_free_end(const sh_rt *rt, sh_vec3 o, sh_vec3 d, const sh_hit *hit);

#ifdef __cplusplus
}
#endif
#endif
