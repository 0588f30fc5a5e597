#include "se_cycles_phase.h"

#include "se_export.h"
#include "se_phase_fit.h"

#include <math.h>
#include <stddef.h>

double se_phase_to_hg(const sh_phase *phase, int *exact) {
  const double gmax = 1.0 - 1e-3;
  *exact = 0;
  switch (phase->type) {
  case SH_PHASE_ISOTROPIC:
    *exact = 1;
    return 0.0;
  case SH_PHASE_HENYEY_GREENSTEIN:
    *exact = fabs(phase->g) <= gmax;
    return fmax(-gmax, fmin(gmax, phase->g));
  case SH_PHASE_NISHITA_HAZY:
    return 0.5 * 0.8;
  case SH_PHASE_NISHITA_MURKY:
    return (50.0 / 83.0) * (16.0 / 17.0);
  case SH_PHASE_RAYLEIGH:
    return 0.0;
  case SH_PHASE_CORNETTE_SHANKS: {
    se_hg_mixture m;
    double g = se_phase_fit_cs(phase->g, 1, &m) ? m.g[0] : se_phase_cs_mean_cosine(phase->g);
    return fmax(-gmax, fmin(gmax, g));
  }
  }
  return 0.0;
}

int se_phase_to_hg_lobes(const sh_phase *phase, double g[SE_HG_MAX_LOBES], int *exact) {
  /* An equal-weight mixture fitted by least squares to the relative error
   * of the normalised phase, uniform in cos over [-1, 1]: Rayleigh's rms and
   * largest relative error 2.8% and 7.6% (one isotropic lobe: 22% and 33%).
   * The Nishita phases keep one lobe of their mean cosine: their forward
   * lobes (x^8, x^32) have much lighter tails than any Henyey-Greenstein
   * lobe, and the best mixtures of 8 equal-weight lobes found still err by
   * 21% (minimax fit) or 39% (least squares) at some angle, which made
   * mountains_sun better (18.5% to 11.3%) but teapot_spot worse (10.8% to
   * 13.9%, relative RMS of the image; docs/scene_export.md). */
  static const double rayleigh[2] = {-0.318085, 0.318085};
  const double *src = NULL;
  int n = 0;
  switch (phase->type) {
  case SH_PHASE_RAYLEIGH:
    src = rayleigh;
    n = 2;
    break;
  default:
    g[0] = se_phase_to_hg(phase, exact);
    return 1;
  }
  *exact = 0;
  for (int i = 0; i < n; i++) g[i] = src[i];
  return n;
}

int se_phase_to_hg_weighted(const sh_phase *phase, double g[SE_HG_MAX_LOBES],
                            double w[SE_HG_MAX_LOBES], int *exact) {
  se_hg_mixture m;
  if (phase->type == SH_PHASE_CORNETTE_SHANKS && se_phase_fit_cs(phase->g, 2, &m)) {
    const double gmax = 1.0 - 1e-3;
    *exact = 0;
    for (int i = 0; i < m.n; i++) {
      g[i] = fmax(-gmax, fmin(gmax, m.g[i]));
      w[i] = m.w[i];
    }
    return m.n;
  }
  int n = se_phase_to_hg_lobes(phase, g, exact);
  for (int i = 0; i < n; i++) w[i] = 1.0 / n;
  return n;
}
