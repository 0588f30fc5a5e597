/* The reference renderer in an atmosphere against an independent
 * quadrature of the single-scattering integral along one camera ray:
 *   L = integral over [t0, t1] of Tr(eye, x) E V(x) Tr(x, sun)
 *         (sigma_R(x) p_R(cos) + sigma_M(x) p_M(cos)) dt
 *       + Tr(eye, x1) L_ground(x1)   (when the ray ends on the ground),
 *   L_ground = albedo / pi E cos Tr(x1, sun),
 * with V the planet's shadow (the sun's ray from x against the ground
 * sphere) and every transmittance a quadrature of the densities written
 * out here: nothing of core/sh_atmosphere.c is used. The outer integral
 * is composite Simpson split where the camera ray crosses the shadow's
 * cylinder, the camera-side optical depth is accumulated by Gauss-Legendre
 * between Simpson's nodes, the sun's by Gauss-Legendre on 200 equal
 * panels. The converged estimate (one pixel, 20000 stratified samples)
 * must agree to 0.1% in every channel, at dusk from 1 m above the ground
 * (the planet's shadow on the air), at sunset towards and away from the
 * sun, and for the Earth from 30,000 km (the lit ground, the limb, a limb
 * the planet's shadow crosses). */
#include <stdio.h>
#include <string.h>

#include "sh_camera.h"
#include "sh_reference.h"
#include "sh_test.h"

/* Bruneton 2017's Earth in km, the contract's reference values. */
#define RG 6360.0
#define RT 6420.0
static const double SR[3] = {5.802e-3, 13.558e-3, 33.1e-3}, HR = 8.0;
static const double SM = 3.996e-3, AM = 0.444e-3, HM = 1.2, G = 0.8;
static const double AO[3] = {0.650e-3, 1.881e-3, 0.085e-3};
static const double ALBEDO[3] = {0.3, 0.2, 0.1};

typedef struct view {
  sh_vec3 center, eye, dir, sun; /* sun: the direction light travels */
  double irradiance;
} view;

static double height(const view *v, sh_vec3 x) {
  return sh_length(sh_sub(x, v->center)) - RG;
}

/* sigma_t per channel at x. */
static void sigma_t(const view *v, sh_vec3 x, double out[3]) {
  double h = height(v, x);
  double r = exp(-h / HR), m = exp(-h / HM);
  double o = fmax(0.0, 1.0 - fabs(h - 25.0) / 15.0);
  for (int k = 0; k < 3; k++) out[k] = SR[k] * r + (SM + AM) * m + AO[k] * o;
}

static const double GX[8] = {-0.9602898564975363, -0.7966664774136267,
                             -0.5255324099163290, -0.1834346424956498,
                             0.1834346424956498,  0.5255324099163290,
                             0.7966664774136267,  0.9602898564975363};
static const double GW[8] = {0.1012285362903763, 0.2223810344533745,
                             0.3137066458778873, 0.3626837833783620,
                             0.3626837833783620, 0.3137066458778873,
                             0.2223810344533745, 0.1012285362903763};

/* Optical depth along p + t d for t in [a, b] by Gauss-Legendre on n
 * equal panels, added to tau. */
static void depth(const view *v, sh_vec3 p, sh_vec3 d, double a, double b,
                  int n, double tau[3]) {
  double h = (b - a) / n;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < 8; j++) {
      double s[3];
      sigma_t(v, sh_madd(p, d, a + h * (i + 0.5 + 0.5 * GX[j])), s);
      for (int k = 0; k < 3; k++) tau[k] += 0.5 * h * GW[j] * s[k];
    }
}

/* The roots of |p + t d - c| = R by the plain quadratic (d unit). */
static int roots(sh_vec3 c, double R, sh_vec3 p, sh_vec3 d, double *t0,
                 double *t1) {
  sh_vec3 q = sh_sub(p, c);
  double b = sh_dot(q, d), cc = sh_dot(q, q) - R * R, disc = b * b - cc;
  if (disc < 0) return 0;
  *t0 = -b - sqrt(disc);
  *t1 = -b + sqrt(disc);
  return 1;
}

/* The sun's transmittance at x, 0 in the planet's shadow. */
static void sun_tr(const view *v, sh_vec3 x, double tr[3]) {
  sh_vec3 w = sh_neg(v->sun);
  double g0, g1, a0, a1, tau[3] = {0, 0, 0};
  if (roots(v->center, RG - 1e-9, x, w, &g0, &g1) && g1 > 0) {
    tr[0] = tr[1] = tr[2] = 0;
    return;
  }
  roots(v->center, RT, x, w, &a0, &a1);
  depth(v, x, w, 0, a1, 200, tau);
  for (int k = 0; k < 3; k++) tr[k] = exp(-tau[k]);
}

