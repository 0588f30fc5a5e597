#include "lmm_method.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lmm_caustic.h"
#include "sh_light.h"
#include "sh_time.h"

typedef struct scratch {
  sh_vec3 *values; /* one mesh point's values */
  sh_vec3 *acc;    /* the running sums of formula 7 */
  /* The candidates of DLM(P): grid index, ray from P, its length. */
  int *cand;
  sh_vec3 *org, *dir;
  double *len;
  unsigned char *blocked;
  int max_cand;
  uint64_t *words; /* one mesh point's light mask */
  int *count;      /* per light: visible candidates that see it */
  int64_t shaded, empty, candidates, volume;
  char pad[64];
} scratch;

struct lmm {
  const sh_scene *scene;
  const sh_rt *rt;
  lmm_options opt;
  lmm_mesh *mesh;
  lmm_caustics *caustics;
  sh_shadow_hook hook;
  scratch *scratch;
  int threads;
  int semi, hard, refined, bits;
  double build_seconds;
};

/* The exact visibility of a light from p (leaving along n), restricted to
 * the surfaces of the given classes. */
static sh_vec3 exact(const lmm *L, sh_vec3 origin, sh_vec3 p, const sh_light *l,
                     unsigned classes, sh_rt_counters *c) {
  sh_vec3 wi;
  double dist;
  sh_light_incident(l, p, &wi, &dist);
  double tmax = isinf(dist) ? INFINITY : dist * (1.0 - 1e-7);
  return sh_rt_visibility_of(L->rt, origin, wi, tmax, classes, c);
}

/* xi(i, P): 1 if the light lies on the outer side of the surface at P. */
static int outer_side(const sh_light *l, sh_vec3 p, sh_vec3 n) {
  if (l->type == SH_LIGHT_DIRECTIONAL) return -sh_dot(l->direction, n) > 0;
  return sh_dot(sh_sub(l->position, p), n) > 0;
}

/* The values of grid point g: the mesh's visibility, plus, in the
 * refract-both scheme (not refined), the refracted paths' transmittance
 * deposited there (formula 6). */
static void point_values(const lmm *L, const int g[3], sh_vec3 *values,
                         sh_rt_counters *c) {
  lmm_mesh_values(L->mesh, g[0], g[1], g[2], values, c);
  if (!L->caustics || L->refined) return;
  for (int l = 0; l < L->scene->nlights; l++)
    values[l] = sh_add(values[l],
                       lmm_caustics_at(L->caustics, g[0], g[1], g[2], l));
}

