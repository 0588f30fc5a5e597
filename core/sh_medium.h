/* The homogeneous medium: normalised phase functions, the segment of a ray
 * inside the medium's bounds, and transmittance. */
#ifndef SH_MEDIUM_H
#define SH_MEDIUM_H

#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The phase function at cos(alpha), normalised so that its integral over
 * the sphere is 1. alpha is the angle between the direction the light
 * travels and the direction towards the eye (cos alpha = 1: forward). */
double sh_phase_eval(const sh_phase *phase, double cos_alpha);

/* Clips the ray o + t d, t in [tmin, tmax], to the box [bmin, bmax].
 * Returns 1 and the clipped interval in *t0, *t1 if it is not empty. */
int sh_box_clip(sh_vec3 bmin, sh_vec3 bmax, sh_vec3 o, sh_vec3 d, double tmin,
                double tmax, double *t0, double *t1);

/* The length of the segment [a, b] inside the medium's bounds; 0 without a
 * medium. */
double sh_medium_length(const sh_medium *m, sh_vec3 a, sh_vec3 b);

/* The length of the ray from p in the unit direction d inside the medium's
 * bounds (up to infinity); 0 without a medium. */
double sh_medium_length_ray(const sh_medium *m, sh_vec3 p, sh_vec3 d);

/* exp(-sigma_t * len) per channel; 1 without a medium. */
sh_vec3 sh_medium_tr(const sh_medium *m, double len);

/* The nearest a ray is taken to pass to a point or spot light when the
 * light it scatters is integrated: 1e-4 of the diagonal of the medium's
 * box (0 without a medium). The in-scattered radiance of a ray through a
 * point light is unbounded (the integral of 1/r^2 diverges there: the
 * camera at a light inside the medium saw 9.3e7 in lmm_tracer and 830 in
 * gl_shafts); every renderer here integrates 1/r^2 with r^2 = (t - b)^2 +
 * max(h, this)^2, h the light's distance from the ray and b the foot of
 * that distance on it, so a ray through the light, or the camera at it,
 * gets I sigma_s p atan((t - b) / this) / this from the light's
 * neighbourhood, the same in every renderer. Rays that pass farther are
 * unchanged. */
double sh_medium_light_min_distance(const sh_medium *m);

/* The index of a point or spot light inside the medium's box (sigma_s
 * above 0) within sh_medium_light_min_distance of the camera, whose image
 * is then made by that convention alone (the tools warn); -1 if none. */
int sh_scene_camera_at_light(const sh_scene *scene);

#ifdef __cplusplus
}
#endif
#endif
