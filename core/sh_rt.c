#include "sh_rt.h"

#include <embree3/rtcore.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_tessellate.h"

/* One shape as Embree sees it: world-space triangles, or the exact shape
 * in object space for the user-geometry callbacks. */
typedef struct sh__prim {
  const sh_shape *shape;
  const sh_rt *rt;
  int analytic;
  float *verts;      /* triangle vertices in the rt's frame, 3 floats each */
  unsigned *indices; /* 3 per triangle */
  int nverts, ntris;
  /* Cylinder frame in object space; a quad's unit normal (cross(u, v),
   * as its triangles face) in axis and its Gram matrix. */
  sh_vec3 axis;
  double length;
  double uu, uv, vv, det;
  unsigned mask; /* the shape's SH_RT_* class bit */
  int identity;  /* the shape has no transform: skip the matrices */
  double diam;   /* analytic: the world bounds' diagonal; triangles: the
                  * largest triangle's longest edge, in frame units */
} sh__prim;

/* Embree holds single-precision floats, whose ulp grows with the distance
 * from the origin: a scene far from the origin, or a very small or very
 * large one, loses its detail, and a planet-sized one loses everything
 * near an eye a metre above its ground. So Embree sees the scene in a
 * frame of its own, q = (p - origin) / unit, moved into in double
 * precision: unit is sh_frame_fit's (a power of two at or above half the
 * shapes' bounds' diagonal) and origin sh_frame_fit's too (a multiple of
 * the unit), unless the camera is within 2^-8 units of a shape's bounds:
 * then that bounds' point nearest the camera, to 2^-22 units, so that the float
 * coordinates' ulps are smallest where the image looks closest (an eye a
 * metre above a planet's ground: ulps of 0.5 m in a frame about the
 * planet's centre, under 1e-6 m within metres of the eye: the quantum
 * is 4 m there). Every shape lies within BALL
 * units of the origin either way (the
 * bounds' diagonal is at most 2 units). A ray from further than FAR_UNITS
 * units away starts at the closest point of that ball it can reach (in
 * double precision), so that a far camera's rays keep their precision.
 *
 * What Embree computes in float is mended in double where it matters: a
 * closest hit's distance, point and normal are recomputed from the hit
 * primitive in double (the triangle's plane from its float vertices,
 * which are the surface; the analytic shape's root from the double ray),
 * and each hit carries the bound `err` on how far from the surface a
 * point may lie and still be put on the wrong side by Embree's float
 * tests (sh_hit), from which sh_rt_offset_hit and sh_rt_free_end step
 * off. */
#define BALL 2.0
enum { FAR_UNITS = 4 };
/* float_err's factors: ulps of a point's largest coordinate, and of a
 * triangle's extent about the point. */
#define ERR_POINT 1.0
#define ERR_TRIANGLE 8.0
/* The frame origin's quantum, in units: a frame coordinate below 2 units
 * made of multiples of it has at most 24 significant bits, a float's. */
#define ORIGIN_QUANTUM 0x1p-22
/* How close to a shape the eye must be for the frame to move to it. */
#define NEAR_UNITS 0x1p-8

struct sh_rt {
  RTCDevice device;
  sh_vec3 origin; /* the frame's origin, world space */
  double unit;    /* the frame's unit length, world space */
  double tri_diam; /* the largest triangle's longest edge, frame units */
  RTCScene scene_all; /* every shape, with its class as geometry mask */
  const sh_scene *scene;
  sh__prim *prims;
  unsigned classes; /* the union of the shapes' classes */
  sh_status device_status;
  char device_message[256];
};

static void on_device_error(void *user, enum RTCError code, const char *str) {
  sh_rt *rt = user;
  if (rt->device_status == SH_OK) {
    rt->device_status = SH_ERR_DEVICE;
    snprintf(rt->device_message, sizeof rt->device_message,
             "Embree error %d: %s", (int)code, str ? str : "(no message)");
  }
}

/* Ray-hit layout of a packet of N rays (struct-of-arrays floats), as in
 * rtcore_ray.h, for use from C. */
enum {
  RAY_ORG_X, RAY_ORG_Y, RAY_ORG_Z, RAY_TNEAR, RAY_DIR_X, RAY_DIR_Y, RAY_DIR_Z,
  RAY_TIME, RAY_TFAR, RAY_MASK, RAY_ID, RAY_FLAGS, HIT_NG_X, HIT_NG_Y,
  HIT_NG_Z, HIT_U, HIT_V, HIT_PRIM, HIT_GEOM, HIT_INST
};
#define SOA(base, field, N, i) (((float *)(base))[(field) * (N) + (i)])
#define SOA_U(base, field, N, i) (((unsigned *)(base))[(field) * (N) + (i)])

