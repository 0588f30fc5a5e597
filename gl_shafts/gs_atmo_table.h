/* The precomputed optical-depth table of an atmosphere (Dobashi, Yamamoto
 * and Nishita 2002, slides 38-44: "create textures of ... optical depth",
 * seed 003): the optical depth from a point at distance r from the planet's
 * centre along a direction of cosine mu to the zenith, up to the top of the
 * atmosphere, per RGB channel, as a 2D table over (r, mu) that the sky and
 * space shaders read as a texture. Where the ray meets the ground the
 * optical depth is infinite (the light is blocked); the table does not store
 * that case: gs__atmo_table_lookup (and the shaders) test the ground sphere
 * exactly and the table covers only the rays that reach the top, so the
 * step at the horizon is not blurred across a texel.
 *
 * Parametrisation (Bruneton and Neyret 2008, the form of Bruneton 2017's
 * transmittance table), chosen because it puts texels where the optical
 * depth varies: with H = sqrt(R_t^2 - R_g^2), rho = sqrt(r^2 - R_g^2) and d
 * the distance to the top along the ray,
 *   u_r  = rho / H,
 *   u_mu = (d - d_min) / (d_max - d_min), d_min = R_t - r, d_max = rho + H,
 * so u_mu = 0 is the zenith and u_mu = 1 the horizon (the ray tangent to
 * the ground). Texel (i, j) holds the value at u_r = i / (n_r - 1), u_mu =
 * j / (n_mu - 1), and the lookup interpolates bilinearly as GL's linear
 * filter does with texture coordinates (u (n - 1) + 0.5) / n.
 *
 * Values are filled in double precision by a function giving the optical
 * depth of a segment: in gl_shafts the core's medium interface
 * (sh_medium_optical_depth), so the table holds
 * what the reference renderer integrates, up to the interpolation error
 * that gs_atmo_table_test measures. */
#ifndef GS_ATMO_TABLE_H
#define GS_ATMO_TABLE_H

#include "sh_error.h"
#include "sh_scene.h"

/* The shell an atmosphere fills: the ground sphere R_g and the top R_t,
 * about a centre. Lengths in scene units. */
typedef struct gs__atmo_shell {
  sh_vec3 center;
  double r_ground, r_top; /* 0 < r_ground < r_top */
} gs__atmo_shell;

/* Where the table's values come from: the optical depth (RGB, >= 0) of
 * the segment [a, b]; ctx is its data. */
typedef struct gs__atmo_source {
  sh_vec3 (*depth)(const void *ctx, sh_vec3 a, sh_vec3 b);
  const void *ctx;
} gs__atmo_source;

/* The source of a medium: sh_medium_optical_depth. */
gs__atmo_source gs__atmo_source_medium(const sh_medium *m);

/* A texel holds log(tau + GS__ATMO_TAU_EPS), per channel, and the lookup
 * returns exp(interpolated) - GS__ATMO_TAU_EPS: tau falls by orders of
 * magnitude from the ground to the top and, for rays grazing the ground,
 * as exp(-h_p / H) with the height h_p of their lowest point, which is
 * nearly linear in u_mu there; its logarithm is nearly linear in both
 * coordinates. Measured by gs_atmo_table_test at 64 x 256 over random rays
 * (the Earth's atmosphere): the transmittance's relative error at most
 * 0.45% (RMS 0.026%), where interpolating tau itself gave 8.3% (RMS 0.23%)
 * even with tau normalised by exp(-h / H_R), and 250% normalised by
 * sigma_t at the start (which bends where the ozone's profile does). */
#define GS__ATMO_TAU_EPS 1e-6
typedef struct gs__atmo_table {
  int n_r, n_mu;        /* texels along u_r and u_mu, each >= 2 */
  double r_ground, r_top;
  float *tau;           /* n_r rows of n_mu texels, RGBA (A = 0), owned */
} gs__atmo_table;

/* Whether the ray from radius r (>= r_ground) with cosine mu to the zenith
 * meets the ground sphere. */
int gs__atmo_hits_ground(double r_ground, double r, double mu);

/* The distance from radius r along cosine mu to the sphere of radius R >=
 * r (the far intersection), without cancellation. */
double gs__atmo_distance_to_sphere(double r, double mu, double R);

/* The table's coordinates (u_r, u_mu) in [0, 1]^2 of (r, mu); r is
 * clamped to [R_g, R_t] and mu to the rays that reach the top. */
void gs__atmo_table_coords(double r_ground, double r_top, double r, double mu,
                           double *u_r, double *u_mu);

/* The inverse: (r, mu) of (u_r, u_mu). */
void gs__atmo_table_point(double r_ground, double r_top, double u_r, double u_mu,
                          double *r, double *mu);

/* The optical depth from radius r along cosine mu to the top, straight
 * from src->depth over the segment to the top sphere (the point
 * placed at center + (0, r, 0)); +INFINITY in every channel where the ray
 * meets the ground. */
sh_vec3 gs__atmo_depth_exact(const gs__atmo_source *src,
                             const gs__atmo_shell *shell, double r, double mu);

/* Fills the table at n_r x n_mu texels (each >= 2). SH_ERR_NOMEM, or
 * SH_ERR_ARG for sizes below 2 or a shell that is not 0 < R_g < R_t. */
sh_status gs__atmo_table_build(gs__atmo_table *t, const gs__atmo_source *src,
                               const gs__atmo_shell *shell, int n_r, int n_mu,
                               sh_error *err);

/* The interpolated optical depth, as the shaders read it: +INFINITY where
 * the ray meets the ground. */
sh_vec3 gs__atmo_table_lookup(const gs__atmo_table *t, double r, double mu);

void gs__atmo_table_free(gs__atmo_table *t);

#endif
