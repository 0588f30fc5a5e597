/* Phase functions in the targets' terms.
 *
 * POV-Ray 3.7 has all five of the format's phase functions: its phase k
 * is 4 pi times a normalised phase for types 1 (isotropic) and 5
 * (Henyey-Greenstein), and for types 2, 3, 4 (Mie hazy, Mie murky,
 * Rayleigh) a shape whose mean over the sphere is not 1. Knowing the mean
 * makes the mapping exact (se_pov.h).
 *
 * Cycles has Henyey-Greenstein lobes only (Volume Scatter's anisotropy,
 * clamped to |g| <= 1 - 1e-3). The Nishita and Rayleigh phases become sums
 * of lobes, each a Volume Scatter shader with its share of sigma_s:
 * - nishita_hazy = 1/2 isotropic + 1/2 lobe 9 x^8 (x = (1 + cos)/2); the
 *   lobe becomes HG with its mean cosine, g = 0.8;
 * - nishita_murky = 33/83 isotropic + 50/83 lobe 50 x^32; HG with g = 16/17;
 * - rayleigh: two HG lobes g = +-sqrt(0.1), half each, which share its
 *   mean cosine 0 and its second moment <cos^2> = 0.4.
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

typedef struct se_hg_lobe {
  double weight; /* share of sigma_s, the lobes' weights sum to 1 */
  double g;
} se_hg_lobe;

/* Writes the Henyey-Greenstein lobes for Cycles (one or two) and returns
 * their number; *exact is 1 if they equal the phase exactly. */
int se_phase_to_hg(const sh_phase *phase, se_hg_lobe lobes[2], int *exact);

/* The name of a phase type as the scene format spells it. */
const char *se_phase_name(sh_phase_type type);

#ifdef __cplusplus
}
#endif
#endif
