#include "lmm_caustic.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sh_rng.h"

/* A growable open-addressing map from (grid point, light) to an RGB sum;
 * it is filled by one thread before rendering and only read afterwards. */
typedef struct entry {
  uint64_t key; /* 0: empty */
  float rgb[3];
  /* The paths' last surface points P_j, summed with their weights. */
  float pj[3], wsum;
} entry;

struct lmm_caustics {
  entry *table;
  uint64_t mask, count;
  int nlights;
  lmm_grid grid;
};

static uint64_t key_of(const lmm_caustics *c, int i, int j, int k, int l) {
  uint64_t lin = lmm_grid_index(&c->grid, i, j, k);
  return 1 + lin * (uint64_t)c->nlights + (uint64_t)l;
}

static entry *find(const lmm_caustics *c, uint64_t key) {
  uint64_t s = sh_hash64(key) & c->mask;
  for (;;) {
    entry *e = &c->table[s];
    if (e->key == key || e->key == 0) return e;
    s = (s + 1) & c->mask;
  }
}

static int grow(lmm_caustics *c) {
  uint64_t old_size = c->mask + 1;
  entry *old = c->table;
  entry *t = calloc((size_t)old_size * 2, sizeof *t);
  if (!t) return 0;
  c->table = t;
  c->mask = old_size * 2 - 1;
  for (uint64_t s = 0; s < old_size; s++)
    if (old[s].key) *find(c, old[s].key) = old[s];
  free(old);
  return 1;
}

static int credit(lmm_caustics *c, uint64_t key, sh_vec3 w, sh_vec3 pj) {
  if ((c->count + 1) * 10 > (c->mask + 1) * 7 && !grow(c)) return 0;
  entry *e = find(c, key);
  if (!e->key) {
    e->key = key;
    c->count++;
  }
  e->rgb[0] += (float)w.x;
  e->rgb[1] += (float)w.y;
  e->rgb[2] += (float)w.z;
  double lum = (w.x + w.y + w.z) / 3.0;
  e->pj[0] += (float)(lum * pj.x);
  e->pj[1] += (float)(lum * pj.y);
  e->pj[2] += (float)(lum * pj.z);
  e->wsum += (float)lum;
  return 1;
}

typedef struct tracer {
  lmm_caustics *c;
  const sh_scene *scene;
  const sh_rt *rt;
  const lmm_grid *grid;
  double h, rho;
  int light;
  sh_vec3 light_pos;
  int directional;
  double norm; /* the unobstructed ray count through a disc, up to d^2 */
} tracer;

/* Credits the grid points within rho of the segment a + t d, t in [0, len],
 * with weight w over the unobstructed count of rays through their disc. */
static int deposit(tracer *tr, sh_vec3 a, sh_vec3 d, double len, sh_vec3 w) {
  uint64_t prev[8], cur[8];
  int nprev = 0;
  double step = tr->h / 3.0;
  for (double s = 0.0; s <= len + step; s += step) {
    sh_vec3 q = sh_madd(a, d, fmin(s, len));
    int ijk[3], ncur = 0;
    lmm_grid_cell(tr->grid, q, ijk);
    for (int corner = 0; corner < 8; corner++) {
      int i = ijk[0] + (corner & 1), j = ijk[1] + ((corner >> 1) & 1),
          k = ijk[2] + ((corner >> 2) & 1);
      if (!lmm_grid_contains(tr->grid, i, j, k)) continue;
      sh_vec3 x = lmm_grid_point(tr->grid, i, j, k), ax = sh_sub(x, a);
      double t = sh_dot(ax, d);
      if (t < 0 || t > len || sh_dot(ax, ax) - t * t > tr->rho * tr->rho)
        continue;
      uint64_t key = key_of(tr->c, i, j, k, tr->light);
      cur[ncur++] = key;
      int seen = 0;
      for (int p = 0; p < nprev; p++) seen |= prev[p] == key;
      if (seen) continue;
      double scale = tr->norm;
      if (!tr->directional) {
        sh_vec3 r = sh_sub(x, tr->light_pos);
        scale *= sh_dot(r, r);
      }
      if (!credit(tr->c, key, sh_scale(w, scale), a)) return 0;
    }
    memcpy(prev, cur, sizeof cur);
    nprev = ncur;
  }
  return 1;
}