/* The closest parameter t in (tnear, tfar) where the object-space ray
 * o + t d meets the analytic shape; writes its object-space normal. */
static int analytic_hit(const sh__prim *pr, sh_vec3 o, sh_vec3 d, double tnear,
                        double tfar, double *t_out, sh_vec3 *n_out) {
  const sh_shape *s = pr->shape;
  double best = tfar;
  int found = 0;
  if (s->type == SH_SHAPE_SPHERE) {
    sh_vec3 oc = sh_sub(o, s->center);
    double a = sh_dot(d, d), b = sh_dot(oc, d);
    double c = sh_dot(oc, oc) - s->radius * s->radius;
    double disc = b * b - a * c;
    if (disc < 0) return 0;
    double sq = sqrt(disc);
    /* Numerically stable roots. */
    double q = b >= 0 ? -(b + sq) : -(b - sq);
    double r0 = q / a, r1 = q != 0 ? c / q : r0;
    if (r0 > r1) {
      double t = r0;
      r0 = r1;
      r1 = t;
    }
    double roots[2] = {r0, r1};
    for (int k = 0; k < 2; k++)
      if (roots[k] > tnear && roots[k] < best) {
        best = roots[k];
        found = 1;
        break;
      }
    if (found)
      *n_out = sh_scale(sh_sub(sh_madd(o, d, best), s->center),
                        1.0 / s->radius);
  } else if (s->type == SH_SHAPE_QUAD) {
    /* The plane's crossing, inside the parallelogram by its coordinates
     * along u and v (inclusive by a relative 1e-12, so that quads sharing
     * an edge leave no gap). */
    double dn = sh_dot(d, pr->axis);
    if (dn == 0) return 0;
    double t = sh_dot(sh_sub(s->corner, o), pr->axis) / dn;
    if (!(t > tnear && t < best)) return 0;
    sh_vec3 x = sh_sub(sh_madd(o, d, t), s->corner);
    double xu = sh_dot(x, s->u), xv = sh_dot(x, s->v);
    double a = (xu * pr->vv - xv * pr->uv) / pr->det;
    double b = (xv * pr->uu - xu * pr->uv) / pr->det;
    const double tol = 1e-12;
    if (a < -tol || a > 1 + tol || b < -tol || b > 1 + tol) return 0;
    best = t;
    found = 1;
    *n_out = pr->axis;
  } else { /* cylinder */
    sh_vec3 oc = sh_sub(o, s->base);
    double op = sh_dot(oc, pr->axis), dp = sh_dot(d, pr->axis);
    sh_vec3 operp = sh_madd(oc, pr->axis, -op), dperp = sh_madd(d, pr->axis, -dp);
    double a = sh_dot(dperp, dperp), b = sh_dot(operp, dperp);
    double c = sh_dot(operp, operp) - s->radius * s->radius;
    double disc = b * b - a * c;
    if (a > 0 && disc >= 0) {
      double sq = sqrt(disc);
      double roots[2] = {(-b - sq) / a, (-b + sq) / a};
      for (int k = 0; k < 2; k++) {
        double t = roots[k], h = op + t * dp;
        if (t > tnear && t < best && h >= 0 && h <= pr->length) {
          best = t;
          found = 1;
          *n_out = sh_scale(sh_madd(operp, dperp, t), 1.0 / s->radius);
        }
      }
    }
    if (s->caps && dp != 0) {
      for (int k = 0; k < 2; k++) {
        double h = k ? pr->length : 0.0;
        double t = (h - op) / dp;
        if (t > tnear && t < best) {
          sh_vec3 q = sh_madd(operp, dperp, t);
          if (sh_dot(q, q) <= s->radius * s->radius) {
            best = t;
            found = 1;
            *n_out = k ? pr->axis : sh_neg(pr->axis);
          }
        }
      }
    }
  }
  if (found) *t_out = best;
  return found;
}

/* The ray of lane i in world space (t in the frame's units: world length
 * / unit), against the exact shape; *t in the frame's units. */
