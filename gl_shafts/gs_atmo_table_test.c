/* The atmosphere's optical-depth table (gs_atmo_table.h): its coordinates
 * and their inverse, the ray geometry, and the interpolation error of the
 * table against the medium's own optical depth (sh_medium_optical_depth)
 * at points between the texels. `ctest -R gs_atmo_table -V` prints the
 * measured errors. */
#include <stdio.h>
#include <stdlib.h>

#include "atmo_quad.h"
#include "gs_atmo_table.h"
#include "sh_rng.h"
#include "sh_test.h"


/* |a - b| / b over the channels, the largest. */
/* Field by field: gs__atmo holds padding (after sh_phase's enum), whose
 * bytes an initialiser leaves indeterminate, so a memcmp of two equal
 * atmospheres failed in a fresh-clone CI build. */
static int same_vec(sh_vec3 a, sh_vec3 b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}
static int same_atmo(const gs__atmo *a, const gs__atmo *b) {
  return same_vec(a->shell.center, b->shell.center) &&
         a->shell.r_ground == b->shell.r_ground &&
         a->shell.r_top == b->shell.r_top &&
         same_vec(a->ground_albedo, b->ground_albedo) &&
         same_vec(a->rayleigh_s, b->rayleigh_s) && a->rayleigh_h == b->rayleigh_h &&
         same_vec(a->mie_s, b->mie_s) && same_vec(a->mie_a, b->mie_a) &&
         a->mie_h == b->mie_h && a->mie_phase.type == b->mie_phase.type &&
         a->mie_phase.g == b->mie_phase.g && same_vec(a->ozone_a, b->ozone_a) &&
         a->ozone_center == b->ozone_center && a->ozone_width == b->ozone_width;
}

static double rel(sh_vec3 a, sh_vec3 b) {
  double e = 0;
  for (int c = 0; c < 3; c++) {
    double x = sh_vget(a, c), y = sh_vget(b, c);
    double d = fabs(x - y) / fmax(fabs(y), 1e-300);
    if (d > e) e = d;
  }
  return e;
}

static void geometry(void) {
  const double rg = 6360, rt = 6420;
  /* Coordinates and their inverse. */
  double worst = 0;
  for (int i = 0; i <= 20; i++)
    for (int j = 0; j <= 40; j++) {
      double ur = i / 20.0, umu = j / 40.0, r, mu, ur2, umu2;
      gs__atmo_table_point(rg, rt, ur, umu, &r, &mu);
      gs__atmo_table_coords(rg, rt, r, mu, &ur2, &umu2);
      worst = fmax(worst, fmax(fabs(ur2 - ur), fabs(umu2 - umu)));
    }
  printf("coordinates' round trip: largest difference %.2e\n", worst);
  SH_CHECK(worst < 1e-6);
  /* u_mu = 0 is the zenith, 1 the horizon. */
  double ur, umu;
  gs__atmo_table_coords(rg, rt, rg + 1, 1.0, &ur, &umu);
  SH_CHECK_NEAR(umu, 0.0, 0, 1e-12);
  double rho = sqrt(1.0 * (2 * rg + 1));
  gs__atmo_table_coords(rg, rt, rg + 1, -rho / (rg + 1), &ur, &umu);
  SH_CHECK_NEAR(umu, 1.0, 0, 1e-9);
  SH_CHECK_NEAR(ur, rho / sqrt((rt - rg) * (rt + rg)), 1e-12, 0);

  /* The distance to the top against the plain formula in long double,
   * from 1 mm above the ground (where the plain double formula cancels). */
  double dworst = 0;
  for (int k = 0; k <= 200; k++) {
    double r = rg + 1e-6 * pow(1e7, k / 200.0);
    if (r > rt) r = rt;
    for (int j = 0; j <= 50; j++) {
      double mu = -1 + 2 * j / 50.0;
      long double lr = r, lmu = mu, R = rt;
      long double d = -lr * lmu + sqrtl(lr * lr * (lmu * lmu - 1) + R * R);
      double got = gs__atmo_distance_to_sphere(r, mu, rt);
      dworst = fmax(dworst, fabs(got - (double)d) / (double)d);
    }
  }
  printf("distance to the top: largest relative difference %.2e\n", dworst);
  SH_CHECK(dworst < 1e-12);

  /* The ground: straight down and just below the horizon meet it, just
   * above and up do not. */
  double r = rg + 0.001, mh = -sqrt(0.001 * (2 * rg + 0.001)) / r;
  SH_CHECK(gs__atmo_hits_ground(rg, r, -1.0));
  SH_CHECK(gs__atmo_hits_ground(rg, r, mh - 1e-9));
  SH_CHECK(!gs__atmo_hits_ground(rg, r, mh + 1e-9));
  SH_CHECK(!gs__atmo_hits_ground(rg, r, 0.0));
}