/* How far the ray from o (inside [lo, hi]) travels before leaving the
 * box; 0 if o is outside. */
static double exit_distance(sh_vec3 lo, sh_vec3 hi, sh_vec3 o, sh_vec3 d) {
  double far = INFINITY;
  for (int a = 0; a < 3; a++) {
    double oa = sh_vget(o, a), da = sh_vget(d, a);
    if (oa < sh_vget(lo, a) || oa > sh_vget(hi, a)) return 0.0;
    if (da > 0) far = fmin(far, (sh_vget(hi, a) - oa) / da);
    else if (da < 0) far = fmin(far, (sh_vget(lo, a) - oa) / da);
  }
  return isfinite(far) ? far : 0.0;
}

/* Follows one ray from the light through semitransparent surfaces. */
static int trace(tracer *tr, sh_vec3 o, sh_vec3 d) {
  sh_vec3 w = sh_v3s(1.0);
  int refracted = 0;
  sh_vec3 lo = tr->grid->origin, hi = lmm_grid_far_corner(tr->grid);
  for (int bounce = 0; bounce < 32; bounce++) {
    sh_hit hit;
    int any = sh_rt_intersect(tr->rt, o, d, 0.0, INFINITY, &hit, NULL);
    double end = any ? hit.t : INFINITY;
    if (refracted) {
      if (!any) end = exit_distance(lo, hi, o, d);
      if (end > 0 && !deposit(tr, o, d, end, w)) return 0;
    }
    if (!any) break;
    const sh_material *mat =
        &tr->scene->materials[tr->scene->shapes[hit.shape].material];
    if (sh_is_black(mat->transmit)) break;
    w = sh_mul(w, mat->transmit);
    if (sh_max3(w) < 1e-4) break;
    int entering = sh_dot(hit.ng, d) < 0;
    sh_vec3 nrm = entering ? hit.ng : sh_neg(hit.ng);
    double eta = entering ? 1.0 / mat->ior : mat->ior;
    double ci = -sh_dot(nrm, d);
    double k = 1.0 - eta * eta * (1.0 - ci * ci);
    if (k < 0) {
      d = sh_reflect(d, nrm);
      o = sh_rt_offset_hit(tr->rt, &hit, nrm);
    } else {
      d = sh_normalize(sh_madd(sh_scale(d, eta), nrm, eta * ci - sqrt(k)));
      o = sh_rt_offset_hit(tr->rt, &hit, sh_neg(nrm));
    }
    refracted = 1;
  }
  return 1;
}

/* Checked every this many rays. */
enum { CANCEL_EVERY = 4096 };

/* Every CANCEL_EVERY rays: 0 to stop (cancelled), after reporting the
 * progress. */
static int go_on(const lmm_caustics_control *ctl, int64_t done, int64_t total) {
  if (!ctl) return 1;
  if (ctl->progress) ctl->progress(ctl->progress_user, (long)done, (long)total);
  return !(ctl->cancel && *ctl->cancel);
}

