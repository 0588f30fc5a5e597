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

/* Height fog's optical depth along a + t (b - a), t in [0, 1], all inside
 * the box, by composite Simpson over t of sigma_t rho(y(t)) |b - a| with
 * rho written out here: an independent check of the closed form. */
static double fog_quadrature(const sh_medium *m, sh_vec3 a, sh_vec3 b) {
  const int n = 200000;
  double len = sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y) +
                    (b.z - a.z) * (b.z - a.z));
  double s = 0;
  for (int i = 0; i <= n; i++) {
    double t = (double)i / n, y = a.y + t * (b.y - a.y);
    double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    s += w * exp(-(y - m->base_height) / m->scale_height);
  }
  return m->sigma_t.y * len * s / (3.0 * n);
}

static void check_fog_depth(const sh_medium *m, sh_vec3 a, sh_vec3 b) {
  double want = fog_quadrature(m, a, b);
  double got = sh_medium_optical_depth(m, a, b).y;
  SH_CHECK_NEAR(got, want, 1e-6, 0);
  /* And the span form along the unit direction. */
  sh_vec3 d = sh_sub(b, a);
  double len = sh_length(d);
  got = sh_medium_optical_depth_span(m, a, sh_scale(d, 1.0 / len), 0, len).y;
  SH_CHECK_NEAR(got, want, 1e-6, 0);
}

/* Height fog: closed-form optical depth against quadrature (slant,
 * horizontal, nearly horizontal, vertical both ways, far from the
 * origin), the contract's formula, coefficients at a point, the majorant,
 * clipping to the box, and the inversion behind distance sampling. */