static int analytic_query(const sh__prim *pr, const float *ray, unsigned N,
                          unsigned i, double *t, sh_vec3 *n) {
  const sh_rt *rt = pr->rt;
  sh_vec3 o = sh_v3(SOA(ray, RAY_ORG_X, N, i), SOA(ray, RAY_ORG_Y, N, i),
                    SOA(ray, RAY_ORG_Z, N, i));
  o = sh_madd(rt->origin, o, rt->unit);
  sh_vec3 d = sh_v3(SOA(ray, RAY_DIR_X, N, i), SOA(ray, RAY_DIR_Y, N, i),
                    SOA(ray, RAY_DIR_Z, N, i));
  d = sh_scale(d, rt->unit);
  const sh_shape *s = pr->shape;
  if (!pr->identity) {
    o = sh_xform_point(&s->inv, o);
    d = sh_xform_vector(&s->inv, d);
  }
  if (!analytic_hit(pr, o, d, SOA(ray, RAY_TNEAR, N, i),
                    SOA(ray, RAY_TFAR, N, i), t, n))
    return 0;
  if (!pr->identity) *n = sh_normalize(sh_xform_normal(&s->inv, *n));
  return 1;
}

/* Whether lane i of an Embree ray packet is active, its mask selects the
 * primitive, and its ray hits it: then *t and *n hold the hit. */
static int analytic_lane_hits(const sh__prim *pr, const int *valid,
                              const float *ray, unsigned N, unsigned i,
                              double *t, sh_vec3 *n) {
  if (valid[i] != -1 || !(SOA_U(ray, RAY_MASK, N, i) & pr->mask)) return 0;
  return analytic_query(pr, ray, N, i, t, n);
}

static void analytic_intersect(const struct RTCIntersectFunctionNArguments *a) {
  const sh__prim *pr = a->geometryUserPtr;
  float *rh = (float *)a->rayhit;
  for (unsigned i = 0; i < a->N; i++) {
    double t;
    sh_vec3 n;
    if (!analytic_lane_hits(pr, a->valid, rh, a->N, i, &t, &n)) continue;
    SOA(rh, RAY_TFAR, a->N, i) = (float)t;
    SOA(rh, HIT_NG_X, a->N, i) = (float)n.x;
    SOA(rh, HIT_NG_Y, a->N, i) = (float)n.y;
    SOA(rh, HIT_NG_Z, a->N, i) = (float)n.z;
    SOA(rh, HIT_U, a->N, i) = 0.0f;
    SOA(rh, HIT_V, a->N, i) = 0.0f;
    SOA_U(rh, HIT_PRIM, a->N, i) = a->primID;
    SOA_U(rh, HIT_GEOM, a->N, i) = a->geomID;
    SOA_U(rh, HIT_INST, a->N, i) = RTC_INVALID_GEOMETRY_ID;
  }
}

static void analytic_occluded(const struct RTCOccludedFunctionNArguments *a) {
  const sh__prim *pr = a->geometryUserPtr;
  float *ray = (float *)a->ray;
  for (unsigned i = 0; i < a->N; i++) {
    double t;
    sh_vec3 n;
    if (analytic_lane_hits(pr, a->valid, ray, a->N, i, &t, &n))
      SOA(ray, RAY_TFAR, a->N, i) = -INFINITY;
  }
}

static void analytic_bounds(const struct RTCBoundsFunctionArguments *a) {
  const sh__prim *pr = a->geometryUserPtr;
  sh_vec3 wlo, whi;
  sh_shape_bounds(pr->shape, &wlo, &whi);
  wlo = sh_scale(sh_sub(wlo, pr->rt->origin), 1.0 / pr->rt->unit);
  whi = sh_scale(sh_sub(whi, pr->rt->origin), 1.0 / pr->rt->unit);
  /* Pad by a relative epsilon: the bounds must hold the float hits. */
  double pad = 1e-6 * (sh_max3(sh_vmax(sh_neg(wlo), whi)) + 1.0);
  a->bounds_o->lower_x = (float)(wlo.x - pad);
  a->bounds_o->lower_y = (float)(wlo.y - pad);
  a->bounds_o->lower_z = (float)(wlo.z - pad);
  a->bounds_o->upper_x = (float)(whi.x + pad);
  a->bounds_o->upper_y = (float)(whi.y + pad);
  a->bounds_o->upper_z = (float)(whi.z + pad);
}

