#include "gs_atmo_table.h"

#include <math.h>
#include <stdlib.h>

#include "sh_medium.h"

int gs__atmo_hits_ground(double r_ground, double r, double mu) {
  /* The ray's closest approach to the centre, r sqrt(1 - mu^2), is below
   * R_g and in front of the point. */
  return mu < 0.0 && r * r * mu * mu >= (r - r_ground) * (r + r_ground);
}

double gs__atmo_distance_to_sphere(double r, double mu, double R) {
  double disc = r * r * (mu * mu - 1.0) + R * R;
  double s = sqrt(fmax(disc, 0.0));
  /* Upwards the two terms of -r mu + s cancel: (R^2 - r^2) / (r mu + s). */
  if (mu > 0.0) {
    double den = r * mu + s;
    return den > 0.0 ? (R - r) * (R + r) / den : 0.0;
  }
  return s - r * mu;
}

void gs__atmo_table_coords(double rg, double rt, double r, double mu,
                           double *u_r, double *u_mu) {
  r = fmin(fmax(r, rg), rt);
  double H = sqrt((rt - rg) * (rt + rg));
  double rho = sqrt((r - rg) * (r + rg));
  double mu_h = r > 0 ? -rho / r : 0.0; /* the horizon's cosine */
  mu = fmin(fmax(mu, mu_h), 1.0);
  double d = gs__atmo_distance_to_sphere(r, mu, rt);
  double dmin = rt - r, dmax = rho + H;
  *u_r = rho / H;
  *u_mu = dmax > dmin ? fmin(fmax((d - dmin) / (dmax - dmin), 0.0), 1.0) : 0.0;
}

void gs__atmo_table_point(double rg, double rt, double u_r, double u_mu,
                          double *r, double *mu) {
  double H = sqrt((rt - rg) * (rt + rg));
  double rho = H * u_r;
  *r = sqrt(rho * rho + rg * rg);
  double dmin = rt - *r, dmax = rho + H;
  double d = dmin + u_mu * (dmax - dmin);
  /* Rt^2 = r^2 + d^2 + 2 r d mu, and Rt^2 - r^2 = H^2 - rho^2. */
  double m = d > 0.0 ? (H * H - rho * rho - d * d) / (2.0 * *r * d) : 1.0;
  *mu = fmin(fmax(m, -1.0), 1.0);
}

static sh_vec3 medium_depth(const void *m, sh_vec3 a, sh_vec3 b) {
  return sh_medium_optical_depth((const sh_medium *)m, a, b);
}

gs__atmo_source gs__atmo_source_medium(const sh_medium *m) {
  gs__atmo_source s = {medium_depth, m};
  return s;
}

sh_vec3 gs__atmo_depth_exact(const gs__atmo_source *src,
                             const gs__atmo_shell *shell, double r, double mu) {
  if (gs__atmo_hits_ground(shell->r_ground, r, mu)) return sh_v3s(INFINITY);
  double d = gs__atmo_distance_to_sphere(r, mu, shell->r_top);
  if (!(d > 0.0)) return sh_v3s(0.0);
  sh_vec3 p = sh_add(shell->center, sh_v3(0.0, r, 0.0));
  sh_vec3 dir = sh_v3(sqrt(fmax(0.0, 1.0 - mu * mu)), mu, 0.0);
  return src->depth(src->ctx, p, sh_madd(p, dir, d));
}

sh_status gs__atmo_table_build(gs__atmo_table *t, const gs__atmo_source *src,
                               const gs__atmo_shell *shell, int n_r, int n_mu,
                               sh_error *err) {
  t->tau = NULL;
  if (n_r < 2 || n_mu < 2)
    return sh_error_set(err, SH_ERR_ARG,
                        "an optical-depth table needs at least 2 x 2 texels, "
                        "not %d x %d", n_r, n_mu);
  if (!(shell->r_ground > 0.0 && shell->r_top > shell->r_ground))
    return sh_error_set(err, SH_ERR_ARG,
                        "an atmosphere needs 0 < ground_radius < top_radius "
                        "(%g, %g)", shell->r_ground, shell->r_top);
  t->tau = malloc((size_t)n_r * n_mu * 4 * sizeof *t->tau);
  if (!t->tau) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  t->n_r = n_r;
  t->n_mu = n_mu;
  t->r_ground = shell->r_ground;
  t->r_top = shell->r_top;
  for (int i = 0; i < n_r; i++)
    for (int j = 0; j < n_mu; j++) {
      double r, mu;
      gs__atmo_table_point(t->r_ground, t->r_top, (double)i / (n_r - 1),
                           (double)j / (n_mu - 1), &r, &mu);
      /* The horizon column grazes the ground: take the ray just above it. */
      if (gs__atmo_hits_ground(t->r_ground, r, mu)) {
        double rho = sqrt((r - t->r_ground) * (r + t->r_ground));
        mu = -rho / r + 1e-12;
      }
      sh_vec3 tau = gs__atmo_depth_exact(src, shell, r, mu);
      if (!isfinite(tau.x + tau.y + tau.z)) tau = sh_v3s(0.0);
      tau = sh_v3(log(tau.x + GS__ATMO_TAU_EPS), log(tau.y + GS__ATMO_TAU_EPS),
                  log(tau.z + GS__ATMO_TAU_EPS));
      float *o = t->tau + 4 * ((size_t)i * n_mu + j);
      o[0] = (float)tau.x;
      o[1] = (float)tau.y;
      o[2] = (float)tau.z;
      o[3] = 0.0f;
    }
  return SH_OK;
}

sh_vec3 gs__atmo_table_lookup(const gs__atmo_table *t, double r, double mu) {
  if (gs__atmo_hits_ground(t->r_ground, r, mu)) return sh_v3s(INFINITY);
  double u_r, u_mu;
  gs__atmo_table_coords(t->r_ground, t->r_top, r, mu, &u_r, &u_mu);
  double x = u_mu * (t->n_mu - 1), y = u_r * (t->n_r - 1);
  int j = (int)floor(x), i = (int)floor(y);
  if (j > t->n_mu - 2) j = t->n_mu - 2;
  if (i > t->n_r - 2) i = t->n_r - 2;
  double fx = x - j, fy = y - i;
  double v[3];
  for (int c = 0; c < 3; c++) {
    const float *row0 = t->tau + 4 * (size_t)i * t->n_mu + c;
    const float *row1 = row0 + 4 * (size_t)t->n_mu;
    double a = row0[4 * j] + fx * (row0[4 * (j + 1)] - row0[4 * j]);
    double b = row1[4 * j] + fx * (row1[4 * (j + 1)] - row1[4 * j]);
    v[c] = a + fy * (b - a);
  }
  return sh_v3(fmax(exp(v[0]) - GS__ATMO_TAU_EPS, 0.0),
               fmax(exp(v[1]) - GS__ATMO_TAU_EPS, 0.0),
               fmax(exp(v[2]) - GS__ATMO_TAU_EPS, 0.0));
}

void gs__atmo_table_free(gs__atmo_table *t) {
  free(t->tau);
  t->tau = NULL;
}