static void test_height_fog(void) {
  sh_medium m = {0};
  m.present = 1;
  m.type = SH_MEDIUM_HEIGHT_FOG;
  m.sigma_s = sh_v3(0.2, 0.4, 0.6);
  m.sigma_a = sh_v3(0.1, 0.1, 0.1);
  m.sigma_t = sh_add(m.sigma_s, m.sigma_a);
  m.base_height = 3.0;
  m.scale_height = 2.5;
  m.bmin = sh_v3(-1e8, -50, -1e8);
  m.bmax = sh_v3(1e8, 100, 1e8);
  check_fog_depth(&m, sh_v3(0, 1, 0), sh_v3(7, 9, -4));      /* slant up */
  check_fog_depth(&m, sh_v3(7, 9, -4), sh_v3(0, 1, 0));      /* down */
  check_fog_depth(&m, sh_v3(-3, 2, 1), sh_v3(40, 2, -30));   /* horizontal */
  check_fog_depth(&m, sh_v3(-3, 2, 1), sh_v3(40, 2 + 1e-9, -30));
  check_fog_depth(&m, sh_v3(-3, 2 - 1e-7, 1), sh_v3(40, 2, -30));
  check_fog_depth(&m, sh_v3(1, -20, 1), sh_v3(1, 30, 1));    /* vertical */
  check_fog_depth(&m, sh_v3(1, 30, 1), sh_v3(1, -20, 1));
  check_fog_depth(&m, sh_v3(5e7, 4, -5e7), sh_v3(5e7 + 9, 6, -5e7 + 3));
  check_fog_depth(&m, sh_v3(5e7, 80, -5e7), sh_v3(5e7 + 50, 80, -5e7));
  /* The contract's form for a vertical segment: sigma_t H / d.y (rho(y0) -
   * rho(y1)) with d.y = 1 per unit length. */
  double H = m.scale_height, b = m.base_height;
  double want = m.sigma_t.z * H * (exp(-(0.0 - b) / H) - exp(-(10.0 - b) / H));
  SH_CHECK_NEAR(sh_medium_optical_depth(&m, sh_v3(2, 0, 2), sh_v3(2, 10, 2)).z,
                want, 1e-12, 0);
  /* A horizontal ray: sigma_t (t1 - t0) rho(y). */
  want = m.sigma_t.x * 12.0 * exp(-(7.0 - b) / H);
  SH_CHECK_NEAR(sh_medium_optical_depth(&m, sh_v3(0, 7, 0), sh_v3(0, 7, 12)).x,
                want, 1e-14, 0);
  /* Only the part inside the box counts: the box ends at y = 100. */
  sh_vec3 up = sh_medium_optical_depth_ray(&m, sh_v3(0, 90, 0), sh_v3(0, 1, 0));
  SH_CHECK_NEAR(up.y, m.sigma_t.y * H * (exp(-(90 - b) / H) - exp(-(100 - b) / H)),
                0, 1e-12);
  sh_vec3 tr = sh_medium_transmittance(&m, sh_v3(0, 7, 0), sh_v3(0, 7, 12));
  SH_CHECK_NEAR(tr.x, exp(-m.sigma_t.x * 12.0 * exp(-(7.0 - b) / H)), 1e-14, 0);
  /* Coefficients at a point and the majorant (at the lowest point). */
  sh_vec3 p = sh_v3(1e7, b + H, 3);
  SH_CHECK_NEAR(sh_medium_sigma_s_at(&m, p).z, 0.6 / exp(1.0), 1e-15, 0);
  SH_CHECK_NEAR(sh_medium_sigma_a_at(&m, p).x, 0.1 / exp(1.0), 1e-15, 0);
  SH_CHECK_NEAR(sh_medium_sigma_t_at(&m, sh_v3(0, b, 0)).y, 0.5, 1e-15, 0);
  sh_vec3 mj = sh_medium_majorant(&m, sh_v3(0, 10, 0), sh_normalize(sh_v3(1, -1, 0)),
                                  0, 4 * sqrt(2.0));
  SH_CHECK_NEAR(mj.x, m.sigma_t.x * exp(-(6.0 - b) / H), 1e-12, 0);
  /* Distance sampling inverts the mean channel's optical depth exactly:
   * tau_k(a, t) = -log(1 - u norm), and 1 / pdf = norm / (k(t) exp(-tau)). */
  sh_vec3 o = sh_v3(0, 12, 0), d = sh_normalize(sh_v3(3, -1, 0.5));
  double k = (m.sigma_t.x + m.sigma_t.y + m.sigma_t.z) / 3.0;
  double a0 = 1.0, b0 = 30.0;
  sh_vec3 tab = sh_medium_optical_depth_span(&m, o, d, a0, b0);
  double norm = -expm1(-(tab.x + tab.y + tab.z) / 3.0);
  for (int i = 0; i < 5; i++) {
    double u = (i + 0.37) / 5, inv_pdf;
    double t = sh_medium_sample_distance(&m, o, d, a0, b0, u, &inv_pdf);
    sh_vec3 tat = sh_medium_optical_depth_span(&m, o, d, a0, t);
    double tau = (tat.x + tat.y + tat.z) / 3.0;
    SH_CHECK_NEAR(tau, -log1p(-u * norm), 1e-12, 1e-9);
    double kt = k * exp(-(o.y + t * d.y - b) / H);
    SH_CHECK_NEAR(inv_pdf, norm / (kt * exp(-tau)), 1e-9, 0);
  }
}

int main(void) {
  test_height_fog();
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
    ph.type = SH_PHASE_CORNETTE_SHANKS;
    SH_CHECK_NEAR(sphere_integral(&ph), 1.0, 1e-6, 0);
  }
  /* Cornette-Shanks: the contract's shape (1 + c^2) / (1 + g^2 - 2 g
   * c)^1.5 up to its constant, and Rayleigh at g = 0. */
  ph.type = SH_PHASE_CORNETTE_SHANKS;
  ph.g = 0.8;
  SH_CHECK_NEAR(sh_phase_eval(&ph, 0.3) / sh_phase_eval(&ph, -0.6),
                (1.09 / pow(1.64 - 0.48, 1.5)) / (1.36 / pow(1.64 + 0.96, 1.5)),
                1e-12, 0);
  ph.g = 0;
  sh_phase ray = {SH_PHASE_RAYLEIGH, 0};
  SH_CHECK_NEAR(sh_phase_eval(&ph, 0.4), sh_phase_eval(&ray, 0.4), 1e-15, 0);
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
