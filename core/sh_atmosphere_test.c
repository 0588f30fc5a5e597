/* The atmosphere against closed forms and an independent fine quadrature:
 * the zenith optical depth (sum of sigma H (1 - exp(-h_top / H)) plus the
 * ozone tent's area), the normalisation of the Rayleigh phase and of the
 * per-channel mixture, optical depth along slant, horizontal, tangent,
 * ground-ending and far-away rays against composite Simpson in long
 * double (split at the nearest point and the ozone's kinks, heights
 * computed directly as |p - center| - R_g), the majorant, distance
 * sampling's normalisation, and the ground's intersections an eye 1 m
 * above a planet of 6360 km. Prints the largest relative error measured. */
#include "sh_atmosphere.h"
#include "sh_medium.h"
#include "sh_rng.h"
#include "sh_test.h"

#include <string.h>

/* Bruneton 2017's Earth in km (the contract's reference values). */
static sh_atmosphere earth(void) {
  sh_atmosphere a = {0};
  a.center = sh_v3(0, -6360, 0);
  a.ground_radius = 6360;
  a.top_radius = 6420;
  a.ground_albedo = sh_v3s(0.1);
  a.rayleigh_sigma_s = sh_v3(5.802e-3, 13.558e-3, 33.1e-3);
  a.rayleigh_H = 8;
  a.has_mie = 1;
  a.mie_sigma_s = sh_v3s(3.996e-3);
  a.mie_sigma_a = sh_v3s(0.444e-3);
  a.mie_H = 1.2;
  a.mie_phase = (sh_phase){SH_PHASE_CORNETTE_SHANKS, 0.8};
  a.has_ozone = 1;
  a.ozone_sigma_a = sh_v3(0.650e-3, 1.881e-3, 0.085e-3);
  a.ozone_height = 25;
  a.ozone_width = 30;
  return a;
}

/* The three densities at a point, written out independently. */
static void ref_density(const sh_atmosphere *a, long double px, long double py,
                        long double pz, long double rho[3]) {
  long double x = px - a->center.x, y = py - a->center.y, z = pz - a->center.z;
  long double h = sqrtl(x * x + y * y + z * z) - a->ground_radius;
  rho[0] = expl(-h / a->rayleigh_H);
  rho[1] = expl(-h / a->mie_H);
  long double t = 1.0L - fabsl(h - a->ozone_height) / (a->ozone_width / 2);
  rho[2] = t > 0 ? t : 0;
}

/* Simpson over [ta, tb] of o + t d with n intervals, added to I. */
static void simpson(const sh_atmosphere *a, sh_vec3 o, sh_vec3 d, long double ta,
                    long double tb, int n, long double I[3]) {
  long double h = (tb - ta) / n, s[3] = {0, 0, 0};
  for (int i = 0; i <= n; i++) {
    long double t = ta + i * h, rho[3];
    ref_density(a, o.x + t * d.x, o.y + t * d.y, o.z + t * d.z, rho);
    long double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    for (int k = 0; k < 3; k++) s[k] += w * rho[k];
  }
  for (int k = 0; k < 3; k++) I[k] += s[k] * h / 3;
}

/* Where the ray crosses the sphere of radius R about the centre, in long
 * double by the plain formula (an independent root finder). */
static int ref_cuts(const sh_atmosphere *a, sh_vec3 o, sh_vec3 d, long double R,
                    long double *c) {
  long double x = o.x - a->center.x, y = o.y - a->center.y, z = o.z - a->center.z;
  long double b = x * d.x + y * d.y + z * d.z;
  long double cc = x * x + y * y + z * z - R * R;
  long double disc = b * b - cc;
  if (disc < 0) return 0;
  c[0] = -b - sqrtl(disc);
  c[1] = -b + sqrtl(disc);
  return 2;
}

/* The reference integrals over [t0, t1], split where the densities have
 * kinks or the height turns. */