/* The table against its source at random points between the texels.
 * What the renderer needs is the transmittance exp(-tau), whose relative
 * error is exp(-(tau_table - tau)) - 1, about the absolute error of tau:
 * its largest and RMS value, and the largest relative error of tau where
 * tau is above 0.01 (below, the relative error of tau means nothing for
 * the image). */
static void interpolation(const gs__atmo_source *src, const gs__atmo_shell *shell,
                          int n_r, int n_mu, double bound_tr, double bound_rel) {
  gs__atmo_table t;
  sh_error err = SH_ERROR_INIT;
  sh_status st = gs__atmo_table_build(&t, src, shell, n_r, n_mu, &err);
  SH_CHECK(st == SH_OK);
  if (st != SH_OK) return;
  sh_rng rng;
  sh_rng_seed(&rng, 12, 0);
  double worst = 0, sum2 = 0, worst_rel = 0, at[2] = {0, 0};
  int n = 0, ground = 0;
  for (int k = 0; k < 4000; k++) {
    /* Heights over the shell, more of them near the ground (the sky's eye
     * and the dense air); directions uniform in mu. */
    double h = (shell->r_top - shell->r_ground) * pow(sh_rng_next(&rng), 3);
    double r = shell->r_ground + h, mu = -1 + 2 * sh_rng_next(&rng);
    sh_vec3 exact = gs__atmo_depth_exact(src, shell, r, mu);
    sh_vec3 got = gs__atmo_table_lookup(&t, r, mu);
    if (!isfinite(exact.x)) {
      ground++;
      SH_CHECK(!isfinite(got.x) && !isfinite(got.y) && !isfinite(got.z));
      continue;
    }
    for (int c = 0; c < 3; c++) {
      double x = sh_vget(got, c), y = sh_vget(exact, c);
      double e = fabs(expm1(-(x - y)));
      sum2 += e * e;
      n++;
      if (e > worst) {
        worst = e;
        at[0] = h;
        at[1] = mu;
      }
      if (y > 0.01) worst_rel = fmax(worst_rel, fabs(x - y) / y);
    }
  }
  printf("table %d x %d: transmittance relative error largest %.3e (h %.4g, mu "
         "%.5f), RMS %.3e over %d channel values (%d rays meet the ground); "
         "optical depth above 0.01 relative error largest %.3e\n",
         n_r, n_mu, worst, at[0], at[1], sqrt(sum2 / n), n, ground, worst_rel);
  SH_CHECK(worst < bound_tr);
  SH_CHECK(worst_rel < bound_rel);
  gs__atmo_table_free(&t);
  sh_error_clear(&err);
}