static sh_status prim_init(sh_rt *rt, sh__prim *pr, const sh_shape *s,
                           sh_error *err) {
  pr->shape = s;
  pr->rt = rt;
  sh_mat4 id = sh_mat4_identity();
  pr->identity = memcmp(&s->xform, &id, sizeof id) == 0;
  if (s->type == SH_SHAPE_QUAD) {
    pr->axis = sh_normalize(sh_cross(s->u, s->v));
    pr->uu = sh_dot(s->u, s->u);
    pr->uv = sh_dot(s->u, s->v);
    pr->vv = sh_dot(s->v, s->v);
    pr->det = pr->uu * pr->vv - pr->uv * pr->uv;
  }
  if (s->type == SH_SHAPE_SPHERE || s->type == SH_SHAPE_CYLINDER ||
      (s->type == SH_SHAPE_QUAD && pr->det > 0 && isfinite(pr->axis.x))) {
    pr->analytic = 1;
    sh_vec3 lo, hi;
    sh_shape_bounds(s, &lo, &hi);
    pr->diam = sh_length(sh_sub(hi, lo));
    if (s->type == SH_SHAPE_CYLINDER) {
      sh_vec3 a = sh_sub(s->top, s->base);
      pr->length = sh_length(a);
      pr->axis = sh_scale(a, 1.0 / pr->length);
    }
    return SH_OK;
  }
  sh_mesh m = {0};
  /* The error bound only matters for curved shapes, which stay exact here.
   * Tessellated about the frame's origin, in the shape's object space, so
   * that the float vertices keep their precision. */
  sh_vec3 oo = sh_xform_point(&s->inv, rt->origin);
  sh_status st = sh_mesh_tessellate_about(s, 1.0, oo, &m, err);
  if (st != SH_OK) return st;
  pr->nverts = m.nverts;
  pr->ntris = m.ntris;
  pr->indices = m.indices;
  pr->verts = m.positions;
  for (int v = 0; v < m.nverts; v++) {
    float *p = pr->verts + 3 * v;
    sh_vec3 w = sh_xform_point(&s->xform, sh_add(oo, sh_v3(p[0], p[1], p[2])));
    w = sh_scale(sh_sub(w, rt->origin), 1.0 / rt->unit);
    p[0] = (float)w.x;
    p[1] = (float)w.y;
    p[2] = (float)w.z;
  }
  for (int t = 0; t < m.ntris; t++) {
    const unsigned *ix = pr->indices + 3 * t;
    for (int k = 0; k < 3; k++) {
      const float *a = pr->verts + 3 * ix[k], *b = pr->verts + 3 * ix[(k + 1) % 3];
      sh_vec3 e = sh_v3((double)a[0] - b[0], (double)a[1] - b[1],
                        (double)a[2] - b[2]);
      pr->diam = fmax(pr->diam, sh_length(e));
    }
  }
  if (pr->diam > rt->tri_diam) rt->tri_diam = pr->diam;
  return SH_OK;
}

static RTCGeometry make_geometry(sh_rt *rt, sh__prim *pr) {
  RTCGeometry g;
  if (pr->analytic) {
    g = rtcNewGeometry(rt->device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, 1);
    rtcSetGeometryUserData(g, pr);
    rtcSetGeometryBoundsFunction(g, analytic_bounds, NULL);
    rtcSetGeometryIntersectFunction(g, analytic_intersect);
    rtcSetGeometryOccludedFunction(g, analytic_occluded);
  } else {
    g = rtcNewGeometry(rt->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                        RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                        (size_t)pr->nverts);
    unsigned *ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0,
                                           RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned),
                                           (size_t)pr->ntris);
    if (!vb || !ib) {
      rtcReleaseGeometry(g);
      return NULL;
    }
    memcpy(vb, pr->verts, sizeof(float) * 3 * (size_t)pr->nverts);
    memcpy(ib, pr->indices, sizeof(unsigned) * 3 * (size_t)pr->ntris);
  }
  rtcSetGeometryMask(g, pr->mask);
  rtcCommitGeometry(g);
  return g;
}

static RTCScene new_scene(sh_rt *rt) {
  RTCScene s = rtcNewScene(rt->device);
  if (s) rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST);
  return s;
}

static unsigned shape_class(const sh_scene *scene, const sh_shape *s) {
  const sh_material *m = &scene->materials[s->material];
  int semi = !sh_is_black(m->transmit);
  if (m->casts_soft_shadows) return semi ? SH_RT_SEMI_SOFT : SH_RT_OPAQUE_SOFT;
  return semi ? SH_RT_SEMI_HARD : SH_RT_OPAQUE_HARD;
}

