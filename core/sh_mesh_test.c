/* Tests of sh_mesh.h and sh_tessellate.h: OBJ, PLY and glTF files written
 * here and loaded through assimp, error codes, heightfield grids, and the
 * tessellation of analytic shapes (accuracy, closedness, orientation). */
#include "sh_mesh.h"
#include "sh_tessellate.h"
#include "sh_test.h"

#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmpdir[256];
static char written[64][512];
static int nwritten = 0;

/* Writes text to a file in the test's directory and returns its path. */
static const char *write_file(const char *name, const char *text) {
  char *path = written[nwritten++];
  int n = snprintf(path, sizeof written[0], "%s/%s", tmpdir, name);
  if (n < 0 || (size_t)n >= sizeof written[0]) {
    fprintf(stderr, "sh_mesh_test: the path %s/%s is too long\n", tmpdir, name);
    exit(1);
  }
  FILE *f = fopen(path, "wb");
  if (f) {
    fputs(text, f);
    fclose(f);
  }
  return path;
}

static void bounds(const sh_mesh *m, sh_vec3 *lo, sh_vec3 *hi) {
  *lo = sh_v3s(DBL_MAX);
  *hi = sh_v3s(-DBL_MAX);
  for (int i = 0; i < m->nverts; i++) {
    sh_vec3 p = sh_v3(m->positions[3 * i], m->positions[3 * i + 1],
                      m->positions[3 * i + 2]);
    *lo = sh_vmin(*lo, p);
    *hi = sh_vmax(*hi, p);
  }
}

static sh_vec3 vert(const sh_mesh *m, unsigned i) {
  return sh_v3(m->positions[3 * i], m->positions[3 * i + 1],
               m->positions[3 * i + 2]);
}

/* The (unnormalised) normal of triangle t by the counter-clockwise rule. */
static sh_vec3 tri_normal(const sh_mesh *m, int t) {
  sh_vec3 a = vert(m, m->indices[3 * t]), b = vert(m, m->indices[3 * t + 1]),
          c = vert(m, m->indices[3 * t + 2]);
  return sh_cross(sh_sub(b, a), sh_sub(c, a));
}

static int indices_valid(const sh_mesh *m) {
  for (int i = 0; i < 3 * m->ntris; i++)
    if (m->indices[i] >= (unsigned)m->nverts)
      return 0;
  return 1;
}

typedef struct edge {
  unsigned a, b;
} edge;

static int edge_cmp(const void *x, const void *y) {
  const edge *p = x, *q = y;
  if (p->a != q->a)
    return p->a < q->a ? -1 : 1;
  if (p->b != q->b)
    return p->b < q->b ? -1 : 1;
  return 0;
}

/* True if every edge is shared by exactly two triangles that traverse it in
 * opposite directions: a closed, consistently oriented surface. */
static int closed_and_oriented(const sh_mesh *m) {
  size_t n = 3 * (size_t)m->ntris;
  edge *e = malloc(n * sizeof *e);
  if (!e)
    return 0;
  for (int t = 0; t < m->ntris; t++)
    for (int k = 0; k < 3; k++) {
      e[3 * t + k].a = m->indices[3 * t + k];
      e[3 * t + k].b = m->indices[3 * t + (k + 1) % 3];
    }
  qsort(e, n, sizeof *e, edge_cmp);
  int ok = 1;
  for (size_t i = 0; i < n && ok; i++) {
    if (i + 1 < n && edge_cmp(&e[i], &e[i + 1]) == 0)
      ok = 0; /* the same directed edge twice */
    edge r = {e[i].b, e[i].a};
    if (!bsearch(&r, e, n, sizeof *e, edge_cmp))
      ok = 0; /* a border edge, or one with inconsistent orientation */
  }
  free(e);
  return ok;
}

static const char cube_obj[] =
    "# a unit cube, quads, counter-clockwise from outside\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n"
    "l 1 7\n";