sh_status lmm_caustics_build(const sh_scene *scene, const sh_rt *rt,
                             const lmm_grid *grid, int64_t rays,
                             const lmm_caustics_control *ctl,
                             lmm_caustics **out, sh_error *err) {
  *out = NULL;
  int64_t pairs = 0, done = 0; /* lights x semitransparent shapes */
  for (int s = 0; s < scene->nshapes; s++)
    if (!sh_is_black(scene->materials[scene->shapes[s].material].transmit))
      pairs += scene->nlights;
  const int64_t total = pairs * rays;
  lmm_caustics *c = calloc(1, sizeof *c);
  if (!c) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  c->nlights = scene->nlights > 0 ? scene->nlights : 1;
  c->mask = (1u << 16) - 1;
  c->table = calloc((size_t)c->mask + 1, sizeof *c->table);
  tracer tr;
  memset(&tr, 0, sizeof tr);
  tr.c = c;
  tr.scene = scene;
  tr.rt = rt;
  c->grid = *grid;
  tr.grid = &c->grid;
  tr.h = grid->h;
  tr.rho = tr.h;
  if (!c->table) goto nomem;
  sh_rng rng;
  sh_rng_seed(&rng, 12345, 678);
  for (int l = 0; l < scene->nlights; l++) {
    const sh_light *light = &scene->lights[l];
    tr.light = l;
    tr.light_pos = light->position;
    tr.directional = light->type == SH_LIGHT_DIRECTIONAL;
    for (int s = 0; s < scene->nshapes; s++) {
      const sh_shape *shape = &scene->shapes[s];
      if (sh_is_black(scene->materials[shape->material].transmit)) continue;
      const int64_t base = done; /* rays of the pairs before this one */
      done += rays;
      sh_vec3 lo, hi;
      if (!sh_shape_bounds(shape, &lo, &hi)) continue;
      sh_vec3 ctr = sh_scale(sh_add(lo, hi), 0.5);
      double R = 0.5 * sh_length(sh_sub(hi, lo));
      double disc = SH_PI * tr.rho * tr.rho;
      if (tr.directional) {
        /* Parallel rays over the disc of radius R across the light,
         * starting upstream of the shape. */
        sh_vec3 dir = light->direction, t, b;
        sh_basis(dir, &t, &b);
        tr.norm = SH_PI * R * R / ((double)rays * disc);
        for (int64_t r = 0; r < rays; r++) {
          if (r % CANCEL_EVERY == 0 && !go_on(ctl, base + r, total))
            goto cancelled;
          double u = sh_rng_next(&rng), v = sh_rng_next(&rng);
          double rad = R * sqrt(u), phi = 2 * SH_PI * v;
          sh_vec3 o = sh_madd(sh_madd(sh_madd(ctr, t, rad * cos(phi)), b,
                                      rad * sin(phi)),
                              dir, -2.0 * R);
          if (!trace(&tr, o, dir)) goto nomem;
        }
      } else {
        /* Directions uniform in the cone that holds the shape's bounding
         * sphere (the whole sphere of directions if the light is in it). */
        sh_vec3 axis = sh_sub(ctr, light->position);
        double d0 = sh_length(axis);
        double cos_max = d0 > R ? sqrt(1.0 - (R / d0) * (R / d0)) : -1.0;
        axis = d0 > 0 ? sh_scale(axis, 1.0 / d0) : sh_v3(0, 1, 0);
        sh_vec3 t, b;
        sh_basis(axis, &t, &b);
        double omega = 2 * SH_PI * (1.0 - cos_max);
        tr.norm = omega / ((double)rays * disc);
        for (int64_t r = 0; r < rays; r++) {
          if (r % CANCEL_EVERY == 0 && !go_on(ctl, base + r, total))
            goto cancelled;
          double ct = 1.0 - sh_rng_next(&rng) * (1.0 - cos_max);
          double st = sqrt(fmax(0.0, 1.0 - ct * ct)), phi = 2 * SH_PI * sh_rng_next(&rng);
          sh_vec3 dir = sh_madd(sh_madd(sh_scale(axis, ct), t, st * cos(phi)),
                                b, st * sin(phi));
          if (!trace(&tr, light->position, dir)) goto nomem;
        }
      }
    }
  }
  go_on(ctl, total, total);
  *out = c;
  return SH_OK;
nomem:
  lmm_caustics_free(c);
  return sh_error_set(err, SH_ERR_NOMEM, "out of memory for refracted paths");
cancelled:
  lmm_caustics_free(c);
  return sh_error_set(err, SH_ERR_CANCELLED,
                      "rendering was cancelled (tracing refracted paths)");
}

void lmm_caustics_free(lmm_caustics *c) {
  if (!c) return;
  free(c->table);
  free(c);
}

sh_vec3 lmm_caustics_at(const lmm_caustics *c, int i, int j, int k, int light) {
  return lmm_caustics_paths(c, i, j, k, light, NULL);
}

sh_vec3 lmm_caustics_paths(const lmm_caustics *c, int i, int j, int k,
                           int light, sh_vec3 *pj) {
  const entry *e = find(c, key_of(c, i, j, k, light));
  if (!e->key) return sh_v3s(0.0);
  if (pj && e->wsum > 0)
    *pj = sh_scale(sh_v3(e->pj[0], e->pj[1], e->pj[2]), 1.0 / e->wsum);
  return sh_v3(e->rgb[0], e->rgb[1], e->rgb[2]);
}

int64_t lmm_caustics_points(const lmm_caustics *c) { return (int64_t)c->count; }