static int surface(void *user, int thread, const sh_hit *hit, sh_vec3 n,
                   sh_vec3 *vis, sh_rt_counters *c) {
  sh_vec3 p = hit->p;
  int shape = hit->shape;
  lmm *L = user;
  scratch *sc = &L->scratch[thread];
  const sh_scene *scene = L->scene;
  if (!scene->materials[scene->shapes[shape].material].receives_soft_shadows)
    return 0;
  sc->shaded++;
  int nl = scene->nlights;
  const lmm_grid *grid = lmm_mesh_grid(L->mesh);
  double h = grid->h, r = h * L->opt.kl;
  int lo[3], hi[3];
  lmm_grid_cell(grid, sh_sub(p, sh_v3s(r)), lo);
  lmm_grid_cell(grid, sh_add(p, sh_v3s(r)), hi);
  for (int l = 0; l < nl; l++) sc->acc[l] = sh_v3s(0.0);
  sh_vec3 origin = sh_rt_offset_hit(L->rt, hit, n);
  /* Steps 1 and 2: the grid points in the sphere, on the front side. */
  int nc = 0;
  for (int k = lo[2]; k <= hi[2] + 1; k++)
    for (int j = lo[1]; j <= hi[1] + 1; j++)
      for (int i = lo[0]; i <= hi[0] + 1; i++) {
        if (!lmm_grid_contains(grid, i, j, k) || nc == sc->max_cand) continue;
        sh_vec3 x = lmm_grid_point(grid, i, j, k), dx = sh_sub(x, p);
        if (sh_dot(dx, dx) > r * r || sh_dot(n, dx) <= 4 * hit->err) continue;
        sh_vec3 to = sh_sub(x, origin);
        double dist = sh_length(to);
        if (dist <= 0) continue;
        sc->cand[3 * nc] = i;
        sc->cand[3 * nc + 1] = j;
        sc->cand[3 * nc + 2] = k;
        sc->org[nc] = origin;
        sc->dir[nc] = sh_scale(to, 1.0 / dist);
        sc->len[nc] = dist;
        nc++;
      }
  sc->candidates += nc;
  /* Step 3: x must be visible from P through opaque surfaces, tested as one
   * stream of coherent rays; in semitransparent scenes the surfaces between
   * weigh x by v(x, P). */
  if (!L->semi)
    sh_rt_occluded_stream(L->rt, nc, sc->org, sc->dir, sc->len, SH_RT_OPAQUE,
                          1, sc->blocked, c);
  int m = 0;
  if (L->bits) {
    /* Opaque scenes: count, light by light, the visible candidates that
     * see the light. */
    int nw = (nl + 63) / 64;
    memset(sc->count, 0, sizeof *sc->count * (size_t)nl);
    for (int q = 0; q < nc; q++) {
      if (sc->blocked[q]) continue;
      int *g = &sc->cand[3 * q];
      if (!lmm_mesh_bits(L->mesh, g[0], g[1], g[2], sc->words, c)) break;
      m++;
      for (int w = 0; w < nw; w++)
        for (uint64_t bits = sc->words[w]; bits; bits &= bits - 1)
          sc->count[64 * w + __builtin_ctzll(bits)]++;
    }
    for (int l = 0; l < nl; l++) sc->acc[l] = sh_v3s((double)sc->count[l]);
  }
  for (int q = 0; !L->bits && q < nc; q++) {
    sh_vec3 vxp;
    if (L->semi)
      vxp = sh_rt_visibility(L->rt, origin, sc->dir[q], sc->len[q], c);
    else
      vxp = sh_v3s(sc->blocked[q] ? 0.0 : 1.0);
    if (sh_is_black(vxp)) continue;
    m++;
    int *g = &sc->cand[3 * q];
    point_values(L, g, sc->values, c);
    if (L->refined) {
      /* V(i, x) xi(i, P) + alpha xi(P_j, P), light by light. */
      for (int l = 0; l < nl; l++) {
        sh_vec3 pj = p;
        sh_vec3 v = outer_side(&scene->lights[l], p, n) ? sc->values[l]
                                                        : sh_v3s(0.0);
        sh_vec3 alpha = lmm_caustics_paths(L->caustics, g[0], g[1], g[2], l,
                                           &pj);
        if (sh_dot(sh_sub(pj, p), n) > 0) v = sh_add(v, alpha);
        sc->acc[l] = sh_add(sc->acc[l], sh_mul(vxp, v));
      }
      continue;
    }
    for (int l = 0; l < nl; l++)
      sc->acc[l] = sh_add(sc->acc[l], sh_mul(vxp, sc->values[l]));
  }
  if (m == 0) {
    sc->empty++;
    return 0; /* formula 3: exact shadow rays */
  }
  for (int l = 0; l < nl; l++) {
    const sh_light *light = &scene->lights[l];
    if (!light->soft_shadows) {
      vis[l] = exact(L, origin, p, light, SH_RT_ALL, c);
      continue;
    }
    if (L->refined)
      vis[l] = sh_scale(sc->acc[l], 1.0 / m); /* xi is inside the sum */
    else
      vis[l] = outer_side(light, p, n) ? sh_scale(sc->acc[l], 1.0 / m)
                                       : sh_v3s(0.0);
    if (L->hard && !sh_is_black(vis[l]))
      vis[l] = sh_mul(vis[l], exact(L, origin, p, light, SH_RT_HARD, c));
  }
  return 1;
}