static void reference(const sh_atmosphere *a, sh_vec3 o, sh_vec3 d, double t0,
                      double t1, long double I[3]) {
  long double cuts[16];
  int n = 0;
  cuts[n++] = t0;
  cuts[n++] = t1;
  long double x = o.x - a->center.x, y = o.y - a->center.y, z = o.z - a->center.z;
  cuts[n++] = -(x * d.x + y * d.y + z * d.z); /* nearest the centre */
  double ks[3] = {a->ozone_height - a->ozone_width / 2, a->ozone_height,
                  a->ozone_height + a->ozone_width / 2};
  for (int k = 0; k < 3; k++) n += ref_cuts(a, o, d, a->ground_radius + ks[k], cuts + n);
  for (int i = 1; i < n; i++)
    for (int j = i; j > 0 && cuts[j] < cuts[j - 1]; j--) {
      long double t = cuts[j];
      cuts[j] = cuts[j - 1];
      cuts[j - 1] = t;
    }
  I[0] = I[1] = I[2] = 0;
  for (int i = 0; i + 1 < n; i++) {
    long double lo = fmaxl(cuts[i], t0), hi = fminl(cuts[i + 1], t1);
    if (hi > lo) simpson(a, o, d, lo, hi, 20000, I);
  }
}

static double worst = 0;

/* Checks the three integrals along o + t d over the part inside the
 * atmosphere and above the ground. */
static void check_ray(const sh_atmosphere *a, sh_vec3 o, sh_vec3 d) {
  d = sh_normalize(d);
  double t0, t1, tg;
  if (!sh_atmosphere_clip(a, o, d, 0, INFINITY, &t0, &t1)) return;
  if (sh_atmosphere_ground_hit(a, o, d, t1, &tg)) t1 = tg;
  if (!(t1 > t0)) return;
  double got[3];
  long double want[3];
  sh_atmosphere_density_integrals(a, o, d, t0, t1, got);
  reference(a, o, d, t0, t1, want);
  /* Each channel's optical depth: the three integrals times the
   * coefficients (a part's own integral can be a sliver, such as the
   * ozone tent's edge grazed, whose relative error says nothing). */
  for (int k = 0; k < 3; k++) {
    long double cr = sh_vget(a->rayleigh_sigma_s, k);
    long double cm = sh_vget(a->mie_sigma_s, k) + sh_vget(a->mie_sigma_a, k);
    long double co = sh_vget(a->ozone_sigma_a, k);
    long double w = cr * want[0] + cm * want[1] + co * want[2];
    long double g = cr * got[0] + cm * got[1] + co * got[2];
    double rel = (double)fabsl((g - w) / w);
    if (rel > worst) worst = rel;
    if (rel > SH_ATMOSPHERE_DEPTH_REL_ERROR)
      fprintf(stderr, "ray o (%g %g %g) d (%g %g %g) channel %d: %.12Lg vs %.12Lg\n",
              o.x, o.y, o.z, d.x, d.y, d.z, k, g, w);
    SH_CHECK(rel <= SH_ATMOSPHERE_DEPTH_REL_ERROR);
  }
}

static sh_vec3 random_dir(sh_rng *r) {
  double z = 2 * sh_rng_next(r) - 1, phi = 2 * SH_PI * sh_rng_next(r);
  double s = sqrt(1 - z * z);
  return sh_v3(s * cos(phi), z, s * sin(phi));
}

static void test_depth_against_quadrature(void) {
  sh_atmosphere a = earth();
  sh_rng r;
  sh_rng_seed(&r, 12, 1);
  /* Vertical, horizontal and tangent rays at chosen heights. */
  double hs[] = {0.001, 0.5, 1, 5, 10, 25, 40, 59.9};
  for (int i = 0; i < 8; i++) {
    sh_vec3 o = sh_v3(0, hs[i], 0);
    check_ray(&a, o, sh_v3(0, 1, 0));
    check_ray(&a, o, sh_v3(1, 0, 0));
    check_ray(&a, o, sh_v3(1, -1e-4, 0.3));
    check_ray(&a, o, sh_v3(1, 0.01, 0));
    check_ray(&a, o, sh_v3(0.2, -1, 0)); /* down to the ground */
    check_ray(&a, sh_v3(-3000, hs[i], 0), sh_v3(1, 0, 0)); /* tangent at hs */
  }
  /* From the ground and from low heights in every direction. */
  for (int i = 0; i < 150; i++) {
    double h = 0.001 + 20 * sh_rng_next(&r) * sh_rng_next(&r);
    check_ray(&a, sh_v3(0, h, 0), random_dir(&r));
  }
  /* From 30,000 km, at random points of the planet's disk and limb. */
  sh_vec3 far = sh_v3(0, -6360, 36360);
  for (int i = 0; i < 100; i++) {
    double ang = 2 * SH_PI * sh_rng_next(&r);
    double rad = 6300 + 130 * sh_rng_next(&r);
    if (i % 2) rad = 6420 * sqrt(sh_rng_next(&r));
    sh_vec3 target = sh_v3(rad * cos(ang), -6360 + rad * sin(ang), 0);
    check_ray(&a, far, sh_sub(target, far));
  }
  fprintf(stderr, "atmosphere optical depth: largest relative error %.2e "
                  "against Simpson (bound %.0e)\n",
          worst, SH_ATMOSPHERE_DEPTH_REL_ERROR);
}