/* The frame Embree sees (above), fitted to the shapes' bounds. */
static void frame_init(sh_rt *rt, const sh_scene *scene) {
  sh_vec3 lo = sh_v3s(INFINITY), hi = sh_v3s(-INFINITY);
  for (int i = 0; i < scene->nshapes; i++) {
    sh_vec3 a, b;
    sh_shape_bounds(&scene->shapes[i], &a, &b);
    lo = sh_vmin(lo, a);
    hi = sh_vmax(hi, b);
  }
  sh_frame_fit(lo, hi, &rt->origin, &rt->unit);
  /* The camera's distance to the nearest shape's bounds. */
  sh_vec3 c = scene->camera.position, near = c;
  double dmin = INFINITY;
  for (int i = 0; i < scene->nshapes; i++) {
    sh_vec3 a, b;
    sh_shape_bounds(&scene->shapes[i], &a, &b);
    sh_vec3 x = sh_vmin(sh_vmax(c, a), b);
    double dx = sh_length(sh_sub(c, x));
    if (dx < dmin) {
      dmin = dx;
      near = x;
    }
  }
  /* An eye closer to a shape than NEAR_UNITS (a metre above a planet's
   * ground): the origin moves to that shape's bounds' point nearest the
   * eye, quantised to ORIGIN_QUANTUM units, so that a coordinate that is a
   * multiple of it (a floor at y = 0) moves into the frame exactly: what
   * lies on a plane there stays on it. Elsewhere the frame stays
   * sh_frame_fit's, in which the lmm mode's light mesh is the same at any
   * scale to 1e-6 (lmm_extremes_test; about the eye it moved by 0.1% at
   * scale 1e-9, its grid points' visibility being sensitive to rounding). */
  if (!(dmin <= rt->unit * NEAR_UNITS)) return;
  sh_vec3 q = sh_sub(near, rt->origin);
  double step = rt->unit * ORIGIN_QUANTUM;
  rt->origin = sh_add(rt->origin, sh_v3(step * round(q.x / step),
                                        step * round(q.y / step),
                                        step * round(q.z / step)));
}

sh_status sh_rt_create(const sh_scene *scene, sh_rt **out, sh_error *err) {
  *out = NULL;
  sh_rt *rt = calloc(1, sizeof *rt);
  if (!rt) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  rt->scene = scene;
  rt->device = rtcNewDevice(NULL);
  if (!rt->device) {
    free(rt);
    return sh_error_set(err, SH_ERR_DEVICE, "cannot create an Embree device");
  }
  rtcSetDeviceErrorFunction(rt->device, on_device_error, rt);
  frame_init(rt, scene);
  rt->prims = calloc((size_t)scene->nshapes + 1, sizeof *rt->prims);
  rt->scene_all = new_scene(rt);
  sh_status st = SH_OK;
  if (!rt->prims || !rt->scene_all)
    st = sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  else if (!rtcGetDeviceProperty(rt->device,
                                 RTC_DEVICE_PROPERTY_RAY_MASK_SUPPORTED))
    st = sh_error_set(err, SH_ERR_DEVICE,
                      "this Embree library was built without ray masks, "
                      "which the renderer needs");
  for (int i = 0; st == SH_OK && i < scene->nshapes; i++) {
    const sh_shape *s = &scene->shapes[i];
    sh__prim *pr = &rt->prims[i];
    st = prim_init(rt, pr, s, err);
    if (st != SH_OK) break;
    pr->mask = shape_class(scene, s);
    rt->classes |= pr->mask;
    RTCGeometry g = make_geometry(rt, pr);
    if (!g) {
      st = sh_error_set(err, SH_ERR_DEVICE, "cannot create geometry");
      break;
    }
    rtcAttachGeometryByID(rt->scene_all, g, (unsigned)i);
    rtcReleaseGeometry(g);
  }
  if (st == SH_OK) {
    rtcCommitScene(rt->scene_all);
    if (rt->device_status != SH_OK)
      st = sh_error_set(err, rt->device_status, "%s", rt->device_message);
  }
  if (st != SH_OK) {
    sh_rt_free(rt);
    return st;
  }
  *out = rt;
  return SH_OK;
}

void sh_rt_free(sh_rt *rt) {
  if (!rt) return;
  if (rt->scene_all) rtcReleaseScene(rt->scene_all);
  if (rt->prims)
    for (int i = 0; i < rt->scene->nshapes; i++) {
      free(rt->prims[i].verts);
      free(rt->prims[i].indices);
    }
  free(rt->prims);
  if (rt->device) rtcReleaseDevice(rt->device);
  free(rt);
}

/* The world-space ray o + t d, t in (tmin, tmax), in the frame Embree
 * sees. A ray from far away starts where it can first reach the unit ball:
 * returns that skipped world length, to add to the hit distances. */
