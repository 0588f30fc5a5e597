/* The scene parser's shapes: the six shape types, their transforms and
 * their materials (docs/scene-format.md, "shapes"). */
#include "sh_parse_int.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const shape_keys[] = {"type", "material", "transform", NULL};
static const char *const mesh_keys[] = {"file", "data", NULL};
static const char *const sphere_keys[] = {"center", "radius", NULL};
static const char *const box_keys[] = {"min", "max", NULL};
static const char *const cylinder_keys[] = {"base", "top", "radius", "caps",
                                            NULL};
static const char *const quad_keys[] = {"corner", "u", "v", NULL};
static const char *const heightfield_keys[] = {"image", "min", "max", NULL};
static const char *const transform_keys[] = {"translate", "rotate_deg", "scale",
                                             "matrix", NULL};
/* In the order of sh_shape_type. */
static const char *const shape_type_names[] = {
    "mesh", "sphere", "box", "cylinder", "quad", "heightfield", NULL};

/* The relative volume of the parallelepiped of the matrix's 3x3 part: 0 for
 * singular matrices, 1 for orthogonal ones, whatever their scale. */
static double conditioning(const sh_mat4 *m) {
  sh_vec3 r[3];
  for (int i = 0; i < 3; i++) r[i] = sh_v3(m->m[i][0], m->m[i][1], m->m[i][2]);
  double det = sh_dot(r[0], sh_cross(r[1], r[2]));
  double size = sh_length(r[0]) * sh_length(r[1]) * sh_length(r[2]);
  return size > 0 ? fabs(det) / size : 0.0;
}

static sh_status parse_matrix(sh__pctx *c, json_t *t, sh_mat4 *m) {
  static const char *want = "an array of 16 finite numbers (row-major)";
  json_t *a = json_object_get(t, "matrix");
  sh_status st = SH_OK;
  sh__push_key(c, "matrix");
  if (!json_is_array(a) || json_array_size(a) != 16)
    return sh__wrong(c, a, want);
  for (int i = 0; i < 16; i++) {
    json_t *e = json_array_get(a, (size_t)i);
    if (!json_is_number(e) || !isfinite(json_number_value(e))) {
      sh__push_index(c, i);
      return sh__wrong(c, e, "a finite number");
    }
    m->m[i / 4][i % 4] = json_number_value(e);
  }
  if (m->m[3][0] != 0 || m->m[3][1] != 0 || m->m[3][2] != 0 ||
      m->m[3][3] != 1) {
    char v[4][40];
    for (int j = 0; j < 4; j++) sh__fmt_num(m->m[3][j], v[j], sizeof v[j]);
    st = sh__fail(c, SH_ERR_SCENE,
                  "expected the last row (elements 12 to 15) to be 0, 0, 0, "
                  "1, found %s, %s, %s, %s",
                  v[0], v[1], v[2], v[3]);
  }
  if (!st) sh__pop(c);
  return st;
}

static sh_status parse_scale(sh__pctx *c, json_t *t, sh_vec3 *s) {
  json_t *v = json_object_get(t, "scale");
  sh_status st;
  *s = sh_v3s(1);
  if (!v) return SH_OK;
  if (json_is_number(v)) {
    double k;
    if ((st = sh__number(c, t, "scale", 1, 1, sh__any, &k))) return st;
    *s = sh_v3s(k);
  } else if (json_is_array(v)) {
    if ((st = sh__vec3(c, t, "scale", 1, sh_v3s(1), sh__any, s))) return st;
  } else {
    sh__push_key(c, "scale");
    return sh__wrong(c, v, "a number or an array of 3 numbers, all nonzero");
  }
  if (s->x == 0 || s->y == 0 || s->z == 0)
    return sh__fail_at(c, "scale", SH_ERR_SCENE,
                       "expected nonzero scale factors, found a zero");
  return SH_OK;
}

