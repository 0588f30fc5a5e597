#include "sh_inscatter.h"

#include <math.h>

#include "sh_light.h"
#include "sh_medium.h"

static int in_cone(const sh_light *l, sh_vec3 o, sh_vec3 d, double t) {
  sh_vec3 v = sh_sub(sh_madd(o, d, t), l->position);
  double z = sh_dot(v, l->direction);
  return z >= 0 && z * z >= l->cos_outer * l->cos_outer * sh_dot(v, v);
}

static int clip_about(const sh_light *l, sh_vec3 o, sh_vec3 d, double t0,
                      double t1, double *a, double *b);

int sh_light_clip(const sh_light *l, sh_vec3 o, sh_vec3 d, double t0,
                  double t1, double *a, double *b) {
  *a = t0;
  *b = t1;
  if (l->type != SH_LIGHT_SPOT || l->cos_outer <= 0) return t1 > t0;
  /* Solved about the ray's point nearest the apex, tf: about a far origin
   * the quadratic's terms are of the order of the squared distance and
   * cancel (a camera 5e7 units from a spot lost the cone, 57% off, in
   * double precision). */
  double dd = sh_dot(d, d);
  double tf = dd > 0 ? sh_dot(sh_sub(l->position, o), d) / dd : 0.0;
  if (!clip_about(l, sh_madd(o, d, tf), d, t0 - tf, t1 - tf, a, b)) {
    *a = t0;
    *b = t1;
    return 0;
  }
  *a = fmax(*a + tf, t0);
  *b = fmin(*b + tf, t1);
  return *b > *a;
}

/* sh_light_clip for a spot, the ray's parameter counted from o. */
static int clip_about(const sh_light *l, sh_vec3 o, sh_vec3 d, double t0,
                      double t1, double *a, double *b) {
  *a = t0;
  *b = t1;
  /* The cone's boundary: f(t) = (v.a + t d.a)^2 - c^2 |v + t d|^2 = 0 and
   * the apex plane v.a + t d.a = 0 split [t0, t1] into pieces; the front
   * nappe is convex, so the pieces inside form one interval. */
  sh_vec3 v = sh_sub(o, l->position), ax = l->direction;
  double c2 = l->cos_outer * l->cos_outer;
  double va = sh_dot(v, ax), da = sh_dot(d, ax);
  double A = da * da - c2, B = va * da - c2 * sh_dot(v, d);
  double C = va * va - c2 * sh_dot(v, v);
  double cuts[6];
  int n = 0;
  cuts[n++] = t0;
  if (fabs(A) > 1e-300) {
    double disc = B * B - A * C;
    if (disc >= 0) {
      double s = sqrt(disc);
      cuts[n++] = (-B - s) / A;
      cuts[n++] = (-B + s) / A;
    }
  } else if (B != 0) {
    cuts[n++] = -C / (2.0 * B);
  }
  if (da != 0) cuts[n++] = -va / da;
  cuts[n++] = t1;
  /* Sort the cuts, keep those inside [t0, t1]. */
  for (int i = 1; i < n; i++)
    for (int j = i; j > 0 && cuts[j] < cuts[j - 1]; j--) {
      double t = cuts[j];
      cuts[j] = cuts[j - 1];
      cuts[j - 1] = t;
    }
  double lo = INFINITY, hi = -INFINITY;
  for (int i = 0; i + 1 < n; i++) {
    double x0 = fmax(cuts[i], t0), x1 = fmin(cuts[i + 1], t1);
    if (x1 <= x0) continue;
    if (in_cone(l, o, d, 0.5 * (x0 + x1))) {
      lo = fmin(lo, x0);
      hi = fmax(hi, x1);
    }
  }
  if (!(hi > lo)) return 0;
  *a = lo;
  *b = hi;
  return 1;
}

/* Radiance scattered towards -d at x by one light, per unit length, with
 * visibility and the light's transmittance; before the camera-side
 * transmittance. Also returns the 1/r^2-free part via *r2 for point lights. */
typedef struct vis_source {
  const sh_rt *rt;
  const sh_shadow_hook *hook;
  int thread, light;
} vis_source;

