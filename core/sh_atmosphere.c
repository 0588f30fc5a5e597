#include "sh_atmosphere.h"

#include <math.h>
#include <stddef.h>

#include "sh_medium.h"

/* Gauss-Legendre nodes and weights on [-1, 1], positive half (8 points). */
static const double GL_X[4] = {0.1834346424956498, 0.5255324099163290,
                               0.7966664774136267, 0.9602898564975363};
static const double GL_W[4] = {0.3626837833783620, 0.3137066458778873,
                               0.2223810344533745, 0.1012285362903763};

/* A density is dropped beyond this many of its scale heights above a
 * piece's lowest point. */
#define DROP_SCALE_HEIGHTS 36.0

int sh_sphere_roots(sh_vec3 center, double R, sh_vec3 o, sh_vec3 d,
                    double *ta, double *tb) {
  sh_vec3 oc = sh_sub(o, center);
  double b = sh_dot(oc, d);
  sh_vec3 perp = sh_madd(oc, d, -b); /* the line's nearest point */
  double rp = sh_length(perp);
  if (!(rp <= R)) return 0;
  double q = sqrt((R - rp) * (R + rp)); /* half the chord */
  double len = sh_length(oc);
  double c = (len - R) * (len + R);
  /* t^2 + 2 b t + c = 0: the root away from 0 without cancellation, the
   * other as c over it. */
  double big = b > 0 ? -b - q : -b + q;
  double small = big != 0 ? c / big : 0.0;
  *ta = fmin(big, small);
  *tb = fmax(big, small);
  return 1;
}

double sh_atmosphere_height(const sh_atmosphere *a, sh_vec3 p) {
  return sh_length(sh_sub(p, a->center)) - a->ground_radius;
}

void sh_atmosphere_densities(const sh_atmosphere *a, double h, double rho[3]) {
  rho[0] = exp(-h / a->rayleigh_H);
  rho[1] = a->has_mie ? exp(-h / a->mie_H) : 0.0;
  rho[2] = a->has_ozone
               ? fmax(0.0, 1.0 - fabs(h - a->ozone_height) /
                                     (0.5 * a->ozone_width))
               : 0.0;
}

/* Optical depth from the three density integrals. */
static sh_vec3 depth_of(const sh_atmosphere *a, const double I[3]) {
  sh_vec3 mie_t = sh_add(a->mie_sigma_s, a->mie_sigma_a);
  sh_vec3 tau = sh_scale(a->rayleigh_sigma_s, I[0]);
  if (a->has_mie) tau = sh_madd(tau, mie_t, I[1]);
  if (a->has_ozone) tau = sh_madd(tau, a->ozone_sigma_a, I[2]);
  return tau;
}

sh_vec3 sh_atmosphere_sigma_s(const sh_atmosphere *a, sh_vec3 p) {
  double rho[3];
  sh_atmosphere_densities(a, sh_atmosphere_height(a, p), rho);
  return sh_add(sh_scale(a->rayleigh_sigma_s, rho[0]),
                sh_scale(a->mie_sigma_s, rho[1]));
}

sh_vec3 sh_atmosphere_sigma_a(const sh_atmosphere *a, sh_vec3 p) {
  double rho[3];
  sh_atmosphere_densities(a, sh_atmosphere_height(a, p), rho);
  return sh_add(sh_scale(a->mie_sigma_a, rho[1]),
                sh_scale(a->ozone_sigma_a, rho[2]));
}

sh_vec3 sh_atmosphere_scattering(const sh_atmosphere *a, sh_vec3 p,
                                 double cos_alpha) {
  double rho[3];
  sh_atmosphere_densities(a, sh_atmosphere_height(a, p), rho);
  const sh_phase rayleigh = {SH_PHASE_RAYLEIGH, 0.0};
  sh_vec3 s = sh_scale(a->rayleigh_sigma_s,
                       rho[0] * sh_phase_eval(&rayleigh, cos_alpha));
  if (a->has_mie)
    s = sh_madd(s, a->mie_sigma_s,
                rho[1] * sh_phase_eval(&a->mie_phase, cos_alpha));
  return s;
}

