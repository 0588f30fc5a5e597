/* Convex polytopes as lists of convex faces: the part of the medium a light
 * can reach and the camera can see (the medium's box clipped by the light's
 * cone or window and by the view frustum), and what of it lies between two
 * virtual planes. Small and fixed-size: a polytope has at most
 * GS__POLY_MAX_FACES faces of at most GS__POLY_MAX_FACE_VERTS vertices. */
#ifndef GS_POLYTOPE_H
#define GS_POLYTOPE_H

#include "sh_math.h"

#define GS__POLY_MAX_FACES 40
#define GS__POLY_MAX_FACE_VERTS 40

/* The half-space n . x <= c. */
typedef struct gs__halfspace {
  sh_vec3 n;
  double c;
} gs__halfspace;

typedef struct gs__face {
  int n;
  sh_vec3 v[GS__POLY_MAX_FACE_VERTS]; /* in order around the face */
} gs__face;

typedef struct gs__poly {
  int nfaces; /* 0: empty */
  gs__face face[GS__POLY_MAX_FACES];
} gs__poly;

/* The half-space through point p whose outward normal is n (keeps
 * n . (x - p) <= 0). */
gs__halfspace gs__halfspace_at(sh_vec3 n, sh_vec3 p);

/* The axis-aligned box [bmin, bmax] as six faces. */
void gs__poly_box(gs__poly *p, sh_vec3 bmin, sh_vec3 bmax);

/* Keeps the part of p inside h. A polytope that would outgrow the fixed
 * capacity is left unclipped by h (it stays a superset, which is all its
 * users need). Returns the number of faces left (0: empty). */
int gs__poly_clip(gs__poly *p, gs__halfspace h);

/* Writes up to `max` of the polytope's vertices (with repeats: each is
 * listed once per face it belongs to); returns how many. */
int gs__poly_vertices(const gs__poly *p, sh_vec3 *out, int max);

/* The points that span the part of p where lo <= a . x <= hi: p's vertices
 * in that range and the points where p's edges cross a . x = lo and
 * a . x = hi. Writes up to `max`; returns how many. */
int gs__poly_slab_points(const gs__poly *p, sh_vec3 a, double lo, double hi,
                         sh_vec3 *out, int max);

/* The convex hull of n 2D points, counter-clockwise without repeated or
 * collinear points, written to out (room for 2n points); returns its size
 * (fewer than 3 for a degenerate set). Reorders pts. */
int gs__hull2d(double (*pts)[2], int n, double (*out)[2]);

#endif
