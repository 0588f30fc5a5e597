/* The POV-Ray target's own helpers: a user string as a POV-Ray string
 * literal, and the scene's phase functions in POV-Ray's terms.
 *
 * POV-Ray 3.7 has all five of the format's phase functions: its phase k
 * is 4 pi times a normalised phase for types 1 (isotropic) and 5
 * (Henyey-Greenstein), and for types 2, 3, 4 (Mie hazy, Mie murky,
 * Rayleigh) a shape whose mean over the sphere is not 1. Knowing the mean
 * makes the mapping exact (se_pov.h). The Cornette-Shanks phase has no
 * POV-Ray type: it becomes a weighted mixture of Henyey-Greenstein lobes
 * fitted to it (se_phase_fit.h), marked inexact. POV-Ray phases several
 * media in one interior with the plain mean of their phases, whatever
 * their scattering (media.cpp, ComputeMediaScatteringAttenuation: k /=
 * medias.size()), so a weighted mixture needs one frame per lobe (the
 * image is the frames' sum, se_pov.h). */
#ifndef SE_POV_TERMS_H
#define SE_POV_TERMS_H

#include "se_buf.h"
#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Appends `in` as a POV-Ray string literal, with its quotes: backslash and
 * double quote are escaped, tab and newline written as \t and \n, and any
 * other control or non-ASCII byte replaced by '_' (POV-Ray 3.7 reads
 * strings as ASCII). */
void se_pov_string(se_buf *b, const char *in);

typedef struct se_phase_pov {
  int type;            /* POV-Ray's scattering type, 1 to 5 */
  double g;            /* eccentricity, type 5 */
  double mean;         /* mean of POV-Ray's k over the sphere */
  const char *comment; /* e.g. "Henyey-Greenstein, POV-Ray type 5" */
  int exact;           /* 0 if POV-Ray's phase only approximates the scene's */
} se_phase_pov;

se_phase_pov se_phase_to_pov(const sh_phase *phase);

/* The phase as n POV-Ray lobes of weights w[i] (summing to 1; returns n,
 * at most SE_POV_MAX_LOBES), each rendered in a frame of its own with
 * |w[i]| and added or, for w[i] < 0, subtracted by the summing step
 * (POV-Ray's frames are summed outside it anyway): one lobe of weight 1
 * (se_phase_to_pov) but for Cornette-Shanks, whose signed fit of
 * SE_POV_SIGNED_LOBES lobes (se_phase_fit_cs_signed: a forward lobe, a
 * weak backward one and a negative one) follows its (1 + mu^2) factor:
 * largest relative error 0.6% for g 0.7, 1.4% for 0.8, against 37% and
 * 52% for the best non-negative mixture (se_phase_fit_test's table), at
 * the cost of three frames (each a whole render) where that mixture took
 * one or two. w[0] > 0 (frame 1 holds the surfaces' light). Without a
 * signed mixture, the non-negative fit's lobes of at least
 * SE_POV_MIN_LOBE_WEIGHT (a backward lobe of 0.3%, g 0.7, is not worth a
 * frame; one of 2.7%, g 0.5, is); if the fit's work space cannot be
 * allocated, the lobe of the mean cosine. */
#define SE_POV_MAX_LOBES 3
#define SE_POV_SIGNED_LOBES 3
#define SE_POV_MIN_LOBE_WEIGHT 0.01
int se_phase_to_pov_lobes(const sh_phase *phase, se_phase_pov lobes[SE_POV_MAX_LOBES],
                          double w[SE_POV_MAX_LOBES]);

#ifdef __cplusplus
}
#endif
#endif
