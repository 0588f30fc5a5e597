// The medium in GLSL, the shaders' twin of core/sh_medium.h: the region it
// fills, optical depth, transmittance and the coefficients at a point. What
// depends on the medium's kind is answered here alone; no other shader code
// looks at the kind. common.glsl includes this file after its box clipping.
//
// MEDIUM (a switch; the values are in gs_shared.h) selects the kind:
//   GS_MEDIUM_HOMOGENEOUS  u_sigma_s and u_sigma_t everywhere in the box
//                          [u_bmin, u_bmax]; optical depth sigma_t times
//                          the length inside it.
//   GS_MEDIUM_HEIGHT_FOG   the coefficients at a point at height y are
//                          u_sigma_s and u_sigma_t times the relative density
//                          rho(y) = exp(-(y - base) / H), with u_fog =
//                          (base, 1 / H), the base in the anchored space of
//                          every position here (gs_view.h). Along a span of
//                          length L whose ends lie at heights y0 and y1, the
//                          integral of rho is L rho(min(y0, y1)) g(|y1 - y0|
//                          / H), g(x) = (1 - exp(-x)) / x: sh_medium.c's
//                          form, without the cancellation of a nearly
//                          horizontal span.
//   GS_MEDIUM_ATMOSPHERE   a planet's air (gs_atmo.h) inside the top sphere
//                          of radius u_rt about u_atmo_c (anchored): the
//                          optical depth of a span from the table
//                          (atmo_table.glsl), the difference of the depths
//                          to the top from its two ends along it (along its
//                          reverse where it points at the ground), as
//                          atmo.glsl's EYE_TAU; a span through the ground
//                          is opaque. The coefficients at a point are not
//                          given here: the sweep does not draw an
//                          atmosphere (gs_atmo_render.h and gs_atmo_light.h
//                          do, from atmo.glsl).
// MEDIUM_VARIES is 1 where the coefficients vary along a ray: the plane
// shaders then take samples at least medium_variation_rate() per unit
// length, so that the density's change inside a slab is followed.

#ifndef MEDIUM
#define MEDIUM GS_MEDIUM_HOMOGENEOUS
#endif
#define MEDIUM_VARIES (MEDIUM != GS_MEDIUM_HOMOGENEOUS)

// The samples per scale height of height change a part of a ray takes in
// height fog: the midpoint rule's error on exp over a quarter of H is
// 0.26%.
const float FOG_SAMPLES_PER_SCALE_HEIGHT = 4.0;

#if MEDIUM == GS_MEDIUM_ATMOSPHERE
#include "atmo_table.glsl"

// The optical depth that stands for a span through the ground.
const float ATMO_OPAQUE = 1e30;

// The part [t0, t1] of o + t d, t in [lo, hi], inside the top sphere.
vec2 medium_clip(vec3 o, vec3 d, float lo, float hi) {
  vec3 q = o - u_atmo_c;
  float a = dot(d, d), b = dot(q, d), lq = length(q);
  float c = (lq - u_rt) * (lq + u_rt), disc = b * b - a * c;
  if (disc < 0.0) return vec2(1.0, 0.0);
  float s = sqrt(disc);
  return vec2(max(lo, (-b - s) / a), min(hi, (-b + s) / a));
}

// The distance from p, inside the top sphere, to it along unit w.
float medium_exit(vec3 p, vec3 w) { return max(medium_clip(p, w, 0.0, BIG).y, 0.0); }

// The radius r, rho2 = r^2 - R_g^2 and the cosine to the vertical of unit
// w at the point q from the planet's centre.
vec3 atmo_point(vec3 q, vec3 w) {
  float r = length(q);
  return vec3(r, (r - u_rg) * (r + u_rg), dot(q, w) / r);
}

// The distance along the ray from a point (atmo_point's a) to the
// ground's nearer meeting (atmo.glsl's ground_t), BIG if it misses it.
float atmo_ground_t(vec3 a) {
  if (!hits_ground(a.x, a.y, a.z)) return BIG;
  float disc = a.x * a.x * a.z * a.z - a.y;
  return max(a.y, 0.0) / max(-a.x * a.z + sqrt(max(disc, 0.0)), 1e-30);
}
#else
// The part [t0, t1] of o + t d, t in [lo, hi], inside the region (empty
// when t0 >= t1).
vec2 medium_clip(vec3 o, vec3 d, float lo, float hi) { return box_clip(o, d, lo, hi); }

// The distance from p, inside the region, to its boundary along unit w.
float medium_exit(vec3 p, vec3 w) { return box_exit(p, w); }
#endif

