#include "sh_medium.h"

#include "sh_atmosphere.h"

#include <math.h>
#include <stdio.h>

double sh_phase_eval(const sh_phase *phase, double c) {
  switch (phase->type) {
  case SH_PHASE_ISOTROPIC:
    return SH_INV_4PI;
  case SH_PHASE_HENYEY_GREENSTEIN: {
    double g = phase->g, den = 1.0 + g * g - 2.0 * g * c;
    return SH_INV_4PI * (1.0 - g * g) / (den * sqrt(den));
  }
  case SH_PHASE_NISHITA_HAZY: {
    /* 1 + 9 ((1 + c)/2)^8 integrates to 8 pi over the sphere. */
    double x = 0.5 * (1.0 + c), x2 = x * x, x4 = x2 * x2;
    return (1.0 + 9.0 * x4 * x4) / (8.0 * SH_PI);
  }
  case SH_PHASE_NISHITA_MURKY: {
    /* 1 + 50 ((1 + c)/2)^32 integrates to 332 pi / 33. */
    double x = 0.5 * (1.0 + c), y = x * x;
    y *= y; /* ^4 */
    y *= y; /* ^8 */
    y *= y; /* ^16 */
    y *= y; /* ^32 */
    return 33.0 * (1.0 + 50.0 * y) / (332.0 * SH_PI);
  }
  case SH_PHASE_RAYLEIGH:
    /* 1 + c^2 integrates to 16 pi / 3. */
    return 3.0 * (1.0 + c * c) / (16.0 * SH_PI);
  case SH_PHASE_CORNETTE_SHANKS: {
    /* Cornette and Shanks 1992: (1 + c^2) / (1 + g^2 - 2 g c)^1.5 times
     * 3 (1 - g^2) / (8 pi (2 + g^2)). */
    double g = phase->g, den = 1.0 + g * g - 2.0 * g * c;
    return 3.0 * (1.0 - g * g) * (1.0 + c * c) /
           (8.0 * SH_PI * (2.0 + g * g) * den * sqrt(den));
  }
  }
  return SH_INV_4PI;
}

int sh_box_clip(sh_vec3 bmin, sh_vec3 bmax, sh_vec3 o, sh_vec3 d, double tmin,
                double tmax, double *t0, double *t1) {
  double lo = tmin, hi = tmax;
  for (int a = 0; a < 3; a++) {
    double oa = sh_vget(o, a), da = sh_vget(d, a);
    double mn = sh_vget(bmin, a), mx = sh_vget(bmax, a);
    if (da == 0) {
      if (oa < mn || oa > mx) return 0;
      continue;
    }
    double inv = 1.0 / da;
    double ta = (mn - oa) * inv, tb = (mx - oa) * inv;
    if (ta > tb) {
      double t = ta;
      ta = tb;
      tb = t;
    }
    if (ta > lo) lo = ta;
    if (tb < hi) hi = tb;
    if (lo > hi) return 0;
  }
  *t0 = lo;
  *t1 = hi;
  return hi > lo;
}

int sh_medium_clip(const sh_medium *m, sh_vec3 o, sh_vec3 d, double tmin,
                   double tmax, double *t0, double *t1) {
  if (!m->present) return 0;
  if (m->type == SH_MEDIUM_ATMOSPHERE) {
    /* The sphere's roots want a unit direction; t scales back. */
    double len = sh_length(d);
    if (!(len > 0)) return 0;
    if (!sh_atmosphere_clip(&m->atmo, o, sh_scale(d, 1.0 / len), tmin * len,
                            tmax * len, t0, t1))
      return 0;
    *t0 /= len;
    *t1 /= len;
    return *t1 > *t0;
  }
  return sh_box_clip(m->bmin, m->bmax, o, d, tmin, tmax, t0, t1);
}

double sh_medium_length(const sh_medium *m, sh_vec3 a, sh_vec3 b) {
  sh_vec3 d = sh_sub(b, a);
  double t0, t1;
  if (!sh_medium_clip(m, a, d, 0.0, 1.0, &t0, &t1)) return 0.0;
  return (t1 - t0) * sh_length(d);
}

double sh_medium_length_ray(const sh_medium *m, sh_vec3 p, sh_vec3 d) {
  double t0, t1;
  if (!sh_medium_clip(m, p, d, 0.0, INFINITY, &t0, &t1)) return 0.0;
  return t1 - t0;
}

/* Height fog's relative density at height y. */
static double fog_density(const sh_medium *m, double y) {
  return exp(-(y - m->base_height) / m->scale_height);
}

