/* The participating medium: normalised phase functions, the region the
 * medium fills, and what depends on its kind (homogeneous, height fog or
 * atmosphere): optical depth, transmittance, the coefficients and the
 * phase at a point, a majorant, distance sampling and, for an atmosphere,
 * the ground. */
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

/* The medium as an interface (after pbrt-v4's and Mitsuba 3's media): what
 * depends on the medium's kind (sh_medium_type) is answered here, and no
 * renderer computes "length times sigma_t" itself.
 *
 * Kinds and formulas (docs/scene-format.md, "Non-uniform media"):
 * - homogeneous: sigma_s, sigma_a, sigma_t the same everywhere in the box;
 *   optical depth sigma_t * length.
 * - height fog: every coefficient at p is its value at base_height times
 *   rho(p) = exp(-(p.y - base_height) / H). Along p + t d, t in [t0, t1],
 *   the integral of rho is rho(y_low) |d| (t1 - t0) g(|d.y| (t1 - t0) / H),
 *   y_low the lower end's height and g(x) = (1 - exp(-x)) / x = -expm1(-x)
 *   / x (g(0) = 1): the contract's sigma_t H / d.y (exp(..t0) - exp(..t1))
 *   rewritten without the cancellation of a nearly horizontal ray and
 *   without overflow far below the base. Optical depth is sigma_t times it.
 * - atmosphere (sh_atmosphere.h): Rayleigh, Mie and ozone densities of the
 *   height above a sphere; the region is the ball of top_radius, and the
 *   ground sphere an opaque surface (sh_medium_ground_hit, _blocks).
 *   Optical depth by Gauss-Legendre panels adapted to the scale heights,
 *   relative error below SH_ATMOSPHERE_DEPTH_REL_ERROR (measured against a
 *   fine quadrature); INFINITY for a span through the planet. The phase
 *   differs per channel (the mixture weighted by each part's sigma_s):
 *   use sh_medium_scattering_at or sh_medium_phase_rgb_at.
 *
 * "Span" functions take o + t d with d a unit vector and [t0, t1] already
 * inside the region (sh_medium_clip); "segment" and "ray" functions clip
 * themselves. Optical depths are per RGB channel, >= 0; all functions
 * return 0 optical depth (transmittance 1, coefficients 0) without a
 * medium. Nothing here allocates or fails. */

/* The region the medium fills (a box; an atmosphere's ball): clips o + t d, t in [tmin, tmax],
 * to it. Returns 1 and the interval in *t0 < *t1 if it is not empty; 0
 * without a medium. */
int sh_medium_clip(const sh_medium *m, sh_vec3 o, sh_vec3 d, double tmin,
                   double tmax, double *t0, double *t1);

/* The length of the segment [a, b] inside the region; 0 without a medium. */
double sh_medium_length(const sh_medium *m, sh_vec3 a, sh_vec3 b);

/* The length of the ray from p in the unit direction d inside the region
 * (up to infinity); 0 without a medium. */
double sh_medium_length_ray(const sh_medium *m, sh_vec3 p, sh_vec3 d);

/* Optical depth along o + t d (d unit), t in [t0, t1] inside the region. */
sh_vec3 sh_medium_optical_depth_span(const sh_medium *m, sh_vec3 o, sh_vec3 d,
                                     double t0, double t1);

/* Optical depth of the part of the segment [a, b] inside the region. */
sh_vec3 sh_medium_optical_depth(const sh_medium *m, sh_vec3 a, sh_vec3 b);

/* Optical depth of the part inside the region of the ray from p in the
 * unit direction d, up to infinity. */
sh_vec3 sh_medium_optical_depth_ray(const sh_medium *m, sh_vec3 p, sh_vec3 d);

/* exp(-optical depth) of the same three. */
sh_vec3 sh_medium_transmittance_span(const sh_medium *m, sh_vec3 o, sh_vec3 d,
                                     double t0, double t1);
sh_vec3 sh_medium_transmittance(const sh_medium *m, sh_vec3 a, sh_vec3 b);
sh_vec3 sh_medium_transmittance_ray(const sh_medium *m, sh_vec3 p, sh_vec3 d);

/* The coefficients at a point p inside the region (per unit length). */
sh_vec3 sh_medium_sigma_s_at(const sh_medium *m, sh_vec3 p);
sh_vec3 sh_medium_sigma_a_at(const sh_medium *m, sh_vec3 p);
sh_vec3 sh_medium_sigma_t_at(const sh_medium *m, sh_vec3 p);

