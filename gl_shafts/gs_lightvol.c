#include "gs_lightvol.h"

#include "gs_medium.h"

#include <stdlib.h>
#include <string.h>

/* A spot's cone, circumscribed by a pyramid of this many sides. */
#define PYRAMID_SIDES 8
/* Spots wider than this (degrees) get a cube shadow map. */
#define SPOT_2D_MAX_DEG 70.0

/* The frame of a spot's shadow map: its light-map frame if it has one. */
static void spot_frame(const sh_light *l, sh_vec3 *right, sh_vec3 *up) {
  if (l->has_map) {
    *right = l->map_right;
    *up = l->map_up;
  } else {
    sh_basis(l->direction, right, up);
  }
}

static void region_init(gs__light_setup *ls, const sh_light *l) {
  ls->nregion = 0;
  if (l->type == SH_LIGHT_SPOT && l->cos_outer > 1e-6) {
    ls->cone_clip = 1;
    sh_vec3 r, u;
    spot_frame(l, &r, &u);
    double so = sin(l->outer_deg * SH_PI / 180.0), co = l->cos_outer;
    /* Tangent planes along the generators at angles phi_i: outward normal
     * -sin(outer) axis + cos(outer) (cos phi r + sin phi u). */
    for (int i = 0; i < PYRAMID_SIDES; i++) {
      double phi = 2.0 * SH_PI * i / PYRAMID_SIDES;
      sh_vec3 radial = sh_add(sh_scale(r, cos(phi)), sh_scale(u, sin(phi)));
      sh_vec3 n = sh_add(sh_scale(l->direction, -so), sh_scale(radial, co));
      ls->region[ls->nregion++] = gs__halfspace_at(n, l->position);
    }
  }
  if (l->type == SH_LIGHT_DIRECTIONAL && l->has_map) {
    /* s(p) and t(p) of sh_light_map_value are affine in p: the projection
     * along the direction onto the window's plane, then the window's
     * coordinates. */
    sh_vec3 u = l->map_u, v = l->map_v, n = l->map_normal, d = l->direction;
    double uu = sh_dot(u, u), uv = sh_dot(u, v), vv = sh_dot(v, v);
    double det = uu * vv - uv * uv;
    sh_vec3 as = sh_scale(sh_sub(sh_scale(u, vv), sh_scale(v, uv)), 1.0 / det);
    sh_vec3 at = sh_scale(sh_sub(sh_scale(v, uu), sh_scale(u, uv)), 1.0 / det);
    double dn = sh_dot(d, n);
    sh_vec3 S = sh_sub(as, sh_scale(n, sh_dot(as, d) / dn));
    sh_vec3 T = sh_sub(at, sh_scale(n, sh_dot(at, d) / dn));
    double s0 = -sh_dot(S, l->map_origin), t0 = -sh_dot(T, l->map_origin);
    double w[2][4] = {{S.x, S.y, S.z, s0}, {T.x, T.y, T.z, t0}};
    memcpy(ls->win_s, w[0], sizeof ls->win_s);
    memcpy(ls->win_t, w[1], sizeof ls->win_t);
    sh_vec3 A[2] = {S, T};
    double c0[2] = {s0, t0};
    for (int k = 0; k < 2; k++) {
      gs__halfspace lo = {sh_neg(A[k]), c0[k]};        /* s >= 0 */
      gs__halfspace hi = {A[k], 1.0 - c0[k]};          /* s <= 1 */
      ls->region[ls->nregion++] = lo;
      ls->region[ls->nregion++] = hi;
    }
  }
}

/* True if every corner of the box is outside one of the region's planes. */
static int box_outside_region(const gs__light_setup *ls, sh_vec3 lo, sh_vec3 hi) {
  for (int h = 0; h < ls->nregion; h++) {
    int out = 1;
    for (int i = 0; i < 8 && out; i++) {
      sh_vec3 c = sh_v3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
      if (sh_dot(ls->region[h].n, c) <= ls->region[h].c) out = 0;
    }
    if (out) return 1;
  }
  return 0;
}

/* A set of points that may receive light (lit volume or a shape's box). */
typedef struct receiver {
  int shape; /* -1 for the lit volume */
  int n;
  sh_vec3 *p;
} receiver;

/* True if a face plane of the caster's box separates it from every segment
 * between the light and the receiver's points (so it cannot shadow them).
 * Touching counts as separated. */