sh_vec3 sh_atmosphere_phase(const sh_atmosphere *a, sh_vec3 p,
                            double cos_alpha) {
  sh_vec3 s = sh_atmosphere_sigma_s(a, p);
  sh_vec3 f = sh_atmosphere_scattering(a, p, cos_alpha);
  const sh_phase rayleigh = {SH_PHASE_RAYLEIGH, 0.0};
  double pr = sh_phase_eval(&rayleigh, cos_alpha);
  return sh_v3(s.x > 0 ? f.x / s.x : pr, s.y > 0 ? f.y / s.y : pr,
               s.z > 0 ? f.z / s.z : pr);
}

int sh_atmosphere_clip(const sh_atmosphere *a, sh_vec3 o, sh_vec3 d,
                       double tmin, double tmax, double *t0, double *t1) {
  double ta, tb;
  if (!sh_sphere_roots(a->center, a->top_radius, o, d, &ta, &tb)) return 0;
  *t0 = fmax(ta, tmin);
  *t1 = fmin(tb, tmax);
  return *t1 > *t0;
}

/* One quadrature panel of a span: [ta, tb] along the ray and the integrals
 * of the three densities over it. */
typedef struct panel {
  double ta, tb;
  double I[3];
} panel;

/* Room for a piece's panels: at most DROP / PANEL + 1 steps for each of
 * the two exponentials, 3 kinks, and 4 panels after both are dropped (up
 * to the kinks and the end). A piece that would need more (it cannot)
 * ends in one last panel. */
#define PIECE_PANELS ((int)(2 * DROP_SCALE_HEIGHTS / SH_ATMOSPHERE_PANEL) + 16)
#define MAX_PANELS (2 * PIECE_PANELS)

/* The line o + t d about the planet: t = tc + s, r(s) = sqrt(rm2 + s^2). */
typedef struct line {
  const sh_atmosphere *a;
  double tc, rm2;
} line;

/* Integrates one piece, from |s| = sl (its lowest point) to sh, on the
 * side `sign` (+1: t = tc + s, -1: t = tc - s), appending panels in the
 * order of growing |s| to out (if not NULL) and adding the integrals to
 * I. Returns the number of panels, or -1 if the piece passes below the
 * ground. */
