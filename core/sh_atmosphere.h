/* A planet's air (the scene format's medium of type "atmosphere", the
 * struct sh_atmosphere of sh_scene.h): its coefficients and phase at a
 * point, optical depth along a span, a majorant, distance sampling, and
 * the ground sphere's intersections. sh_medium.h's functions answer for an
 * atmosphere through these; renderers call sh_medium_*, and these
 * directly only for what is particular to a planet (the ground).
 *
 * Geometry. Lengths are scene units (kilometres in the project's scenes).
 * h(p) = |p - center| - ground_radius. The medium's region is the ball of
 * top_radius (a ray is clipped to that sphere); the ground, the sphere of
 * ground_radius, is an opaque surface the renderers intersect. Every
 * function works in double precision about the planet's centre with
 * cancellation-free forms: a sphere's roots by the stable quadratic (the
 * smaller root as c / q, c = (|o - center| - R)(|o - center| + R), the
 * discriminant from the distance of the ray's line to the centre), heights
 * along a span as differences (s^2 - s_lo^2) / (r + r_lo) from the span's
 * lowest point, so an eye 1 m above a ground of radius 6360 km, or 30,000
 * km away, keeps its heights to about 1e-12 of the radius.
 *
 * Optical depth. Along o + t d (d unit), the integral of each density
 * (Rayleigh's exp(-h/H_R), Mie's exp(-h/H_M), the ozone's tent) is split
 * at the point of the line nearest the centre into pieces on which the
 * height grows monotonically away from the piece's lowest end. Each piece
 * is cut into panels at equal steps of height above that end, the step
 * SH_ATMOSPHERE_PANEL times the smallest scale height whose density is
 * still above exp(-36) of its value at the lowest end (beyond that a
 * density is dropped: its tail is below 1e-14 of its integral), and at the
 * ozone tent's three kinks; each panel is integrated in the distance
 * along the ray by SH_ATMOSPHERE_GL-point Gauss-Legendre. Along a panel the
 * densities change by at most exp(SH_ATMOSPHERE_PANEL) and are analytic
 * in the distance (also at the tangent point, where h grows as s^2), so
 * the rule converges fast. Measured against composite Simpson in long
 * double with 20000 intervals per piece between kinks
 * (core/sh_atmosphere_test.c, Bruneton 2017's Earth in km, 300 rays:
 * vertical, slant, horizontal at the ground, tangent a metre above the
 * ground and higher, ending on the ground, from 30,000 km away), the
 * largest relative error of a channel's optical depth is 1.4e-10 with
 * panels of 4 scale heights (the same with 2: the reference's own floor;
 * 2.1e-9 with 6, 3.8e-9 with 8), held by the test below
 * SH_ATMOSPHERE_DEPTH_REL_ERROR (it prints the value measured). A span
 * crossing the whole air near the ground takes a few tens of panels of 8
 * points. A span whose lowest point lies below the ground (by more than 1e-9 of top_radius)
 * passes through the planet: its optical depth is INFINITY (transmittance
 * 0), as the ground is opaque. */
#ifndef SH_ATMOSPHERE_H
#define SH_ATMOSPHERE_H

#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Panel height in scale heights, and the Gauss-Legendre order. */
#define SH_ATMOSPHERE_PANEL 4.0
#define SH_ATMOSPHERE_GL 8
/* The bound the test holds the optical depth's relative error to. */
#define SH_ATMOSPHERE_DEPTH_REL_ERROR 1e-8

/* The roots ta <= tb of |o + t d - center| = R (d unit), by the stable
 * quadratic; 0 if the line misses the sphere. */
int sh_sphere_roots(sh_vec3 center, double R, sh_vec3 o, sh_vec3 d,
                    double *ta, double *tb);

/* The height of p above the ground. */
double sh_atmosphere_height(const sh_atmosphere *a, sh_vec3 p);

/* The relative densities at height h: rho[0] Rayleigh's, rho[1] Mie's
 * (0 without Mie), rho[2] the ozone's (0 without ozone). */
void sh_atmosphere_densities(const sh_atmosphere *a, double h, double rho[3]);

/* The coefficients at p. */
sh_vec3 sh_atmosphere_sigma_s(const sh_atmosphere *a, sh_vec3 p);
sh_vec3 sh_atmosphere_sigma_a(const sh_atmosphere *a, sh_vec3 p);

/* sigma_s(p) times the phase function at p, per channel: Rayleigh's
 * sigma_s p_rayleigh(cos) + Mie's sigma_s p_mie(cos). */
sh_vec3 sh_atmosphere_scattering(const sh_atmosphere *a, sh_vec3 p,
                                 double cos_alpha);

/* The phase function at p per channel: the mixture of Rayleigh's and
 * Mie's weighted by their sigma_s there (Rayleigh's where sigma_s is 0).
 * Each channel's is normalised. */
sh_vec3 sh_atmosphere_phase(const sh_atmosphere *a, sh_vec3 p,
                            double cos_alpha);

/* Clips o + t d, t in [tmin, tmax], to the ball of top_radius. */
int sh_atmosphere_clip(const sh_atmosphere *a, sh_vec3 o, sh_vec3 d,
                       double tmin, double tmax, double *t0, double *t1);

/* The integrals of the three relative densities along o + t d (d unit),
 * t in [t0, t1], in units of length (the method above); each INFINITY if
 * the span passes below the ground. */
void sh_atmosphere_density_integrals(const sh_atmosphere *a, sh_vec3 o,
                                     sh_vec3 d, double t0, double t1,
                                     double integral[3]);

/* Optical depth along the span: the density integrals times the
 * coefficients. */
sh_vec3 sh_atmosphere_optical_depth(const sh_atmosphere *a, sh_vec3 o,
                                    sh_vec3 d, double t0, double t1);

/* A majorant of sigma_t over the span: the exponential parts at its lowest
 * point plus the ozone's largest value over its heights. */
sh_vec3 sh_atmosphere_majorant(const sh_atmosphere *a, sh_vec3 o, sh_vec3 d,
                               double t0, double t1);

/* Distance sampling along the span [t0, t1] (as sh_medium_sample_distance):
 * the density is proportional to k_j exp(-tau(t)) with k_j the mean
 * channel's mean extinction over the quadrature panel j holding t and tau
 * the piecewise linear optical depth those panels give; it is sampled by
 * exact inversion, so *inv_pdf is exact for the sample drawn. Uniform where
 * the span's mean optical depth is below 1e-6. */
double sh_atmosphere_sample_distance(const sh_atmosphere *a, sh_vec3 o,
                                     sh_vec3 d, double t0, double t1,
                                     double u, double *inv_pdf);

/* The nearest point of the ground on o + t d (d unit), t in (0, tmax):
 * returns 1 and *t, else 0. */
int sh_atmosphere_ground_hit(const sh_atmosphere *a, sh_vec3 o, sh_vec3 d,
                             double tmax, double *t);

/* 1 if the ground lies on x + t w (w unit), t in (0, tmax): the planet's
 * shadow. A point on the ground looking above its horizon is not blocked,
 * one looking below it is, without any offset. */
int sh_atmosphere_ground_blocks(const sh_atmosphere *a, sh_vec3 x, sh_vec3 w,
                                double tmax);

#ifdef __cplusplus
}
#endif
#endif