/* The zenith from the ground: each exponential gives sigma H (1 -
 * exp(-h_top / H)), the ozone tent (wholly below the top) sigma_a w / 2. */
static void test_zenith(void) {
  sh_atmosphere a = earth();
  sh_medium m = {0};
  m.present = 1;
  m.type = SH_MEDIUM_ATMOSPHERE;
  m.atmo = a;
  double ht = a.top_radius - a.ground_radius;
  for (int k = 0; k < 3; k++) {
    double sr = sh_vget(a.rayleigh_sigma_s, k);
    double sm = sh_vget(a.mie_sigma_s, k) + sh_vget(a.mie_sigma_a, k);
    double so = sh_vget(a.ozone_sigma_a, k);
    double want = sr * a.rayleigh_H * -expm1(-ht / a.rayleigh_H) +
                  sm * a.mie_H * -expm1(-ht / a.mie_H) + so * a.ozone_width / 2;
    sh_vec3 tau = sh_medium_optical_depth_ray(&m, sh_v3(0, 0, 0), sh_v3(0, 1, 0));
    SH_CHECK_NEAR(sh_vget(tau, k), want, 1e-10, 0);
    sh_vec3 tr = sh_medium_transmittance_ray(&m, sh_v3(0, 0, 0), sh_v3(0, 1, 0));
    SH_CHECK_NEAR(sh_vget(tr, k), exp(-want), 1e-10, 0);
  }
  /* The same column seen from far above, straight down to the ground. */
  sh_vec3 tau = sh_medium_optical_depth(&m, sh_v3(0, 30000, 0), sh_v3(0, 0, 0));
  double want = 5.802e-3 * 8 * -expm1(-60 / 8.0) +
                4.44e-3 * 1.2 * -expm1(-60 / 1.2) + 0.650e-3 * 15;
  SH_CHECK_NEAR(tau.x, want, 1e-10, 0);
  /* Through the planet: opaque. */
  tau = sh_medium_optical_depth(&m, sh_v3(-7000, -6360, 0), sh_v3(7000, -6360, 0));
  SH_CHECK(isinf(tau.x));
  SH_CHECK(sh_medium_transmittance(&m, sh_v3(-7000, -6360, 0),
                                   sh_v3(7000, -6360, 0)).y == 0);
}

/* 2 pi * integral over cos alpha in [-1, 1] of each channel. */
static sh_vec3 phase_integral(const sh_atmosphere *a, sh_vec3 p) {
  const int n = 200000;
  double h = 2.0 / n;
  sh_vec3 s = sh_v3s(0);
  for (int i = 0; i <= n; i++) {
    double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    s = sh_madd(s, sh_atmosphere_phase(a, p, -1.0 + i * h), w);
  }
  return sh_scale(s, 2.0 * SH_PI * h / 3.0);
}

static void test_phase(void) {
  sh_atmosphere a = earth();
  const sh_phase rayleigh = {SH_PHASE_RAYLEIGH, 0};
  /* Rayleigh's 3 (1 + c^2) / (16 pi). */
  SH_CHECK_NEAR(sh_phase_eval(&rayleigh, 0.3), 3 * 1.09 / (16 * SH_PI), 1e-15, 0);
  double heights[] = {0, 1, 8, 30};
  for (int i = 0; i < 4; i++) {
    sh_vec3 p = sh_v3(0, heights[i], 0);
    sh_vec3 s = phase_integral(&a, p);
    SH_CHECK_NEAR(s.x, 1, 1e-6, 0);
    SH_CHECK_NEAR(s.y, 1, 1e-6, 0);
    SH_CHECK_NEAR(s.z, 1, 1e-6, 0);
    /* The mixture times sigma_s is the scattering, channel by channel. */
    sh_vec3 f = sh_atmosphere_scattering(&a, p, 0.9);
    sh_vec3 g = sh_mul(sh_atmosphere_sigma_s(&a, p), sh_atmosphere_phase(&a, p, 0.9));
    SH_CHECK_NEAR(f.z, g.z, 1e-13, 0);
  }
  /* The mixture's weights: at the ground, red is Mie's more than blue. */
  sh_vec3 p0 = sh_v3(0, 0, 0), ph = sh_atmosphere_phase(&a, p0, 1.0);
  SH_CHECK(ph.x > ph.z);
  double wm = 3.996e-3 / (3.996e-3 + 5.802e-3);
  double want = wm * sh_phase_eval(&a.mie_phase, 1.0) +
                (1 - wm) * sh_phase_eval(&rayleigh, 1.0);
  SH_CHECK_NEAR(ph.x, want, 1e-12, 0);
}