/* sigma_s p per channel at x for the view direction d. */
static void scatter(const view *v, sh_vec3 x, sh_vec3 d, double out[3]) {
  double h = height(v, x), c = sh_dot(sh_neg(v->sun), d);
  double pr = 3 * (1 + c * c) / (16 * SH_PI);
  double den = 1 + G * G - 2 * G * c;
  double pm = 3 * (1 - G * G) * (1 + c * c) / (8 * SH_PI * (2 + G * G) * den * sqrt(den));
  for (int k = 0; k < 3; k++)
    out[k] = SR[k] * exp(-h / HR) * pr + SM * exp(-h / HM) * pm;
}

/* Where the camera ray crosses the boundary of the planet's shadow (the
 * cylinder of radius RG along the sun, behind the planet), into cuts. */
static int shadow_cuts(const view *v, double lo, double hi, double *cuts) {
  sh_vec3 s = v->sun, q = sh_sub(v->eye, v->center), d = v->dir;
  sh_vec3 qp = sh_sub(q, sh_scale(s, sh_dot(q, s)));
  sh_vec3 dp = sh_sub(d, sh_scale(s, sh_dot(d, s)));
  double A = sh_dot(dp, dp), B = sh_dot(qp, dp), C = sh_dot(qp, qp) - RG * RG;
  int n = 0;
  double disc = B * B - A * C;
  if (A > 0 && disc > 0) {
    double t[2] = {(-B - sqrt(disc)) / A, (-B + sqrt(disc)) / A};
    for (int i = 0; i < 2; i++)
      if (t[i] > lo && t[i] < hi) cuts[n++] = t[i];
  }
  double ds = sh_dot(d, s);
  if (ds != 0) {
    double t = -sh_dot(q, s) / ds; /* the terminator's plane */
    if (t > lo && t < hi) cuts[n++] = t;
  }
  return n;
}

/* The quadrature of the whole pixel. */
static void quadrature(const view *v, double L[3]) {
  double t0, t1, g0, g1;
  L[0] = L[1] = L[2] = 0;
  if (!roots(v->center, RT, v->eye, v->dir, &t0, &t1)) return;
  t0 = fmax(t0, 0);
  int ground = roots(v->center, RG, v->eye, v->dir, &g0, &g1) && g0 > 0;
  if (ground) t1 = g0;
  double cuts[8];
  int nc = 0;
  cuts[nc++] = t0;
  nc += shadow_cuts(v, t0, t1, cuts + nc);
  cuts[nc++] = t1;
  for (int i = 1; i < nc; i++)
    for (int j = i; j > 0 && cuts[j] < cuts[j - 1]; j--) {
      double t = cuts[j];
      cuts[j] = cuts[j - 1];
      cuts[j - 1] = t;
    }
  double tau[3] = {0, 0, 0};
  for (int c = 0; c + 1 < nc; c++) {
    const int n = 4000;
    double a = cuts[c], h = (cuts[c + 1] - a) / n;
    for (int i = 0; i <= n; i++) {
      double t = a + i * h;
      if (i > 0) depth(v, v->eye, v->dir, t - h, t, 1, tau);
      sh_vec3 x = sh_madd(v->eye, v->dir, t);
      /* Just inside the piece at its ends, so the shadow test agrees
       * with the side the piece is on. */
      sh_vec3 xs = sh_madd(v->eye, v->dir, i == 0 ? t + 1e-9 * h : i == n ? t - 1e-9 * h : t);
      double tr[3], f[3];
      sun_tr(v, xs, tr);
      scatter(v, x, v->dir, f);
      double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
      for (int k = 0; k < 3; k++)
        L[k] += w * h / 3 * exp(-tau[k]) * v->irradiance * tr[k] * f[k];
    }
  }
  if (ground) {
    sh_vec3 p = sh_madd(v->eye, v->dir, t1);
    sh_vec3 n = sh_normalize(sh_sub(p, v->center));
    double cosl = sh_dot(n, sh_neg(v->sun)), tr[3];
    if (cosl > 0) {
      sun_tr(v, sh_madd(p, n, 1e-9), tr);
      for (int k = 0; k < 3; k++)
        L[k] += exp(-tau[k]) * ALBEDO[k] / SH_PI * v->irradiance * cosl * tr[k];
    }
  }
}