static const char pyramid_ply[] =
    "ply\nformat ascii 1.0\nelement vertex 5\n"
    "property float x\nproperty float y\nproperty float z\n"
    "element face 5\nproperty list uchar int vertex_indices\nend_header\n"
    "-1 0 -1\n1 0 -1\n1 0 1\n-1 0 1\n0 2 0\n"
    "4 0 1 2 3\n3 0 4 1\n3 1 4 2\n3 2 4 3\n3 3 4 0\n";

/* Base64 of a byte buffer, for a glTF data: URI. */
static void base64(const unsigned char *in, size_t n, char *out) {
  static const char tab[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  size_t o = 0;
  for (size_t i = 0; i < n; i += 3) {
    unsigned v = (unsigned)in[i] << 16;
    if (i + 1 < n)
      v |= (unsigned)in[i + 1] << 8;
    if (i + 2 < n)
      v |= in[i + 2];
    out[o++] = tab[(v >> 18) & 63];
    out[o++] = tab[(v >> 12) & 63];
    out[o++] = i + 1 < n ? tab[(v >> 6) & 63] : '=';
    out[o++] = i + 2 < n ? tab[v & 63] : '=';
  }
  out[o] = '\0';
}

static void test_load(void) {
  sh_mesh m;
  sh_error err = SH_ERROR_INIT;
  sh_vec3 lo, hi;

  const char *obj = write_file("cube.obj", cube_obj);
  SH_CHECK(sh_mesh_load(obj, NULL, &m, &err) == SH_OK);
  SH_CHECK(m.ntris == 12); /* the line is skipped */
  SH_CHECK(m.nverts == 8);
  SH_CHECK(indices_valid(&m));
  bounds(&m, &lo, &hi);
  SH_CHECK(lo.x == 0 && lo.y == 0 && lo.z == 0);
  SH_CHECK(hi.x == 1 && hi.y == 1 && hi.z == 1);
  SH_CHECK(closed_and_oriented(&m));
  /* Outward: every normal points away from the centre. */
  int outward = 1;
  for (int t = 0; t < m.ntris; t++) {
    sh_vec3 c = vert(&m, m.indices[3 * t]);
    if (sh_dot(tri_normal(&m, t), sh_sub(c, sh_v3s(0.5))) <= 0)
      outward = 0;
  }
  SH_CHECK(outward);
  sh_mesh_free(&m);
  SH_CHECK(m.positions == NULL && m.ntris == 0);
  sh_mesh_free(&m);

  const char *ply = write_file("pyramid.ply", pyramid_ply);
  SH_CHECK(sh_mesh_load(ply, NULL, &m, &err) == SH_OK);
  SH_CHECK(m.ntris == 6);
  SH_CHECK(indices_valid(&m));
  bounds(&m, &lo, &hi);
  SH_CHECK(lo.x == -1 && lo.y == 0 && lo.z == -1);
  SH_CHECK(hi.x == 1 && hi.y == 2 && hi.z == 1);
  sh_mesh_free(&m);

  /* glTF: one quad (two triangles) drawn by two nodes with different
   * translations, so the node transforms must be applied. */
  unsigned char buf[60];
  float pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  unsigned short idx[6] = {0, 1, 2, 0, 2, 3};
  memcpy(buf, pos, 48);
  memcpy(buf + 48, idx, 12);
  char b64[128];
  base64(buf, sizeof buf, b64);
  char gltf[2048];
  snprintf(gltf, sizeof gltf,
           "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0,\n"
           " \"scenes\": [{\"nodes\": [0, 1]}],\n"
           " \"nodes\": [{\"mesh\": 0, \"translation\": [0, 0, 5]},\n"
           "             {\"mesh\": 0, \"translation\": [10, 0, 0]}],\n"
           " \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0},"
           " \"indices\": 1}]}],\n"
           " \"buffers\": [{\"byteLength\": 60, \"uri\": "
           "\"data:application/octet-stream;base64,%s\"}],\n"
           " \"bufferViews\": [{\"buffer\": 0, \"byteOffset\": 0, "
           "\"byteLength\": 48},\n"
           "   {\"buffer\": 0, \"byteOffset\": 48, \"byteLength\": 12}],\n"
           " \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, "
           "\"count\": 4, \"type\": \"VEC3\", \"min\": [0, 0, 0], \"max\": "
           "[1, 1, 0]},\n"
           "   {\"bufferView\": 1, \"componentType\": 5123, \"count\": 6, "
           "\"type\": \"SCALAR\"}]}\n",
           b64);
  const char *gl = write_file("quad.gltf", gltf);
  sh_status gs = sh_mesh_load(gl, NULL, &m, &err);
  SH_CHECK(gs == SH_OK);
  if (gs != SH_OK)
    fprintf(stderr, "glTF: %s\n", err.message);
  SH_CHECK(m.ntris == 4);
  SH_CHECK(m.nverts == 8);
  SH_CHECK(indices_valid(&m));
  bounds(&m, &lo, &hi);
  SH_CHECK(lo.x == 0 && lo.y == 0 && lo.z == 0);
  SH_CHECK(hi.x == 11 && hi.y == 1 && hi.z == 5);
  /* Both copies still face +Z. */
  for (int t = 0; t < m.ntris; t++)
    SH_CHECK(tri_normal(&m, t).z > 0);
  sh_mesh_free(&m);

  /* A missing file, garbage, a file with no triangles. */
  char missing[512];
  snprintf(missing, sizeof missing, "%s/missing.obj", tmpdir);
  SH_CHECK(sh_mesh_load(missing, NULL, &m, &err) == SH_ERR_IO);
  SH_CHECK(strstr(err.message, "missing.obj") != NULL);
  SH_CHECK(m.positions == NULL && m.ntris == 0);
  const char *junk = write_file("junk.ply", "ply\nthis is not a mesh\n");
  SH_CHECK(sh_mesh_load(junk, NULL, &m, &err) == SH_ERR_MESH);
  SH_CHECK(strstr(err.message, "junk.ply") != NULL);
  junk = write_file("junk.gltf", "{ \"asset\": [ not json");
  SH_CHECK(sh_mesh_load(junk, NULL, &m, &err) == SH_ERR_MESH);
  junk = write_file("junk.nosuchext", "\x01\x02\x03 binary junk");
  SH_CHECK(sh_mesh_load(junk, NULL, &m, &err) == SH_ERR_MESH);
  const char *lines = write_file("lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n");
  SH_CHECK(sh_mesh_load(lines, NULL, &m, &err) == SH_ERR_MESH);
  SH_CHECK(m.positions == NULL);
  SH_CHECK(sh_mesh_load(NULL, NULL, &m, &err) == SH_ERR_ARG);
  sh_error_clear(&err);
}

/* A glTF in tmpdir/sub whose buffer is named by `uri`, a triangle of three
 * float vertices (36 bytes). */
static const char *escape_gltf(const char *name, const char *uri) {
  char text[1024], path[300];
  snprintf(text, sizeof text,
           "{\"asset\": {\"version\": \"2.0\"}, \"scenes\": [{\"nodes\": [0]}],"
           " \"scene\": 0, \"nodes\": [{\"mesh\": 0}], \"meshes\": "
           "[{\"primitives\": [{\"attributes\": {\"POSITION\": 0}}]}],"
           " \"buffers\": [{\"uri\": \"%s\", \"byteLength\": 36}],"
           " \"bufferViews\": [{\"buffer\": 0, \"byteOffset\": 0, "
           "\"byteLength\": 36}], \"accessors\": [{\"bufferView\": 0, "
           "\"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\", "
           "\"min\": [0, 0, 0], \"max\": [1, 1, 0]}]}",
           uri);
  snprintf(path, sizeof path, "sub/%s", name);
  return write_file(path, text);
}

/* Files a mesh names must lie in the scene's tree, however they are spelt
 * (issue 11, "files that escape"), and vertices must be finite. */
static void test_confined(void) {
  sh_mesh m;
  sh_error err = SH_ERROR_INIT;
  char sub[300];
  snprintf(sub, sizeof sub, "%s/sub", tmpdir);
  SH_CHECK(mkdir(sub, 0700) == 0);
  /* The secret: a valid triangle's bytes, outside sub. */
  float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  char secret[300];
  snprintf(secret, sizeof secret, "%s/secret.bin", tmpdir);
  FILE *f = fopen(secret, "wb");
  SH_CHECK(f != NULL);
  if (f) {
    fwrite(tri, sizeof tri, 1, f);
    fclose(f);
  }
  const char *uris[] = {"../secret.bin", "./../secret.bin", "%2E%2E/secret.bin",
                        "..//secret.bin", "link.bin"};
  char link[320];
  snprintf(link, sizeof link, "%s/link.bin", sub);
  SH_CHECK(symlink(secret, link) == 0);
  for (int i = 0; i < 5; i++) {
    char name[32];
    snprintf(name, sizeof name, "escape%d.gltf", i);
    const char *gl = escape_gltf(name, uris[i]);
    sh_status st = sh_mesh_load(gl, sub, &m, &err);
    SH_CHECK(st == SH_ERR_MESH);
    SH_CHECK(m.positions == NULL);
    if (st == SH_OK) sh_mesh_free(&m);
    /* Debian's assimp (5.2) does not decode a percent-encoded URI: it
     * looks for a file named "%2E%2E", finds none and fails; were it to
     * decode, the confinement would refuse the result like the rest. */
    if (i == 2) continue;
    if (st == SH_ERR_MESH) SH_CHECK(strstr(err.message, "outside") != NULL);
    /* With the whole tmpdir as the scene's tree, the same file loads. */
    st = sh_mesh_load(gl, tmpdir, &m, &err);
    SH_CHECK(st == SH_OK);
    if (st == SH_OK) SH_CHECK(m.ntris == 1);
    sh_mesh_free(&m);
  }
  remove(link);
  remove(secret);
  /* An OBJ's material library is a file it names, too. */
  write_file("outside.mtl", "newmtl m\nKd 1 1 1\n");
  const char *obj = write_file(
      "sub/mtl.obj", "mtllib ../outside.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  SH_CHECK(sh_mesh_load(obj, sub, &m, &err) == SH_ERR_MESH);
  SH_CHECK(strstr(err.message, "outside.mtl") != NULL);
  /* A file outside the tree that does not exist is refused as outside,
   * not left to assimp as missing: a glTF buffer, an OBJ's library. */
  const char *gone = escape_gltf("gone.gltf", "../nodir/gone.bin");
  SH_CHECK(sh_mesh_load(gone, sub, &m, &err) == SH_ERR_MESH);
  SH_CHECK(strstr(err.message, "outside") != NULL &&
           strstr(err.message, "gone.bin") != NULL);
  obj = write_file("sub/gone.obj",
                   "mtllib ../gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  SH_CHECK(sh_mesh_load(obj, sub, &m, &err) == SH_ERR_MESH);
  SH_CHECK(strstr(err.message, "outside") != NULL &&
           strstr(err.message, "gone.mtl") != NULL);
  /* Inside the tree a missing library is still assimp's business: it
   * loads without it. */
  obj = write_file("sub/gone_inside.obj",
                   "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  SH_CHECK(sh_mesh_load(obj, sub, &m, &err) == SH_OK);
  sh_mesh_free(&m);
  /* Vertices that are not finite floats, with the vertex named. */
  const char *bad[] = {"v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                       "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n",
                       "v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n"};
  const char *which[] = {"vertex 1 ", "vertex 2 ", "vertex 3 "};
  for (int i = 0; i < 3; i++) {
    char name[32];
    snprintf(name, sizeof name, "nonfinite%d.obj", i);
    const char *p = write_file(name, bad[i]);
    SH_CHECK(sh_mesh_load(p, NULL, &m, &err) == SH_ERR_MESH);
    SH_CHECK(strstr(err.message, which[i]) != NULL);
    SH_CHECK(m.positions == NULL);
  }
  sh_error_clear(&err);
}

static void test_heightfield(void) {
  sh_image img;
  sh_error err = SH_ERROR_INIT;
  sh_mesh m;
  SH_CHECK(sh_image_alloc(&img, 3, 2, &err) == SH_OK);
  /* Greys 0, 0.5, 1 / 0.25, 0.75, a colour whose mean is 0.2. */
  float g[5] = {0, 0.5f, 1, 0.25f, 0.75f};
  for (int i = 0; i < 5; i++)
    img.rgb[3 * i] = img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = g[i];
  img.rgb[15] = 0.6f;
  img.rgb[16] = 0.0f;
  img.rgb[17] = 0.0f;
  sh_vec3 lo = sh_v3(-2, 1, 10), hi = sh_v3(2, 3, 12);
  SH_CHECK(sh_mesh_heightfield(&img, lo, hi, &m, &err) == SH_OK);
  SH_CHECK(m.nverts == 6 && m.ntris == 4);
  SH_CHECK(indices_valid(&m));
  double want_y[6] = {1, 2, 3, 1.5, 2.5, 1.4};
  for (int j = 0; j < 2; j++)
    for (int i = 0; i < 3; i++) {
      sh_vec3 p = vert(&m, (unsigned)(j * 3 + i));
      SH_CHECK_NEAR(p.x, -2 + i * 2.0, 0, 1e-6);
      SH_CHECK_NEAR(p.z, 10 + j * 2.0, 0, 1e-6);
      SH_CHECK_NEAR(p.y, want_y[j * 3 + i], 0, 1e-6);
    }
  for (int t = 0; t < m.ntris; t++)
    SH_CHECK(tri_normal(&m, t).y > 0);
  sh_mesh_free(&m);
  /* Too small an image, an empty box. */
  sh_image_free(&img);
  SH_CHECK(sh_image_alloc(&img, 1, 5, &err) == SH_OK);
  SH_CHECK(sh_mesh_heightfield(&img, lo, hi, &m, &err) == SH_ERR_ARG);
  sh_image_free(&img);
  SH_CHECK(sh_image_alloc(&img, 2, 2, &err) == SH_OK);
  SH_CHECK(sh_mesh_heightfield(&img, hi, lo, &m, &err) == SH_ERR_ARG);
  sh_image_free(&img);
  sh_error_clear(&err);
}

/* Checks a tessellated sphere: vertices on it, every triangle within
 * max_error of it (and not needlessly fine), closed and outward. */
static void check_sphere(sh_vec3 c, double r, double max_error) {
  sh_shape s = {.type = SH_SHAPE_SPHERE, .center = c, .radius = r};
  sh_mesh m;
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(sh_mesh_tessellate(&s, max_error, &m, &err) == SH_OK);
  SH_CHECK(m.ntris > 0 && indices_valid(&m));
  double tol = 4 * FLT_EPSILON * (r + sh_length(c));
  double worst_vertex = 0, worst_depth = 0;
  for (int i = 0; i < m.nverts; i++) {
    double d = fabs(sh_length(sh_sub(vert(&m, (unsigned)i), c)) - r);
    worst_vertex = fmax(worst_vertex, d);
  }
  SH_CHECK(worst_vertex <= max_error);
  SH_CHECK(worst_vertex <= tol);
  int outward = 1;
  for (int t = 0; t < m.ntris; t++) {
    sh_vec3 a = vert(&m, m.indices[3 * t]), b = vert(&m, m.indices[3 * t + 1]),
            cc = vert(&m, m.indices[3 * t + 2]);
    sh_vec3 n = tri_normal(&m, t);
    /* The point of the triangle's plane nearest the centre, if it lies in
     * the triangle, is the triangle's deepest point; otherwise sample. */
    double plane = fabs(sh_dot(sh_normalize(n), sh_sub(a, c)));
    worst_depth = fmax(worst_depth, r - plane);
    sh_vec3 centroid = sh_scale(sh_add(sh_add(a, b), cc), 1.0 / 3);
    SH_CHECK(r - sh_length(sh_sub(centroid, c)) <= max_error + tol);
    if (sh_dot(n, sh_sub(centroid, c)) <= 0)
      outward = 0;
  }
  SH_CHECK(outward);
  SH_CHECK(worst_depth <= max_error + tol);
  /* Not wastefully fine: the bound is at least a third used. */
  SH_CHECK(worst_depth >= max_error / 3 || m.ntris <= 8 * 2);
  SH_CHECK(closed_and_oriented(&m));
  /* Euler characteristic of a sphere: V - E + F = 2, E = 3F / 2. */
  SH_CHECK(m.nverts - 3 * m.ntris / 2 + m.ntris == 2);
  sh_mesh_free(&m);
  sh_error_clear(&err);
}

static void test_tessellate(void) {
  check_sphere(sh_v3(0, 0, 0), 1.0, 0.01);
  check_sphere(sh_v3(1, -2, 3), 2.5, 0.001);
  check_sphere(sh_v3(0, 0, 0), 0.1, 1.0); /* coarsest: an octahedron */
  check_sphere(sh_v3(0, 5, 0), 1.0, 0.2);

  sh_shape s;
  sh_mesh m;
  sh_error err = SH_ERROR_INIT;
  memset(&s, 0, sizeof s);
  s.type = SH_SHAPE_SPHERE;
  s.radius = 1;
  SH_CHECK(sh_mesh_tessellate(&s, 0.0, &m, &err) == SH_ERR_ARG);
  SH_CHECK(sh_mesh_tessellate(&s, 1e-12, &m, &err) == SH_ERR_ARG);
  s.radius = 0;
  SH_CHECK(sh_mesh_tessellate(&s, 0.1, &m, &err) == SH_ERR_ARG);

  /* A box: 12 triangles, closed, outward. */
  memset(&s, 0, sizeof s);
  s.type = SH_SHAPE_BOX;
  s.bmin = sh_v3(-1, 0, 2);
  s.bmax = sh_v3(3, 1, 2.5);
  SH_CHECK(sh_mesh_tessellate(&s, 0.1, &m, &err) == SH_OK);
  SH_CHECK(m.ntris == 12 && m.nverts == 8);
  SH_CHECK(closed_and_oriented(&m));
  sh_vec3 lo, hi;
  bounds(&m, &lo, &hi);
  SH_CHECK(lo.x == -1 && lo.y == 0 && lo.z == 2);
  SH_CHECK(hi.x == 3 && hi.y == 1 && hi.z == 2.5);
  sh_vec3 mid = sh_v3(1, 0.5, 2.25);
  for (int t = 0; t < m.ntris; t++)
    SH_CHECK(sh_dot(tri_normal(&m, t),
                    sh_sub(vert(&m, m.indices[3 * t]), mid)) > 0);
  sh_mesh_free(&m);

  /* A quad faces u x v. */
  memset(&s, 0, sizeof s);
  s.type = SH_SHAPE_QUAD;
  s.corner = sh_v3(1, 1, 1);
  s.u = sh_v3(0, 0, 2);
  s.v = sh_v3(3, 0, 0);
  SH_CHECK(sh_mesh_tessellate(&s, 0.1, &m, &err) == SH_OK);
  SH_CHECK(m.ntris == 2 && m.nverts == 4);
  for (int t = 0; t < m.ntris; t++) {
    sh_vec3 n = tri_normal(&m, t);
    SH_CHECK(n.y > 0 && fabs(n.x) < 1e-6 && fabs(n.z) < 1e-6);
    SH_CHECK_NEAR(sh_length(n), 6.0, 0, 1e-5);
  }
  sh_mesh_free(&m);

  /* A capped cylinder along a slanted axis: closed, outward, on the
   * surface within max_error. */
  memset(&s, 0, sizeof s);
  s.type = SH_SHAPE_CYLINDER;
  s.base = sh_v3(0, 0, 0);
  s.top = sh_v3(1, 2, 2); /* length 3 */
  s.radius = 0.5;
  s.caps = 1;
  double e = 0.005;
  SH_CHECK(sh_mesh_tessellate(&s, e, &m, &err) == SH_OK);
  SH_CHECK(closed_and_oriented(&m));
  int n = (m.ntris) / 4;
  SH_CHECK(m.nverts == 2 * n + 2);
  SH_CHECK(0.5 * (1 - cos(SH_PI / n)) <= e);
  SH_CHECK(0.5 * (1 - cos(SH_PI / (n - 1))) > e);
  sh_vec3 w = sh_v3(1.0 / 3, 2.0 / 3, 2.0 / 3);
  for (int i = 0; i < 2 * n; i++) {
    sh_vec3 p = vert(&m, (unsigned)i);
    double along = sh_dot(p, w);
    double radial = sh_length(sh_sub(p, sh_scale(w, along)));
    SH_CHECK_NEAR(radial, 0.5, 0, 1e-6);
    SH_CHECK(fabs(along) < 1e-6 || fabs(along - 3) < 1e-6);
  }
  sh_vec3 centre = sh_v3(0.5, 1, 1);
  int outward = 1;
  for (int t = 0; t < m.ntris; t++) {
    sh_vec3 a = vert(&m, m.indices[3 * t]), b = vert(&m, m.indices[3 * t + 1]),
            c = vert(&m, m.indices[3 * t + 2]);
    sh_vec3 cen = sh_scale(sh_add(sh_add(a, b), c), 1.0 / 3);
    if (sh_dot(tri_normal(&m, t), sh_sub(cen, centre)) <= 0)
      outward = 0;
  }
  SH_CHECK(outward);
  sh_mesh_free(&m);
  s.caps = 0;
  SH_CHECK(sh_mesh_tessellate(&s, e, &m, &err) == SH_OK);
  SH_CHECK(m.ntris == 2 * n && !closed_and_oriented(&m));
  sh_mesh_free(&m);
  s.top = s.base;
  SH_CHECK(sh_mesh_tessellate(&s, e, &m, &err) == SH_ERR_ARG);

  /* Meshes and heightfields are copied. */
  memset(&s, 0, sizeof s);
  s.type = SH_SHAPE_MESH;
  SH_CHECK(sh_mesh_tessellate(&s, 0.1, &m, &err) == SH_ERR_ARG);
  sh_shape box;
  memset(&box, 0, sizeof box);
  box.type = SH_SHAPE_BOX;
  box.bmax = sh_v3s(1);
  SH_CHECK(sh_mesh_tessellate(&box, 0.1, &s.mesh, &err) == SH_OK);
  s.type = SH_SHAPE_HEIGHTFIELD;
  SH_CHECK(sh_mesh_tessellate(&s, 0.1, &m, &err) == SH_OK);
  SH_CHECK(m.ntris == 12 && m.nverts == 8);
  SH_CHECK(m.positions != s.mesh.positions);
  SH_CHECK(memcmp(m.indices, s.mesh.indices, 36 * sizeof(unsigned)) == 0);
  SH_CHECK(memcmp(m.positions, s.mesh.positions, 24 * sizeof(float)) == 0);
  sh_mesh_free(&m);
  sh_mesh_free(&s.mesh);
  sh_error_clear(&err);
}

int main(void) {
  if (!sh_test_tmpdir(tmpdir, sizeof tmpdir, "sh_mesh_test")) return EXIT_FAILURE;
  test_load();
  test_confined();
  test_heightfield();
  test_tessellate();
  for (int i = 0; i < nwritten; i++)
    remove(written[i]);
  char sub[300];
  snprintf(sub, sizeof sub, "%s/sub", tmpdir);
  rmdir(sub);
  if (rmdir(tmpdir) != 0)
    perror(tmpdir);
  SH_TEST_DONE();
}