static int piece(const line *L, double sl, double sh, int sign, panel *out,
                 double I[3]) {
  const sh_atmosphere *a = L->a;
  double rl = sqrt(L->rm2 + sl * sl), hl = rl - a->ground_radius;
  if (hl < -1e-9 * a->top_radius) return -1;
  double rh = sqrt(L->rm2 + sh * sh);
  double dmax = (sh - sl) * (sh + sl) / (rh + rl); /* height gained */
  double kinks[3] = {INFINITY, INFINITY, INFINITY};
  if (a->has_ozone) {
    double w = 0.5 * a->ozone_width;
    kinks[0] = a->ozone_height - w - hl;
    kinks[1] = a->ozone_height - hl;
    kinks[2] = a->ozone_height + w - hl;
  }
  int n = 0;
  double delta = 0.0, s0 = sl;
  while (delta < dmax && s0 < sh) {
    /* The smallest scale height still worth integrating. */
    double H = INFINITY;
    if (delta < DROP_SCALE_HEIGHTS * a->rayleigh_H) H = a->rayleigh_H;
    if (a->has_mie && delta < DROP_SCALE_HEIGHTS * a->mie_H) H = fmin(H, a->mie_H);
    double next = fmin(delta + SH_ATMOSPHERE_PANEL * H, dmax);
    for (int k = 0; k < 3; k++)
      if (kinks[k] > delta && kinks[k] < next) next = kinks[k];
    if (n == PIECE_PANELS - 1) next = dmax;
    double s1 = next >= dmax ? sh : sqrt(sl * sl + next * (2.0 * rl + next));
    s1 = fmin(s1, sh);
    /* Skip a panel where nothing is left: no exponential worth it and no
     * ozone (the ozone is 0 outside its kinks). */
    int ozone = a->has_ozone && next > kinks[0] && delta < kinks[2];
    double J[3] = {0, 0, 0};
    if (isfinite(H) || ozone) {
      double mid = 0.5 * (s0 + s1), half = 0.5 * (s1 - s0);
      for (int i = 0; i < 8; i++) {
        double x = i < 4 ? -GL_X[i] : GL_X[i - 4];
        double w = GL_W[i < 4 ? i : i - 4];
        double s = mid + half * x;
        double r = sqrt(L->rm2 + s * s);
        double h = hl + (s - sl) * (s + sl) / (r + rl);
        double rho[3];
        sh_atmosphere_densities(a, h, rho);
        J[0] += w * rho[0];
        J[1] += w * rho[1];
        J[2] += w * rho[2];
      }
      for (int k = 0; k < 3; k++) J[k] *= half;
    }
    for (int k = 0; k < 3; k++) I[k] += J[k];
    if (out) {
      double ta = L->tc + sign * s0, tb = L->tc + sign * s1;
      out[n].ta = fmin(ta, tb);
      out[n].tb = fmax(ta, tb);
      for (int k = 0; k < 3; k++) out[n].I[k] = J[k];
    }
    n++;
    delta = next;
    s0 = s1;
  }
  return n;
}

/* Puts the n panels of a piece walked backwards (t decreasing) in the
 * order of t; returns n. */
static int reverse(panel *out, int n) {
  for (int i = 0; out && i < n / 2; i++) {
    panel p = out[i];
    out[i] = out[n - 1 - i];
    out[n - 1 - i] = p;
  }
  return n;
}

/* Walks the span [t0, t1] of o + t d (d unit): fills out (if not NULL,
 * room for MAX_PANELS) with its panels in the order of t and I with the
 * integrals. Returns the number of panels, or -1 if the span passes below
 * the ground. */
static int walk(const sh_atmosphere *a, sh_vec3 o, sh_vec3 d, double t0,
                double t1, panel *out, double I[3]) {
  I[0] = I[1] = I[2] = 0.0;
  if (!(t1 > t0)) return 0;
  sh_vec3 oc = sh_sub(o, a->center);
  double b = sh_dot(oc, d);
  sh_vec3 perp = sh_madd(oc, d, -b);
  line L = {a, -b, sh_dot(perp, perp)};
  double s0 = t0 - L.tc, s1 = t1 - L.tc;
  if (s0 >= 0) return piece(&L, s0, s1, 1, out, I);
  if (s1 <= 0) return reverse(out, piece(&L, -s1, -s0, -1, out, I));
  int n = reverse(out, piece(&L, 0.0, -s0, -1, out, I));
  if (n < 0) return -1;
  int m = piece(&L, 0.0, s1, 1, out ? out + n : NULL, I);
  return m < 0 ? -1 : n + m;
}

void sh_atmosphere_density_integrals(const sh_atmosphere *a, sh_vec3 o,
                                     sh_vec3 d, double t0, double t1,
                                     double integral[3]) {
  if (walk(a, o, d, t0, t1, NULL, integral) < 0)
    integral[0] = integral[1] = integral[2] = INFINITY;
}

sh_vec3 sh_atmosphere_optical_depth(const sh_atmosphere *a, sh_vec3 o,
                                    sh_vec3 d, double t0, double t1) {
  double I[3];
  if (walk(a, o, d, t0, t1, NULL, I) < 0) return sh_v3s(INFINITY);
  return depth_of(a, I);
}

