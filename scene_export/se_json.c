#include "se_json.h"

#include <jansson.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "se_jsontext.h"

static json_t *vec(sh_vec3 v) {
  return json_pack("[fff]", v.x, v.y, v.z);
}

/* Where the export's files go and how they are named: file names in the
 * export are relative to its directory and stay in its tree (a scene names
 * no other files, docs/scene-format.md, "Files"). */
typedef struct files {
  se_output *out;
  char *dir;      /* the export's directory, resolved */
  char *prefix;   /* the export's path without ".json": copies are
                     PREFIX.<what><i>.<ext> */
  const char *stem; /* the export's file name without ".json" */
  int failed;     /* out of memory, or a file that cannot be read */
  sh_status why_status; /* the first failure's status */
  char *why;      /* the first failure's message */
} files;

/* PREFIX.WHAT<i>EXT, malloc'd. */
static char *copy_name(const char *prefix, const char *what, int i,
                       const char *ext) {
  int n = snprintf(NULL, 0, "%s.%s%d%s", prefix, what, i, ext);
  char *s = n >= 0 ? malloc((size_t)n + 1) : NULL;
  if (s) snprintf(s, (size_t)n + 1, "%s.%s%d%s", prefix, what, i, ext);
  return s;
}

/* Records the first failure: `fmt` with the file's kind and path. */
static void fail_as(files *f, sh_status status, const char *fmt, const char *what,
                    const char *path) {
  if (!f->failed) {
    f->why_status = status;
    int n = snprintf(NULL, 0, fmt, what, path);
    f->why = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (f->why) snprintf(f->why, (size_t)n + 1, fmt, what, path);
  }
  f->failed = 1;
}

static void fail(files *f, const char *what, const char *path) {
  fail_as(f, SH_ERR_IO, "cannot copy the %s file '%s' into the export", what, path);
}

/* A file the scene loaded, as the export names it: its path relative to
 * the export's directory if it lies in that tree, else a copy of its bytes
 * written beside the export as STEM.<what><i>.<ext>. A file that names
 * other files (`nnamed`: a glTF's buffers, an OBJ's material library) is
 * not copied: the copy would not find them, so the export fails. */
static json_t *file_ref(files *f, const char *path, const char *what, int i, int nnamed) {
  char *real = realpath(path, NULL);
  if (!real) {
    fail(f, what, path);
    return NULL;
  }
  size_t n = strlen(f->dir);
  if (!strncmp(real, f->dir, n) && real[n] == '/') {
    json_t *s = json_string(real + n + 1);
    free(real);
    return s;
  }
  if (nnamed > 0) {
    fail_as(f, SH_ERR_SCENE,
            "the %s file '%s' names other files (a glTF's buffers, an OBJ's material "
            "library), which a copy beside the export would not find: write the export "
            "in a directory whose tree holds the mesh (then the export refers to it)",
            what, path);
    free(real);
    return NULL;
  }
  const char *slash = strrchr(real, '/'), *dot = strrchr(real, '.');
  const char *ext = dot && dot > slash + 1 ? dot : "";
  char *copy = copy_name(f->prefix, what, i, ext);
  char *name = copy_name(f->stem, what, i, ext);
  FILE *in = fopen(real, "rb");
  se_buf *b = copy && name && in ? se_output_text(f->out, copy) : NULL;
  char chunk[1 << 16];
  size_t got;
  while (b && (got = fread(chunk, 1, sizeof chunk, in)) > 0)
    se_buf_append(b, chunk, got);
  if (!b || ferror(in) || b->failed) fail(f, what, path);
  if (in) fclose(in);
  json_t *s = b ? json_string(name) : NULL;
  free(real);
  free(copy);
  free(name);
  return s;
}

static int is_identity(const sh_mat4 *m) {
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 4; c++)
      if (m->m[r][c] != (r == c ? 1.0 : 0.0)) return 0;
  return 1;
}

static json_t *camera(const sh_camera *c) {
  return json_pack("{s:o, s:o, s:o, s:f, s:i, s:i}", "position", vec(c->position),
                   "look_at", vec(c->look_at), "up", vec(c->up), "fov_y_deg",
                   c->fov_y_deg, "width", c->width, "height", c->height);
}

static json_t *phase_object(const sh_phase *ph) {
  static const char *types[] = {"isotropic", "henyey_greenstein", "nishita_hazy",
                                "nishita_murky", "rayleigh", "cornette_shanks"};
  json_t *phase = json_pack("{s:s}", "type", types[ph->type]);
  if (phase && (ph->type == SH_PHASE_HENYEY_GREENSTEIN ||
                ph->type == SH_PHASE_CORNETTE_SHANKS))
    json_object_set_new(phase, "g", json_real(ph->g));
  return phase;
}