static sh_vec3 scatter_at(const sh_scene *scene, const vis_source *vs,
                          const sh_light *l, sh_vec3 x, sh_vec3 d,
                          sh_rt_counters *c, double *r2) {
  sh_vec3 wi;
  double dist;
  sh_vec3 e = sh_light_incident(l, x, &wi, &dist);
  *r2 = dist * dist;
  if (sh_is_black(e)) return e;
  const sh_medium *m = &scene->medium;
  /* The planet's shadow (an atmosphere's ground; never for other kinds). */
  if (sh_medium_ground_blocks(m, x, wi, dist)) return sh_v3s(0.0);
  e = sh_mul(e, l->type == SH_LIGHT_DIRECTIONAL
                    ? sh_medium_transmittance_ray(m, x, wi)
                    : sh_medium_transmittance(m, x, l->position));
  sh_vec3 vis;
  if (vs->hook && vs->hook->volume &&
      vs->hook->volume(vs->hook->user, vs->thread, x, vs->light, &vis, c)) {
    e = sh_mul(e, vis);
  } else if (vs->rt) {
    double tmax = l->type == SH_LIGHT_DIRECTIONAL ? INFINITY : dist * (1.0 - 1e-7);
    vis = sh_rt_visibility(vs->rt, x, wi, tmax, c);
    if (sh_is_black(vis)) return vis;
    e = sh_mul(e, vis);
  }
  return sh_mul(e, sh_medium_scattering_at(m, x, sh_dot(wi, d)));
}

sh_vec3 sh_inscatter_light(const sh_scene *scene, const sh_rt *rt,
                           const sh_shadow_hook *hook, int thread,
                           const sh_light *l, sh_vec3 o, sh_vec3 d,
                           double t0, double t1, int n, sh_rng *rng,
                           sh_rt_counters *c, uint64_t *samples) {
  sh_vec3 sum = sh_v3s(0.0);
  vis_source vs = {rt, hook, thread, hook ? (int)(l - scene->lights) : -1};
  double a, b;
  if (n < 1 || !sh_light_clip(l, o, d, t0, t1, &a, &b)) return sum;
  const sh_medium *m = &scene->medium;
  if (samples) *samples += (uint64_t)n;
  if (l->type == SH_LIGHT_DIRECTIONAL) {
    /* Sample t by the camera-side transmittance of the mean channel
     * (sh_medium_sample_distance). */
    for (int i = 0; i < n; i++) {
      double u = (i + sh_rng_next(rng)) / n, inv_pdf;
      double t = sh_medium_sample_distance(m, o, d, a, b, u, &inv_pdf);
      double r2;
      sh_vec3 x = sh_madd(o, d, t);
      sh_vec3 s = scatter_at(scene, &vs, l, x, d, c, &r2);
      sh_vec3 tr = sh_medium_transmittance_span(m, o, d, t0, t);
      sum = sh_add(sum, sh_scale(sh_mul(s, tr), inv_pdf));
    }
  } else {
    /* Equiangular sampling (Kulla and Fajardo 2012): density proportional
     * to 1/r^2 along the ray. */
    /* h at least the light's minimal distance (sh_medium.h): the density
     * is then proportional to 1/r_eff^2, r_eff^2 = (t - bt)^2 + h^2, and
     * the weight r^2 (tb - ta) / h below turns each sample's 1/r^2 into
     * the convention's 1/r_eff^2 (f / pdf = the rest * (tb - ta) / h). */
    double bt = sh_dot(sh_sub(l->position, o), d);
    double h = sh_length(sh_sub(sh_madd(o, d, bt), l->position));
    /* A ray through the light: a floor relative to the lengths at hand
     * (an absolute one would swamp a scene a billionth of a unit across). */
    double span = isfinite(b - a) ? b - a : fabs(a);
    h = fmax(fmax(h, sh_medium_light_min_distance(m)), 1e-9 * (fabs(bt) + span));
    if (!(h > 0)) return sum;
    double ta = atan2(a - bt, h), tb = atan2(b - bt, h);
    for (int i = 0; i < n; i++) {
      double u = (i + sh_rng_next(rng)) / n;
      double t = bt + h * tan(ta + u * (tb - ta));
      t = sh_clamp(t, a, b);
      double r2;
      sh_vec3 x = sh_madd(o, d, t);
      sh_vec3 s = scatter_at(scene, &vs, l, x, d, c, &r2);
      double w = r2 * (tb - ta) / h;
      sh_vec3 tr = sh_medium_transmittance_span(m, o, d, t0, t);
      sum = sh_add(sum, sh_scale(sh_mul(s, tr), w));
    }
  }
  return sh_scale(sum, 1.0 / n);
}