/* Renders the one-pixel camera of `v` with the reference and compares. */
static void check_view(const char *what, view v) {
  v.dir = sh_normalize(v.dir);
  v.sun = sh_normalize(v.sun);
  sh_vec3 at = sh_add(v.eye, v.dir);
  char text[2048];
  snprintf(text, sizeof text,
           "{\"format\": \"shafts-scene\", \"version\": 1,"
           " \"camera\": {\"position\": [%.17g, %.17g, %.17g],"
           "  \"look_at\": [%.17g, %.17g, %.17g], \"up\": [0, 0.6, 0.8],"
           "  \"fov_y_deg\": 10, \"width\": 1, \"height\": 1},"
           " \"medium\": {\"type\": \"atmosphere\", \"center\": [%.17g, %.17g, %.17g],"
           "  \"ground_radius\": 6360, \"top_radius\": 6420,"
           "  \"ground_albedo\": [0.3, 0.2, 0.1],"
           "  \"rayleigh\": {\"sigma_s\": [5.802e-3, 13.558e-3, 33.1e-3], \"scale_height\": 8},"
           "  \"mie\": {\"sigma_s\": [3.996e-3, 3.996e-3, 3.996e-3],"
           "   \"sigma_a\": [0.444e-3, 0.444e-3, 0.444e-3], \"scale_height\": 1.2,"
           "   \"phase\": {\"type\": \"cornette_shanks\", \"g\": 0.8}},"
           "  \"ozone\": {\"sigma_a\": [0.650e-3, 1.881e-3, 0.085e-3],"
           "   \"center_height\": 25, \"width\": 30}},"
           " \"lights\": [{\"type\": \"directional\","
           "  \"direction\": [%.17g, %.17g, %.17g], \"irradiance\": [%g, %g, %g]}]}",
           v.eye.x, v.eye.y, v.eye.z, at.x, at.y, at.z, v.center.x, v.center.y,
           v.center.z, v.sun.x, v.sun.y, v.sun.z, v.irradiance, v.irradiance,
           v.irradiance);
  sh_scene *s = sh_test_parse(text, "atmo.json");
  SH_CHECK(s != NULL);
  if (!s) return;
  sh_camera_frame frame;
  sh_camera_frame_init(&s->camera, &frame);
  v.dir = sh_camera_dir(&frame, 0.5, 0.5); /* the pixel's own ray */
  double want[3];
  quadrature(&v, want);
  sh_reference_options opt = sh_reference_defaults(s);
  opt.spp = 20000;
  opt.threads = 1;
  sh_image img;
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(sh_render_reference(s, &opt, &img, NULL, &err) == SH_OK);
  for (int k = 0; k < 3; k++) {
    double got = img.rgb[k];
    fprintf(stderr, "%s, channel %d: reference %.8g, quadrature %.8g (relative "
                    "difference %.2e)\n",
            what, k, got, want[k], fabs(got - want[k]) / want[k]);
    SH_CHECK(want[k] > 0);
    SH_CHECK_NEAR(got, want[k], 1e-3, 0);
  }
  sh_image_free(&img);
  sh_scene_free(s);
  sh_error_clear(&err);
}

static sh_vec3 elevation(double az_deg, double el_deg) {
  double a = az_deg * SH_PI / 180, e = el_deg * SH_PI / 180;
  return sh_v3(cos(e) * cos(a), sin(e), cos(e) * sin(a));
}

int main(void) {
  sh_vec3 c = sh_v3(0, -RG, 0), eye = sh_v3(0, 0.001, 0);
  /* The sun 3 degrees up towards +x, and 2 degrees below the horizon. */
  sh_vec3 sunset = sh_neg(elevation(0, 3)), dusk = sh_neg(elevation(0, -2));
  check_view("sunset, towards the sun", (view){c, eye, elevation(10, 4), sunset, 20});
  check_view("sunset, away from the sun", (view){c, eye, elevation(180, 8), sunset, 20});
  check_view("sunset, the ground", (view){c, eye, elevation(30, -0.2), sunset, 20});
  check_view("dusk, towards the sun", (view){c, eye, elevation(0, 2), dusk, 20});
  check_view("dusk, the zenith", (view){c, eye, elevation(0, 89), dusk, 20});
  /* The Earth from 30,000 km, the sun from the right and a little behind. */
  sh_vec3 far = sh_v3(0, 0, 36360), o = sh_v3(0, 0, 0);
  sh_vec3 sun = sh_v3(-1, 0, -0.35);
  check_view("space, the lit ground", (view){o, far, sh_sub(sh_v3(3000, 1000, 0), far), sun, 20});
  check_view("space, the lit limb", (view){o, far, sh_sub(sh_v3(6380, 0, 0), far), sun, 20});
  check_view("space, the limb across the planet's shadow",
             (view){o, far, sh_sub(sh_v3(-600, 6357, 0), far), sun, 20});
  SH_TEST_DONE();
}