/* The visibility of a light from x in the medium, interpolated from the
 * eight mesh points of x's cell. Where they agree, that value; where they
 * differ, the cell holds a shadow's edge, perhaps a surface, and only the
 * points that x sees count (the surfaces' rule, step 3 of algorithm Psi),
 * weighted by their trilinear weights renormalised: a zero-thickness wall
 * through the cell must not let the lit points on its far side light x (a
 * closed room's fog took up to 0.0026 of the light outside so). A point
 * lying on a surface counts as hidden (its ray from x is tested a little
 * beyond it). With none visible, 0: the tracer's exact shadow ray. */
static int volume(void *user, int thread, sh_vec3 x, int light, sh_vec3 *vis,
                  sh_rt_counters *c) {
  lmm *L = user;
  scratch *sc = &L->scratch[thread];
  const sh_light *l = &L->scene->lights[light];
  if (!l->soft_shadows || L->hard) return 0;
  const lmm_grid *grid = lmm_mesh_grid(L->mesh);
  int ijk[3];
  lmm_grid_cell(grid, x, ijk);
  sh_vec3 base = lmm_grid_point(grid, ijk[0], ijk[1], ijk[2]);
  sh_vec3 f = sh_scale(sh_sub(x, base), 1.0 / grid->h);
  sh_vec3 value[8];
  double weight[8];
  int differ = 0, first = -1;
  for (int corner = 0; corner < 8; corner++) {
    int di = corner & 1, dj = (corner >> 1) & 1, dk = (corner >> 2) & 1;
    int g[3] = {ijk[0] + di, ijk[1] + dj, ijk[2] + dk};
    if (!lmm_grid_contains(grid, g[0], g[1], g[2])) return 0;
    weight[corner] = (di ? f.x : 1 - f.x) * (dj ? f.y : 1 - f.y) *
                     (dk ? f.z : 1 - f.z);
    if (weight[corner] == 0) continue;
    point_values(L, g, sc->values, c);
    value[corner] = sc->values[light];
    if (first < 0)
      first = corner;
    else if (value[corner].x != value[first].x || value[corner].y != value[first].y ||
             value[corner].z != value[first].z)
      differ = 1;
  }
  sh_vec3 sum = sh_v3s(0.0);
  double total = 0;
  for (int corner = 0; corner < 8; corner++) {
    if (weight[corner] == 0) continue;
    double w = weight[corner];
    if (differ) {
      int di = corner & 1, dj = (corner >> 1) & 1, dk = (corner >> 2) & 1;
      sh_vec3 to = sh_sub(lmm_grid_point(grid, ijk[0] + di, ijk[1] + dj, ijk[2] + dk), x);
      double len = sh_length(to);
      if (len > 0 &&
          sh_rt_occluded(L->rt, x, sh_scale(to, 1.0 / len), len * (1.0 + 1e-6), SH_RT_ALL, c))
        continue;
    }
    sum = sh_madd(sum, value[corner], w);
    total += w;
  }
  if (!(total > 0)) return 0;
  sc->volume++;
  *vis = sh_scale(sum, 1.0 / total);
  return 1;
}

double lmm_default_step(const sh_scene *scene) {
  sh_vec3 lo = sh_v3s(INFINITY), hi = sh_v3s(-INFINITY);
  for (int i = 0; i < scene->nshapes; i++) {
    sh_vec3 a, b;
    if (!sh_shape_bounds(&scene->shapes[i], &a, &b)) continue;
    lo = sh_vmin(lo, a);
    hi = sh_vmax(hi, b);
  }
  if (!(lo.x <= hi.x)) sh_scene_bounds(scene, &lo, &hi);
  double diag = sh_length(sh_sub(hi, lo));
  return diag > 0 ? diag / 100.0 : 0.01;
}

