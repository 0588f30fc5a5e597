#include "gs_geometry.h"

#include <stdlib.h>
#include <string.h>

#include "sh_tessellate.h"

/* A growing array of vertices: position and normal, 6 floats each. */
typedef struct vbuf {
  float *v;
  size_t n, cap;
} vbuf;

static int push(vbuf *b, sh_vec3 p, sh_vec3 n) {
  if (b->n == b->cap) {
    size_t cap = b->cap ? 2 * b->cap : 4096;
    float *v = realloc(b->v, cap * 6 * sizeof *v);
    if (!v) return 0;
    b->v = v;
    b->cap = cap;
  }
  float *o = b->v + 6 * b->n++;
  o[0] = (float)p.x;
  o[1] = (float)p.y;
  o[2] = (float)p.z;
  o[3] = (float)n.x;
  o[4] = (float)n.y;
  o[5] = (float)n.z;
  return 1;
}

static sh_vec3 vertex(const sh_mesh *m, unsigned i) {
  const float *p = m->positions + 3 * (size_t)i;
  return sh_v3(p[0], p[1], p[2]);
}

/* The tessellation error for a curved shape of radius r around object-space
 * point c: 1/64 of a pixel's footprint at its nearest distance. Silhouettes
 * would need a quarter, but the shading of a cylinder's wall (drawn on its
 * inscribed facets with exact normals) shows every facet in its highlights:
 * the Debelov table's error falls from 4.3% at a quarter pixel to 2.0% at
 * 1/64 (the rest is shadow-map edges), for 376 triangles instead of 112. */
static double curve_error(const sh_shape *s, const gs__view *view, sh_vec3 c,
                          double r) {
  sh_vec3 w = sh_xform_point(&s->xform, c);
  double scale = sh_length(sh_xform_vector(&s->xform, sh_v3(1, 0, 0)));
  scale = fmax(scale, sh_length(sh_xform_vector(&s->xform, sh_v3(0, 1, 0))));
  scale = fmax(scale, sh_length(sh_xform_vector(&s->xform, sh_v3(0, 0, 1))));
  double dist = sh_length(sh_sub(w, view->frame.origin)) - r * scale;
  double pixel = 2.0 * view->sy / view->height;
  double e = pixel / 64 * fmax(dist, 0.0) / scale;
  return fmax(e, 1e-4 * r);
}

static int cmp_u64(const void *a, const void *b) {
  unsigned long long x = *(const unsigned long long *)a, y = *(const unsigned long long *)b;
  return x < y ? -1 : x > y;
}

/* True if every edge of the mesh is used once in each direction: a closed,
 * consistently oriented surface (the inside of a shadow caster is then
 * behind its front). Returns 0 if memory runs out. */
static int mesh_closed(const sh_mesh *m) {
  size_t n = 3 * (size_t)m->ntris;
  if (n == 0) return 0;
  unsigned long long *e = malloc(n * sizeof *e);
  if (!e) return 0;
  for (int t = 0; t < m->ntris; t++)
    for (int k = 0; k < 3; k++) {
      unsigned long long a = m->indices[3 * t + k], b = m->indices[3 * t + (k + 1) % 3];
      e[3 * (size_t)t + k] = a << 32 | b;
    }
  qsort(e, n, sizeof *e, cmp_u64);
  int closed = 1;
  for (size_t i = 0; i < n && closed; i++) {
    if (i + 1 < n && e[i + 1] == e[i]) closed = 0;
    unsigned long long rev = (e[i] & 0xffffffffULL) << 32 | e[i] >> 32;
    if (closed && !bsearch(&rev, e, n, sizeof *e, cmp_u64)) closed = 0;
  }
  free(e);
  return closed;
}

/* The object-space shading normal of a triangle's vertex: exact for a
 * sphere and a cylinder's wall; 0 for flat shading. */
static sh_vec3 smooth_normal(const sh_shape *s, sh_vec3 p, sh_vec3 face_n) {
  if (s->type == SH_SHAPE_SPHERE) return sh_normalize(sh_sub(p, s->center));
  if (s->type == SH_SHAPE_CYLINDER) {
    sh_vec3 ax = sh_normalize(sh_sub(s->top, s->base));
    if (fabs(sh_dot(face_n, ax)) > 0.999) return sh_v3s(0); /* a cap */
    sh_vec3 d = sh_sub(p, s->base);
    return sh_normalize(sh_madd(d, ax, -sh_dot(d, ax)));
  }
  return sh_v3s(0);
}