/* An atmosphere's own keys (docs/scene-format.md, "atmosphere"). */
static json_t *atmosphere(const sh_atmosphere *a) {
  json_t *o = json_pack(
      "{s:s, s:o, s:f, s:f, s:o, s:{s:o, s:f}}", "type", "atmosphere", "center",
      vec(a->center), "ground_radius", a->ground_radius, "top_radius",
      a->top_radius, "ground_albedo", vec(a->ground_albedo), "rayleigh",
      "sigma_s", vec(a->rayleigh_sigma_s), "scale_height", a->rayleigh_H);
  if (o && a->has_mie)
    json_object_set_new(o, "mie",
                        json_pack("{s:o, s:o, s:f, s:o}", "sigma_s",
                                  vec(a->mie_sigma_s), "sigma_a",
                                  vec(a->mie_sigma_a), "scale_height", a->mie_H,
                                  "phase", phase_object(&a->mie_phase)));
  if (o && a->has_ozone)
    json_object_set_new(o, "ozone",
                        json_pack("{s:o, s:f, s:f}", "sigma_a",
                                  vec(a->ozone_sigma_a), "center_height",
                                  a->ozone_height, "width", a->ozone_width));
  return o;
}

json_t *se_json_medium(const sh_medium *m) {
  if (m->type == SH_MEDIUM_ATMOSPHERE) return atmosphere(&m->atmo);
  json_t *phase = phase_object(&m->phase);
  json_t *o = json_pack("{s:o, s:o, s:o, s:{s:o, s:o}}", "sigma_s",
                        vec(m->sigma_s), "sigma_a", vec(m->sigma_a), "phase",
                        phase, "bounds", "min", vec(m->bmin), "max",
                        vec(m->bmax));
  if (o && m->type == SH_MEDIUM_HEIGHT_FOG) {
    json_object_set_new(o, "type", json_string("height_fog"));
    json_object_set_new(o, "base_height", json_real(m->base_height));
    json_object_set_new(o, "scale_height", json_real(m->scale_height));
  }
  return o;
}

static json_t *light(files *f, const sh_light *l, int i) {
  json_t *o = NULL;
  switch (l->type) {
  case SH_LIGHT_POINT:
    o = json_pack("{s:s, s:o, s:o}", "type", "point", "position",
                  vec(l->position), "intensity", vec(l->intensity));
    break;
  case SH_LIGHT_SPOT:
    o = json_pack("{s:s, s:o, s:o, s:o, s:f, s:f, s:f}", "type", "spot",
                  "position", vec(l->position), "direction", vec(l->direction),
                  "intensity", vec(l->intensity), "outer_angle_deg", l->outer_deg,
                  "inner_angle_deg", l->inner_deg, "exponent", l->exponent);
    if (o && l->has_map)
      json_object_set_new(o, "light_map",
                          json_pack("{s:o, s:o}", "image",
                                    file_ref(f, l->map_file, "map", i, 0),
                                    "up", vec(l->map_up)));
    break;
  case SH_LIGHT_DIRECTIONAL:
    o = json_pack("{s:s, s:o, s:o}", "type", "directional", "direction",
                  vec(l->direction), "irradiance", vec(l->irradiance));
    if (o && l->angular_diameter_deg > 0)
      json_object_set_new(o, "angular_diameter_deg",
                          json_real(l->angular_diameter_deg));
    if (o && l->has_map)
      json_object_set_new(o, "light_map",
                          json_pack("{s:o, s:o, s:o, s:o}", "image",
                                    file_ref(f, l->map_file, "map", i, 0),
                                    "origin",
                                    vec(l->map_origin), "u", vec(l->map_u), "v",
                                    vec(l->map_v)));
    break;
  }
  if (o) json_object_set_new(o, "soft_shadows", json_boolean(l->soft_shadows));
  return o;
}

static json_t *material(const sh_material *m) {
  return json_pack("{s:o, s:o, s:f, s:o, s:o, s:f, s:o, s:b, s:b}", "diffuse",
                   vec(m->diffuse), "specular", vec(m->specular), "shininess",
                   m->shininess, "reflect", vec(m->reflect), "transmit",
                   vec(m->transmit), "ior", m->ior, "emission", vec(m->emission),
                   "casts_soft_shadows", m->casts_soft_shadows,
                   "receives_soft_shadows", m->receives_soft_shadows);
}

