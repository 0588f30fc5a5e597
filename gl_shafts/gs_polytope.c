#include "gs_polytope.h"

#include <stdlib.h>
#include <string.h>

gs__halfspace gs__halfspace_at(sh_vec3 n, sh_vec3 p) {
  gs__halfspace h = {n, sh_dot(n, p)};
  return h;
}

static void quad(gs__face *f, sh_vec3 a, sh_vec3 b, sh_vec3 c, sh_vec3 d) {
  f->n = 4;
  f->v[0] = a;
  f->v[1] = b;
  f->v[2] = c;
  f->v[3] = d;
}

void gs__poly_box(gs__poly *p, sh_vec3 lo, sh_vec3 hi) {
  sh_vec3 c[8];
  for (int i = 0; i < 8; i++)
    c[i] = sh_v3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
  p->nfaces = 6;
  quad(&p->face[0], c[0], c[4], c[6], c[2]); /* -x */
  quad(&p->face[1], c[1], c[3], c[7], c[5]); /* +x */
  quad(&p->face[2], c[0], c[1], c[5], c[4]); /* -y */
  quad(&p->face[3], c[2], c[6], c[7], c[3]); /* +y */
  quad(&p->face[4], c[0], c[2], c[3], c[1]); /* -z */
  quad(&p->face[5], c[4], c[5], c[7], c[6]); /* +z */
}

/* Sorting the new cap's points by angle around their centroid. */
typedef struct cap_point {
  sh_vec3 p;
  double angle;
} cap_point;

static int by_angle(const void *a, const void *b) {
  double x = ((const cap_point *)a)->angle, y = ((const cap_point *)b)->angle;
  return x < y ? -1 : x > y;
}

int gs__poly_clip(gs__poly *p, gs__halfspace h) {
  if (p->nfaces == 0) return 0;
  double len = sh_length(h.n);
  if (len == 0) return p->nfaces;
  /* Distances scaled to the polytope's size, for a tolerance. */
  double scale = 0;
  for (int f = 0; f < p->nfaces; f++)
    for (int i = 0; i < p->face[f].n; i++)
      scale = fmax(scale, sh_max3(sh_vmax(p->face[f].v[i],
                                          sh_neg(p->face[f].v[i]))));
  double eps = 1e-12 * (scale + fabs(h.c) / len) * len;
  /* Nothing beyond the plane (it may hold a face): unchanged. */
  int beyond = 0;
  for (int f = 0; f < p->nfaces && !beyond; f++)
    for (int i = 0; i < p->face[f].n && !beyond; i++)
      beyond = sh_dot(h.n, p->face[f].v[i]) - h.c > eps;
  if (!beyond) return p->nfaces;

  gs__poly *out = malloc(sizeof *out);
  if (!out) return p->nfaces;
  cap_point cap[2 * GS__POLY_MAX_FACES * 2];
  int ncap = 0, overflow = 0;
  out->nfaces = 0;
  for (int f = 0; f < p->nfaces && !overflow; f++) {
    const gs__face *in = &p->face[f];
    gs__face nf;
    nf.n = 0;
    for (int i = 0; i < in->n; i++) {
      sh_vec3 a = in->v[i], b = in->v[(i + 1) % in->n];
      double da = sh_dot(h.n, a) - h.c, db = sh_dot(h.n, b) - h.c;
      if (da <= eps) {
        if (nf.n == GS__POLY_MAX_FACE_VERTS) overflow = 1;
        else nf.v[nf.n++] = a;
        if (da >= -eps && ncap < (int)(sizeof cap / sizeof cap[0]))
          cap[ncap++].p = a;
      }
      if ((da < -eps && db > eps) || (da > eps && db < -eps)) {
        sh_vec3 x = sh_madd(a, sh_sub(b, a), da / (da - db));
        if (nf.n == GS__POLY_MAX_FACE_VERTS) overflow = 1;
        else nf.v[nf.n++] = x;
        if (ncap < (int)(sizeof cap / sizeof cap[0])) cap[ncap++].p = x;
        else overflow = 1;
      }
    }
    if (nf.n >= 3) {
      if (out->nfaces == GS__POLY_MAX_FACES) overflow = 1;
      else out->face[out->nfaces++] = nf;
    }
  }
  if (!overflow && ncap >= 3 && out->nfaces > 0) {
    /* The cap: the new points in the plane, ordered around their centroid
     * so that the face's normal is h.n (outwards), duplicates dropped. */
    sh_vec3 c = sh_v3s(0);
    for (int i = 0; i < ncap; i++) c = sh_add(c, cap[i].p);
    c = sh_scale(c, 1.0 / ncap);
    sh_vec3 t, b, n = sh_scale(h.n, 1.0 / len);
    sh_basis(n, &t, &b);
    for (int i = 0; i < ncap; i++) {
      sh_vec3 d = sh_sub(cap[i].p, c);
      cap[i].angle = atan2(sh_dot(d, b), sh_dot(d, t));
    }
    qsort(cap, (size_t)ncap, sizeof cap[0], by_angle);
    gs__face nf;
    nf.n = 0;
    /* Relative to the coordinates: an absolute part (it was + 1) merged
     * every vertex of a scene a billionth of a unit across. */
    double tol = 1e-9 * scale;
    for (int i = 0; i < ncap && nf.n < GS__POLY_MAX_FACE_VERTS; i++) {
      if (nf.n && sh_length(sh_sub(cap[i].p, nf.v[nf.n - 1])) <= tol) continue;
      nf.v[nf.n++] = cap[i].p;
    }
    while (nf.n > 1 && sh_length(sh_sub(nf.v[0], nf.v[nf.n - 1])) <= tol) nf.n--;
    if (nf.n >= 3) {
      if (out->nfaces == GS__POLY_MAX_FACES) overflow = 1;
      else out->face[out->nfaces++] = nf;
    }
  }
  if (!overflow) {
    /* Fewer than four faces cannot enclose a volume: empty. */
    if (out->nfaces < 4) out->nfaces = 0;
    memcpy(p, out, sizeof *p);
  }
  free(out);
  return p->nfaces;
}

