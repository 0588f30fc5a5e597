/* The POV-Ray target's own helpers: a user string as a POV-Ray string
 * literal, and the scene's phase functions in POV-Ray's terms.
 *
 * POV-Ray 3.7 has all five of the format's phase functions: its phase k
 * is 4 pi times a normalised phase for types 1 (isotropic) and 5
 * (Henyey-Greenstein), and for types 2, 3, 4 (Mie hazy, Mie murky,
 * Rayleigh) a shape whose mean over the sphere is not 1. Knowing the mean
 * makes the mapping exact (se_pov.h). The Cornette-Shanks phase has no
 * POV-Ray type: it becomes the Henyey-Greenstein lobe of its mean cosine,
 * marked inexact. */
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

#ifdef __cplusplus
}
#endif
#endif
