/* Tessellation of analytic shapes: see sh_tessellate.h for the accuracy
 * guarantee. */
#include "sh_tessellate.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SH__MAX_TRIS (1 << 24)

static sh_status sh__alloc(sh_mesh *m, long nverts, long ntris, sh_error *err) {
  memset(m, 0, sizeof *m);
  if (ntris > SH__MAX_TRIS)
    return sh_error_set(err, SH_ERR_ARG,
                        "tessellating to the requested accuracy would need "
                        "%ld triangles (more than %d)",
                        ntris, SH__MAX_TRIS);
  m->positions = malloc((size_t)nverts * 3 * sizeof(float));
  m->indices = malloc((size_t)ntris * 3 * sizeof(unsigned));
  if (!m->positions || !m->indices) {
    sh_mesh_free(m);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory tessellating");
  }
  m->nverts = (int)nverts;
  m->ntris = (int)ntris;
  return SH_OK;
}

static void sh__setv(sh_mesh *m, long i, sh_vec3 p) {
  m->positions[3 * i] = (float)p.x;
  m->positions[3 * i + 1] = (float)p.y;
  m->positions[3 * i + 2] = (float)p.z;
}

static void sh__sett(sh_mesh *m, long t, long a, long b, long c) {
  m->indices[3 * t] = (unsigned)a;
  m->indices[3 * t + 1] = (unsigned)b;
  m->indices[3 * t + 2] = (unsigned)c;
}

/* A point of the unit sphere at latitude lat and longitude lon. */
static sh_vec3 sh__sph(double lat, double lon) {
  return sh_v3(cos(lat) * cos(lon), sin(lat), cos(lat) * sin(lon));
}

/* 1 minus the distance from the origin to the plane of a triangle whose
 * vertices lie on the unit sphere: a bound on how far any point of the
 * triangle (which lies inside the sphere) is from the sphere. */
static double sh__tri_depth(sh_vec3 a, sh_vec3 b, sh_vec3 c) {
  sh_vec3 n = sh_cross(sh_sub(b, a), sh_sub(c, a));
  double l = sh_length(n);
  return l > 0 ? 1.0 - fabs(sh_dot(n, a)) / l : 1.0;
}

/* The largest sh__tri_depth over the triangles of the n-band sphere. The
 * triangles of one band are rotations of each other, so one quad per band
 * is enough; the sphere is symmetric about the equator, so half the bands
 * are. */
static double sh__sphere_depth(int n) {
  double dlat = SH_PI / n, dlon = SH_PI / n, worst = 0;
  for (int b = 0; b < (n + 1) / 2; b++) {
    double lat0 = SH_PI / 2 - b * dlat, lat1 = lat0 - dlat;
    sh_vec3 A = sh__sph(lat0, 0), B = sh__sph(lat0, dlon);
    sh_vec3 C = sh__sph(lat1, 0), D = sh__sph(lat1, dlon);
    double d;
    if (b == 0) {
      d = sh__tri_depth(A, D, C);
    } else {
      d = fmax(sh__tri_depth(A, B, D), sh__tri_depth(A, D, C));
    }
    worst = fmax(worst, d);
  }
  return worst;
}

static sh_status sh__sphere(sh_vec3 c, double r, double max_error,
                            sh_mesh *m, sh_error *err) {
  double rel = max_error / r;
  /* The equatorial quad's depth is about 1 - cos^2(pi / 2n): start just
   * below that estimate and step up to the exact bound. */
  int n = 2;
  if (rel < 1) {
    double est = SH_PI / (2.0 * acos(sqrt(1.0 - rel)));
    if (est > 4096)
      return sh_error_set(err, SH_ERR_ARG,
                          "a sphere of radius %g cannot be tessellated to "
                          "within %g: too many triangles",
                          r, max_error);
    n = (int)est - 2;
    if (n < 2)
      n = 2;
  }
  while (sh__sphere_depth(n) > rel)
    n++;
  int nlon = 2 * n;
  long nverts = 2 + (long)(n - 1) * nlon;
  long ntris = 2L * nlon + 2L * nlon * (n - 2);
  sh_status s = sh__alloc(m, nverts, ntris, err);
  if (s != SH_OK)
    return s;
  /* Vertex 0 is the north pole, then rings 1 .. n-1 from north to south,
   * then the south pole. */
  sh__setv(m, 0, sh_madd(c, sh_v3(0, 1, 0), r));
  for (int i = 1; i < n; i++)
    for (int k = 0; k < nlon; k++)
      sh__setv(m, 1 + (long)(i - 1) * nlon + k,
               sh_madd(c, sh__sph(SH_PI / 2 - i * SH_PI / n, k * SH_PI / n), r));
  long south = nverts - 1;
  sh__setv(m, south, sh_madd(c, sh_v3(0, -1, 0), r));
  long t = 0;
  for (int k = 0; k < nlon; k++) {
    int k1 = (k + 1) % nlon;
    sh__sett(m, t++, 0, 1 + k1, 1 + k);
  }
  for (int i = 1; i + 1 < n; i++) {
    long up = 1 + (long)(i - 1) * nlon, lo = up + nlon;
    for (int k = 0; k < nlon; k++) {
      int k1 = (k + 1) % nlon;
      sh__sett(m, t++, up + k, up + k1, lo + k1);
      sh__sett(m, t++, up + k, lo + k1, lo + k);
    }
  }
  long last = 1 + (long)(n - 2) * nlon;
  for (int k = 0; k < nlon; k++) {
    int k1 = (k + 1) % nlon;
    sh__sett(m, t++, south, last + k, last + k1);
  }
  return SH_OK;
}