/* The tessellation error of a shape seen from the view (1 for shapes with
 * no curved surface). */
static double shape_error(const sh_shape *s, const gs__view *view) {
  if (s->type == SH_SHAPE_SPHERE) return curve_error(s, view, s->center, s->radius);
  if (s->type == SH_SHAPE_CYLINDER)
    return curve_error(s, view, sh_scale(sh_add(s->base, s->top), 0.5), s->radius);
  return 1.0;
}

/* Grid lines for a quad much larger than the eye's height above it (a
 * ground quad 2e7 m across with the eye 1 m up): the parameter t0 of the
 * eye's foot (clamped to [0, 1]) and lines at t0 +- step 2^k, so that the
 * cells grow geometrically away from the eye. Drawn as two triangles, such
 * a quad's shadow map and surface passes interpolate depth and position
 * across vertices 1e7 m away, and the lit ground near the eye came out
 * 8.5% off at some scales and not at others (rounding). A tensor grid has
 * no T-junctions. Writes at most QUAD_LINES values, sorted; returns how
 * many. */
enum { QUAD_LINES = 128 };
static int quad_lines(double t0, double step, double *out) {
  int n = 0;
  out[n++] = 0.0;
  t0 = fmin(fmax(t0, 0.0), 1.0);
  double lo[QUAD_LINES / 2];
  int nlo = 0;
  for (double d = step; t0 - d > 0 && nlo < QUAD_LINES / 2 - 2; d *= 2) lo[nlo++] = t0 - d;
  while (nlo > 0) out[n++] = lo[--nlo];
  if (t0 > 0 && t0 < 1) out[n++] = t0;
  for (double d = step; t0 + d < 1 && n < QUAD_LINES - 1; d *= 2) out[n++] = t0 + d;
  out[n++] = 1.0;
  return n;
}

/* A quad larger than 64 times the eye's height above its plane as a grid
 * refined about the eye (quad_lines), in object space about oo; 0 (and
 * nothing made) for a smaller one. */
static int quad_grid(const sh_shape *s, sh_vec3 eye, sh_vec3 oo, sh_mesh *m) {
  sh_vec3 e = sh_xform_point(&s->inv, eye), n = sh_cross(s->u, s->v);
  double lu = sh_length(s->u), lv = sh_length(s->v), ln = sh_length(n);
  if (!(ln > 0)) return 0;
  sh_vec3 x = sh_sub(e, s->corner);
  double h = fabs(sh_dot(x, n)) / ln, size = fmax(lu, lv);
  if (!(size > 64 * h)) return 0;
  h = fmax(h, 1e-9 * size);
  double uu = lu * lu, vv = lv * lv, uv = sh_dot(s->u, s->v), det = uu * vv - uv * uv;
  double xu = sh_dot(x, s->u), xv = sh_dot(x, s->v);
  double a0 = (xu * vv - xv * uv) / det, b0 = (xv * uu - xu * uv) / det;
  double la[QUAD_LINES], lb[QUAD_LINES];
  int na = quad_lines(a0, h / lu, la), nb = quad_lines(b0, h / lv, lb);
  m->nverts = na * nb;
  m->ntris = 2 * (na - 1) * (nb - 1);
  m->positions = malloc(sizeof(float) * 3 * (size_t)m->nverts);
  m->indices = malloc(sizeof(unsigned) * 3 * (size_t)m->ntris);
  if (!m->positions || !m->indices) {
    free(m->positions);
    free(m->indices);
    memset(m, 0, sizeof *m);
    return -1;
  }
  for (int j = 0; j < nb; j++)
    for (int i = 0; i < na; i++) {
      sh_vec3 p = sh_sub(sh_add(s->corner, sh_add(sh_scale(s->u, la[i]), sh_scale(s->v, lb[j]))), oo);
      float *f = m->positions + 3 * (j * na + i);
      f[0] = (float)p.x;
      f[1] = (float)p.y;
      f[2] = (float)p.z;
    }
  unsigned *t = m->indices;
  for (int j = 0; j + 1 < nb; j++)
    for (int i = 0; i + 1 < na; i++) {
      unsigned p00 = (unsigned)(j * na + i), p10 = p00 + 1, p01 = p00 + (unsigned)na,
               p11 = p01 + 1;
      unsigned tri[6] = {p00, p10, p11, p00, p11, p01};
      memcpy(t, tri, sizeof tri);
      t += 6;
    }
  return 1;
}