/* The majorant bounds sigma_t along spans; distance sampling's density
 * integrates to 1 (the mean of 1 / pdf over stratified u is the length)
 * and its samples stay in the span. */
static void test_majorant_and_sampling(void) {
  sh_medium m = {0};
  m.present = 1;
  m.type = SH_MEDIUM_ATMOSPHERE;
  m.atmo = earth();
  sh_rng r;
  sh_rng_seed(&r, 5, 2);
  for (int i = 0; i < 20; i++) {
    sh_vec3 o = sh_v3(0, 0.001 + 30 * sh_rng_next(&r), 0), d = random_dir(&r);
    double t0, t1, tg;
    if (!sh_medium_clip(&m, o, d, 0, INFINITY, &t0, &t1)) continue;
    if (sh_medium_ground_hit(&m, o, d, t1, &tg)) t1 = tg;
    sh_vec3 maj = sh_medium_majorant(&m, o, d, t0, t1);
    sh_vec3 tau = sh_medium_optical_depth_span(&m, o, d, t0, t1);
    double K = (tau.x + tau.y + tau.z) / 3;
    const int n = 20000;
    double sum = 0;
    int inside = 1, below = 1, slope = 0, slopes = 0;
    for (int j = 0; j < n; j++) {
      double ip, u = (j + 0.5) / n;
      double t = sh_medium_sample_distance(&m, o, d, t0, t1, u, &ip);
      inside &= t >= t0 && t <= t1;
      sum += ip;
      sh_vec3 s = sh_medium_sigma_t_at(&m, sh_madd(o, d, t0 + (t1 - t0) * u));
      below &= s.x <= maj.x * (1 + 1e-12) && s.z <= maj.z * (1 + 1e-12);
      /* t(u) inverts the distribution: dt/du = 1 / pdf, away from the
       * panels' edges. */
      if (j % 100 == 0) {
        double ia, ib, e = 1e-7;
        double ta = sh_medium_sample_distance(&m, o, d, t0, t1, u - e, &ia);
        double tb = sh_medium_sample_distance(&m, o, d, t0, t1, u + e, &ib);
        slopes++;
        slope += fabs((tb - ta) / (2 * e) - ip) <= 1e-4 * ip;
      }
    }
    SH_CHECK(inside);
    SH_CHECK(below);
    SH_CHECK(slope >= slopes - 3);
    /* The mean of 1 / pdf is the length (its variance grows as exp(K)). */
    if (K < 2) SH_CHECK_NEAR(sum / n, t1 - t0, 5e-3, 0);
  }
}

/* An eye 1 m above a ground of 6360 km: the ground's hit is exact to the
 * length's precision, points on the ground see the sun above their horizon
 * and not below it, without offsets. */