static int separated(const sh_light *l, sh_vec3 lo, sh_vec3 hi,
                     const receiver *r, double eps) {
  for (int k = 0; k < 3; k++) {
    double bl = sh_vget(lo, k), bh = sh_vget(hi, k);
    for (int side = 0; side < 2; side++) {
      int ok = 1;
      if (l->type == SH_LIGHT_DIRECTIONAL) {
        double dk = sh_vget(l->direction, k);
        ok = side ? dk <= eps : dk >= -eps;
      } else {
        double lk = sh_vget(l->position, k);
        ok = side ? lk >= bh - eps : lk <= bl + eps;
      }
      for (int i = 0; i < r->n && ok; i++) {
        double x = sh_vget(r->p[i], k);
        ok = side ? x >= bh - eps : x <= bl + eps;
      }
      if (ok) return 1;
    }
  }
  return 0;
}

/* Marks in ls->casts the shapes that may shadow the lit volume or another
 * shape; returns how many. */
static int find_casters(gs__light_setup *ls, const gs__geometry *geom,
                        double eps, int *nomem) {
  int nrec = 0, ncasters = 0;
  receiver *rec = calloc((size_t)geom->nshapes + 1, sizeof *rec);
  sh_vec3 *pts = malloc(((size_t)geom->nshapes * 8 +
                         GS__POLY_MAX_FACES * GS__POLY_MAX_FACE_VERTS) * sizeof *pts);
  if (!rec || !pts) {
    free(rec);
    free(pts);
    *nomem = 1;
    return 0;
  }
  sh_vec3 *next = pts;
  if (ls->vol->nfaces) {
    rec[nrec].shape = -1;
    rec[nrec].p = next;
    rec[nrec].n = gs__poly_vertices(ls->vol, next,
                                    GS__POLY_MAX_FACES * GS__POLY_MAX_FACE_VERTS);
    next += rec[nrec++].n;
  }
  for (int i = 0; i < geom->nshapes; i++) {
    const gs__shape_draw *s = &geom->shape[i];
    if (s->count == 0 || box_outside_region(ls, s->bmin, s->bmax)) continue;
    rec[nrec].shape = i;
    rec[nrec].p = next;
    rec[nrec].n = 8;
    for (int c = 0; c < 8; c++)
      next[c] = sh_v3(c & 1 ? s->bmax.x : s->bmin.x, c & 2 ? s->bmax.y : s->bmin.y,
                      c & 4 ? s->bmax.z : s->bmin.z);
    next += 8;
    nrec++;
  }
  for (int i = 0; i < geom->nshapes; i++) {
    const gs__shape_draw *c = &geom->shape[i];
    ls->casts[i] = 0;
    if (c->count == 0 || box_outside_region(ls, c->bmin, c->bmax)) continue;
    for (int j = 0; j < nrec && !ls->casts[i]; j++) {
      if (rec[j].shape == i && c->convex) continue;
      if (!separated(ls->light, c->bmin, c->bmax, &rec[j], eps)) ls->casts[i] = 1;
    }
    ncasters += ls->casts[i];
  }
  free(rec);
  free(pts);
  return ncasters;
}

/* Row r of a matrix from a linear form a . (p - o) + b. */
static void set_row(sh_mat4 *m, int r, sh_vec3 a, sh_vec3 o, double b) {
  m->m[r][0] = a.x;
  m->m[r][1] = a.y;
  m->m[r][2] = a.z;
  m->m[r][3] = b - sh_dot(a, o);
}

static void shadow_2d_spot(gs__light_setup *ls, const sh_light *l) {
  sh_vec3 r, u;
  spot_frame(l, &r, &u);
  double k = 1.0 / l->tan_outer;
  sh_mat4 m = {{{0}}};
  set_row(&m, 0, sh_scale(r, k), l->position, 0);
  set_row(&m, 1, sh_scale(u, k), l->position, 0);
  m.m[2][3] = ls->shadow_near;
  set_row(&m, 3, l->direction, l->position, 0);
  ls->nfaces = 1;
  ls->face_vp[0] = m;
  ls->shadow_span = 2.0 * l->tan_outer;
}

