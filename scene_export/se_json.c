#include "se_json.h"

#include <jansson.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "se_jsontext.h"

static json_t *vec(sh_vec3 v) {
  return json_pack("[fff]", v.x, v.y, v.z);
}

/* An absolute path for a file the scene loaded (it exists). */
static json_t *file_path(const char *path) {
  char *real = realpath(path, NULL);
  json_t *s = json_string(real ? real : path);
  free(real);
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

static json_t *medium(const sh_medium *m) {
  static const char *types[] = {"isotropic", "henyey_greenstein", "nishita_hazy",
                                "nishita_murky", "rayleigh"};
  json_t *phase = json_pack("{s:s}", "type", types[m->phase.type]);
  if (phase && m->phase.type == SH_PHASE_HENYEY_GREENSTEIN)
    json_object_set_new(phase, "g", json_real(m->phase.g));
  return json_pack("{s:o, s:o, s:o, s:{s:o, s:o}}", "sigma_s", vec(m->sigma_s),
                   "sigma_a", vec(m->sigma_a), "phase", phase, "bounds", "min",
                   vec(m->bmin), "max", vec(m->bmax));
}

static json_t *light(const sh_light *l) {
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
                          json_pack("{s:o, s:o}", "image", file_path(l->map_file),
                                    "up", vec(l->map_up)));
    break;
  case SH_LIGHT_DIRECTIONAL:
    o = json_pack("{s:s, s:o, s:o}", "type", "directional", "direction",
                  vec(l->direction), "irradiance", vec(l->irradiance));
    if (o && l->has_map)
      json_object_set_new(o, "light_map",
                          json_pack("{s:o, s:o, s:o, s:o}", "image",
                                    file_path(l->map_file), "origin",
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

static json_t *shape(const sh_scene *s, const sh_shape *sh) {
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
      json_object_set_new(o, "file", file_path(sh->file));
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
    json_object_set_new(o, "image", file_path(sh->file));
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
  json_t *root = json_pack("{s:s, s:i, s:o, s:o, s:o}", "format", "shafts-scene",
                           "version", 1, "camera", camera(&s->camera),
                           "background", vec(s->background), "ambient",
                           vec(s->ambient));
  if (!root) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  if (s->medium.present) json_object_set_new(root, "medium", medium(&s->medium));
  json_t *lights = json_array(), *materials = json_object(), *shapes = json_array();
  for (int i = 0; i < s->nlights; i++) json_array_append_new(lights, light(&s->lights[i]));
  for (int i = 0; i < s->nmaterials; i++)
    json_object_set_new(materials, s->materials[i].name, material(&s->materials[i]));
  for (int i = 0; i < s->nshapes; i++) json_array_append_new(shapes, shape(s, &s->shapes[i]));
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
  if (!b) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  return SH_OK;
}
