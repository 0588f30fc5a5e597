#include "se_pov_terms.h"

#include "se_export.h"
#include "se_phase_fit.h"

void se_pov_string(se_buf *b, const char *in) {
  se_buf_puts(b, "\"");
  for (const unsigned char *p = (const unsigned char *)in; *p; p++) {
    if (*p == '\\') se_buf_puts(b, "\\\\");
    else if (*p == '"') se_buf_puts(b, "\\\"");
    else if (*p == '\n') se_buf_puts(b, "\\n");
    else if (*p == '\t') se_buf_puts(b, "\\t");
    else if (*p < 0x20 || *p >= 0x7f) se_buf_puts(b, "_");
    else se_buf_append(b, (const char *)p, 1);
  }
  se_buf_puts(b, "\"");
}

se_phase_pov se_phase_to_pov(const sh_phase *phase) {
  se_phase_pov p = {1, 0.0, 1.0, "isotropic, POV-Ray type 1", 1};
  switch (phase->type) {
  case SH_PHASE_ISOTROPIC:
    break;
  case SH_PHASE_HENYEY_GREENSTEIN:
    p.type = 5;
    p.g = phase->g;
    p.comment = "Henyey-Greenstein, POV-Ray type 5";
    break;
  case SH_PHASE_NISHITA_HAZY:
    /* 0.576655375 (1 + 9 x^8), x = (1 + c)/2 uniform on [0, 1]: mean
     * 0.576655375 (1 + 9/9). */
    p.type = 2;
    p.mean = 0.576655375 * 2.0;
    p.comment = "Nishita hazy = Mie hazy, POV-Ray type 2";
    break;
  case SH_PHASE_NISHITA_MURKY:
    /* 0.495714547 (1 + 50 x^32): mean 0.495714547 (1 + 50/33). */
    p.type = 3;
    p.mean = 0.495714547 * (1.0 + 50.0 / 33.0);
    p.comment = "Nishita murky = Mie murky, POV-Ray type 3";
    break;
  case SH_PHASE_RAYLEIGH:
    /* 0.799372013 (1 + c^2): mean 0.799372013 (1 + 1/3). */
    p.type = 4;
    p.mean = 0.799372013 * (4.0 / 3.0);
    p.comment = "Rayleigh, POV-Ray type 4";
    break;
  case SH_PHASE_CORNETTE_SHANKS:
    /* POV-Ray has no Cornette-Shanks phase: the Henyey-Greenstein lobe of
     * its mean cosine (se_export.h), approximated; se_phase_to_pov_lobes
     * has the fitted lobes. */
    p.type = 5;
    p.g = se_phase_cs_mean_cosine(phase->g);
    p.comment = "Cornette-Shanks approximated by the Henyey-Greenstein lobe of its "
                "mean cosine, POV-Ray type 5";
    p.exact = 0;
    break;
  }
  return p;
}


int se_phase_to_pov_lobes(const sh_phase *phase, se_phase_pov lobes[SE_POV_MAX_LOBES],
                          double w[SE_POV_MAX_LOBES]) {
  lobes[0] = se_phase_to_pov(phase);
  w[0] = 1.0;
  se_hg_mixture m;
  if (phase->type != SH_PHASE_CORNETTE_SHANKS ||
      !se_phase_fit_cs_signed(phase->g, SE_POV_SIGNED_LOBES, &m))
    return 1;
  int negative = 0;
  for (int i = 0; i < m.n; i++) negative |= m.w[i] < 0.0;
  /* No signed mixture: the non-negative fit's lobes worth a frame. */
  if (!negative && !se_phase_fit_cs_lobes(phase->g, 2, SE_POV_MIN_LOBE_WEIGHT, &m)) return 1;
  /* The first lobe (frame 1 of a medium, with the surfaces' light) is
   * added: the heaviest positive one goes first. */
  for (int i = 1; i < m.n && m.w[0] < 0.0; i++)
    if (m.w[i] > 0.0) {
      double tg = m.g[0], tw = m.w[0];
      m.g[0] = m.g[i];
      m.w[0] = m.w[i];
      m.g[i] = tg;
      m.w[i] = tw;
    }
  for (int i = 0; i < m.n; i++) {
    lobes[i] = lobes[0];
    lobes[i].g = m.g[i];
    lobes[i].comment = "Cornette-Shanks approximated by Henyey-Greenstein lobes fitted to it "
                       "(se_phase_fit.h), POV-Ray type 5";
    w[i] = m.w[i];
  }
  return m.n;
}