static sh_status sh__cylinder(sh_vec3 base, sh_vec3 top, double r, int caps,
                              double max_error, sh_mesh *m, sh_error *err) {
  sh_vec3 axis = sh_sub(top, base);
  double len = sh_length(axis);
  if (!(len > 0))
    return sh_error_set(err, SH_ERR_ARG,
                        "a cylinder's base and top must differ");
  sh_vec3 w = sh_scale(axis, 1.0 / len), tu, tv;
  sh_basis(w, &tu, &tv); /* (tu, tv, w) is right-handed */
  double rel = max_error / r;
  int n = 3;
  if (rel < 1 - cos(SH_PI / 3)) {
    double est = SH_PI / acos(1.0 - rel);
    if (est > SH__MAX_TRIS / 4)
      return sh_error_set(err, SH_ERR_ARG,
                          "a cylinder of radius %g cannot be tessellated to "
                          "within %g: too many triangles",
                          r, max_error);
    n = (int)ceil(est);
    while (n > 3 && 1.0 - cos(SH_PI / (n - 1)) <= rel)
      n--;
    while (1.0 - cos(SH_PI / n) > rel)
      n++;
  }
  long nverts = 2L * n + (caps ? 2 : 0);
  long ntris = 2L * n + (caps ? 2L * n : 0);
  sh_status s = sh__alloc(m, nverts, ntris, err);
  if (s != SH_OK)
    return s;
  /* Vertices 0 .. n-1 ring the base, n .. 2n-1 the top, counter-clockwise
   * seen from the top's side. */
  for (int k = 0; k < n; k++) {
    double a = 2.0 * SH_PI * k / n;
    sh_vec3 radial = sh_add(sh_scale(tu, r * cos(a)), sh_scale(tv, r * sin(a)));
    sh__setv(m, k, sh_add(base, radial));
    sh__setv(m, n + k, sh_add(top, radial));
  }
  long t = 0;
  for (int k = 0; k < n; k++) {
    int k1 = (k + 1) % n;
    sh__sett(m, t++, k, k1, n + k1);
    sh__sett(m, t++, k, n + k1, n + k);
  }
  if (caps) {
    long cb = 2L * n, ct = cb + 1;
    sh__setv(m, cb, base);
    sh__setv(m, ct, top);
    for (int k = 0; k < n; k++) {
      int k1 = (k + 1) % n;
      sh__sett(m, t++, cb, k1, k);
      sh__sett(m, t++, ct, n + k, n + k1);
    }
  }
  return SH_OK;
}

static sh_status sh__box(sh_vec3 lo, sh_vec3 hi, sh_mesh *m, sh_error *err) {
  sh_status s = sh__alloc(m, 8, 12, err);
  if (s != SH_OK)
    return s;
  /* Vertex i has x from bit 0, y from bit 1, z from bit 2. */
  for (int i = 0; i < 8; i++)
    sh__setv(m, i, sh_v3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y,
                         i & 4 ? hi.z : lo.z));
  /* Each face as a loop of corners, counter-clockwise seen from outside. */
  static const int faces[6][4] = {
      {0, 4, 6, 2}, /* -x */
      {1, 3, 7, 5}, /* +x */
      {0, 1, 5, 4}, /* -y */
      {2, 6, 7, 3}, /* +y */
      {0, 2, 3, 1}, /* -z */
      {4, 5, 7, 6}, /* +z */
  };
  for (int f = 0; f < 6; f++) {
    sh__sett(m, 2 * f, faces[f][0], faces[f][1], faces[f][2]);
    sh__sett(m, 2 * f + 1, faces[f][0], faces[f][2], faces[f][3]);
  }
  return SH_OK;
}