/* The phase function at p, for the kinds with one phase function
 * (homogeneous and height fog: the same everywhere). For an atmosphere it
 * is Rayleigh's alone: use the two below. */
const sh_phase *sh_medium_phase_at(const sh_medium *m, sh_vec3 p);

/* The phase function at p per RGB channel, normalised: for an atmosphere
 * the mixture of Rayleigh's and Mie's phase weighted by their sigma_s at
 * p; for the other kinds the medium's phase in every channel. */
sh_vec3 sh_medium_phase_rgb_at(const sh_medium *m, sh_vec3 p,
                               double cos_alpha);

/* sigma_s(p) times the phase function at p, per channel: what a renderer
 * multiplies the incident radiance by, for every kind (0 without a
 * medium). */
sh_vec3 sh_medium_scattering_at(const sh_medium *m, sh_vec3 p,
                                double cos_alpha);

/* The ground of an atmosphere (an opaque Lambert sphere of ground_radius
 * with ground_albedo); both 0 for the other kinds and without a medium.
 * sh_medium_ground_hit: the nearest ground point on o + t d (d unit), t in
 * (0, tmax), in *t. sh_medium_ground_blocks: 1 if the ground lies on
 * x + t w (w unit), t in (0, tmax) (the planet's shadow; exact for points
 * on the ground, without offsets). */
int sh_medium_ground_hit(const sh_medium *m, sh_vec3 o, sh_vec3 d,
                         double tmax, double *t);
int sh_medium_ground_blocks(const sh_medium *m, sh_vec3 x, sh_vec3 w,
                            double tmax);

/* A majorant of sigma_t over the span o + t d, t in [t0, t1] (d unit,
 * inside the region): sigma_t nowhere exceeds it there. Exact (the
 * maximum) for homogeneous media and height fog (at the span's lowest
 * point); for an atmosphere Rayleigh's and Mie's at the lowest point plus
 * the ozone's largest value over the span's heights. */
sh_vec3 sh_medium_majorant(const sh_medium *m, sh_vec3 o, sh_vec3 d, double t0,
                           double t1);

/* A majorant of sigma_t over the part of the box [lo, hi] inside the
 * region: sigma_t nowhere exceeds it there. Exact (the maximum) for
 * homogeneous media and height fog (at the part's lowest height); for an
 * atmosphere sh_atmosphere_majorant over the heights the box spans. 0
 * without a medium or where the box misses the region's bounding box. */
sh_vec3 sh_medium_majorant_box(const sh_medium *m, sh_vec3 lo, sh_vec3 hi);

/* Distance sampling along the span o + t d, t in [a, b] (d unit, inside
 * the region), by the transmittance of the mean channel: density
 * proportional to k(t) exp(-tau_k(a, t)), k the mean of sigma_t's channels
 * at t and tau_k its optical depth, normalised over [a, b] by inverting
 * the closed-form optical depth (for an atmosphere, its piecewise
 * constant approximation over the quadrature's panels, inverted exactly:
 * sh_atmosphere_sample_distance). Where the span's mean optical depth is
 * below 1e-6 the density is uniform instead. u in [0, 1). Returns the
 * sample t and sets *inv_pdf to 1 / its density. */
double sh_medium_sample_distance(const sh_medium *m, sh_vec3 o, sh_vec3 d,
                                 double a, double b, double u,
                                 double *inv_pdf);

/* Sets `err`'s location (the scene's file, line and column of its
 * medium's `type`, key path medium.type) for a refusal of the medium's
 * kind whose message the caller has set; nothing if `err` is NULL. */
void sh_medium_locate_type(const sh_scene *scene, sh_error *err);

/* For a tool that renders the medium kinds in `kinds`, a mask of
 * SH_MEDIUM_KIND(type) bits: SH_ERR_SCENE, located at the scene's
 * medium.type and naming `who` (the tool) and the kinds it renders, if the
 * medium is of another kind; SH_OK otherwise. */
#define SH_MEDIUM_KIND(type) (1u << (unsigned)(type))
sh_status sh_medium_require_kinds(const sh_scene *scene, const char *who,
                                  unsigned kinds, sh_error *err);

/* The name of a medium type as the scene format spells it. */
const char *sh_medium_type_name(sh_medium_type type);

/* The nearest a ray is taken to pass to a point or spot light when the
 * light it scatters is integrated: 1e-4 of the diagonal of the medium's
 * box (for an atmosphere, 1e-4 of the air's thickness, top_radius -
 * ground_radius: 6 m for the Earth in km, where the box's diagonal would
 * give 2.2 km; 0 without a medium). The in-scattered radiance of a ray through a
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
