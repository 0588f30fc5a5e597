/* For the atmosphere's tests: an independent numerical integration of the
 * contract's atmosphere in double precision (composite 5-point
 * Gauss-Legendre, the ray split where the ozone's profile bends), for the
 * optical depth of a segment and the single-scattered radiance of a ray
 * under a directional sun, with the ground a Lambert sphere lit through the
 * air and the planet's shadow. Slow and plain on purpose: it shares no
 * code with the shaders, nor with the tables (only gs__atmo's densities). */
#ifndef ATMO_QUAD_H
#define ATMO_QUAD_H

#include <math.h>

#include "gs_atmo.h"
#include "sh_medium.h"

static const double aq__gx[5] = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                 0.5384693101056831, 0.9061798459386640};
static const double aq__gw[5] = {0.2369268850561891, 0.4786286704993665,
                                 0.5688888888888889, 0.4786286704993665,
                                 0.2369268850561891};

/* Earth's atmosphere with the contract's reference values (Bruneton
 * 2017), in km, ground albedo 0.3. */
static inline gs__atmo aq_earth(void) {
  gs__atmo a = {{{0, -6360, 0}, 6360, 6420},
                {0.3, 0.3, 0.3},
                {5.802e-3, 13.558e-3, 33.1e-3}, 8,
                {3.996e-3, 3.996e-3, 3.996e-3}, {0.444e-3, 0.444e-3, 0.444e-3}, 1.2,
                {SH_PHASE_CORNETTE_SHANKS, 0.8},
                {0.650e-3, 1.881e-3, 0.085e-3}, 25, 30};
  return a;
}

/* The parameters t in (0, len) where o + t d (d unit) crosses a sphere of
 * radius R about c; returns how many (0 to 2), into t[]. */
static inline int aq__cross(sh_vec3 o, sh_vec3 d, double len, sh_vec3 c, double R,
                            double *t) {
  sh_vec3 oc = sh_sub(o, c);
  double b = sh_dot(oc, d), q = sh_dot(oc, oc) - R * R, disc = b * b - q;
  if (disc <= 0) return 0;
  double s = sqrt(disc), r0 = -b - s, r1 = -b + s;
  int n = 0;
  if (r0 > 0 && r0 < len) t[n++] = r0;
  if (r1 > 0 && r1 < len) t[n++] = r1;
  return n;
}

/* The cut points of [0, len] (ascending, ends included) where the ozone
 * bends; returns their number. */
static inline int aq__cuts(const gs__atmo *a, sh_vec3 o, sh_vec3 d, double len,
                           double *cut) {
  double radii[3], t[2];
  int nk = gs__atmo_kinks(a, radii), n = 0;
  cut[n++] = 0;
  for (int k = 0; k < nk; k++) {
    int m = aq__cross(o, d, len, a->shell.center, radii[k], t);
    for (int i = 0; i < m; i++) cut[n++] = t[i];
  }
  cut[n++] = len;
  for (int i = 1; i < n; i++) /* insertion sort */
    for (int j = i; j > 0 && cut[j] < cut[j - 1]; j--) {
      double x = cut[j];
      cut[j] = cut[j - 1];
      cut[j - 1] = x;
    }
  return n;
}

static inline double aq__height(const gs__atmo *a, sh_vec3 p) {
  return sh_length(sh_sub(p, a->shell.center)) - a->shell.r_ground;
}

/* The optical depth of the segment [p, q] (gs__segment_depth, ctx a const
 * gs__atmo *), `panels` panels per piece. */
static inline sh_vec3 aq_depth_n(const gs__atmo *a, sh_vec3 p, sh_vec3 q, int panels) {
  double len = sh_length(sh_sub(q, p));
  if (!(len > 0)) return sh_v3s(0);
  sh_vec3 d = sh_scale(sh_sub(q, p), 1.0 / len);
  double cut[8];
  int n = aq__cuts(a, p, d, len, cut);
  sh_vec3 sum = sh_v3s(0);
  for (int i = 0; i + 1 < n; i++) {
    double w = (cut[i + 1] - cut[i]) / panels;
    for (int k = 0; k < panels; k++)
      for (int g = 0; g < 5; g++) {
        double t = cut[i] + w * (k + 0.5 + 0.5 * aq__gx[g]);
        double h = aq__height(a, sh_madd(p, d, t));
        sum = sh_add(sum, sh_scale(gs__atmo_sigma_t(a, h), 0.5 * w * aq__gw[g]));
      }
  }
  return sum;
}

static inline sh_vec3 aq_depth(const void *ctx, sh_vec3 p, sh_vec3 q) {
  return aq_depth_n((const gs__atmo *)ctx, p, q, 64);
}

/* The far parameter of o + t d on the sphere R about c, or -1. */
static inline double aq__exit(sh_vec3 o, sh_vec3 d, sh_vec3 c, double R) {
  sh_vec3 oc = sh_sub(o, c);
  double b = sh_dot(oc, d), disc = b * b - (sh_dot(oc, oc) - R * R);
  return disc < 0 ? -1 : -b + sqrt(disc);
}