sh_status sh__parse_transform(sh__parser *p, json_t *t, sh_mat4 *xform,
                              sh_mat4 *inv) {
  sh__pctx *c = &p->c;
  sh_mat4 m = sh_mat4_identity(), mi;
  sh_status st;
  if (!json_is_object(t)) return sh__wrong(c, t, "an object (a transform)");
  if ((st = sh__check_keys(c, t, SH__KEYS(transform_keys), "a transform")))
    return st;
  const char *where = "transform";
  if (json_object_get(t, "matrix")) {
    for (int i = 0; transform_keys[i]; i++) {
      if (strcmp(transform_keys[i], "matrix") == 0 ||
          !json_object_get(t, transform_keys[i]))
        continue;
      sh__push_key(c, transform_keys[i]);
      return sh__fail_key(c, SH_ERR_SCENE,
                          "'matrix' cannot be combined with translate, "
                          "rotate_deg or scale");
    }
    if ((st = parse_matrix(c, t, &m))) return st;
    where = "matrix";
  } else {
    sh_vec3 tr, rot, sc;
    if ((st = sh__vec3(c, t, "translate", 0, sh_v3s(0), sh__any, &tr)) ||
        (st = sh__vec3(c, t, "rotate_deg", 0, sh_v3s(0), sh__any, &rot)) ||
        (st = parse_scale(c, t, &sc)))
      return st;
    /* Scale, then rotate about X, Y, Z, then translate. */
    m = sh_mat4_scale(sc);
    m = sh_mat4_mul(sh_mat4_rotate(0, rot.x), m);
    m = sh_mat4_mul(sh_mat4_rotate(1, rot.y), m);
    m = sh_mat4_mul(sh_mat4_rotate(2, rot.z), m);
    m = sh_mat4_mul(sh_mat4_translate(tr), m);
  }
  int ok = conditioning(&m) > 1e-12 && sh_mat4_inverse(m, &mi);
  for (int i = 0; i < 4 && ok; i++)
    for (int j = 0; j < 4; j++) ok = ok && isfinite(mi.m[i][j]);
  if (!ok) {
    if (strcmp(where, "matrix") == 0)
      return sh__fail_at(c, "matrix", SH_ERR_SCENE,
                         "the matrix is singular (not invertible)");
    return sh__fail(c, SH_ERR_SCENE,
                    "the transform is singular (not invertible)");
  }
  *xform = m;
  *inv = mi;
  return SH_OK;
}

static sh_status parse_transform(sh__parser *p, json_t *o, sh_shape *sh) {
  json_t *t;
  sh_status st;
  sh->xform = sh->inv = sh_mat4_identity();
  if ((st = sh__object(&p->c, o, "transform", 0, &t)) || !t) return st;
  sh__push_key(&p->c, "transform");
  if ((st = sh__parse_transform(p, t, &sh->xform, &sh->inv))) return st;
  sh__pop(&p->c);
  return SH_OK;
}

/* Resolves member "material" of a shape to an index of the scene's
 * materials. */
static sh_status find_material(sh__parser *p, json_t *o, int *out) {
  sh__pctx *c = &p->c;
  const sh_scene *s = p->scene;
  const char *name;
  sh_status st;
  if ((st = sh__string(c, o, "material", 1, &name))) return st;
  for (int i = 0; i < s->nmaterials; i++)
    if (strcmp(s->materials[i].name, name) == 0) {
      *out = i;
      return SH_OK;
    }
  if (s->nmaterials == 0)
    return sh__fail_at(c, "material", SH_ERR_SCENE,
                       "unknown material '%s'; the scene defines no "
                       "materials",
                       name);
  const char **names = calloc((unsigned)s->nmaterials + 1u, sizeof *names);
  if (!names) return sh__fail_at(c, "material", SH_ERR_NOMEM, "out of memory");
  for (int i = 0; i < s->nmaterials; i++) names[i] = s->materials[i].name;
  st = sh__fail_unknown(c, "material", "material", name, names,
                        "the materials are");
  free(names);
  return st;
}

static sh_status parse_mesh_file(sh__parser *p, json_t *o, sh_shape *sh) {
  const char *name;
  sh_status st;
  sh_error e = SH_ERROR_INIT;
  int has_file = json_object_get(o, "file") != NULL;
  int has_data = json_object_get(o, "data") != NULL;
  if (has_file && has_data) {
    sh__push_key(&p->c, "data");
    sh__fail_key(&p->c, SH_ERR_SCENE,
                 "a mesh takes either file or data, not both");
    sh__pop(&p->c);
    return SH_ERR_SCENE;
  }
  if (has_data) return sh__parse_mesh_data(p, o, &sh->mesh, &sh->data);
  if (!has_file)
    return sh__fail(&p->c, SH_ERR_SCENE,
                    "missing required key 'file' or 'data' (a mesh needs a "
                    "mesh file or the name of a mesh in memory)");
  if ((st = sh__string(&p->c, o, "file", 1, &name)) ||
      (st = sh__resolve_file(p, "file", name, &sh->file)) ||
      (st =
           sh__check_file(p, "file", name, sh->file, "mesh file", SH_ERR_MESH)))
    return st;
  /* The files the mesh names stay in the scene's tree (or, for a mesh the
   * scene names by an absolute path, in the mesh's own directory). */
  const char *root = name[0] == '/' ? NULL : p->base_dir ? p->base_dir : "";
  if ((st = sh__mesh_load_named(sh->file, root, &sh->mesh, &sh->named, &sh->nnamed, &e)))
    sh__fail_from(&p->c, "file", &e, ""); /* it names the file */
  sh_error_clear(&e);
  return st;
}

