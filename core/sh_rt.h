/* Ray queries against the scene's surfaces through Embree.
 *
 * Spheres, cylinders and quads keep their exact form (Embree user
 * geometry, intersected in double precision in object space under their
 * transform: a ground quad as large as a planet is then exact near an eye
 * a metre above it); every other shape is triangles. One
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
  /* A bound on how far from the surface a point near p may lie and still
   * be put on the wrong side of it by Embree's single-precision tests (a
   * shadow ray from it missing the surface or hitting it at once), beyond
   * the rounding of the point itself into Embree's frame (which
   * sh_rt_offset_by and sh_rt_free_end add): for a triangle the rounding
   * of its float vertices relative to a ray origin at the point (8
   * FLT_EPSILON of their distance), for an analytic shape a few double
   * ulps of its size. World length. t, p and ng are double precision
   * (sh_rt.c). */
  double err;
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
   * surface point hit->p with unit normal n (facing the viewer) on shape
   * hit->shape; shadow rays leave from sh_rt_offset_hit(rt, hit, n), as
   * the tracer's own do. The tracer still skips lights behind the
   * surface. */
  int (*surface)(void *user, int thread, const sh_hit *hit, sh_vec3 n,
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
 * shape (-1 for a miss) to shape[i]. The distance is Embree's, in single
 * precision in its frame, not refined as sh_rt_intersect's is: for
 * counting and timing rays (lmm_bench), not for placing points. */
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
 * the unit normal n (pass -n for the other side): p moved along n by err
 * (a bound on the float error of the surface about p, world length) and
 * by the rounding of the point itself into the frame Embree sees, so that
 * the new ray cannot hit the surface it leaves nor start behind it. The
 * frame is centred where the camera looks from (sh_rt.c), so that the
 * distance is a few float ulps of the distance from there, not of the
 * scene's size: micrometres for a point a metre from an eye on a
 * planet. */
sh_vec3 sh_rt_offset_by(const sh_rt *rt, sh_vec3 p, sh_vec3 n, double err);

/* sh_rt_offset_by with the hit's own bound (sh_hit.err). */
sh_vec3 sh_rt_offset_hit(const sh_rt *rt, const sh_hit *hit, sh_vec3 n);

/* sh_rt_offset_by for a point on an unknown primitive: the bound for the
 * scene's largest triangle (a scene holding a triangle as large as a
 * planet gets offsets of float ulps of that size; pass the hit where it
 * is known). */
sh_vec3 sh_rt_offset(const sh_rt *rt, sh_vec3 p, sh_vec3 n);

/* The end of the ray o + t d's free part before `hit` (found by
 * sh_rt_intersect on that ray): the largest t whose point lies on the
 * ray's side of the hit surface by at least hit->err (and its own
 * rounding), so that a point sampled there (a medium's in-scatter at the
 * segment's end) is on the near side for Embree too and its shadow ray
 * meets the surface. A float hit distance may lie beyond the surface, and
 * a sample there, inside a closed shape, saw a light the surface hides
 * (fd6a843). hit->t is exact in double precision and hit->err a few float
 * ulps of the distance from the frame's origin (the camera), so near the
 * eye the free end is the surface's distance less FLT_EPSILON of the
 * largest coordinate's distance from the frame's origin, over |cos|, for
 * an analytic surface, and for a triangle 8 FLT_EPSILON of the triangle's
 * extent about the point over |cos| more. Never below 0. */
double sh_rt_free_end(const sh_rt *rt, sh_vec3 o, sh_vec3 d, const sh_hit *hit);

#ifdef __cplusplus
}
#endif
#endif
