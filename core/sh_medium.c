#include "sh_medium.h"

#include <math.h>

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

double sh_medium_length(const sh_medium *m, sh_vec3 a, sh_vec3 b) {
  if (!m->present) return 0.0;
  sh_vec3 d = sh_sub(b, a);
  double t0, t1;
  if (!sh_box_clip(m->bmin, m->bmax, a, d, 0.0, 1.0, &t0, &t1)) return 0.0;
  return (t1 - t0) * sh_length(d);
}

double sh_medium_length_ray(const sh_medium *m, sh_vec3 p, sh_vec3 d) {
  if (!m->present) return 0.0;
  double t0, t1;
  if (!sh_box_clip(m->bmin, m->bmax, p, d, 0.0, INFINITY, &t0, &t1))
    return 0.0;
  return t1 - t0;
}

sh_vec3 sh_medium_tr(const sh_medium *m, double len) {
  if (!m->present || len <= 0) return sh_v3s(1.0);
  return sh_vexp(sh_scale(m->sigma_t, -len));
}

double sh_medium_light_min_distance(const sh_medium *m) {
  return m->present ? 1e-4 * sh_length(sh_sub(m->bmax, m->bmin)) : 0.0;
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