/* (1 - exp(-x)) / x for x >= 0, 1 at 0, without cancellation. */
static double one_minus_exp_over(double x) {
  return x > 0 ? -expm1(-x) / x : 1.0;
}

/* The integral of the relative density along o + t d, t in [t0, t1], in
 * units of length (|d| = dlen): for a homogeneous medium the length. */
static double density_integral(const sh_medium *m, sh_vec3 o, sh_vec3 d,
                               double t0, double t1, double dlen) {
  double len = (t1 - t0) * dlen;
  if (m->type != SH_MEDIUM_HEIGHT_FOG) return len;
  double y0 = o.y + t0 * d.y, y1 = o.y + t1 * d.y;
  double rise = fabs(y1 - y0) / m->scale_height;
  return len * fog_density(m, fmin(y0, y1)) * one_minus_exp_over(rise);
}

sh_vec3 sh_medium_optical_depth_span(const sh_medium *m, sh_vec3 o, sh_vec3 d,
                                     double t0, double t1) {
  if (!m->present || !(t1 > t0)) return sh_v3s(0.0);
  if (m->type == SH_MEDIUM_ATMOSPHERE)
    return sh_atmosphere_optical_depth(&m->atmo, o, d, t0, t1);
  return sh_scale(m->sigma_t, density_integral(m, o, d, t0, t1, 1.0));
}

sh_vec3 sh_medium_optical_depth(const sh_medium *m, sh_vec3 a, sh_vec3 b) {
  sh_vec3 d = sh_sub(b, a);
  double t0, t1;
  if (!sh_medium_clip(m, a, d, 0.0, 1.0, &t0, &t1)) return sh_v3s(0.0);
  if (m->type == SH_MEDIUM_ATMOSPHERE) {
    double len = sh_length(d);
    return sh_atmosphere_optical_depth(&m->atmo, a, sh_scale(d, 1.0 / len),
                                       t0 * len, t1 * len);
  }
  return sh_scale(m->sigma_t, density_integral(m, a, d, t0, t1, sh_length(d)));
}

sh_vec3 sh_medium_optical_depth_ray(const sh_medium *m, sh_vec3 p, sh_vec3 d) {
  double t0, t1;
  if (!sh_medium_clip(m, p, d, 0.0, INFINITY, &t0, &t1)) return sh_v3s(0.0);
  return sh_medium_optical_depth_span(m, p, d, t0, t1);
}

sh_vec3 sh_medium_transmittance_span(const sh_medium *m, sh_vec3 o, sh_vec3 d,
                                     double t0, double t1) {
  return sh_vexp(sh_neg(sh_medium_optical_depth_span(m, o, d, t0, t1)));
}

sh_vec3 sh_medium_transmittance(const sh_medium *m, sh_vec3 a, sh_vec3 b) {
  return sh_vexp(sh_neg(sh_medium_optical_depth(m, a, b)));
}

sh_vec3 sh_medium_transmittance_ray(const sh_medium *m, sh_vec3 p, sh_vec3 d) {
  return sh_vexp(sh_neg(sh_medium_optical_depth_ray(m, p, d)));
}

/* The relative density at p: 1 for a homogeneous medium. */
static double density_at(const sh_medium *m, sh_vec3 p) {
  return m->type == SH_MEDIUM_HEIGHT_FOG ? fog_density(m, p.y) : 1.0;
}

sh_vec3 sh_medium_sigma_s_at(const sh_medium *m, sh_vec3 p) {
  if (!m->present) return sh_v3s(0.0);
  if (m->type == SH_MEDIUM_ATMOSPHERE) return sh_atmosphere_sigma_s(&m->atmo, p);
  return m->type == SH_MEDIUM_HOMOGENEOUS ? m->sigma_s
                                          : sh_scale(m->sigma_s, density_at(m, p));
}

sh_vec3 sh_medium_sigma_a_at(const sh_medium *m, sh_vec3 p) {
  if (!m->present) return sh_v3s(0.0);
  if (m->type == SH_MEDIUM_ATMOSPHERE) return sh_atmosphere_sigma_a(&m->atmo, p);
  return m->type == SH_MEDIUM_HOMOGENEOUS ? m->sigma_a
                                          : sh_scale(m->sigma_a, density_at(m, p));
}

sh_vec3 sh_medium_sigma_t_at(const sh_medium *m, sh_vec3 p) {
  if (!m->present) return sh_v3s(0.0);
  if (m->type == SH_MEDIUM_ATMOSPHERE)
    return sh_add(sh_atmosphere_sigma_s(&m->atmo, p),
                  sh_atmosphere_sigma_a(&m->atmo, p));
  return m->type == SH_MEDIUM_HOMOGENEOUS ? m->sigma_t
                                          : sh_scale(m->sigma_t, density_at(m, p));
}