static json_t *shape(files *f, const sh_scene *s, const sh_shape *sh,
                     int i) {
  static const char *types[] = {"mesh", "sphere", "box", "cylinder", "quad",
                                "heightfield"};
  json_t *o = json_pack("{s:s, s:s}", "type", types[sh->type], "material",
                        s->materials[sh->material].name);
  if (!o) return NULL;
  switch (sh->type) {
  case SH_SHAPE_MESH:
    /* A mesh from memory keeps its name: the reader passes it again. */
    if (sh->data)
      json_object_set_new(o, "data", json_string(sh->data));
    else
      json_object_set_new(o, "file", file_ref(f, sh->file, "mesh", i, sh->nnamed));
    break;
  case SH_SHAPE_SPHERE:
    json_object_set_new(o, "center", vec(sh->center));
    json_object_set_new(o, "radius", json_real(sh->radius));
    break;
  case SH_SHAPE_BOX:
    json_object_set_new(o, "min", vec(sh->bmin));
    json_object_set_new(o, "max", vec(sh->bmax));
    break;
  case SH_SHAPE_CYLINDER:
    json_object_set_new(o, "base", vec(sh->base));
    json_object_set_new(o, "top", vec(sh->top));
    json_object_set_new(o, "radius", json_real(sh->radius));
    json_object_set_new(o, "caps", json_boolean(sh->caps));
    break;
  case SH_SHAPE_QUAD:
    json_object_set_new(o, "corner", vec(sh->corner));
    json_object_set_new(o, "u", vec(sh->u));
    json_object_set_new(o, "v", vec(sh->v));
    break;
  case SH_SHAPE_HEIGHTFIELD:
    json_object_set_new(o, "image", file_ref(f, sh->file, "height", i, 0));
    json_object_set_new(o, "min", vec(sh->bmin));
    json_object_set_new(o, "max", vec(sh->bmax));
    break;
  }
  if (!is_identity(&sh->xform)) {
    json_t *m = json_array();
    for (int r = 0; r < 4; r++)
      for (int c = 0; c < 4; c++) json_array_append_new(m, json_real(sh->xform.m[r][c]));
    json_object_set_new(o, "transform", json_pack("{s:o}", "matrix", m));
  }
  return o;
}

static json_t *render(const sh_render_settings *r) {
  json_t *o = json_pack("{s:i, s:i, s:I, s:f}", "spp", r->spp, "max_depth",
                        r->max_depth, "seed", (json_int_t)r->seed, "exposure",
                        r->exposure);
  if (!o) return NULL;
  /* The renderers' keys as the scene gave them (the renderers check them). */
  for (int i = 0; i < r->nparams; i++)
    json_object_set_new(o, r->params[i].key,
                        json_loads(r->params[i].json, JSON_DECODE_ANY, NULL));
  return o;
}

sh_status se_json_build(const sh_scene *s, const se_options *opt,
                        const char *json_path, se_output *out, se_notes *notes,
                        sh_error *err) {
  (void)opt;
  (void)notes;
  files f = {out, NULL, NULL, NULL, 0, SH_OK, NULL};
  size_t n = strlen(json_path);
  const char *slash = strrchr(json_path, '/');
  /* The export's directory: the part before the last slash ("/" for the
   * root, "." for none). */
  size_t dl = slash ? (slash == json_path ? 1 : (size_t)(slash - json_path)) : 0;
  char *parent = malloc(dl + 2);
  if (parent) {
    memcpy(parent, slash ? json_path : ".", slash ? dl : 1);
    parent[slash ? dl : 1] = '\0';
    f.dir = realpath(parent, NULL);
    free(parent);
  }
  size_t pl = n > 5 && !strcmp(json_path + n - 5, ".json") ? n - 5 : n;
  f.prefix = malloc(pl + 1);
  if (f.prefix) {
    memcpy(f.prefix, json_path, pl);
    f.prefix[pl] = '\0';
    f.stem = f.prefix + (slash ? slash - json_path + 1 : 0);
  }
  if (!f.dir || !f.prefix) {
    free(f.dir);
    free(f.prefix);
    return sh_error_set(err, SH_ERR_IO, "cannot resolve the directory of '%s'",
                        json_path);
  }
  json_t *root = json_pack("{s:s, s:i, s:o, s:o, s:o}", "format", "shafts-scene",
                           "version", 1, "camera", camera(&s->camera),
                           "background", vec(s->background), "ambient",
                           vec(s->ambient));
  if (!root) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  if (s->medium.present) json_object_set_new(root, "medium", se_json_medium(&s->medium));
  json_t *lights = json_array(), *materials = json_object(), *shapes = json_array();
  for (int i = 0; i < s->nlights; i++) json_array_append_new(lights, light(&f, &s->lights[i], i));
  for (int i = 0; i < s->nmaterials; i++)
    json_object_set_new(materials, s->materials[i].name, material(&s->materials[i]));
  for (int i = 0; i < s->nshapes; i++) json_array_append_new(shapes, shape(&f, s, &s->shapes[i], i));
  json_object_set_new(root, "lights", lights);
  json_object_set_new(root, "materials", materials);
  json_object_set_new(root, "shapes", shapes);
  json_object_set_new(root, "render", render(&s->render));
  /* A NULL from a failed allocation makes json_object_set_new fail too; a
   * complete tree has every member. */
  int complete = lights && materials && shapes &&
                 json_array_size(lights) == (size_t)s->nlights &&
                 json_object_size(materials) == (size_t)s->nmaterials &&
                 json_array_size(shapes) == (size_t)s->nshapes &&
                 json_object_get(root, "render") &&
                 (!s->medium.present || json_object_get(root, "medium"));
  se_buf *b = complete ? se_output_text(out, json_path) : NULL;
  if (b) {
    se_json_text(b, root, 2);
    se_buf_puts(b, "\n");
  }
  json_decref(root);
  free(f.dir);
  free(f.prefix);
  if (f.failed) {
    sh_status st = sh_error_set(err, f.why ? f.why_status : SH_ERR_NOMEM, "%s",
                                f.why ? f.why : "out of memory");
    free(f.why);
    return st;
  }
  if (!b) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  return SH_OK;
}