static void test_ground(void) {
  sh_atmosphere a = earth();
  sh_vec3 eye = sh_v3(0, 0.001, 0);
  double t;
  /* 45 degrees down: the sphere's near root, by the exact formula
   * t = -b - sqrt(b^2 - c) with b = -R' / sqrt 2, R' = 6360.001. */
  SH_CHECK(sh_atmosphere_ground_hit(&a, eye, sh_normalize(sh_v3(1, -1, 0)), INFINITY, &t));
  long double Rp = (long double)(eye.y - a.center.y), b = -Rp / sqrtl(2.0L);
  long double c = Rp * Rp - 6360.0L * 6360.0L;
  long double want = c / (-b + sqrtl(b * b - c));
  SH_CHECK_NEAR(t, (double)want, 1e-12, 0);
  /* Looking just above the horizon misses; just below hits far away. */
  double dip = sqrt(2 * 0.001 / 6360.0); /* the horizon's dip */
  SH_CHECK(!sh_atmosphere_ground_hit(&a, eye, sh_normalize(sh_v3(1, -dip * 0.99, 0)),
                                     INFINITY, &t));
  SH_CHECK(sh_atmosphere_ground_hit(&a, eye, sh_normalize(sh_v3(1, -dip * 1.01, 0)),
                                    INFINITY, &t));
  SH_CHECK(t > 3.0 && t < 3.2); /* 1% below the horizon (at 3.57 km): 3.1 km */
  /* Points on the ground at many places: the sun 1e-6 above the local
   * horizon lights them, 1e-6 below it does not. */
  sh_rng r;
  sh_rng_seed(&r, 9, 3);
  for (int i = 0; i < 1000; i++) {
    sh_vec3 n = random_dir(&r);
    sh_vec3 p = sh_madd(a.center, n, a.ground_radius);
    sh_vec3 tg = sh_normalize(sh_cross(n, random_dir(&r)));
    SH_CHECK(!sh_atmosphere_ground_blocks(&a, p, sh_normalize(sh_madd(tg, n, 1e-6)), INFINITY));
    SH_CHECK(sh_atmosphere_ground_blocks(&a, p, sh_normalize(sh_madd(tg, n, -1e-6)), INFINITY));
  }
  /* The planet's shadow: a point above the night side. */
  SH_CHECK(sh_atmosphere_ground_blocks(&a, sh_v3(0, -12730, 0), sh_v3(0, 1, 0), INFINITY));
  SH_CHECK(!sh_atmosphere_ground_blocks(&a, sh_v3(0, -12730, 0), sh_v3(0, 1, 0), 10));
}

/* The medium's segment and ray forms agree with the span form along a unit
 * direction, whatever the length of the direction they are given. */
static void test_medium_forms(void) {
  sh_medium m = {0};
  m.present = 1;
  m.type = SH_MEDIUM_ATMOSPHERE;
  m.atmo = earth();
  sh_vec3 a = sh_v3(-300, 2, 40), b = sh_v3(500, 30, -60);
  sh_vec3 d = sh_sub(b, a);
  double len = sh_length(d);
  sh_vec3 u = sh_scale(d, 1 / len);
  sh_vec3 seg = sh_medium_optical_depth(&m, a, b);
  sh_vec3 span = sh_atmosphere_optical_depth(&m.atmo, a, u, 0, len);
  SH_CHECK_NEAR(seg.y, span.y, 1e-14, 0);
  double t0, t1, s0, s1;
  SH_CHECK(sh_medium_clip(&m, a, sh_scale(d, 3.0), 0, INFINITY, &t0, &t1));
  SH_CHECK(sh_atmosphere_clip(&m.atmo, a, u, 0, INFINITY, &s0, &s1));
  SH_CHECK_NEAR(t1 * 3 * len, s1, 1e-12, 0);
  SH_CHECK_NEAR(sh_medium_length(&m, a, b), len, 1e-14, 0);
  sh_vec3 ray = sh_medium_optical_depth_ray(&m, a, u);
  SH_CHECK_NEAR(ray.z, sh_atmosphere_optical_depth(&m.atmo, a, u, 0, s1).z, 1e-14, 0);
  /* The coefficients at a point: sigma_t = sigma_s + sigma_a, and the
   * ground-level sigma_s of the contract's values. */
  sh_vec3 p0 = sh_v3(0, 0, 0);
  sh_vec3 st = sh_medium_sigma_t_at(&m, p0);
  sh_vec3 ss = sh_medium_sigma_s_at(&m, p0), sa = sh_medium_sigma_a_at(&m, p0);
  SH_CHECK_NEAR(st.x, ss.x + sa.x, 1e-15, 0);
  SH_CHECK_NEAR(ss.z, 33.1e-3 + 3.996e-3, 1e-14, 0);
  SH_CHECK_NEAR(sa.z, 0.444e-3, 1e-14, 0); /* no ozone at the ground */
  sh_vec3 p25 = sh_v3(0, 25, 0);
  SH_CHECK_NEAR(sh_medium_sigma_a_at(&m, p25).y,
                0.444e-3 * exp(-25 / 1.2) + 1.881e-3, 1e-12, 0);
  SH_CHECK(!strcmp(sh_medium_type_name(m.type), "atmosphere"));
  /* A point light's floor: 1e-4 of the air's 60 km, not of the box. */
  SH_CHECK_NEAR(sh_medium_light_min_distance(&m), 6e-3, 1e-12, 0);
}

int main(void) {
  test_zenith();
  test_phase();
  test_depth_against_quadrature();
  test_majorant_and_sampling();
  test_ground();
  test_medium_forms();
  SH_TEST_DONE();
}
