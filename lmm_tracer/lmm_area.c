#include "lmm_area.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sh_light.h"
#include "sh_rng.h"

struct lmm_area {
  const sh_scene *scene;
  const sh_rt *rt;
  double radius;
  int samples;
  sh_shadow_hook hook;
};

static uint64_t point_seed(sh_vec3 p) {
  uint64_t h = 1469598103934665603ULL;
  double v[3] = {p.x, p.y, p.z};
  unsigned char b[sizeof v];
  memcpy(b, v, sizeof v);
  for (size_t i = 0; i < sizeof b; i++) h = (h ^ b[i]) * 1099511628211ULL;
  return h;
}

static int surface(void *user, int thread, const sh_hit *hit, sh_vec3 n,
                   sh_vec3 *vis, sh_rt_counters *c) {
  sh_vec3 p = hit->p;
  (void)thread;
  const lmm_area *A = user;
  sh_vec3 origin = sh_rt_offset_hit(A->rt, hit, n);
  /* Deterministic per point, so that images do not depend on threads. */
  sh_rng rng;
  sh_rng_seed(&rng, point_seed(p), 7);
  int side = (int)ceil(sqrt((double)A->samples)), count = side * side;
  for (int l = 0; l < A->scene->nlights; l++) {
    const sh_light *light = &A->scene->lights[l];
    sh_vec3 wi;
    double dist;
    sh_light_incident(light, p, &wi, &dist);
    if (light->type == SH_LIGHT_DIRECTIONAL || A->radius <= 0) {
      double tmax = isinf(dist) ? INFINITY : dist * (1.0 - 1e-7);
      vis[l] = sh_rt_visibility(A->rt, origin, wi, tmax, c);
      continue;
    }
    /* The sphere seen from p is a disc of radius R across wi (a good
     * approximation at the distances of interest); stratified samples on
     * it, an equal-area map of the unit square. */
    sh_vec3 t, b, sum = sh_v3s(0.0);
    sh_basis(wi, &t, &b);
    for (int s = 0; s < count; s++) {
      double u = ((s % side) + sh_rng_next(&rng)) / side;
      double v = ((s / side) + sh_rng_next(&rng)) / side;
      double r = A->radius * sqrt(u), phi = 2.0 * SH_PI * v;
      sh_vec3 q = sh_madd(sh_madd(light->position, t, r * cos(phi)), b,
                          r * sin(phi));
      sh_vec3 to = sh_sub(q, origin);
      double d = sh_length(to);
      sum = sh_add(sum, sh_rt_visibility(A->rt, origin, sh_scale(to, 1.0 / d),
                                         d * (1.0 - 1e-7), c));
    }
    vis[l] = sh_scale(sum, 1.0 / count);
  }
  return 1;
}

sh_status lmm_area_create(const sh_scene *scene, const sh_rt *rt,
                          double radius, int samples, lmm_area **out,
                          sh_error *err) {
  *out = NULL;
  if (samples < 1 || !(radius >= 0))
    return sh_error_set(err, SH_ERR_ARG,
                        "area lights need samples >= 1 and radius >= 0");
  lmm_area *A = calloc(1, sizeof *A);
  if (!A) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  A->scene = scene;
  A->rt = rt;
  A->radius = radius;
  A->samples = samples;
  A->hook.surface = surface;
  A->hook.user = A;
  *out = A;
  return SH_OK;
}

void lmm_area_free(lmm_area *A) { free(A); }

const sh_shadow_hook *lmm_area_hook(const lmm_area *A) { return &A->hook; }
