/* Phase functions against their normalisation, and the medium's geometry. */
#include "sh_medium.h"
#include "sh_test.h"

/* 2 pi * integral over cos alpha in [-1, 1] by composite Simpson. */
static double sphere_integral(const sh_phase *ph) {
  const int n = 400000;
  double h = 2.0 / n, s = 0;
  for (int i = 0; i <= n; i++) {
    double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    s += w * sh_phase_eval(ph, -1.0 + i * h);
  }
  return 2.0 * SH_PI * s * h / 3.0;
}

int main(void) {
  sh_phase ph = {SH_PHASE_ISOTROPIC, 0};
  SH_CHECK_NEAR(sphere_integral(&ph), 1.0, 1e-9, 0);
  ph.type = SH_PHASE_RAYLEIGH;
  SH_CHECK_NEAR(sphere_integral(&ph), 1.0, 1e-9, 0);
  ph.type = SH_PHASE_NISHITA_HAZY;
  SH_CHECK_NEAR(sphere_integral(&ph), 1.0, 1e-9, 0);
  ph.type = SH_PHASE_NISHITA_MURKY;
  SH_CHECK_NEAR(sphere_integral(&ph), 1.0, 1e-9, 0);
  const double gs[] = {-0.9, -0.3, 0.0, 0.5, 0.9};
  for (int i = 0; i < 5; i++) {
    ph.type = SH_PHASE_HENYEY_GREENSTEIN;
    ph.g = gs[i];
    SH_CHECK_NEAR(sphere_integral(&ph), 1.0, 1e-6, 0);
  }
  /* Shapes: forward peaks where they should, and the unnormalised forms of
   * the format up to their constants. */
  ph.type = SH_PHASE_NISHITA_HAZY;
  SH_CHECK_NEAR(sh_phase_eval(&ph, 1.0) / sh_phase_eval(&ph, -1.0), 10.0,
                1e-12, 0);
  ph.type = SH_PHASE_NISHITA_MURKY;
  SH_CHECK_NEAR(sh_phase_eval(&ph, 1.0) / sh_phase_eval(&ph, -1.0), 51.0,
                1e-12, 0);
  double c = cos(1.0), x = 0.5 * (1 + c);
  SH_CHECK_NEAR(sh_phase_eval(&ph, c) / sh_phase_eval(&ph, -1.0),
                1 + 50 * pow(x, 32), 1e-12, 0);
  ph.type = SH_PHASE_RAYLEIGH;
  SH_CHECK_NEAR(sh_phase_eval(&ph, 0.0) / sh_phase_eval(&ph, 1.0), 0.5, 1e-12,
                0);
  ph.type = SH_PHASE_HENYEY_GREENSTEIN;
  ph.g = 0.6;
  SH_CHECK_NEAR(sh_phase_eval(&ph, 1.0), (1 - 0.36) / (4 * SH_PI * pow(0.4, 3)),
                1e-12, 0);

  /* Box clipping and path lengths. */
  sh_medium m = {0};
  m.present = 1;
  m.bmin = sh_v3(-1, -1, -1);
  m.bmax = sh_v3(1, 1, 1);
  m.sigma_t = sh_v3(0.5, 1.0, 2.0);
  double t0, t1;
  SH_CHECK(sh_box_clip(m.bmin, m.bmax, sh_v3(-5, 0, 0), sh_v3(1, 0, 0), 0,
                       INFINITY, &t0, &t1));
  SH_CHECK_NEAR(t0, 4.0, 1e-12, 0);
  SH_CHECK_NEAR(t1, 6.0, 1e-12, 0);
  SH_CHECK(!sh_box_clip(m.bmin, m.bmax, sh_v3(-5, 2, 0), sh_v3(1, 0, 0), 0,
                        INFINITY, &t0, &t1));
  SH_CHECK_NEAR(sh_medium_length(&m, sh_v3(0, 0, 0), sh_v3(3, 0, 0)), 1.0,
                1e-12, 0);
  SH_CHECK_NEAR(sh_medium_length_ray(&m, sh_v3(0, 0, 0), sh_v3(0, 1, 0)), 1.0,
                1e-12, 0);
  /* Homogeneous: optical depth sigma_t times the length inside the box. */
  sh_vec3 tr = sh_medium_transmittance(&m, sh_v3(-3, 0, 0), sh_v3(3, 0, 0));
  SH_CHECK_NEAR(tr.x, exp(-1.0), 1e-12, 0);
  SH_CHECK_NEAR(tr.z, exp(-4.0), 1e-12, 0);
  tr = sh_medium_transmittance_ray(&m, sh_v3(0, 0, 0), sh_v3(0, -1, 0));
  SH_CHECK_NEAR(tr.y, exp(-1.0), 1e-12, 0);
  sh_vec3 mj = sh_medium_majorant(&m, sh_v3(0, 0, 0), sh_v3(1, 0, 0), 0, 1);
  SH_CHECK(mj.x == 0.5 && mj.z == 2.0);
  SH_TEST_DONE();
}