static sh_status parse_heightfield(sh__parser *p, json_t *o, sh_shape *sh) {
  sh__pctx *c = &p->c;
  sh_image img = {0, 0, NULL};
  sh_status st;
  sh_error e = SH_ERROR_INIT;
  if ((st = sh__min_max(c, o, &sh->bmin, &sh->bmax)) ||
      (st = sh__load_image(p, o, "image", 1, &img, &sh->file)))
    return st;
  if (img.width < 2 || img.height < 2) {
    st = sh__fail_at(c, "image", SH_ERR_IMAGE,
                     "a heightfield image needs at least 2 x 2 pixels, "
                     "found %d x %d",
                     img.width, img.height);
  } else {
    if ((st = sh_mesh_heightfield(&img, sh->bmin, sh->bmax, &sh->mesh, &e)))
      sh__fail_from(c, "image", &e, "cannot build the heightfield: ");
    sh_error_clear(&e);
  }
  sh_image_free(&img);
  return st;
}

sh_status sh__parse_shape(sh__parser *p, json_t *o, void *item) {
  sh_shape *sh = item;
  static const char *const *const type_keys[] = {mesh_keys, sphere_keys,
                                                 box_keys,  cylinder_keys,
                                                 quad_keys, heightfield_keys};
  sh__pctx *c = &p->c;
  sh_status st;
  int type;
  char what[40];
  if ((st = sh__choice(c, o, "type", 1, shape_type_names, 0, "shape type",
                       &type)))
    return st;
  sh->type = (sh_shape_type)type;
  snprintf(what, sizeof what, "a %s", shape_type_names[type]);
  if ((st =
           sh__check_keys(c, o, SH__KEYS(shape_keys, type_keys[type]), what)) ||
      (st = find_material(p, o, &sh->material)) ||
      (st = parse_transform(p, o, sh)))
    return st;
  switch (sh->type) {
  case SH_SHAPE_MESH: return parse_mesh_file(p, o, sh);
  case SH_SHAPE_SPHERE:
    return (st = sh__vec3(c, o, "center", 1, sh_v3s(0), sh__any, &sh->center))
               ? st
               : sh__number(c, o, "radius", 1, 0, sh__gt0, &sh->radius);
  case SH_SHAPE_BOX: return sh__min_max(c, o, &sh->bmin, &sh->bmax);
  case SH_SHAPE_CYLINDER:
    if ((st = sh__vec3(c, o, "base", 1, sh_v3s(0), sh__any, &sh->base)) ||
        (st = sh__vec3(c, o, "top", 1, sh_v3s(0), sh__any, &sh->top)) ||
        (st = sh__number(c, o, "radius", 1, 0, sh__gt0, &sh->radius)) ||
        (st = sh__boolean(c, o, "caps", 0, 1, &sh->caps)))
      return st;
    if (sh_is_black(sh_sub(sh->top, sh->base)))
      return sh__fail_at(c, "top", SH_ERR_SCENE,
                         "top equals base: the cylinder has no axis");
    return SH_OK;
  case SH_SHAPE_QUAD:
    if ((st = sh__vec3(c, o, "corner", 1, sh_v3s(0), sh__any, &sh->corner)) ||
        (st = sh__direction(c, o, "u", 1, &sh->u, NULL)) ||
        (st = sh__direction(c, o, "v", 1, &sh->v, NULL)))
      return st;
    if (sh__parallel(sh->u, sh->v))
      return sh__fail_at(c, "v", SH_ERR_SCENE,
                         "u and v are parallel: the quad has no area");
    return SH_OK;
  case SH_SHAPE_HEIGHTFIELD: return parse_heightfield(p, o, sh);
  }
  return SH_OK;
}
