/* The reference renderer in height fog against an independent quadrature of
 * the single-scattering integral along one camera ray:
 *   L = sum over lights of the integral over [t0, t1] of
 *       sigma_s(x) p(cos) E(x) Tr(x, light) Tr(x0, x) dt,
 * with every transmittance itself a composite Simpson quadrature of
 * sigma_t(y) = sigma_t exp(-(y - base) / H) written out here, so that
 * nothing of sh_medium's closed forms is used. The converged estimate (one
 * pixel, many stratified samples) must agree to 0.1%. */
#include <string.h>

#include "sh_camera.h"
#include "sh_reference.h"
#include "sh_test.h"

static const char *FOG_SCENE =
    "{\"format\": \"shafts-scene\", \"version\": 1,"
    " \"camera\": {\"position\": [0.5, 1, 7], \"look_at\": [0, 2, 0],"
    "  \"fov_y_deg\": 50, \"width\": 9, \"height\": 7},"
    " \"medium\": {\"type\": \"height_fog\", \"base_height\": 0.5,"
    "  \"scale_height\": 1.5, \"sigma_s\": [0.3, 0.2, 0.1],"
    "  \"sigma_a\": [0.05, 0.05, 0.05],"
    "  \"phase\": {\"type\": \"henyey_greenstein\", \"g\": 0.4},"
    "  \"bounds\": {\"min\": [-4, 0, -4], \"max\": [4, 5, 4]}},"
    " \"lights\": [{\"type\": \"directional\", \"direction\": [0.3, -1, -0.2],"
    "  \"irradiance\": [2, 2, 2]},"
    "  {\"type\": \"point\", \"position\": [1, 3, 0.5],"
    "   \"intensity\": [5, 5, 5]}]}";

typedef struct fog {
  double sigma_s, sigma_t, base, H, g;
  sh_vec3 bmin, bmax;
} fog;

static double density(const fog *f, sh_vec3 x) {
  return exp(-(x.y - f->base) / f->H);
}

/* Optical depth of [a, b] (inside the box) by composite Simpson. */
static double depth(const fog *f, sh_vec3 a, sh_vec3 b) {
  const int n = 200;
  double s = 0;
  for (int i = 0; i <= n; i++) {
    double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    s += w * density(f, sh_add(a, sh_scale(sh_sub(b, a), (double)i / n)));
  }
  return f->sigma_t * sh_length(sh_sub(b, a)) * s / (3.0 * n);
}

/* Where the ray from p (inside the box) along d leaves it. */
static double exit_t(const fog *f, sh_vec3 p, sh_vec3 d) {
  double t = INFINITY;
  double pa[3] = {p.x, p.y, p.z}, da[3] = {d.x, d.y, d.z};
  double lo[3] = {f->bmin.x, f->bmin.y, f->bmin.z};
  double hi[3] = {f->bmax.x, f->bmax.y, f->bmax.z};
  for (int a = 0; a < 3; a++) {
    if (da[a] > 0) t = fmin(t, (hi[a] - pa[a]) / da[a]);
    if (da[a] < 0) t = fmin(t, (lo[a] - pa[a]) / da[a]);
  }
  return t;
}

/* Where the ray from o (outside) along d enters the box. */
static double entry_t(const fog *f, sh_vec3 o, sh_vec3 d) {
  double t = 0;
  double oa[3] = {o.x, o.y, o.z}, da[3] = {d.x, d.y, d.z};
  double lo[3] = {f->bmin.x, f->bmin.y, f->bmin.z};
  double hi[3] = {f->bmax.x, f->bmax.y, f->bmax.z};
  for (int a = 0; a < 3; a++) {
    if (da[a] != 0) {
      double ta = (lo[a] - oa[a]) / da[a], tb = (hi[a] - oa[a]) / da[a];
      t = fmax(t, fmin(ta, tb));
    }
  }
  return t;
}

static double hg(double g, double c) {
  double den = 1 + g * g - 2 * g * c;
  return (1 - g * g) / (4 * SH_PI * den * sqrt(den));
}

/* The single-scattering integral along o + t d (red channel). */
static double quadrature(const fog *f, sh_vec3 o, sh_vec3 d, sh_vec3 sun_dir,
                         double sun_e, sh_vec3 lpos, double lint) {
  double t0 = entry_t(f, o, d);
  double t1 = exit_t(f, sh_add(o, sh_scale(d, t0 + 1e-12)), d) + t0;
  const int n = 4000;
  double h = (t1 - t0) / n, s = 0;
  sh_vec3 x0 = sh_add(o, sh_scale(d, t0));
  for (int i = 0; i <= n; i++) {
    double t = t0 + i * h;
    sh_vec3 x = sh_add(o, sh_scale(d, t));
    double cam = exp(-depth(f, x0, x));
    sh_vec3 wi = sh_neg(sun_dir);
    double ts = exit_t(f, x, wi);
    double sun = sun_e * exp(-depth(f, x, sh_add(x, sh_scale(wi, ts)))) *
                 hg(f->g, sh_dot(wi, d));
    sh_vec3 tl = sh_sub(lpos, x);
    double r2 = sh_dot(tl, tl);
    double pt = lint / r2 * exp(-depth(f, x, lpos)) *
                hg(f->g, sh_dot(sh_scale(tl, 1 / sqrt(r2)), d));
    double v = f->sigma_s * density(f, x) * (sun + pt) * cam;
    double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    s += w * v;
  }
  return s * h / 3.0;
}

int main(void) {
  sh_scene *s = sh_test_parse(FOG_SCENE, "fog.json");
  SH_CHECK(s != NULL);
  if (!s) SH_TEST_DONE();
  SH_CHECK(s->medium.type == SH_MEDIUM_HEIGHT_FOG);
  fog f = {0.3, 0.35, 0.5, 1.5, 0.4, sh_v3(-4, 0, -4), sh_v3(4, 5, 4)};
  const int px = 6, py = 2;
  sh_camera_frame frame;
  sh_camera_frame_init(&s->camera, &frame);
  sh_vec3 d = sh_camera_dir(&frame, px + 0.5, py + 0.5);
  double want = quadrature(&f, s->camera.position, d,
                           sh_normalize(sh_v3(0.3, -1, -0.2)), 2.0,
                           sh_v3(1, 3, 0.5), 5.0);
  sh_reference_options opt = sh_reference_defaults(s);
  opt.spp = 20000;
  opt.threads = 1;
  opt.crop = (sh_crop){px, py, px + 1, py + 1};
  sh_image img;
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(sh_render_reference(s, &opt, &img, NULL, &err) == SH_OK);
  double got = img.rgb[0];
  fprintf(stderr, "height fog, one ray: reference %.8g, quadrature %.8g "
                  "(relative difference %.2e)\n",
          got, want, fabs(got - want) / want);
  SH_CHECK(want > 1e-3);
  SH_CHECK_NEAR(got, want, 1e-3, 0);
  sh_image_free(&img);
  sh_scene_free(s);
  sh_error_clear(&err);
  SH_TEST_DONE();
}