int main(void) {
  geometry();

  /* The table is filled from the independent quadrature of atmo_quad.h
   * (its own accuracy checked first) and from the core's medium, which
   * agree. */
  gs__atmo a = aq_earth();
  const gs__atmo_shell *shell = &a.shell;
  gs__atmo_source src = {aq_depth, &a};
  {
    /* The zenith from the ground: the contract's closed form, the sum of
     * sigma H (1 - exp(-h_top / H)) and the ozone's area (its triangle lies
     * inside the shell). */
    sh_vec3 z = gs__atmo_depth_exact(&src, shell, shell->r_ground, 1.0);
    double ht = shell->r_top - shell->r_ground;
    sh_vec3 want = sh_add(
        sh_add(sh_scale(a.rayleigh_s, a.rayleigh_h * -expm1(-ht / a.rayleigh_h)),
               sh_scale(sh_add(a.mie_s, a.mie_a), a.mie_h * -expm1(-ht / a.mie_h))),
        sh_scale(a.ozone_a, 0.5 * a.ozone_width));
    printf("zenith optical depth %.9g %.9g %.9g, closed form %.9g %.9g %.9g\n",
           z.x, z.y, z.z, want.x, want.y, want.z);
    SH_CHECK(rel(z, want) < 1e-9);
    /* A grazing ray, against the quadrature at four times the panels. */
    double r = shell->r_ground + 0.001, mu = -sqrt(0.001 * (2 * 6360 + 0.001)) / r + 1e-7;
    sh_vec3 p = sh_add(shell->center, sh_v3(0, r, 0));
    sh_vec3 dir = sh_v3(sqrt(1 - mu * mu), mu, 0);
    sh_vec3 q = sh_madd(p, dir, gs__atmo_distance_to_sphere(r, mu, shell->r_top));
    double e = rel(aq_depth(&a, p, q), aq_depth_n(&a, p, q, 256));
    printf("quadrature at the horizon: 64 against 256 panels %.2e\n", e);
    SH_CHECK(e < 1e-9);
  }
  {
    /* Texel values are the function's own. */
    gs__atmo_table t;
    sh_error err = SH_ERROR_INIT;
    SH_CHECK(gs__atmo_table_build(&t, &src, shell, 8, 16, &err) == SH_OK);
    double r, mu;
    gs__atmo_table_point(shell->r_ground, shell->r_top, 3 / 7.0, 5 / 15.0, &r, &mu);
    sh_vec3 x = gs__atmo_table_lookup(&t, r, mu);
    sh_vec3 y = gs__atmo_depth_exact(&src, shell, r, mu);
    SH_CHECK(rel(x, y) < 1e-6);
    gs__atmo_table_free(&t);
    SH_CHECK(gs__atmo_table_build(&t, &src, shell, 1, 16, &err) == SH_ERR_ARG);
    sh_error_clear(&err);
  }
  /* gl_shafts' default table and a coarser one. */
  interpolation(&src, shell, 64, 256, 6e-3, 5e-2);
  interpolation(&src, shell, 32, 128, 2e-2, 1.2e-1);

  /* The same atmosphere as the core parses it: its optical depth against
   * the quadrature, and the table filled from it (what gl_shafts does). */
  char json[2048];
  snprintf(json, sizeof json,
           "{\"format\": \"shafts-scene\", \"version\": 1,"
           " \"camera\": {\"position\": [0, 0.001, 0], \"look_at\": [1, 0.001, 0],"
           "  \"fov_y_deg\": 60, \"width\": 8, \"height\": 8},"
           " \"medium\": {\"type\": \"atmosphere\", \"center\": [0, -6360, 0],"
           "  \"ground_radius\": 6360, \"top_radius\": 6420,"
           "  \"rayleigh\": {\"sigma_s\": [%.17g, %.17g, %.17g], \"scale_height\": 8},"
           "  \"mie\": {\"sigma_s\": [%.17g, %.17g, %.17g], \"sigma_a\": [%.17g, %.17g, %.17g],"
           "   \"scale_height\": 1.2, \"phase\": {\"type\": \"cornette_shanks\", \"g\": 0.8}},"
           "  \"ozone\": {\"sigma_a\": [%.17g, %.17g, %.17g], \"center_height\": 25, \"width\": 30}}}",
           a.rayleigh_s.x, a.rayleigh_s.y, a.rayleigh_s.z, a.mie_s.x, a.mie_s.y, a.mie_s.z,
           a.mie_a.x, a.mie_a.y, a.mie_a.z, a.ozone_a.x, a.ozone_a.y, a.ozone_a.z);
  sh_scene *s = sh_test_parse(json, "earth");
  SH_CHECK(s != NULL);
  if (s) {
    gs__atmo b;
    gs__atmo_from_medium(&s->medium, &b);
    b.ground_albedo = a.ground_albedo;
    SH_CHECK(same_atmo(&a, &b));
    gs__atmo_source med = gs__atmo_source_medium(&s->medium);
    sh_rng rng;
    sh_rng_seed(&rng, 7, 0);
    double worst = 0;
    for (int k = 0; k < 300; k++) {
      double r = shell->r_ground + 60 * pow(sh_rng_next(&rng), 3), mu = -1 + 2 * sh_rng_next(&rng);
      sh_vec3 x = gs__atmo_depth_exact(&med, shell, r, mu), y = gs__atmo_depth_exact(&src, shell, r, mu);
      if (isfinite(y.x)) worst = fmax(worst, rel(x, y));
    }
    printf("the core's optical depth against the quadrature: largest relative "
           "difference %.2e over 300 rays\n", worst);
    SH_CHECK(worst < 1e-7);
    interpolation(&med, shell, 64, 256, 6e-3, 5e-2);
    sh_scene_free(s);
  }
  printf("%d checks, %d failed\n", sh_test_checks, sh_test_failures);
  return sh_test_failures ? 1 : 0;
}
