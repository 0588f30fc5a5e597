/* In-scattered radiance against closed forms and fine quadrature. */
#include "sh_inscatter.h"
#include "sh_light.h"
#include "sh_medium.h"
#include "sh_test.h"

#include <string.h>

static sh_scene make_scene(sh_vec3 sigma_s, sh_vec3 sigma_a, sh_phase ph) {
  sh_scene s;
  memset(&s, 0, sizeof s);
  s.medium.present = 1;
  s.medium.sigma_s = sigma_s;
  s.medium.sigma_a = sigma_a;
  s.medium.sigma_t = sh_add(sigma_s, sigma_a);
  s.medium.phase = ph;
  s.medium.bmin = sh_v3s(-100);
  s.medium.bmax = sh_v3s(100);
  return s;
}

/* The in-scattering integral by the midpoint rule with n steps. */
static sh_vec3 quadrature(const sh_scene *s, const sh_light *l, sh_vec3 o,
                          sh_vec3 d, double t0, double t1, int n) {
  sh_vec3 sum = sh_v3s(0);
  double h = (t1 - t0) / n;
  for (int i = 0; i < n; i++) {
    double t = t0 + (i + 0.5) * h;
    sh_vec3 x = sh_madd(o, d, t), wi;
    double dist;
    sh_vec3 e = sh_light_incident(l, x, &wi, &dist);
    double len = l->type == SH_LIGHT_DIRECTIONAL
                     ? sh_medium_length_ray(&s->medium, x, wi)
                     : sh_medium_length(&s->medium, x, l->position);
    /* Homogeneous: exp(-sigma_t length), computed here independently. */
    e = sh_mul(e, sh_vexp(sh_scale(s->medium.sigma_t, -(len + (t - t0)))));
    double p = sh_phase_eval(&s->medium.phase, sh_dot(wi, d));
    sum = sh_add(sum, sh_scale(sh_mul(e, s->medium.sigma_s), p * h));
  }
  return sum;
}

