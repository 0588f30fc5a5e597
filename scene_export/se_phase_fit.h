/* The Cornette-Shanks phase as a weighted mixture of Henyey-Greenstein
 * lobes, for the renderers that have Henyey-Greenstein lobes only (POV-Ray
 * 3.7's type 5, Cycles' Volume Scatter).
 *
 * The phase (Cornette and Shanks 1992, "Physically reasonable analytic
 * expression for the single-scattering phase function", Applied Optics
 * 31(16); the contract's `cornette_shanks`, sh_phase_eval):
 *
 *   p_CS(mu; g) = 3/(8 pi) (1 - g^2)/(2 + g^2) (1 + mu^2) / (1 + g^2 - 2 g mu)^(3/2)
 *
 * and a lobe p_HG(mu; g_i) = (1 - g_i^2) / (4 pi (1 + g_i^2 - 2 g_i mu)^(3/2)).
 * The mixture sum_i w_i p_HG(mu; g_i) has w_i >= 0 and sum_i w_i = 1, so
 * it is a normalised phase (the scattered energy is kept).
 *
 * The fit (se_phase_fit_cs) minimises the chi-square distance
 * sum_j p_CS(mu_j) (m(mu_j) / p_CS(mu_j) - 1)^2 over mu_j uniform in cos
 * in [-1, 1] (2001 samples): the relative error weighted by the phase
 * itself, i.e. the error of the scattered light rather than of the phase's
 * value at every angle. It holds the forward peak, where the light is (the
 * plain relative error over cos leaves the peak of g 0.9 to a few samples
 * and overshoots it by 95% for g 0.8), at the cost of the sides. Method:
 * non-negative least squares (Lawson and Hanson's active set, on the
 * normal equations) for the weights of 195 candidate lobes g in [-0.97,
 * 0.97] (step 0.01), with the sum of the weights held by a heavy row; the
 * candidates with weight are merged into clusters of neighbours (each at
 * its weights' mean g), the K heaviest clusters kept, and their g refined
 * by a pattern search (steps 0.01 halved to 1e-5), the weights solved
 * again by non-negative least squares at every step. Deterministic, a
 * bounded number of steps: about 30 ms optimised (-O2), under 0.1 s at
 * -O0.
 *
 * What it reaches (se_phase_fit_test prints the table; docs/scene_export.md
 * "Non-uniform media"): no mixture of Henyey-Greenstein lobes with w_i >=
 * 0 follows the Cornette-Shanks (1 + mu^2) factor, which makes its sides
 * (90 degrees) darker than its forward peak and its back allow: whatever
 * the lobes, the mixture is too bright sideways. The best mixture is one
 * forward lobe and a weak backward one (its weight 11% for g 0.3, 2.7% for
 * 0.5, 0.3% for 0.7, 0.07% for 0.8): the least squares over all 195
 * candidates put their weight on those two clusters only, so a third or
 * fourth lobe is never added. Against the Henyey-Greenstein lobe
 * of the mean cosine (g 0.8: 0.8436, 47% bright straight ahead) the fit
 * (g 0.8: 0.8237) is 15% bright there and up to 52% bright at the side;
 * for g 0.3 and 0.5 the two lobes bring the largest error from 40% to 11%
 * and 18%. With signed weights (se_phase_fit_cs_signed, below: for a
 * renderer that sums the lobes itself) three lobes follow the factor to
 * 0.2-3%. The Cornette-Shanks phase stays approximated. */
#ifndef SE_PHASE_FIT_H
#define SE_PHASE_FIT_H

#ifdef __cplusplus
extern "C" {
#endif

#define SE_PHASE_FIT_MAX_LOBES 4

/* A mixture of n Henyey-Greenstein lobes: eccentricities g[i] in
 * [-0.97, 0.97], weights w[i] summing to 1, the largest |w| first; w[i] > 0
 * but from se_phase_fit_cs_signed. */
typedef struct se_hg_mixture {
  int n;
  double g[SE_PHASE_FIT_MAX_LOBES];
  double w[SE_PHASE_FIT_MAX_LOBES];
} se_hg_mixture;

/* The normalised Henyey-Greenstein phase at cos mu. */
double se_phase_hg(double g, double mu);

/* The mixture's phase at cos mu. */
double se_hg_mixture_eval(const se_hg_mixture *m, double mu);

/* Fits at most k lobes (1 <= k <= SE_PHASE_FIT_MAX_LOBES; other k are
 * clamped) to the Cornette-Shanks phase of eccentricity g, as described
 * above; g beyond +-0.95 is clamped to it (the candidates end at 0.97), a
 * NaN taken as 0. Writes *out (n may be below k when fewer clusters carry
 * weight) and returns 1; returns 0 with out->n = 0 only if the 3.6 MB of
 * work space cannot be allocated. */
int se_phase_fit_cs(double g, int k, se_hg_mixture *out);

/* The fit of k lobes (2 <= k <= SE_PHASE_FIT_MAX_LOBES; other k give
 * se_phase_fit_cs) whose weights may be NEGATIVE, for a renderer that sums
 * lobes itself (POV-Ray's frames: se_pov_terms.h): the weights sum to 1,
 * sum |w_i| <= SE_PHASE_FIT_MAX_ABS, the lobes are at least 0.02 apart and
 * the mixture is >= 0 at every cos of a grid of 20001 (so it is a phase).
 * A negative lobe takes light from the sides: with three lobes (a forward
 * one, a weak backward one and a negative one near g 0.25) the mixture
 * follows the (1 + mu^2) factor that no non-negative mixture gets (the
 * table of se_phase_fit_test: g 0.7 largest relative error 0.6% against
 * 37%). The weights minimise the same chi-square distance as
 * se_phase_fit_cs with sum w = 1 held exactly (the equality-constrained
 * least squares, its KKT system); the lobes start from every increasing
 * k-tuple of a grid over [-0.96, 0.96] (13 points; 9 for k = 4) and are
 * the six best refined by a pattern search (steps 0.02 halved to 1e-5,
 * at most 300 sweeps). Lobes are ordered by |w|, largest first. If no signed mixture is feasible or
 * better than the non-negative fit, *out is se_phase_fit_cs(g, k). Returns
 * 0 as se_phase_fit_cs does. Slower than se_phase_fit_cs (six pattern
 * searches over k lobes, each step solving the weights), growing with k;
 * the exporter fits once per export (k = 3). */
#define SE_PHASE_FIT_MAX_ABS 3.0
int se_phase_fit_cs_signed(double g, int k, se_hg_mixture *out);

/* The fit of at most kmax lobes whose lightest lobe weighs at least
 * min_weight: se_phase_fit_cs with kmax, kmax - 1, ... lobes until it
 * holds (one lobe always does). For a renderer where each lobe costs (a
 * POV-Ray frame). Returns 0 as se_phase_fit_cs does. */
int se_phase_fit_cs_lobes(double g, int kmax, double min_weight, se_hg_mixture *out);

/* The largest and the RMS relative error of the mixture against the
 * Cornette-Shanks phase of eccentricity g, over cos uniform in [-1, 1]
 * (4001 samples; either pointer may be NULL), and the relative error
 * straight ahead (cos = 1) in *forward (may be NULL). */
void se_phase_fit_error(double g, const se_hg_mixture *m, double *max_rel,
                        double *rms_rel, double *forward);

#ifdef __cplusplus
}
#endif
#endif
