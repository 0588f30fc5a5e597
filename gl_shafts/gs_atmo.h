/* An atmosphere as gl_shafts draws it (docs/scene-format.md, "Non-uniform
 * media", type atmosphere; Nishita et al. 1993, Dobashi, Yamamoto and
 * Nishita 2002): a shell of air between the ground sphere R_g and the top
 * R_t about a centre, whose Rayleigh and Mie coefficients fall as exp(-h /
 * H) with the height h above the ground, and an ozone layer that absorbs
 * only, with a tent profile max(0, 1 - |h - h_o| / (w / 2)). The ground is
 * an opaque Lambert sphere. Lengths in scene units, coefficients per unit
 * length. This is the plain set of numbers the shaders take; the core's
 * medium (sh_medium.h) remains what the tables are computed from. */
#ifndef GS_ATMO_H
#define GS_ATMO_H

#include "gs_atmo_table.h"
#include "sh_error.h"
#include "sh_scene.h"

typedef struct gs__atmo {
  gs__atmo_shell shell;
  sh_vec3 ground_albedo;
  sh_vec3 rayleigh_s;       /* at the ground */
  double rayleigh_h;        /* H_R > 0 */
  sh_vec3 mie_s, mie_a;     /* at the ground; 0 without Mie */
  double mie_h;             /* H_M > 0 (1 without Mie) */
  sh_phase mie_phase;       /* isotropic without Mie */
  sh_vec3 ozone_a;          /* 0 without ozone */
  double ozone_center, ozone_width; /* h_o, w > 0 (1 without ozone) */
} gs__atmo;

/* The atmosphere of a medium of type SH_MEDIUM_ATMOSPHERE (sh_scene.h's
 * sh_atmosphere); an absent Mie or ozone part gets coefficients 0. */
void gs__atmo_from_medium(const sh_medium *m, gs__atmo *a);

/* The relative densities at height h: Rayleigh's exp(-h / H_R), Mie's
 * exp(-h / H_M) and the ozone's tent. */
void gs__atmo_density(const gs__atmo *a, double h, double *rayleigh,
                      double *mie, double *ozone);

/* sigma_t at height h: Rayleigh's sigma_s, Mie's sigma_s + sigma_a and the
 * ozone's sigma_a, each times its density. */
sh_vec3 gs__atmo_sigma_t(const gs__atmo *a, double h);

/* The radii at which the ozone's profile bends (h_o - w/2, h_o, h_o + w/2
 * above the ground, those strictly inside the shell), ascending, into
 * out[3]; returns how many. Quadratures split a ray at them. */
int gs__atmo_kinks(const gs__atmo *a, double out[3]);

#endif