static double set_ray(const sh_rt *rt, struct RTCRay *r, sh_vec3 o, sh_vec3 d,
                      double tmin, double tmax, unsigned mask) {
  double inv = 1.0 / rt->unit;
  sh_vec3 q = sh_scale(sh_sub(o, rt->origin), inv);
  double skip = 0.0;
  double dd = sh_dot(d, d);
  if (sh_dot(q, q) > FAR_UNITS * FAR_UNITS && dd > 0) {
    /* Nothing lies on the ray before the foot of the perpendicular from
     * the origin less the ball's radius (with a margin for the float
     * vertices), nor after tmax. */
    double foot = -sh_dot(q, d) / dd, radius = BALL / sqrt(dd);
    skip = fmin(fmax(foot - radius, 0.0) * rt->unit, tmax);
    if (skip > 0) {
      q = sh_scale(sh_sub(sh_madd(o, d, skip), rt->origin), inv);
      tmin = fmax(tmin - skip, 0.0);
      tmax -= skip;
    }
  }
  r->org_x = (float)q.x;
  r->org_y = (float)q.y;
  r->org_z = (float)q.z;
  r->dir_x = (float)d.x;
  r->dir_y = (float)d.y;
  r->dir_z = (float)d.z;
  r->tnear = (float)(tmin * inv);
  r->tfar = tmax * inv >= FLT_MAX ? INFINITY : (float)(tmax * inv);
  r->time = 0.0f;
  r->mask = mask;
  r->id = 0;
  r->flags = 0;
  return skip;
}

/* A world-space point from the frame Embree sees. */
static sh_vec3 from_frame(const sh_rt *rt, const float *q) {
  return sh_madd(rt->origin, sh_v3(q[0], q[1], q[2]), rt->unit);
}

/* The largest coordinate's size of world point p in the frame. */
static double frame_size(const sh_rt *rt, sh_vec3 p) {
  sh_vec3 q = sh_scale(sh_sub(p, rt->origin), 1.0 / rt->unit);
  return fmax(fabs(q.x), fmax(fabs(q.y), fabs(q.z)));
}

/* A bound, in world length, on how far a point near p may be moved across
 * a surface by Embree's float arithmetic, for a surface whose relevant
 * extent about p (its triangle's vertices' distances, frame units) is
 * `extent`: the point's own rounding into the frame (half an ulp a
 * coordinate: at most 0.87 FLT_EPSILON of its largest) and the rounding
 * of the surface's float vertices relative to a ray origin at the point,
 * with the plane's normal computed from them (a few ulps of their
 * distance; Embree's Pluecker test). The factors are margins on those
 * counts, checked by core/sh_rt_test.c's fans of rays at closed boxes and
 * core/sh_reference_planet_test.c. */
static double float_err(const sh_rt *rt, sh_vec3 p, double extent) {
  return (ERR_POINT * frame_size(rt, p) + ERR_TRIANGLE * extent) * FLT_EPSILON *
         rt->unit;
}

/* The closest hit on an analytic shape, in double precision: the root of
 * the double-precision ray (Embree's was found from the ray's float
 * origin, its distance rounded to float), its point projected onto the
 * exact sphere. `ng` is Embree's float normal, kept if the double ray
 * misses (a tangent ray). */
static void refine_analytic(const sh__prim *pr, sh_vec3 o,
                            sh_vec3 d, double tmin, double tmax, sh_vec3 ng,
                            sh_hit *hit) {
  const sh_shape *s = pr->shape;
  sh_vec3 lo = o, ld = d, n;
  if (!pr->identity) {
    lo = sh_xform_point(&s->inv, o);
    ld = sh_xform_vector(&s->inv, d);
  }
  double t;
  if (analytic_hit(pr, lo, ld, tmin, tmax, &t, &n)) {
    hit->t = t;
    ng = pr->identity ? n : sh_xform_normal(&s->inv, n);
  }
  hit->p = sh_madd(o, d, hit->t);
  hit->ng = sh_normalize(ng);
  if (s->type == SH_SHAPE_SPHERE) {
    /* Project the point back onto the exact sphere. */
    sh_vec3 lp = sh_sub(sh_xform_point(&s->inv, hit->p), s->center);
    lp = sh_scale(sh_normalize(lp), s->radius);
    hit->p = sh_xform_point(&s->xform, sh_add(lp, s->center));
  }
  /* The double-precision test sees the float origin exactly: only its
   * rounding counts (added where a point leaves: sh_rt_offset_by), and the
   * quadratic's cancellation, a few double ulps of the shape's size. */
  hit->err = 64 * DBL_EPSILON * pr->diam;
}

/* The closest hit on triangle `prim`, in double precision: the ray's
 * crossing of the plane of the triangle's float vertices (exact in the
 * world as doubles), rather than Embree's float distance, which may lie
 * on either side of the surface by its float error. */
