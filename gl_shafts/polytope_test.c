/* The convex polytopes that bound a light's lit volume: clipping a box by
 * planes, the points spanning a slab of it, and 2D convex hulls. */
#include <stdlib.h>

#include "gs_polytope.h"
#include "sh_test.h"

/* The volume of a convex polytope: the sum of the cones from its centroid
 * to its faces. */
static double volume(const gs__poly *p) {
  sh_vec3 c = sh_v3s(0);
  int n = 0;
  for (int f = 0; f < p->nfaces; f++)
    for (int i = 0; i < p->face[f].n; i++, n++) c = sh_add(c, p->face[f].v[i]);
  if (!n) return 0;
  c = sh_scale(c, 1.0 / n);
  double v = 0;
  for (int f = 0; f < p->nfaces; f++) {
    const gs__face *fc = &p->face[f];
    for (int i = 1; i + 1 < fc->n; i++) {
      sh_vec3 a = sh_sub(fc->v[0], c), b = sh_sub(fc->v[i], c), d = sh_sub(fc->v[i + 1], c);
      v += fabs(sh_dot(a, sh_cross(b, d))) / 6.0;
    }
  }
  return v;
}

static int inside(sh_vec3 p, sh_vec3 lo, sh_vec3 hi, double eps) {
  return p.x >= lo.x - eps && p.y >= lo.y - eps && p.z >= lo.z - eps &&
         p.x <= hi.x + eps && p.y <= hi.y + eps && p.z <= hi.z + eps;
}

int main(void) {
  gs__poly *p = malloc(sizeof *p);
  /* A 2 x 3 x 4 box. */
  gs__poly_box(p, sh_v3(0, 0, 0), sh_v3(2, 3, 4));
  SH_CHECK(p->nfaces == 6);
  SH_CHECK_NEAR(volume(p), 24.0, 1e-12, 0);
  /* Cut in half by x <= 1. */
  SH_CHECK(gs__poly_clip(p, gs__halfspace_at(sh_v3(1, 0, 0), sh_v3(1, 0, 0))) == 6);
  SH_CHECK_NEAR(volume(p), 12.0, 1e-12, 0);
  /* A corner off: x + y + z <= 1 keeps the tetrahedron of volume 1/6. */
  SH_CHECK(gs__poly_clip(p, gs__halfspace_at(sh_v3(1, 1, 1), sh_v3(1, 0, 0))) == 4);
  SH_CHECK_NEAR(volume(p), 1.0 / 6.0, 1e-12, 0);
  for (int f = 0; f < p->nfaces; f++)
    for (int i = 0; i < p->face[f].n; i++)
      SH_CHECK(inside(p->face[f].v[i], sh_v3(0, 0, 0), sh_v3(1, 1, 1), 1e-12));
  /* Clipped away entirely; clipping an empty polytope keeps it empty. */
  SH_CHECK(gs__poly_clip(p, gs__halfspace_at(sh_v3(-1, 0, 0), sh_v3(5, 0, 0))) == 0);
  SH_CHECK(gs__poly_clip(p, gs__halfspace_at(sh_v3(1, 0, 0), sh_v3(5, 0, 0))) == 0);
  /* A plane through a face (degenerate): the box stays. */
  gs__poly_box(p, sh_v3(-1, -1, -1), sh_v3(1, 1, 1));
  gs__poly_clip(p, gs__halfspace_at(sh_v3(0, 0, 1), sh_v3(0, 0, 1)));
  SH_CHECK_NEAR(volume(p), 8.0, 1e-9, 0);

  /* A cube cut by many planes (a circumscribed octagonal prism). */
  gs__poly_box(p, sh_v3(-1, -1, -1), sh_v3(1, 1, 1));
  for (int k = 0; k < 8; k++) {
    double a = k * SH_PI / 4;
    gs__poly_clip(p, gs__halfspace_at(sh_v3(cos(a), sin(a), 0), sh_v3(cos(a) * 0.9, sin(a) * 0.9, 0)));
  }
  /* A regular octagon of inradius 0.9, height 2: 8 * 0.9^2 * tan(22.5 deg) * 2. */
  SH_CHECK_NEAR(volume(p), 16 * 0.81 * tan(SH_PI / 8), 1e-9, 0);

  /* Slab points: the part of the unit cube with 0.25 <= x <= 0.5. */
  gs__poly_box(p, sh_v3(0, 0, 0), sh_v3(1, 1, 1));
  sh_vec3 pts[256];
  int n = gs__poly_slab_points(p, sh_v3(1, 0, 0), 0.25, 0.5, pts, 256);
  SH_CHECK(n > 0);
  int lo = 0, hi = 0;
  for (int i = 0; i < n; i++) {
    SH_CHECK(pts[i].x >= 0.25 - 1e-12 && pts[i].x <= 0.5 + 1e-12);
    lo += fabs(pts[i].x - 0.25) < 1e-12;
    hi += fabs(pts[i].x - 0.5) < 1e-12;
  }
  SH_CHECK(lo >= 4 && hi >= 4); /* both cross-sections' corners */
  /* A slab beyond the cube holds nothing. */
  SH_CHECK(gs__poly_slab_points(p, sh_v3(1, 0, 0), 2, 3, pts, 256) == 0);

  /* 2D hulls: a square with inner and collinear points. */
  double in[9][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5},
                     {0.5, 0}, {0, 0.5}, {0.2, 0.7}, {1, 1}};
  double out[18][2];
  int h = gs__hull2d(in, 9, out);
  SH_CHECK(h == 4);
  double area = 0;
  for (int i = 0; i < h; i++) {
    int j = (i + 1) % h;
    area += out[i][0] * out[j][1] - out[j][0] * out[i][1];
  }
  SH_CHECK_NEAR(0.5 * area, 1.0, 1e-12, 0); /* counter-clockwise, area 1 */
  /* Random points: every point inside the hull. */
  srand(7);
  double r[200][2], hr[400][2];
  for (int i = 0; i < 200; i++) {
    r[i][0] = rand() / (double)RAND_MAX;
    r[i][1] = rand() / (double)RAND_MAX;
  }
  double copy[200][2];
  for (int i = 0; i < 200; i++) copy[i][0] = r[i][0], copy[i][1] = r[i][1];
  h = gs__hull2d(r, 200, hr);
  SH_CHECK(h >= 3);
  int all_in = 1;
  for (int i = 0; i < 200; i++)
    for (int k = 0; k < h; k++) {
      const double *a = hr[k], *b = hr[(k + 1) % h];
      double c = (b[0] - a[0]) * (copy[i][1] - a[1]) - (b[1] - a[1]) * (copy[i][0] - a[0]);
      if (c < -1e-12) all_in = 0;
    }
  SH_CHECK(all_in);
  free(p);
  SH_TEST_DONE();
}