const sh_phase *sh_medium_phase_at(const sh_medium *m, sh_vec3 p) {
  (void)p;
  return &m->phase;
}

sh_vec3 sh_medium_phase_rgb_at(const sh_medium *m, sh_vec3 p,
                               double cos_alpha) {
  if (m->present && m->type == SH_MEDIUM_ATMOSPHERE)
    return sh_atmosphere_phase(&m->atmo, p, cos_alpha);
  return sh_v3s(sh_phase_eval(&m->phase, cos_alpha));
}

sh_vec3 sh_medium_scattering_at(const sh_medium *m, sh_vec3 p,
                                double cos_alpha) {
  if (!m->present) return sh_v3s(0.0);
  if (m->type == SH_MEDIUM_ATMOSPHERE)
    return sh_atmosphere_scattering(&m->atmo, p, cos_alpha);
  return sh_scale(sh_medium_sigma_s_at(m, p), sh_phase_eval(&m->phase, cos_alpha));
}

int sh_medium_ground_hit(const sh_medium *m, sh_vec3 o, sh_vec3 d,
                         double tmax, double *t) {
  return m->present && m->type == SH_MEDIUM_ATMOSPHERE &&
         sh_atmosphere_ground_hit(&m->atmo, o, d, tmax, t);
}

int sh_medium_ground_blocks(const sh_medium *m, sh_vec3 x, sh_vec3 w,
                            double tmax) {
  return m->present && m->type == SH_MEDIUM_ATMOSPHERE &&
         sh_atmosphere_ground_blocks(&m->atmo, x, w, tmax);
}

sh_vec3 sh_medium_majorant(const sh_medium *m, sh_vec3 o, sh_vec3 d, double t0,
                           double t1) {
  if (!m->present) return sh_v3s(0.0);
  if (m->type == SH_MEDIUM_ATMOSPHERE)
    return sh_atmosphere_majorant(&m->atmo, o, d, t0, t1);
  if (m->type != SH_MEDIUM_HEIGHT_FOG) return m->sigma_t;
  double y = fmin(o.y + t0 * d.y, o.y + t1 * d.y);
  return sh_scale(m->sigma_t, fog_density(m, y));
}

sh_vec3 sh_medium_majorant_box(const sh_medium *m, sh_vec3 lo, sh_vec3 hi) {
  if (!m->present || lo.x > m->bmax.x || lo.y > m->bmax.y || lo.z > m->bmax.z ||
      hi.x < m->bmin.x || hi.y < m->bmin.y || hi.z < m->bmin.z)
    return sh_v3s(0.0);
  if (m->type == SH_MEDIUM_ATMOSPHERE) {
    /* Over the heights the box spans: from its point nearest the centre to
     * its corner farthest from it, a span whose ends are the least and the
     * largest height (sh_atmosphere_majorant takes both from the ends and
     * the point nearest the centre). */
    sh_vec3 c = m->atmo.center;
    sh_vec3 near = sh_vmin(sh_vmax(c, lo), hi), far;
    far.x = c.x - lo.x > hi.x - c.x ? lo.x : hi.x;
    far.y = c.y - lo.y > hi.y - c.y ? lo.y : hi.y;
    far.z = c.z - lo.z > hi.z - c.z ? lo.z : hi.z;
    double len = sh_length(sh_sub(far, near));
    if (!(len > 0)) return sh_atmosphere_majorant(&m->atmo, near, sh_v3(0, 1, 0), 0, 0);
    return sh_atmosphere_majorant(&m->atmo, near, sh_scale(sh_sub(far, near), 1.0 / len),
                                  0.0, len);
  }
  if (m->type != SH_MEDIUM_HEIGHT_FOG) return m->sigma_t;
  return sh_scale(m->sigma_t, fog_density(m, fmax(lo.y, m->bmin.y)));
}

/* Height fog: the t in [a, inf) at which the density integral from a
 * reaches w (>= 0), along a unit d; INFINITY if it never does (a ray going
 * up holds at most rho(y_a) H / d.y). */
static double fog_invert(const sh_medium *m, sh_vec3 o, sh_vec3 d, double a,
                         double w) {
  double H = m->scale_height, rho = fog_density(m, o.y + a * d.y);
  double base = w / rho; /* the length it would take at a's density */
  /* w = rho H / d.y (1 - exp(-d.y s / H)), so s = -H / d.y log1p(-z),
   * z = w d.y / (rho H); written as base * (-log1p(-z) / z). */
  double z = base * d.y / H;
  if (z >= 1.0) return INFINITY;
  double f = z != 0 ? -log1p(-z) / z : 1.0;
  return a + base * f;
}