sh_status lmm_create(const sh_scene *scene, const sh_rt *rt,
                     const lmm_options *opt, int threads, lmm **out,
                     sh_error *err) {
  *out = NULL;
  if (!(opt->h > 0) || !(opt->kl > 0) || opt->kl > 16 || threads < 1)
    return sh_error_set(err, SH_ERR_ARG,
                        "the mesh step must be > 0, kl in (0, 16], threads "
                        ">= 1");
  lmm *L = calloc(1, sizeof *L);
  if (!L) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  L->scene = scene;
  L->rt = rt;
  L->opt = *opt;
  L->threads = threads;
  L->semi = sh_scene_has_semitransparent(scene);
  L->hard = (sh_rt_classes(rt) & SH_RT_HARD) != 0;
  sh_status st = lmm_mesh_create(scene, rt, opt->h, opt->capacity_log2,
                                 &L->mesh, err);
  if (st != SH_OK) {
    lmm_free(L);
    return st;
  }
  if (opt->scheme == LMM_SCHEME_REFRACT_BOTH && L->semi) {
    double t0 = sh_seconds();
    lmm_caustics_control ctl = {opt->cancel, opt->progress, opt->progress_user};
    st = lmm_caustics_build(scene, rt, lmm_mesh_grid(L->mesh), opt->caustic_rays,
                            &ctl, &L->caustics, err);
    if (st != SH_OK) {
      lmm_free(L);
      return st;
    }
    L->refined = opt->refined;
    lmm_mesh_set_direct_only(L->mesh);
    L->build_seconds = sh_seconds() - t0;
  }
  int nl = scene->nlights > 0 ? scene->nlights : 1;
  L->scratch = calloc((size_t)threads, sizeof *L->scratch);
  if (!L->scratch) {
    lmm_free(L);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  }
  /* The grid points a sphere of radius kl steps can hold. */
  int side = 2 * (int)ceil(opt->kl) + 3;
  int max_cand = side * side * side;
  for (int t = 0; t < threads; t++) {
    scratch *sc = &L->scratch[t];
    sc->values = calloc((size_t)nl, sizeof(sh_vec3));
    sc->acc = calloc((size_t)nl, sizeof(sh_vec3));
    sc->max_cand = max_cand;
    sc->cand = calloc((size_t)max_cand * 3, sizeof(int));
    sc->org = calloc((size_t)max_cand, sizeof(sh_vec3));
    sc->dir = calloc((size_t)max_cand, sizeof(sh_vec3));
    sc->len = calloc((size_t)max_cand, sizeof(double));
    sc->blocked = calloc((size_t)max_cand, 1);
    sc->words = calloc((size_t)(nl + 63) / 64, sizeof(uint64_t));
    sc->count = calloc((size_t)nl, sizeof(int));
    if (!sc->values || !sc->acc || !sc->cand || !sc->org || !sc->dir ||
        !sc->len || !sc->blocked || !sc->words || !sc->count) {
      lmm_free(L);
      return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
    }
  }
  lmm_mesh_stats ms;
  lmm_mesh_get_stats(L->mesh, &ms);
  L->bits = ms.bits;
  L->hook.surface = surface;
  L->hook.volume = opt->volume ? volume : NULL;
  L->hook.user = L;
  *out = L;
  return SH_OK;
}

void lmm_free(lmm *L) {
  if (!L) return;
  if (L->scratch)
    for (int t = 0; t < L->threads; t++) {
      scratch *sc = &L->scratch[t];
      free(sc->values);
      free(sc->acc);
      free(sc->cand);
      free(sc->org);
      free(sc->dir);
      free(sc->len);
      free(sc->blocked);
      free(sc->words);
      free(sc->count);
    }
  free(L->scratch);
  lmm_mesh_free(L->mesh);
  lmm_caustics_free(L->caustics);
  free(L);
}

const sh_shadow_hook *lmm_hook(const lmm *L) { return &L->hook; }

void lmm_get_stats(const lmm *L, lmm_stats *st) {
  memset(st, 0, sizeof *st);
  lmm_mesh_get_stats(L->mesh, &st->mesh);
  for (int t = 0; t < L->threads; t++) {
    st->shaded_points += L->scratch[t].shaded;
    st->empty_sets += L->scratch[t].empty;
    st->candidate_rays += L->scratch[t].candidates;
    st->volume_lookups += L->scratch[t].volume;
  }
  st->caustic_points = L->caustics ? lmm_caustics_points(L->caustics) : 0;
  st->build_seconds = L->build_seconds;
}