// Whether the medium hides the point at view depth z on the pixel ray o +
// z d from the eye: an atmosphere's ground in front of it.
bool medium_hides(vec3 o, vec3 d, float z) {
#if MEDIUM == GS_MEDIUM_ATMOSPHERE
  float dl = length(d);
  return atmo_ground_t(atmo_point(o - u_zref * d - u_atmo_c, d / dl)) < (z + u_zref) * dl;
#else
  return false;
#endif
}

#if MEDIUM == GS_MEDIUM_HEIGHT_FOG
// The relative density at height y. The exponent is held below 80, where
// float's exp overflows (a point 80 scale heights below the base sees no
// light either way).
float fog_density(float y) { return exp(min((u_fog.x - y) * u_fog.y, 80.0)); }

// (1 - exp(-x)) / x for x >= 0: below 0.03 its series (error under 1e-8),
// where 1 - exp(-x) would lose digits.
float one_minus_exp_over(float x) {
  return x < 0.03 ? 1.0 - x * (0.5 - x * (1.0 / 6.0 - x * (1.0 / 24.0)))
                  : (1.0 - exp(-x)) / x;
}
#endif

// The optical depth along o + t d, t in [t0, t1] (t0 <= t1), a span inside
// the region; dl is |d| (1.0 for a unit d, which the compiler folds).
vec3 optical_depth_span(vec3 o, vec3 d, float dl, float t0, float t1) {
  float len = (t1 - t0) * dl;
#if MEDIUM == GS_MEDIUM_ATMOSPHERE
  vec3 w = d / dl, q0 = o + t0 * d - u_atmo_c, q1 = q0 + len * w;
  vec3 a = atmo_point(q0, w);
  if (hits_ground(a.x, a.y, a.z)) {
    // The span ends short of the ground or is blocked; then the reverse
    // reaches the top.
    if (atmo_ground_t(a) < len) return vec3(ATMO_OPAQUE);
    vec3 b = atmo_point(q1, -w);
    return max(tau_top(b.x, b.y, b.z) - tau_top(a.x, a.y, -a.z), 0.0);
  }
  vec3 b = atmo_point(q1, w);
  return max(tau_top(a.x, a.y, a.z) - tau_top(b.x, b.y, b.z), 0.0);
#endif
#if MEDIUM == GS_MEDIUM_HEIGHT_FOG
  float y0 = o.y + t0 * d.y, rise = (t1 - t0) * abs(d.y);
  float low = d.y < 0.0 ? y0 - rise : y0;
  len *= fog_density(low) * one_minus_exp_over(rise * u_fog.y);
#endif
  return u_sigma_t * len;
}

// The optical depth of the part of the segment [a, b] inside the region.
vec3 optical_depth(vec3 a, vec3 b) {
  vec3 d = b - a;
  vec2 t = medium_clip(a, d, 0.0, 1.0);
  return t.y > t.x ? optical_depth_span(a, d, length(d), t.x, t.y) : vec3(0.0);
}

// The optical depth of the part inside the region of the ray from p in the
// unit direction w.
vec3 optical_depth_ray(vec3 p, vec3 w) {
  vec2 t = medium_clip(p, w, 0.0, BIG);
  return t.y > t.x ? optical_depth_span(p, w, 1.0, t.x, t.y) : vec3(0.0);
}

// exp(-tau); one exp where sigma_t is grey (GREY_SIGMA).
vec3 transmittance(vec3 tau) {
#if GREY_SIGMA
  return vec3(exp(-tau.x));
#else
  return exp(-tau);
#endif
}

// The relative density at a point p inside the region: the coefficients
// there are u_sigma_s and u_sigma_t times it.
float density_at(vec3 p) {
#if MEDIUM == GS_MEDIUM_HEIGHT_FOG
  return fog_density(p.y);
#else
  return 1.0;
#endif
}

// The coefficients at a point p inside the region.
vec3 sigma_s_at(vec3 p) { return u_sigma_s * density_at(p); }
vec3 sigma_t_at(vec3 p) { return u_sigma_t * density_at(p); }

// The samples per unit length that the medium's variation asks of a ray in
// the unit direction w (0 where it does not vary).
float medium_variation_rate(vec3 w) {
#if MEDIUM == GS_MEDIUM_HEIGHT_FOG
  return abs(w.y) * u_fog.y * FOG_SAMPLES_PER_SCALE_HEIGHT;
#else
  return 0.0;
#endif
}
