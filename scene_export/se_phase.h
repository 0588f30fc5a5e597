/* Phase functions in the targets' terms.
 *
 * POV-Ray 3.7 has all five of the format's phase functions: its phase k
 * is 4 pi times a normalised phase for types 1 (isotropic) and 5
 * (Henyey-Greenstein), and for types 2, 3, 4 (Mie hazy, Mie murky,
 * Rayleigh) a shape whose mean over the sphere is not 1. Knowing the mean
 * makes the mapping exact (se_pov.h).
 *
 * Cycles has Henyey-Greenstein lobes only (Volume Scatter's anisotropy,
 * clamped to |g| <= 1 - 1e-3), and one lobe per medium: Cycles 3.4 sums the
 * phase functions of several Volume Scatter closures without their weights
 * (two lobes of half the density each scatter twice the light, measured),
 * so a mixture of lobes cannot be built from shaders. The Nishita and
 * Rayleigh phases become one lobe with the same mean cosine <cos>:
 * - nishita_hazy: 1/2 isotropic + 1/2 the lobe 9 x^8 (x = (1 + cos)/2,
 *   whose mean cosine is 0.8): g = 0.4;
 * - nishita_murky: 33/83 isotropic + 50/83 the lobe 50 x^32 (mean cosine
 *   16/17): g = 800/1411;
 * - rayleigh: symmetric, g = 0 (isotropic).
 * These are approximations (the notes say so); isotropic and
 * Henyey-Greenstein are exact. */
#ifndef SE_PHASE_H
#define SE_PHASE_H

#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct se_phase_pov {
  int type;            /* POV-Ray's scattering type, 1 to 5 */
  double g;            /* eccentricity, type 5 */
  double mean;         /* mean of POV-Ray's k over the sphere */
  const char *comment; /* e.g. "Henyey-Greenstein, POV-Ray type 5" */
} se_phase_pov;

se_phase_pov se_phase_to_pov(const sh_phase *phase);

/* The Henyey-Greenstein g for Cycles; *exact is 1 if the lobe equals the
 * phase exactly. */
double se_phase_to_hg(const sh_phase *phase, int *exact);

/* The name of a phase type as the scene format spells it. */
const char *se_phase_name(sh_phase_type type);

#ifdef __cplusplus
}
#endif
#endif
