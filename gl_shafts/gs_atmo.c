#include "gs_atmo.h"

#include <math.h>

void gs__atmo_density(const gs__atmo *a, double h, double *rayleigh,
                      double *mie, double *ozone) {
  *rayleigh = exp(-h / a->rayleigh_h);
  *mie = exp(-h / a->mie_h);
  *ozone = fmax(0.0, 1.0 - fabs(h - a->ozone_center) / (0.5 * a->ozone_width));
}

sh_vec3 gs__atmo_sigma_t(const gs__atmo *a, double h) {
  double dr, dm, dz;
  gs__atmo_density(a, h, &dr, &dm, &dz);
  return sh_add(sh_add(sh_scale(a->rayleigh_s, dr),
                       sh_scale(sh_add(a->mie_s, a->mie_a), dm)),
                sh_scale(a->ozone_a, dz));
}

int gs__atmo_kinks(const gs__atmo *a, double out[3]) {
  int n = 0;
  double top = a->shell.r_top - a->shell.r_ground;
  for (int k = -1; k <= 1; k++) {
    double h = a->ozone_center + 0.5 * k * a->ozone_width;
    if (h > 0.0 && h < top) out[n++] = a->shell.r_ground + h;
  }
  return n;
}

void gs__atmo_from_medium(const sh_medium *m, gs__atmo *a) {
  const sh_atmosphere *s = &m->atmo;
  gs__atmo z = {{s->center, s->ground_radius, s->top_radius},
                s->ground_albedo,
                s->rayleigh_sigma_s, s->rayleigh_H,
                {0, 0, 0}, {0, 0, 0}, 1.0, {SH_PHASE_ISOTROPIC, 0.0},
                {0, 0, 0}, 0.0, 1.0};
  if (s->has_mie) {
    z.mie_s = s->mie_sigma_s;
    z.mie_a = s->mie_sigma_a;
    z.mie_h = s->mie_H;
    z.mie_phase = s->mie_phase;
  }
  if (s->has_ozone) {
    z.ozone_a = s->ozone_sigma_a;
    z.ozone_center = s->ozone_height;
    z.ozone_width = s->ozone_width;
  }
  *a = z;
}