static sh_status sh__quad(sh_vec3 c, sh_vec3 u, sh_vec3 v, sh_mesh *m,
                          sh_error *err) {
  sh_status s = sh__alloc(m, 4, 2, err);
  if (s != SH_OK)
    return s;
  sh__setv(m, 0, c);
  sh__setv(m, 1, sh_add(c, u));
  sh__setv(m, 2, sh_add(sh_add(c, u), v));
  sh__setv(m, 3, sh_add(c, v));
  sh__sett(m, 0, 0, 1, 2);
  sh__sett(m, 1, 0, 2, 3);
  return SH_OK;
}

static sh_status sh__copy(const sh_mesh *src, sh_mesh *m, sh_error *err) {
  if (!src->positions || !src->indices || src->ntris < 1 || src->nverts < 1)
    return sh_error_set(err, SH_ERR_ARG,
                        "the shape has no triangles to copy");
  sh_status s = sh__alloc(m, src->nverts, src->ntris, err);
  if (s != SH_OK)
    return s;
  memcpy(m->positions, src->positions, (size_t)src->nverts * 3 * sizeof(float));
  memcpy(m->indices, src->indices, (size_t)src->ntris * 3 * sizeof(unsigned));
  return SH_OK;
}

sh_status sh_mesh_tessellate(const sh_shape *shape, double max_error,
                             sh_mesh *out, sh_error *err) {
  if (!out)
    return sh_error_set(err, SH_ERR_ARG,
                        "sh_mesh_tessellate was given no output mesh");
  memset(out, 0, sizeof *out);
  if (!shape)
    return sh_error_set(err, SH_ERR_ARG, "sh_mesh_tessellate was given no shape");
  if (!(max_error > 0) || !isfinite(max_error))
    return sh_error_set(err, SH_ERR_ARG,
                        "the tessellation error bound must be positive, not %g",
                        max_error);
  switch (shape->type) {
  case SH_SHAPE_SPHERE:
    if (!(shape->radius > 0))
      return sh_error_set(err, SH_ERR_ARG,
                          "a sphere's radius must be positive, not %g",
                          shape->radius);
    return sh__sphere(shape->center, shape->radius, max_error, out, err);
  case SH_SHAPE_CYLINDER:
    if (!(shape->radius > 0))
      return sh_error_set(err, SH_ERR_ARG,
                          "a cylinder's radius must be positive, not %g",
                          shape->radius);
    return sh__cylinder(shape->base, shape->top, shape->radius, shape->caps,
                        max_error, out, err);
  case SH_SHAPE_BOX:
    return sh__box(sh_vmin(shape->bmin, shape->bmax),
                   sh_vmax(shape->bmin, shape->bmax), out, err);
  case SH_SHAPE_QUAD:
    return sh__quad(shape->corner, shape->u, shape->v, out, err);
  case SH_SHAPE_MESH:
  case SH_SHAPE_HEIGHTFIELD:
    return sh__copy(&shape->mesh, out, err);
  }
  return sh_error_set(err, SH_ERR_ARG, "unknown shape type %d",
                      (int)shape->type);
}

sh_status sh_mesh_tessellate_about(const sh_shape *shape, double max_error,
                                   sh_vec3 origin, sh_mesh *out,
                                   sh_error *err) {
  if (!shape)
    return sh_mesh_tessellate(shape, max_error, out, err);
  /* The analytic shapes are moved before they become floats. */
  sh_shape moved = *shape;
  moved.center = sh_sub(shape->center, origin);
  moved.bmin = sh_sub(shape->bmin, origin);
  moved.bmax = sh_sub(shape->bmax, origin);
  moved.base = sh_sub(shape->base, origin);
  moved.top = sh_sub(shape->top, origin);
  moved.corner = sh_sub(shape->corner, origin);
  sh_status st = sh_mesh_tessellate(&moved, max_error, out, err);
  if (st == SH_OK &&
      (shape->type == SH_SHAPE_MESH || shape->type == SH_SHAPE_HEIGHTFIELD))
    for (long i = 0; i < (long)out->nverts; i++)
      sh__setv(out, i, sh_sub(sh_v3(out->positions[3 * i],
                                    out->positions[3 * i + 1],
                                    out->positions[3 * i + 2]),
                              origin));
  return st;
}