int gs__poly_vertices(const gs__poly *p, sh_vec3 *out, int max) {
  int n = 0;
  for (int f = 0; f < p->nfaces; f++)
    for (int i = 0; i < p->face[f].n && n < max; i++) out[n++] = p->face[f].v[i];
  return n;
}

int gs__poly_slab_points(const gs__poly *p, sh_vec3 a, double lo, double hi,
                         sh_vec3 *out, int max) {
  int n = 0;
  for (int f = 0; f < p->nfaces; f++) {
    const gs__face *fc = &p->face[f];
    for (int i = 0; i < fc->n; i++) {
      sh_vec3 u = fc->v[i], v = fc->v[(i + 1) % fc->n];
      double su = sh_dot(a, u), sv = sh_dot(a, v);
      if (su >= lo && su <= hi && n < max) out[n++] = u;
      double cuts[2] = {lo, hi};
      for (int k = 0; k < 2; k++) {
        double s = cuts[k];
        if (((su < s && sv > s) || (su > s && sv < s)) && n < max)
          out[n++] = sh_madd(u, sh_sub(v, u), (s - su) / (sv - su));
      }
    }
  }
  return n;
}

static int by_xy(const void *a, const void *b) {
  const double *p = a, *q = b;
  if (p[0] != q[0]) return p[0] < q[0] ? -1 : 1;
  return p[1] < q[1] ? -1 : p[1] > q[1];
}

static double cross2(const double *o, const double *a, const double *b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

int gs__hull2d(double (*pts)[2], int n, double (*out)[2]) {
  /* Andrew's monotone chain. */
  if (n < 3) {
    for (int i = 0; i < n; i++) {
      out[i][0] = pts[i][0];
      out[i][1] = pts[i][1];
    }
    return n;
  }
  qsort(pts, (size_t)n, sizeof pts[0], by_xy);
  int k = 0;
  for (int i = 0; i < n; i++) {
    while (k >= 2 && cross2(out[k - 2], out[k - 1], pts[i]) <= 0) k--;
    out[k][0] = pts[i][0];
    out[k][1] = pts[i][1];
    k++;
  }
  for (int i = n - 2, lower = k + 1; i >= 0; i--) {
    while (k >= lower && cross2(out[k - 2], out[k - 1], pts[i]) <= 0) k--;
    out[k][0] = pts[i][0];
    out[k][1] = pts[i][1];
    k++;
  }
  return k - 1; /* the last point repeats the first */
}