/* The first t > 0 where o + t d meets the ground, or -1. */
static inline double aq__ground(const gs__atmo *a, sh_vec3 o, sh_vec3 d) {
  sh_vec3 oc = sh_sub(o, a->shell.center);
  double R = a->shell.r_ground, b = sh_dot(oc, d);
  double q = sh_dot(oc, oc) - R * R, disc = b * b - q;
  if (disc < 0 || b > 0) return -1;
  double t = q / (-b + sqrt(disc));
  return t > 0 ? t : -1;
}

/* The transmittance from p to the sun along the unit direction l towards
 * it: 0 where the ground blocks. */
static inline sh_vec3 aq_sun_tr(const gs__atmo *a, sh_vec3 p, sh_vec3 l) {
  if (aq__ground(a, p, l) > 0) return sh_v3s(0);
  double t = aq__exit(p, l, a->shell.center, a->shell.r_top);
  if (t <= 0) return sh_v3s(1);
  return sh_vexp(sh_neg(aq_depth_n(a, p, sh_madd(p, l, t), 16)));
}

/* The single-scattered radiance towards the eye at o along the unit ray d,
 * under a sun of irradiance E whose light travels along sun_dir (unit),
 * with `steps` Gauss panels along the ray's part in the air (split at the
 * ozone's bends): the in-scattering with Rayleigh's and Mie's phase
 * weighted by their sigma_s, plus the ground's Lambert radiance through the
 * air, plus `background` times the ray's transmittance where it leaves. */
static inline sh_vec3 aq_radiance(const gs__atmo *a, sh_vec3 o, sh_vec3 d, sh_vec3 sun_dir,
                                  sh_vec3 E, sh_vec3 background, int steps) {
  sh_vec3 l = sh_neg(sun_dir);
  double t0 = 0, t1;
  sh_vec3 oc = sh_sub(o, a->shell.center);
  if (sh_dot(oc, oc) > a->shell.r_top * a->shell.r_top) {
    double b = sh_dot(oc, d), disc = b * b - (sh_dot(oc, oc) - a->shell.r_top * a->shell.r_top);
    if (disc <= 0 || b > 0) return background;
    t0 = -b - sqrt(disc);
  }
  double tg = aq__ground(a, o, d);
  t1 = tg > 0 ? tg : aq__exit(o, d, a->shell.center, a->shell.r_top);
  /* cos alpha: the light travels along sun_dir, the eye lies along -d. */
  double c = sh_dot(sun_dir, sh_neg(d));
  sh_phase ray = {SH_PHASE_RAYLEIGH, 0};
  double pr = sh_phase_eval(&ray, c), pm = sh_phase_eval(&a->mie_phase, c);
  sh_vec3 o0 = sh_madd(o, d, t0);
  double len = t1 - t0, cut[8];
  int n = aq__cuts(a, o0, d, len, cut);
  sh_vec3 L = sh_v3s(0), tau = sh_v3s(0);
  double tprev = 0;
  for (int i = 0; i + 1 < n; i++) {
    double w = (cut[i + 1] - cut[i]) / steps;
    for (int k = 0; k < steps; k++)
      for (int g = 0; g < 5; g++) {
        double t = cut[i] + w * (k + 0.5 + 0.5 * aq__gx[g]);
        sh_vec3 p = sh_madd(o0, d, t);
        tau = sh_add(tau, aq_depth_n(a, sh_madd(o0, d, tprev), p, 1));
        tprev = t;
        double h = aq__height(a, p), dr, dm, dz;
        gs__atmo_density(a, h, &dr, &dm, &dz);
        sh_vec3 s = sh_add(sh_scale(a->rayleigh_s, dr * pr), sh_scale(a->mie_s, dm * pm));
        sh_vec3 f = sh_mul(sh_mul(s, aq_sun_tr(a, p, l)), sh_vexp(sh_neg(tau)));
        L = sh_add(L, sh_scale(sh_mul(f, E), 0.5 * w * aq__gw[g]));
      }
  }
  tau = sh_add(tau, aq_depth_n(a, sh_madd(o0, d, tprev), sh_madd(o0, d, len), 1));
  sh_vec3 Tr = sh_vexp(sh_neg(tau));
  if (tg > 0) {
    sh_vec3 p = sh_madd(o, d, tg);
    sh_vec3 n = sh_normalize(sh_sub(p, a->shell.center));
    double cosl = sh_dot(n, l);
    if (cosl > 0) {
      sh_vec3 Eg = sh_scale(sh_mul(E, aq_sun_tr(a, sh_madd(p, n, 1e-9 * a->shell.r_ground), l)), cosl);
      L = sh_add(L, sh_mul(Tr, sh_scale(sh_mul(a->ground_albedo, Eg), 1.0 / SH_PI)));
    }
  } else {
    L = sh_add(L, sh_mul(Tr, background));
  }
  return L;
}

#endif