/* Tessellates shape s with error e and appends its triangles to b in the
 * anchored space (gs_view.h), filling d (its range starting at b's end;
 * its bounds and centre stay in world space). */
static sh_status shape_vertices(const sh_shape *s, double e, sh_vec3 anchor,
                                sh_vec3 eye, gs__shape_draw *d, vbuf *b,
                                long *triangles, sh_error *err) {
  sh_mesh m = {0};
  /* About the anchor, so that the float vertices keep their precision. */
  sh_vec3 oo = sh_xform_point(&s->inv, anchor);
  int grid = s->type == SH_SHAPE_QUAD ? quad_grid(s, eye, oo, &m) : 0;
  if (grid < 0) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  sh_status st = grid ? SH_OK : sh_mesh_tessellate_about(s, e, oo, &m, err);
  if (st != SH_OK) return st;
  d->error = e;
  d->xform = s->xform;
  if (s->type == SH_SHAPE_SPHERE) {
    /* Drawn exactly (the shader intersects the true sphere): the camera
     * pass inflates the inscribed mesh about the centre to circumscribe
     * it; shadow maps keep it inscribed, behind the true surface. */
    d->exact_sphere = 1;
    d->inflate = s->radius / (s->radius - e);
    d->center = sh_xform_point(&s->xform, s->center);
  }
  d->first = (int)b->n;
  d->material = s->material;
  d->bmin = sh_v3s(INFINITY);
  d->bmax = sh_v3s(-INFINITY);
  d->convex = s->type == SH_SHAPE_SPHERE || s->type == SH_SHAPE_BOX ||
              s->type == SH_SHAPE_QUAD || (s->type == SH_SHAPE_CYLINDER && s->caps);
  d->closed = s->type == SH_SHAPE_SPHERE || s->type == SH_SHAPE_BOX ||
              (s->type == SH_SHAPE_CYLINDER && s->caps) ||
              (s->type == SH_SHAPE_MESH && mesh_closed(&m));
  /* A mirroring transform turns counter-clockwise triangles clockwise. */
  sh_vec3 c0 = sh_xform_vector(&s->xform, sh_v3(1, 0, 0));
  sh_vec3 c1 = sh_xform_vector(&s->xform, sh_v3(0, 1, 0));
  sh_vec3 c2 = sh_xform_vector(&s->xform, sh_v3(0, 0, 1));
  d->mirrored = sh_dot(sh_cross(c0, c1), c2) < 0;
  for (int t = 0; t < m.ntris && st == SH_OK; t++) {
    sh_vec3 o[3], w[3];
    for (int k = 0; k < 3; k++) {
      o[k] = sh_add(oo, vertex(&m, m.indices[3 * t + k]));
      w[k] = sh_xform_point(&s->xform, o[k]);
    }
    sh_vec3 fn = sh_cross(sh_sub(w[1], w[0]), sh_sub(w[2], w[0]));
    if (sh_length(fn) == 0) continue; /* degenerate */
    fn = sh_normalize(fn);
    sh_vec3 on = sh_normalize(sh_cross(sh_sub(o[1], o[0]), sh_sub(o[2], o[0])));
    for (int k = 0; k < 3; k++) {
      sh_vec3 n = smooth_normal(s, o[k], on);
      n = sh_is_black(n) ? fn : sh_normalize(sh_xform_normal(&s->inv, n));
      if (!push(b, sh_sub(w[k], anchor), n)) st = sh_error_set(err, SH_ERR_NOMEM, "out of memory");
      d->bmin = sh_vmin(d->bmin, w[k]);
      d->bmax = sh_vmax(d->bmax, w[k]);
    }
    (*triangles)++;
  }
  d->count = (int)b->n - d->first;
  sh_mesh_free(&m);
  if (st == SH_OK && b->n > (size_t)1 << 30)
    st = sh_error_set(err, SH_ERR_ARG, "the scene has too many triangles for GL");
  return st;
}