double sh_medium_sample_distance(const sh_medium *m, sh_vec3 o, sh_vec3 d,
                                 double a, double b, double u,
                                 double *inv_pdf) {
  if (m->type == SH_MEDIUM_ATMOSPHERE)
    return sh_atmosphere_sample_distance(&m->atmo, o, d, a, b, u, inv_pdf);
  double k = (m->sigma_t.x + m->sigma_t.y + m->sigma_t.z) / 3.0;
  double len = b - a;
  if (m->type != SH_MEDIUM_HEIGHT_FOG) {
    /* Density proportional to exp(-k (t - a)). */
    double kl = k * len;
    if (kl < 1e-6) {
      *inv_pdf = len;
      return a + u * len;
    }
    double norm = -expm1(-kl); /* 1 - exp(-k len) */
    double t = a - log1p(-u * norm) / k;
    *inv_pdf = norm / (k * exp(-k * (t - a)));
    return t;
  }
  double kl = k * density_integral(m, o, d, a, b, 1.0);
  if (!(kl >= 1e-6)) {
    *inv_pdf = len;
    return a + u * len;
  }
  double norm = -expm1(-kl);
  double tau = -log1p(-u * norm); /* the mean channel's depth from a */
  double t = sh_clamp(fog_invert(m, o, d, a, tau / k), a, b);
  double kt = k * density_at(m, sh_madd(o, d, t));
  /* exp(-tau) is the mean channel's transmittance from a to t. */
  *inv_pdf = norm / (kt * exp(-tau));
  return t;
}

double sh_medium_light_min_distance(const sh_medium *m) {
  if (!m->present) return 0.0;
  if (m->type == SH_MEDIUM_ATMOSPHERE)
    return 1e-4 * (m->atmo.top_radius - m->atmo.ground_radius);
  return 1e-4 * sh_length(sh_sub(m->bmax, m->bmin));
}

int sh_scene_camera_at_light(const sh_scene *scene) {
  const sh_medium *m = &scene->medium;
  if (!m->present || sh_is_black(m->sigma_s)) return -1;
  double r = sh_medium_light_min_distance(m);
  for (int i = 0; i < scene->nlights; i++) {
    const sh_light *l = &scene->lights[i];
    sh_vec3 p = l->position;
    if (l->type == SH_LIGHT_DIRECTIONAL || p.x < m->bmin.x || p.x > m->bmax.x ||
        p.y < m->bmin.y || p.y > m->bmax.y || p.z < m->bmin.z || p.z > m->bmax.z)
      continue;
    if (sh_length(sh_sub(p, scene->camera.position)) <= r) return i;
  }
  return -1;
}

const char *sh_medium_type_name(sh_medium_type type) {
  switch (type) {
  case SH_MEDIUM_HOMOGENEOUS: return "homogeneous";
  case SH_MEDIUM_HEIGHT_FOG: return "height_fog";
  case SH_MEDIUM_ATMOSPHERE: return "atmosphere";
  }
  return "unknown";
}

/* Fills the location of a refusal. */
static void refusal_at(const sh_scene *scene, int line, int column,
                       const char *path, sh_error *err) {
  if (!err) return;
  sh_error_set_file(err, scene->file);
  sh_error_set_key(err, "%s", path);
  err->line = line;
  err->column = column;
}

void sh_medium_locate_type(const sh_scene *scene, sh_error *err) {
  refusal_at(scene, scene->medium.line, scene->medium.column, "medium.type", err);
}

sh_status sh_medium_require_kinds(const sh_scene *scene, const char *who,
                                  unsigned kinds, sh_error *err) {
  const sh_medium *m = &scene->medium;
  if (!m->present || (kinds & SH_MEDIUM_KIND(m->type))) return SH_OK;
  /* The kinds it renders, as the format spells them. */
  char names[128] = "";
  size_t len = 0;
  for (int t = SH_MEDIUM_HOMOGENEOUS; t <= SH_MEDIUM_ATMOSPHERE; t++)
    if (kinds & SH_MEDIUM_KIND(t) && len < sizeof names)
      len += (size_t)snprintf(names + len, sizeof names - len, "%s%s",
                              len ? " and " : "", sh_medium_type_name((sh_medium_type)t));
  sh_error_set(err, SH_ERR_SCENE,
               "%s renders %s media only, not a medium of type '%s'; "
               "lmm_tracer renders it (docs/scene-format.md, \"Non-uniform "
               "media\")",
               who, names, sh_medium_type_name(m->type));
  refusal_at(scene, m->line, m->column, "medium.type", err);
  return SH_ERR_SCENE;
}