int main(void) {
  sh_rng rng;
  sh_rng_seed(&rng, 1, 2);
  sh_phase iso = {SH_PHASE_ISOTROPIC, 0};

  /* 1. Point light, isotropic, (almost) no extinction: the atan closed form
   * sigma_s I / (4 pi h) (atan((D + b)/h) - atan(b/h)). Equiangular sampling
   * makes the estimate exact up to extinction, whatever the sample count. */
  {
    double ss = 1e-7;
    sh_scene s = make_scene(sh_v3s(ss), sh_v3s(0), iso);
    sh_light l = {0};
    l.type = SH_LIGHT_POINT;
    l.position = sh_v3(1, 2, 3);
    l.intensity = sh_v3(100, 200, 300);
    sh_vec3 c = sh_v3(-4, 0.5, 1), w = sh_normalize(sh_v3(1, 0.2, 0.1));
    double D = 9.0;
    sh_vec3 q = sh_sub(c, l.position);
    double b = sh_dot(w, q), h = sqrt(sh_dot(q, q) - b * b);
    double closed = ss * 100 / (4 * SH_PI * h) * (atan((D + b) / h) - atan(b / h));
    for (int n = 1; n <= 16; n *= 4) {
      sh_vec3 est = sh_inscatter_light(&s, NULL, NULL, 0, &l, c, w, 0, D, n, &rng, NULL,
                                       NULL);
      SH_CHECK_NEAR(est.x, closed, 1e-5, 0);
      SH_CHECK_NEAR(est.z, 3 * closed, 1e-5, 0);
    }
  }

  /* 2. Point light with extinction and HG phase, against fine quadrature. */
  {
    sh_phase hg = {SH_PHASE_HENYEY_GREENSTEIN, 0.6};
    sh_scene s = make_scene(sh_v3(0.2, 0.3, 0.4), sh_v3(0.1, 0, 0.05), hg);
    sh_light l = {0};
    l.type = SH_LIGHT_POINT;
    l.position = sh_v3(0, 1, 0);
    l.intensity = sh_v3s(50);
    sh_vec3 c = sh_v3(-5, 0, 0), w = sh_v3(1, 0, 0);
    sh_vec3 ref = quadrature(&s, &l, c, w, 0, 10, 2000000);
    sh_vec3 est = sh_inscatter_light(&s, NULL, NULL, 0, &l, c, w, 0, 10, 256, &rng,
                                     NULL, NULL);
    SH_CHECK_NEAR(est.x, ref.x, 2e-3, 0);
    SH_CHECK_NEAR(est.y, ref.y, 2e-3, 0);
    SH_CHECK_NEAR(est.z, ref.z, 2e-3, 0);
  }

  /* 3. Spot light: the cone clip changes nothing but the variance. */
  {
    sh_scene s = make_scene(sh_v3s(0.1), sh_v3s(0.02), iso);
    sh_light l = {0};
    l.type = SH_LIGHT_SPOT;
    l.position = sh_v3(0, 3, 0);
    l.direction = sh_v3(0.1, -1, 0);
    l.intensity = sh_v3s(80);
    l.outer_deg = 25;
    l.inner_deg = 15;
    l.exponent = 1;
    sh_light_prepare(&l, sh_v3(0, 1, 0), 0, NULL);
    sh_vec3 c = sh_v3(-4, 0.2, 0.3), w = sh_normalize(sh_v3(1, 0.05, 0));
    sh_vec3 ref = quadrature(&s, &l, c, w, 0, 8, 2000000);
    sh_vec3 est = sh_inscatter_light(&s, NULL, NULL, 0, &l, c, w, 0, 8, 256, &rng, NULL,
                                     NULL);
    SH_CHECK(ref.x > 0);
    SH_CHECK_NEAR(est.x, ref.x, 2e-3, 0);
    double a, b;
    SH_CHECK(sh_light_clip(&l, c, w, 0, 8, &a, &b));
    SH_CHECK(a > 0 && b < 8 && a < b);
    /* A ray that misses the cone. */
    SH_CHECK(!sh_light_clip(&l, sh_v3(-4, 5, 0), sh_v3(1, 0, 0), 0, 8, &a, &b));
  }

  /* 4. Directional light, ray at constant depth s below the top of the
   * medium, perpendicular to the light: sigma_s p E exp(-sigma_t s)
   * (1 - exp(-sigma_t D)) / sigma_t. */
  {
    sh_phase ray = {SH_PHASE_RAYLEIGH, 0};
    sh_scene s = make_scene(sh_v3(0.05, 0.1, 0.2), sh_v3(0.05, 0, 0), ray);
    s.medium.bmax.y = 2.0;
    sh_light l = {0};
    l.type = SH_LIGHT_DIRECTIONAL;
    l.direction = sh_v3(0, -1, 0);
    l.irradiance = sh_v3(3, 2, 1);
    sh_light_prepare(&l, sh_v3(0, 0, 1), 0, NULL);
    double depth = 1.5, D = 20;
    sh_vec3 c = sh_v3(-10, 2.0 - depth, 0), w = sh_v3(1, 0, 0);
    double p = sh_phase_eval(&ray, 0.0);
    for (int k = 0; k < 3; k++) {
      double ss = sh_vget(s.medium.sigma_s, k), st = sh_vget(s.medium.sigma_t, k);
      double closed = ss * p * sh_vget(l.irradiance, k) * exp(-st * depth) *
                      (1 - exp(-st * D)) / st;
      sh_vec3 est = sh_inscatter_light(&s, NULL, NULL, 0, &l, c, w, 0, D, 1024, &rng,
                                       NULL, NULL);
      SH_CHECK_NEAR(sh_vget(est, k), closed, 1e-3, 0);
    }
  }

  /* 5. The camera at a point light (issue 11): the ray passes through the
   * light, where the integral of 1/r^2 diverges. By the convention
   * (sh_medium_light_min_distance: 1e-4 of the box's diagonal) it is
   * sigma_s I / (4 pi r) atan(D / r), finite, and so for rays passing
   * nearer than r; a ray passing farther is unchanged (case 1). */
  {
    double ss = 1e-7;
    sh_scene s = make_scene(sh_v3s(ss), sh_v3s(0), iso);
    double r = sh_medium_light_min_distance(&s.medium);
    SH_CHECK_NEAR(r, 1e-4 * sqrt(3.0) * 200, 1e-12, 0);
    sh_light l = {0};
    l.type = SH_LIGHT_POINT;
    l.position = sh_v3(1, 2, 3);
    l.intensity = sh_v3s(100);
    sh_vec3 w = sh_normalize(sh_v3(1, 0.2, 0.1));
    double D = 9.0;
    double closed = ss * 100 / (4 * SH_PI * r) * atan(D / r);
    for (int n = 1; n <= 16; n *= 4) {
      sh_vec3 est = sh_inscatter_light(&s, NULL, NULL, 0, &l, l.position, w, 0, D, n, &rng,
                                       NULL, NULL);
      SH_CHECK(isfinite(est.x));
      SH_CHECK_NEAR(est.x, closed, 1e-5, 0);
    }
    /* A ray passing at r / 2 from the light takes the same. */
    sh_vec3 side = sh_normalize(sh_cross(w, sh_v3(0, 1, 0)));
    sh_vec3 o = sh_madd(l.position, side, 0.5 * r);
    sh_vec3 est = sh_inscatter_light(&s, NULL, NULL, 0, &l, o, w, 0, D, 4, &rng, NULL, NULL);
    SH_CHECK_NEAR(est.x, closed, 1e-5, 0);
  }
  SH_TEST_DONE();
}