sh_status gs__geometry_build(const sh_scene *scene, const gs__view *view,
                             gs__geometry *g, sh_error *err) {
  memset(g, 0, sizeof *g);
  g->shape = calloc((size_t)(scene->nshapes ? scene->nshapes : 1), sizeof *g->shape);
  if (!g->shape) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  vbuf b = {0};
  sh_status st = SH_OK;
  for (int i = 0; i < scene->nshapes && st == SH_OK; i++) {
    const sh_shape *s = &scene->shapes[i];
    st = shape_vertices(s, shape_error(s, view), view->anchor, view->frame.origin,
                        &g->shape[i], &b, &g->triangles, err);
  }
  g->nshapes = scene->nshapes;
  g->nverts = (int)b.n;
  g->anchor = view->anchor;
  if (st == SH_OK) {
    glCreateVertexArrays(1, &g->vao);
    glCreateBuffers(1, &g->vbo);
    glNamedBufferData(g->vbo, (GLsizeiptr)(b.n * 6 * sizeof(float)), b.v,
                      GL_STATIC_DRAW);
    glVertexArrayVertexBuffer(g->vao, 0, g->vbo, 0, 6 * sizeof(float));
    for (GLuint a = 0; a < 2; a++) {
      glEnableVertexArrayAttrib(g->vao, a);
      glVertexArrayAttribFormat(g->vao, a, 3, GL_FLOAT, GL_FALSE,
                                a * 3 * sizeof(float));
      glVertexArrayAttribBinding(g->vao, a, 0);
    }
    st = gs__gl_check("uploading the scene's triangles", err);
  }
  free(b.v);
  if (st != SH_OK) gs__geometry_free(g);
  return st;
}

sh_status gs__geometry_update(const sh_scene *scene, const gs__view *view,
                              gs__geometry *g, int *rebuilt, int *changed,
                              sh_error *err) {
  *rebuilt = *changed = 0;
  if (scene->nshapes != g->nshapes)
    return sh_error_set(err, SH_ERR_ARG,
                        "the scene's shapes changed in number (%d, was %d): "
                        "make a new renderer",
                        scene->nshapes, g->nshapes);
  vbuf b = {0};
  sh_status st = SH_OK;
  int whole = memcmp(&g->anchor, &view->anchor, sizeof g->anchor) != 0;
  for (int i = 0; i < g->nshapes && st == SH_OK && !whole; i++) {
    const sh_shape *s = &scene->shapes[i];
    gs__shape_draw *d = &g->shape[i];
    double e = shape_error(s, view);
    if (e == d->error && !memcmp(&d->xform, &s->xform, sizeof d->xform)) continue;
    gs__shape_draw nd = *d;
    long tris = 0;
    b.n = 0;
    st = shape_vertices(s, e, view->anchor, view->frame.origin, &nd, &b, &tris, err);
    if (st != SH_OK) break;
    /* Another tessellation may have another vertex count: then the whole
     * buffer is built again. */
    if (nd.count != d->count) {
      whole = 1;
      break;
    }
    nd.first = d->first;
    *d = nd;
    *changed = 1;
    glNamedBufferSubData(g->vbo, (GLintptr)((size_t)d->first * 6 * sizeof(float)),
                         (GLsizeiptr)(b.n * 6 * sizeof(float)), b.v);
  }
  free(b.v);
  if (st == SH_OK && whole) {
    gs__geometry_free(g);
    st = gs__geometry_build(scene, view, g, err);
    *rebuilt = *changed = 1;
  }
  if (st == SH_OK) st = gs__gl_check("updating the scene's triangles", err);
  return st;
}

void gs__geometry_free(gs__geometry *g) {
  if (g->vbo) glDeleteBuffers(1, &g->vbo);
  if (g->vao) glDeleteVertexArrays(1, &g->vao);
  free(g->shape);
  memset(g, 0, sizeof *g);
}