static void shadow_cube(gs__light_setup *ls, const sh_light *l) {
  /* The cube-map face conventions of the GL specification (table 8.19):
   * face i is selected by its major axis and addressed by (sc, tc) / ma. */
  static const double sc[6][3] = {{0, 0, -1}, {0, 0, 1}, {1, 0, 0},
                                  {1, 0, 0},  {1, 0, 0}, {-1, 0, 0}};
  static const double tc[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                                  {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  static const double ma[6][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                  {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  ls->nfaces = 6;
  ls->shadow_span = 2.0;
  for (int f = 0; f < 6; f++) {
    sh_mat4 m = {{{0}}};
    set_row(&m, 0, sh_v3(sc[f][0], sc[f][1], sc[f][2]), l->position, 0);
    set_row(&m, 1, sh_v3(tc[f][0], tc[f][1], tc[f][2]), l->position, 0);
    m.m[2][3] = ls->shadow_near;
    set_row(&m, 3, sh_v3(ma[f][0], ma[f][1], ma[f][2]), l->position, 0);
    ls->face_vp[f] = m;
  }
}

/* An orthographic map along the light covering what the camera sees of the
 * lit region (the scene's bounds inside the frustum and the region), deep
 * enough to hold every caster on the way. */
static int shadow_ortho(gs__light_setup *ls, const sh_light *l,
                        const sh_scene *scene, const gs__view *view) {
  sh_vec3 lo, hi;
  int whole = gs__medium_shadow_bounds(scene, &lo, &hi);
  gs__poly *rp = malloc(sizeof *rp);
  if (!rp) return 0;
  gs__poly_box(rp, lo, hi);
  gs__halfspace fr[5];
  gs__view_frustum(view, fr);
  for (int i = 0; i < 5 && !whole; i++) gs__poly_clip(rp, fr[i]);
  for (int i = 0; i < ls->nregion; i++) gs__poly_clip(rp, ls->region[i]);
  if (rp->nfaces == 0) {
    free(rp);
    return 1; /* nothing visible is lit: the map stays empty */
  }
  sh_vec3 a, b, w = l->direction;
  sh_basis(w, &a, &b);
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  double s1 = -INFINITY, s0 = INFINITY;
  for (int f = 0; f < rp->nfaces; f++)
    for (int i = 0; i < rp->face[f].n; i++) {
      sh_vec3 p = rp->face[f].v[i];
      x0 = fmin(x0, sh_dot(a, p));
      x1 = fmax(x1, sh_dot(a, p));
      y0 = fmin(y0, sh_dot(b, p));
      y1 = fmax(y1, sh_dot(b, p));
      s1 = fmax(s1, sh_dot(w, p));
    }
  free(rp);
  for (int i = 0; i < 8; i++)
    s0 = fmin(s0, sh_dot(w, sh_v3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y,
                                  i & 4 ? hi.z : lo.z)));
  /* Relative to the map's extent and position (an absolute 1e-9 was as
   * large as a scene a billionth of a unit across). */
  double pad = 1e-3 * fmax(x1 - x0, y1 - y0) +
               1e-9 * (fabs(x0) + fabs(x1) + fabs(y0) + fabs(y1));
  if (!(pad > 0)) pad = 1e-9;
  x0 -= pad, x1 += pad, y0 -= pad, y1 += pad, s0 -= pad, s1 += pad;
  sh_mat4 m = {{{0}}};
  sh_vec3 o = sh_v3s(0);
  set_row(&m, 0, sh_scale(a, 2.0 / (x1 - x0)), o, -(x1 + x0) / (x1 - x0));
  set_row(&m, 1, sh_scale(b, 2.0 / (y1 - y0)), o, -(y1 + y0) / (y1 - y0));
  set_row(&m, 2, sh_scale(w, -1.0 / (s1 - s0)), o, s1 / (s1 - s0));
  m.m[3][3] = 1.0;
  ls->nfaces = 1;
  ls->face_vp[0] = m;
  ls->shadow_span = fmax(x1 - x0, y1 - y0);
  return 1;
}

/* Whether a counter-clockwise triangle facing the light looks
 * counter-clockwise through the map's projection m, whose forward axis is
 * fwd, at point c in front of the light. */
static int light_front(const sh_mat4 *m, sh_vec3 c, sh_vec3 fwd) {
  sh_vec3 a, b;
  sh_basis(sh_neg(fwd), &a, &b); /* a x b = -fwd: the normal faces the light */
  sh_vec3 v[3] = {c, sh_add(c, a), sh_add(c, b)};
  double x[3], y[3];
  for (int i = 0; i < 3; i++) {
    double w = m->m[3][0] * v[i].x + m->m[3][1] * v[i].y + m->m[3][2] * v[i].z + m->m[3][3];
    x[i] = (m->m[0][0] * v[i].x + m->m[0][1] * v[i].y + m->m[0][2] * v[i].z + m->m[0][3]) / w;
    y[i] = (m->m[1][0] * v[i].x + m->m[1][1] * v[i].y + m->m[1][2] * v[i].z + m->m[1][3]) / w;
  }
  return (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]) > 0;
}

/* The view-depth range and the screen rectangle (ndc x0, y0, x1, y1, within
 * [-1, 1]; x0 > x1 if p is empty) of a polytope in the view frustum. */
static void poly_bounds(const gs__poly *p, const gs__view *view, double *zmin,
                        double *zmax, double rect[4]) {
  *zmin = INFINITY;
  *zmax = -INFINITY;
  rect[0] = rect[1] = 1.0;
  rect[2] = rect[3] = -1.0;
  for (int f = 0; f < p->nfaces; f++)
    for (int i = 0; i < p->face[f].n; i++) {
      sh_vec3 q = p->face[f].v[i];
      double z = gs__view_depth(view, q), x, y;
      *zmin = fmin(*zmin, z);
      *zmax = fmax(*zmax, z);
      gs__view_ndc(view, q, &x, &y);
      rect[0] = fmin(rect[0], x);
      rect[1] = fmin(rect[1], y);
      rect[2] = fmax(rect[2], x);
      rect[3] = fmax(rect[3], y);
    }
  for (int k = 0; k < 2; k++) {
    rect[k] = fmax(rect[k], -1.0);
    rect[k + 2] = fmin(rect[k + 2], 1.0);
  }
}

sh_status gs__light_setup_init(gs__light_setup *ls, const sh_scene *scene,
                               int index, const gs__view *view,
                               const gs__geometry *geom, sh_error *err) {
  memset(ls, 0, sizeof *ls);
  const sh_light *l = &scene->lights[index];
  ls->light = l;
  ls->vol = malloc(sizeof *ls->vol);
  if (!ls->vol) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  ls->vol->nfaces = 0;
  region_init(ls, l);

  sh_vec3 lo, hi;
  sh_scene_bounds(scene, &lo, &hi);
  double size = sh_length(sh_sub(hi, lo));
  double eps = 1e-7 * (size > 0 ? size : 1.0);

  const sh_medium *m = &scene->medium;
  if (m->present && !sh_is_black(m->sigma_s)) {
    gs__poly_box(ls->vol, m->bmin, m->bmax);
    for (int i = 0; i < ls->nregion; i++) gs__poly_clip(ls->vol, ls->region[i]);
    gs__halfspace fr[5];
    gs__view_frustum(view, fr);
    for (int i = 0; i < 5; i++) gs__poly_clip(ls->vol, fr[i]);
  }
  poly_bounds(ls->vol, view, &ls->zmin, &ls->zmax, ls->rect);
  gs__poly *reach = malloc(sizeof *reach);
  if (!reach) {
    gs__light_setup_free(ls);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  }
  gs__poly_box(reach, lo, hi);
  for (int i = 0; i < ls->nregion; i++) gs__poly_clip(reach, ls->region[i]);
  gs__halfspace frs[5];
  gs__view_frustum(view, frs);
  for (int i = 0; i < 5; i++) gs__poly_clip(reach, frs[i]);
  double zr[2];
  poly_bounds(reach, view, &zr[0], &zr[1], ls->surface_rect);
  free(reach);
  if (ls->vol->nfaces && !(ls->zmax > ls->zmin)) ls->vol->nfaces = 0;

  int nomem = 0;
  ls->shadow = GS__SHADOW_NONE;
  ls->casts = calloc((size_t)(geom->nshapes ? geom->nshapes : 1), 1);
  if (!ls->casts) nomem = 1;
  else if (find_casters(ls, geom, eps, &nomem) > 0) {
    /* Perspective maps store near / distance, of relative precision at
     * any near distance: tiny against the scene (1e-4 of a planet's bounds
     * was 1.8 km, and a spot 30 m above the ground cast no shadow). */
    ls->shadow_near = 1e-10 * (size > 0 ? size : 1.0);
    if (l->type == SH_LIGHT_DIRECTIONAL) {
      ls->shadow = GS__SHADOW_2D;
      if (!shadow_ortho(ls, l, scene, view)) nomem = 1;
    } else if (l->type == SH_LIGHT_SPOT && l->outer_deg <= SPOT_2D_MAX_DEG) {
      ls->shadow = GS__SHADOW_2D;
      shadow_2d_spot(ls, l);
    } else {
      ls->shadow = GS__SHADOW_CUBE;
      shadow_cube(ls, l);
    }
    for (int f = 0; f < ls->nfaces; f++) {
      const sh_mat4 *m = &ls->face_vp[f];
      if (l->type == SH_LIGHT_DIRECTIONAL) {
        ls->light_front[f] = light_front(m, sh_v3s(0), l->direction);
      } else {
        sh_vec3 fwd = sh_normalize(sh_v3(m->m[3][0], m->m[3][1], m->m[3][2]));
        ls->light_front[f] = light_front(m, sh_add(l->position, fwd), fwd);
      }
    }
    if (ls->shadow == GS__SHADOW_2D) {
      sh_mat4 bias = {{{0.5, 0, 0, 0.5}, {0, 0.5, 0, 0.5}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
      /* For perspective maps the bias must act on clip coordinates before
       * the division: x' = 0.5 x + 0.5 w. */
      ls->lookup = sh_mat4_mul(bias, ls->face_vp[0]);
    }
  }
  if (nomem) {
    gs__light_setup_free(ls);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  }
  return SH_OK;
}

void gs__light_setup_free(gs__light_setup *ls) {
  free(ls->vol);
  free(ls->casts);
  ls->vol = NULL;
  ls->casts = NULL;
}