static void refine_triangle(const sh_rt *rt, const sh__prim *pr, unsigned prim,
                            sh_vec3 o, sh_vec3 d, sh_hit *hit) {
  const unsigned *ix = pr->indices + 3 * prim;
  sh_vec3 v[3];
  for (int k = 0; k < 3; k++) v[k] = from_frame(rt, pr->verts + 3 * ix[k]);
  hit->ng = sh_normalize(sh_cross(sh_sub(v[1], v[0]), sh_sub(v[2], v[0])));
  double dn = sh_dot(d, hit->ng);
  if (dn != 0) {
    /* The plane through the vertices' centroid, for the smallest
     * cancellation. */
    sh_vec3 c = sh_scale(sh_add(sh_add(v[0], v[1]), v[2]), 1.0 / 3.0);
    double t = sh_dot(sh_sub(c, o), hit->ng) / dn;
    if (isfinite(t)) hit->t = t;
  }
  hit->p = sh_madd(o, d, hit->t);
  double extent = 0;
  for (int k = 0; k < 3; k++)
    extent = fmax(extent, sh_length(sh_sub(v[k], hit->p)));
  hit->err = ERR_TRIANGLE * FLT_EPSILON * extent;
}

static int closest(const sh_rt *rt, unsigned mask, sh_vec3 o, sh_vec3 d,
                   double tmin, double tmax, sh_hit *hit) {
  struct RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  struct RTCRayHit rh;
  double skip = set_ray(rt, &rh.ray, o, d, tmin, tmax, mask);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rh.hit.Ng_x = rh.hit.Ng_y = rh.hit.Ng_z = 0.0f;
  rh.hit.u = rh.hit.v = 0.0f;
  rtcIntersect1(rt->scene_all, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return 0;
  const sh__prim *pr = &rt->prims[rh.hit.geomID];
  hit->shape = (int)rh.hit.geomID;
  hit->t = skip + rh.ray.tfar * rt->unit;
  if (pr->analytic)
    refine_analytic(pr, o, d, tmin, tmax,
                    sh_v3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z), hit);
  else
    refine_triangle(rt, pr, rh.hit.primID, o, d, hit);
  return 1;
}

int sh_rt_intersect(const sh_rt *rt, sh_vec3 o, sh_vec3 d, double tmin,
                    double tmax, sh_hit *hit, sh_rt_counters *c) {
  if (c) c->closest++;
  return closest(rt, SH_RT_ALL, o, d, tmin, tmax, hit);
}

int sh_rt_occluded(const sh_rt *rt, sh_vec3 o, sh_vec3 d, double tmax,
                   unsigned classes, sh_rt_counters *c) {
  if (!(classes & rt->classes)) return 0;
  struct RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  struct RTCRay r;
  set_ray(rt, &r, o, d, 0.0, tmax, classes);
  if (c) c->occlusion++;
  rtcOccluded1(rt->scene_all, &ctx, &r);
  return r.tfar < 0;
}

sh_vec3 sh_rt_visibility_of(const sh_rt *rt, sh_vec3 o, sh_vec3 d, double tmax,
                            unsigned classes, sh_rt_counters *c) {
  unsigned opaque = classes & (SH_RT_OPAQUE_SOFT | SH_RT_OPAQUE_HARD);
  unsigned semi = classes & (SH_RT_SEMI_SOFT | SH_RT_SEMI_HARD) & rt->classes;
  if (sh_rt_occluded(rt, o, d, tmax, opaque, c)) return sh_v3s(0.0);
  sh_vec3 vis = sh_v3s(1.0);
  if (!semi) return vis;
  /* Walk the semitransparent crossings in order; coincident hits (shared
   * edges, duplicate faces) fall within the step and count once. */
  double t = 0.0;
  sh_hit h;
  for (int k = 0; k < 256; k++) {
    if (c) c->closest++;
    if (!closest(rt, semi, o, d, t, tmax, &h)) break;
    vis = sh_mul(vis, rt->scene->materials[rt->scene->shapes[h.shape].material]
                          .transmit);
    if (sh_max3(vis) <= 0) break;
    /* Past the crossing by its float bound along the ray, or by a
     * relative 1e-5 of the distance, where coincident primitives lie. */
    double dn = fmax(fabs(sh_dot(d, h.ng)), 1e-3);
    t = h.t + fmax(1e-5 * h.t, 2 * (h.err + float_err(rt, h.p, 0.0)) / dn);
  }
  return vis;
}

