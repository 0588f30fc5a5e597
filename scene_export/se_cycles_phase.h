/* The Blender target's phase functions: the scene's phases as Cycles'
 * Henyey-Greenstein lobes.
 *
 * Cycles has Henyey-Greenstein lobes only (Volume Scatter's anisotropy,
 * clamped to |g| <= 1 - 1e-3). Cycles 3.4 sums the phase functions of
 * several Volume Scatter closures without their weights (two lobes of half
 * the density each scatter about twice the light, measured), so only
 * equal-weight mixtures can be built (se_phase_to_hg_lobes below). The
 * Nishita phases become one lobe with the same mean cosine <cos>:
 * - nishita_hazy: 1/2 isotropic + 1/2 the lobe 9 x^8 (x = (1 + cos)/2,
 *   whose mean cosine is 0.8): g = 0.4;
 * - nishita_murky: 33/83 isotropic + 50/83 the lobe 50 x^32 (mean cosine
 *   16/17): g = 800/1411;
 * - rayleigh: symmetric, g = 0 as one lobe; two lobes g = +-0.318085;
 * - cornette_shanks: the lobe fitted to it (se_phase_fit_cs with one
 *   lobe: g = 0.7433 for the format's g = 0.7, 0.8237 for 0.8; the
 *   energy-weighted fit, which holds the forward peak: its mean cosine
 *   0.757 and 0.844 were 31% and 47% bright there), or, where one lobe is
 *   chosen per point, the fitted mixture (se_phase_to_hg_weighted).
 * These are approximations (the notes say so); isotropic and
 * Henyey-Greenstein are exact. */
#ifndef SE_CYCLES_PHASE_H
#define SE_CYCLES_PHASE_H

#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The Henyey-Greenstein g for Cycles; *exact is 1 if the lobe equals the
 * phase exactly. */
double se_phase_to_hg(const sh_phase *phase, int *exact);

/* Cycles 3.4 evaluates several Volume Scatter closures as the plain sum of
 * their phase functions, with the closures' total sigma_s (it merges
 * closures of equal g first). n lobes of distinct g, each of density
 * sigma_s / n^2, therefore scatter sigma_s times the equal-weight mean of
 * the n phases, and an added absorption sigma_s (1 - 1/n) restores the
 * extinction: an exact equal-weight mixture (at most 8 lobes, Cycles'
 * MAX_VOLUME_CLOSURE). The lobes' g for Cycles, at most SE_HG_MAX_LOBES,
 * all distinct; returns their number. *exact is 1 if the mixture equals the
 * phase. nishita_hazy and rayleigh get fitted mixtures; the others one lobe
 * (se_phase_to_hg). */
#define SE_HG_MAX_LOBES 8
int se_phase_to_hg_lobes(const sh_phase *phase, double g[SE_HG_MAX_LOBES], int *exact);

/* The lobes g[i] with weights w[i] (summing to 1; returns their number)
 * for a material that chooses one lobe per shading point with probability
 * w[i] (the atmosphere's, se_blender_atmo.h), where the weights need not
 * be equal: Cornette-Shanks as its fitted mixture (se_phase_fit_cs, two
 * lobes: one forward, one weak backward), the others as
 * se_phase_to_hg_lobes with equal weights. *exact as there. */
int se_phase_to_hg_weighted(const sh_phase *phase, double g[SE_HG_MAX_LOBES],
                            double w[SE_HG_MAX_LOBES], int *exact);

#ifdef __cplusplus
}
#endif
#endif