sh_vec3 sh_atmosphere_majorant(const sh_atmosphere *a, sh_vec3 o, sh_vec3 d,
                               double t0, double t1) {
  sh_vec3 oc = sh_sub(o, a->center);
  double tc = -sh_dot(oc, d);
  double tl = sh_clamp(tc, t0, t1);
  double hlo = sh_atmosphere_height(a, sh_madd(o, d, tl));
  double hhi = fmax(sh_atmosphere_height(a, sh_madd(o, d, t0)),
                    sh_atmosphere_height(a, sh_madd(o, d, t1)));
  double rho[3];
  sh_atmosphere_densities(a, hlo, rho);
  /* The tent's largest value over [hlo, hhi]: at its peak if that lies
   * inside, else at the nearer end. */
  if (a->has_ozone) {
    double hp = sh_clamp(a->ozone_height, hlo, hhi);
    double r2[3];
    sh_atmosphere_densities(a, hp, r2);
    rho[2] = r2[2];
  }
  return depth_of(a, rho);
}

double sh_atmosphere_sample_distance(const sh_atmosphere *a, sh_vec3 o,
                                     sh_vec3 d, double t0, double t1,
                                     double u, double *inv_pdf) {
  panel p[MAX_PANELS];
  double I[3];
  double len = t1 - t0;
  int n = walk(a, o, d, t0, t1, p, I);
  double K = 0.0;
  if (n > 0) {
    sh_vec3 tau = depth_of(a, I);
    K = (tau.x + tau.y + tau.z) / 3.0;
  }
  if (n <= 0 || !(K >= 1e-6) || !isfinite(K)) {
    *inv_pdf = len;
    return t0 + u * len;
  }
  double norm = -expm1(-K); /* 1 - exp(-K) */
  double target = -log1p(-u * norm);
  double cum = 0.0;
  int last = -1;
  for (int j = 0; j < n; j++) {
    sh_vec3 tj = depth_of(a, p[j].I);
    double kj = (tj.x + tj.y + tj.z) / 3.0;
    if (!(kj > 0) || !(p[j].tb > p[j].ta)) continue;
    last = j;
    if (target < cum + kj || j == n - 1) {
      double lambda = kj / (p[j].tb - p[j].ta);
      double t = sh_clamp(p[j].ta + (target - cum) / lambda, p[j].ta, p[j].tb);
      double tau_t = cum + lambda * (t - p[j].ta);
      *inv_pdf = norm / (lambda * exp(-tau_t));
      return t;
    }
    cum += kj;
  }
  /* Rounding left the target past the last panel with mass: its end. */
  if (last >= 0) {
    sh_vec3 tj = depth_of(a, p[last].I);
    double kj = (tj.x + tj.y + tj.z) / 3.0;
    double lambda = kj / (p[last].tb - p[last].ta);
    *inv_pdf = norm / (lambda * exp(-cum));
    return p[last].tb;
  }
  *inv_pdf = len;
  return t0 + u * len;
}

int sh_atmosphere_ground_hit(const sh_atmosphere *a, sh_vec3 o, sh_vec3 d,
                             double tmax, double *t) {
  double ta, tb;
  if (!sh_sphere_roots(a->center, a->ground_radius, o, d, &ta, &tb)) return 0;
  double th = ta > 0 ? ta : tb;
  if (!(th > 0) || !(th < tmax)) return 0;
  *t = th;
  return 1;
}

int sh_atmosphere_ground_blocks(const sh_atmosphere *a, sh_vec3 x, sh_vec3 w,
                                double tmax) {
  sh_vec3 oc = sh_sub(x, a->center);
  /* Going away from the centre (at or above the horizon) from a point at
   * or above the ground: never blocked. */
  if (sh_dot(oc, w) >= 0) return 0;
  double ta, tb;
  if (!sh_sphere_roots(a->center, a->ground_radius, x, w, &ta, &tb)) return 0;
  return tb > 0 && ta < tmax;
}