sh_vec3 sh_rt_visibility(const sh_rt *rt, sh_vec3 o, sh_vec3 d, double tmax,
                         sh_rt_counters *c) {
  return sh_rt_visibility_of(rt, o, d, tmax, SH_RT_ALL, c);
}

unsigned sh_rt_classes(const sh_rt *rt) { return rt->classes; }

enum { STREAM_BATCH = 256 };

/* The context of a ray stream, told whether its rays are coherent. */
static void stream_context(struct RTCIntersectContext *ctx, int coherent) {
  rtcInitIntersectContext(ctx);
  ctx->flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                        : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
}

/* How many of a stream's n rays the batch starting at base holds. */
static int stream_batch(int n, int base) {
  return n - base < STREAM_BATCH ? n - base : STREAM_BATCH;
}

void sh_rt_intersect_stream(const sh_rt *rt, int n, const sh_vec3 *o,
                            const sh_vec3 *d, double *t, int *shape,
                            int coherent, sh_rt_counters *c) {
  struct RTCRayHit rh[STREAM_BATCH];
  double skip[STREAM_BATCH];
  struct RTCIntersectContext ctx;
  stream_context(&ctx, coherent);
  for (int base = 0; base < n; base += STREAM_BATCH) {
    int m = stream_batch(n, base);
    for (int i = 0; i < m; i++) {
      skip[i] = set_ray(rt, &rh[i].ray, o[base + i], d[base + i], 0.0,
                        INFINITY, SH_RT_ALL);
      rh[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh[i].hit.primID = RTC_INVALID_GEOMETRY_ID;
      rh[i].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rh[i].hit.Ng_x = rh[i].hit.Ng_y = rh[i].hit.Ng_z = 0.0f;
      rh[i].hit.u = rh[i].hit.v = 0.0f;
    }
    rtcIntersect1M(rt->scene_all, &ctx, rh, (unsigned)m, sizeof rh[0]);
    for (int i = 0; i < m; i++) {
      int miss = rh[i].hit.geomID == RTC_INVALID_GEOMETRY_ID;
      t[base + i] = miss ? INFINITY : skip[i] + rh[i].ray.tfar * rt->unit;
      shape[base + i] = miss ? -1 : (int)rh[i].hit.geomID;
    }
  }
  if (c) c->closest += (uint64_t)n;
}

void sh_rt_occluded_stream(const sh_rt *rt, int n, const sh_vec3 *o,
                           const sh_vec3 *d, const double *tmax,
                           unsigned classes, int coherent,
                           unsigned char *occluded, sh_rt_counters *c) {
  struct RTCRay r[STREAM_BATCH];
  struct RTCIntersectContext ctx;
  stream_context(&ctx, coherent);
  for (int base = 0; base < n; base += STREAM_BATCH) {
    int m = stream_batch(n, base);
    for (int i = 0; i < m; i++)
      set_ray(rt, &r[i], o[base + i], d[base + i], 0.0, tmax[base + i],
              classes);
    rtcOccluded1M(rt->scene_all, &ctx, r, (unsigned)m, sizeof r[0]);
    for (int i = 0; i < m; i++) occluded[base + i] = r[i].tfar < 0;
  }
  if (c) c->occlusion += (uint64_t)n;
}

sh_vec3 sh_rt_offset_by(const sh_rt *rt, sh_vec3 p, sh_vec3 n, double err) {
  /* The point's own rounding at the new place, and the surface's bound. */
  double e = err + float_err(rt, p, 0.0);
  return sh_madd(p, n, e + float_err(rt, sh_madd(p, n, e), 0.0));
}

sh_vec3 sh_rt_offset(const sh_rt *rt, sh_vec3 p, sh_vec3 n) {
  return sh_rt_offset_by(rt, p, n, float_err(rt, p, rt->tri_diam));
}

sh_vec3 sh_rt_offset_hit(const sh_rt *rt, const sh_hit *hit, sh_vec3 n) {
  return sh_rt_offset_by(rt, hit->p, n, hit->err);
}

double sh_rt_free_end(const sh_rt *rt, sh_vec3 o, sh_vec3 d, const sh_hit *hit) {
  double dn = sh_dot(d, hit->ng);
  if (dn == 0) return hit->t;
  /* hit->t is the surface's own distance in double precision (its
   * tangent plane's for a curved shape, nearer than the surface itself
   * when the ray leaves the shape); step back by the side's bound along
   * the normal, with the point's rounding there. */
  double e = hit->err + float_err(rt, hit->p, 0.0);
  double t = sh_dot(sh_sub(hit->p, o), hit->ng) / dn - e / fabs(dn);
  return fmax(fmin(t, hit->t), 0.0);
}
