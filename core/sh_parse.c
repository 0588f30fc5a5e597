/* The scene parser: JSON text to a validated sh_scene. This file holds the
 * entry points, JSON syntax errors, and the top-level sections; lights and
 * shapes have files of their own (sh_parse_int.h). */
#include "sh_parse.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "sh_file.h"
#include "sh_json_locate.h"
#include "sh_parse_int.h"

static const char *const top_keys[] = {
    "format", "version",   "camera", "background", "ambient", "medium",
    "lights", "materials", "shapes", "render",     NULL};
static const char *const camera_keys[] = {
    "position", "look_at", "up", "fov_y_deg", "width", "height", NULL};
static const char *const medium_type_key[] = {"type", NULL};
/* Homogeneous media and height fog; "type" is common to every kind. */
static const char *const medium_keys[] = {"sigma_s", "sigma_a", "phase",
                                          "bounds", NULL};
static const char *const height_fog_keys[] = {"base_height", "scale_height",
                                              NULL};
static const char *const atmosphere_keys[] = {
    "center", "ground_radius", "top_radius", "ground_albedo", "rayleigh",
    "mie",    "ozone",         NULL};
static const char *const rayleigh_keys[] = {"sigma_s", "scale_height", NULL};
static const char *const mie_keys[] = {"sigma_s", "sigma_a", "scale_height",
                                       "phase", NULL};
static const char *const ozone_keys[] = {"sigma_a", "center_height", "width",
                                         NULL};
/* In the order of sh_medium_type. */
static const char *const medium_type_names[] = {"homogeneous", "height_fog",
                                                "atmosphere", NULL};
static const char *const bounds_keys[] = {"min", "max", NULL};
static const char *const phase_keys[] = {"type", NULL};
static const char *const phase_hg_keys[] = {"g", NULL};
static const char *const material_keys[] = {
    "diffuse",  "specular", "shininess",          "reflect",
    "transmit", "ior",      "emission",           "casts_soft_shadows",
    "receives_soft_shadows", NULL};
/* The project's own keys (docs/scene-format.md, "render"). */
static const char *const render_keys[] = {
    "spp",    "max_depth",      "seed", "exposure",  "planes", "lattice",
    "light_map_res", "shadow_map_res", "xi", "jitter", "mesh_step", "kl",
    "scheme", NULL};
/* In the order of sh_phase_type. */
static const char *const phase_names[] = {"isotropic",    "henyey_greenstein",
                                          "nishita_hazy", "nishita_murky",
                                          "rayleigh",     "cornette_shanks",
                                          NULL};

#define MAX_IMAGE_SIZE 65536

sh_status sh__parse_camera(sh__parser *p, json_t *root) {
  sh__pctx *c = &p->c;
  sh_camera *cam = &p->scene->camera;
  json_t *o;
  long long w, h;
  sh_status st;
  if ((st = sh__object(c, root, "camera", 1, &o))) return st;
  sh__push_key(c, "camera");
  if ((st = sh__check_keys(c, o, SH__KEYS(camera_keys), "the camera")) ||
      (st =
           sh__vec3(c, o, "position", 1, sh_v3s(0), sh__any, &cam->position)) ||
      (st = sh__vec3(c, o, "look_at", 1, sh_v3s(0), sh__any, &cam->look_at)) ||
      (st = sh__direction(c, o, "up", 0, &cam->up, NULL)) ||
      (st = sh__number(c, o, "fov_y_deg", 1, 0, (sh__range){1e-6, 180, 0, 1},
                       &cam->fov_y_deg)) ||
      (st = sh__integer(c, o, "width", 1, 0, 1, MAX_IMAGE_SIZE, &w)) ||
      (st = sh__integer(c, o, "height", 1, 0, 1, MAX_IMAGE_SIZE, &h)))
    return st;
  cam->width = (int)w;
  cam->height = (int)h;
  sh_vec3 d = sh_sub(cam->look_at, cam->position);
  if (sh_is_black(d))
    return sh__fail_at(c, "look_at", SH_ERR_SCENE,
                       "look_at equals position: the camera has no viewing "
                       "direction");
  if (sh__parallel(cam->up, d)) {
    if (json_object_get(o, "up"))
      return sh__fail_at(c, "up", SH_ERR_SCENE,
                         "up is parallel to the viewing direction (look_at - "
                         "position); give an up vector across it");
    return sh__fail(c, SH_ERR_SCENE,
                    "the viewing direction (look_at - position) is parallel "
                    "to the default up [0, 1, 0]; give an \"up\" across it");
  }
  sh__pop(c);
  return SH_OK;
}

/* Reads the optional phase object member "phase" of `holder` into *ph
 * (isotropic when absent, unless `required`), and where its type stands
 * into *line, *column when they are not NULL. */
static sh_status parse_phase(sh__parser *p, json_t *holder, int required,
                             sh_phase *ph, int *line, int *column) {
  sh__pctx *c = &p->c;
  json_t *o;
  int type;
  sh_status st;
  char what[80];
  ph->type = SH_PHASE_ISOTROPIC;
  ph->g = 0;
  if ((st = sh__object(c, holder, "phase", required, &o)) || !o) return st;
  sh__push_key(c, "phase");
  if ((st = sh__choice(c, o, "type", 1, phase_names, 0, "phase function",
                       &type)))
    return st;
  ph->type = (sh_phase_type)type;
  if (line) sh__where(c, "type", line, column);
  snprintf(what, sizeof what, "a phase function of type '%s'",
           phase_names[type]);
  if (ph->type == SH_PHASE_HENYEY_GREENSTEIN ||
      ph->type == SH_PHASE_CORNETTE_SHANKS) {
    if ((st =
             sh__check_keys(c, o, SH__KEYS(phase_keys, phase_hg_keys), what)) ||
        (st = sh__number(c, o, "g", 1, 0, (sh__range){-1, 1, 1, 1}, &ph->g)))
      return st;
  } else if ((st = sh__check_keys(c, o, SH__KEYS(phase_keys), what))) {
    return st;
  }
  sh__pop(c);
  return SH_OK;
}

/* Reads the atmosphere's own members (the medium object `o` is the
 * current path) into m->atmo, and derives the medium's box, its largest
 * coefficients and its phase (sh_scene.h). */
static sh_status parse_atmosphere(sh__parser *p, json_t *o, sh_medium *m) {
  sh__pctx *c = &p->c;
  sh_atmosphere *a = &m->atmo;
  json_t *r, *mie, *oz;
  sh_status st;
  if ((st = sh__check_keys(c, o, SH__KEYS(medium_type_key, atmosphere_keys),
                           "a medium of type 'atmosphere'")) ||
      (st = sh__vec3(c, o, "center", 1, sh_v3s(0), sh__any, &a->center)) ||
      (st = sh__number(c, o, "ground_radius", 1, 0, sh__gt0,
                       &a->ground_radius)) ||
      (st = sh__number(c, o, "top_radius", 1, 0, sh__gt0, &a->top_radius)))
    return st;
  if (!(a->top_radius > a->ground_radius)) {
    char g[40], t[40];
    sh__fmt_num(a->ground_radius, g, sizeof g);
    sh__fmt_num(a->top_radius, t, sizeof t);
    return sh__fail_at(c, "top_radius", SH_ERR_SCENE,
                       "expected top_radius > ground_radius (%s), found %s", g,
                       t);
  }
  if ((st = sh__vec3(c, o, "ground_albedo", 0, sh_v3s(0.1), sh__quantity,
                     &a->ground_albedo)) ||
      (st = sh__object(c, o, "rayleigh", 1, &r)))
    return st;
  sh__push_key(c, "rayleigh");
  if ((st = sh__check_keys(c, r, SH__KEYS(rayleigh_keys),
                           "the atmosphere's rayleigh")) ||
      (st = sh__vec3(c, r, "sigma_s", 1, sh_v3s(0), sh__quantity,
                     &a->rayleigh_sigma_s)) ||
      (st = sh__number(c, r, "scale_height", 1, 0, sh__gt0, &a->rayleigh_H)))
    return st;
  sh__pop(c);
  if ((st = sh__object(c, o, "mie", 0, &mie))) return st;
  if ((a->has_mie = mie != NULL)) {
    sh__push_key(c, "mie");
    if ((st = sh__check_keys(c, mie, SH__KEYS(mie_keys),
                             "the atmosphere's mie")) ||
        (st = sh__vec3(c, mie, "sigma_s", 1, sh_v3s(0), sh__quantity,
                       &a->mie_sigma_s)) ||
        (st = sh__vec3(c, mie, "sigma_a", 0, sh_v3s(0), sh__quantity,
                       &a->mie_sigma_a)) ||
        (st = sh__number(c, mie, "scale_height", 1, 0, sh__gt0, &a->mie_H)) ||
        (st = parse_phase(p, mie, 1, &a->mie_phase, NULL, NULL)))
      return st;
    sh__pop(c);
  }
  if ((st = sh__object(c, o, "ozone", 0, &oz))) return st;
  if ((a->has_ozone = oz != NULL)) {
    sh__push_key(c, "ozone");
    if ((st = sh__check_keys(c, oz, SH__KEYS(ozone_keys),
                             "the atmosphere's ozone")) ||
        (st = sh__vec3(c, oz, "sigma_a", 1, sh_v3s(0), sh__quantity,
                       &a->ozone_sigma_a)) ||
        (st = sh__number(c, oz, "center_height", 1, 0, sh__any,
                         &a->ozone_height)) ||
        (st = sh__number(c, oz, "width", 1, 0, sh__gt0, &a->ozone_width)))
      return st;
    sh__pop(c);
  }
  m->sigma_s = sh_add(a->rayleigh_sigma_s, a->mie_sigma_s);
  m->sigma_a = sh_add(a->mie_sigma_a, a->ozone_sigma_a);
  m->phase.type = SH_PHASE_RAYLEIGH;
  m->phase.g = 0;
  m->bmin = sh_sub(a->center, sh_v3s(a->top_radius));
  m->bmax = sh_add(a->center, sh_v3s(a->top_radius));
  return SH_OK;
}

sh_status sh__parse_medium(sh__parser *p, json_t *root) {
  sh__pctx *c = &p->c;
  sh_medium *m = &p->scene->medium;
  json_t *o, *b;
  sh_status st;
  int type;
  if ((st = sh__object(c, root, "medium", 0, &o)) || !o) return st;
  sh__push_key(c, "medium");
  if ((st = sh__choice(c, o, "type", 0, medium_type_names, 0, "medium type",
                       &type)))
    return st;
  m->type = (sh_medium_type)type;
  sh__where(c, json_object_get(o, "type") ? "type" : NULL, &m->line,
            &m->column);
  if (m->type == SH_MEDIUM_ATMOSPHERE) {
    if ((st = parse_atmosphere(p, o, m))) return st;
  } else {
    if (m->type == SH_MEDIUM_HEIGHT_FOG) {
      if ((st = sh__check_keys(
               c, o, SH__KEYS(medium_type_key, medium_keys, height_fog_keys),
               "a medium of type 'height_fog'")) ||
          (st = sh__number(c, o, "base_height", 0, 0, sh__any,
                           &m->base_height)) ||
          (st = sh__number(c, o, "scale_height", 1, 0, sh__gt0,
                           &m->scale_height)))
        return st;
    } else if ((st = sh__check_keys(c, o, SH__KEYS(medium_type_key, medium_keys),
                                    "a homogeneous medium"))) {
      return st;
    }
    if ((st = sh__vec3(c, o, "sigma_s", 1, sh_v3s(0), sh__quantity,
                       &m->sigma_s)) ||
        (st = sh__vec3(c, o, "sigma_a", 0, sh_v3s(0), sh__quantity,
                       &m->sigma_a)) ||
        (st = parse_phase(p, o, 0, &m->phase, &m->phase_line,
                          &m->phase_column)) ||
        (st = sh__object(c, o, "bounds", 1, &b)))
      return st;
    sh__push_key(c, "bounds");
    if ((st = sh__check_keys(c, b, SH__KEYS(bounds_keys),
                             "the medium's bounds")) ||
        (st = sh__min_max(c, b, &m->bmin, &m->bmax)))
      return st;
    sh__pop(c);
  }
  m->sigma_t = sh_add(m->sigma_s, m->sigma_a);
  m->present = 1;
  sh__pop(c);
  return SH_OK;
}

void *sh__parse_objects(sh__parser *p, json_t *root, const char *key,
                        const char *what, size_t size,
                        sh_status (*read_one)(sh__parser *p, json_t *o,
                                              void *item),
                        int *count, sh_status *st) {
  sh__pctx *c = &p->c;
  json_t *a;
  *count = 0;
  if ((*st = sh__array(c, root, key, 0, &a)) || !a) return NULL;
  size_t n = json_array_size(a);
  if (n == 0) return NULL;
  char *base = n > INT_MAX / 2 ? NULL : calloc(n, size);
  if (!base) {
    *st = sh__fail_at(c, key, SH_ERR_NOMEM, "out of memory");
    return NULL;
  }
  *count = (int)n;
  sh__push_key(c, key);
  for (size_t i = 0; i < n; i++) {
    json_t *o = json_array_get(a, i);
    sh__push_index(c, (int)i);
    if (!json_is_object(o)) *st = sh__wrong(c, o, what);
    else *st = read_one(p, o, base + i * size);
    if (*st) return base;
    sh__pop(c);
  }
  sh__pop(c);
  return base;
}

/* The lights, then the shapes (sh__parse_light and sh__parse_shape read one
 * element each). */
static sh_status parse_lights_and_shapes(sh__parser *p, json_t *root) {
  sh_scene *s = p->scene;
  sh_status st;
  s->lights = sh__parse_objects(p, root, "lights", "an object (a light)",
                                sizeof *s->lights, sh__parse_light,
                                &s->nlights, &st);
  if (st == SH_OK)
    s->shapes = sh__parse_objects(p, root, "shapes", "an object (a shape)",
                                  sizeof *s->shapes, sh__parse_shape,
                                  &s->nshapes, &st);
  return st;
}

static sh_status parse_materials(sh__parser *p, json_t *root) {
  sh__pctx *c = &p->c;
  sh_scene *s = p->scene;
  json_t *o, *mo;
  const char *name;
  sh_status st;
  if ((st = sh__object(c, root, "materials", 0, &o)) || !o) return st;
  size_t n = json_object_size(o);
  if (n == 0) return SH_OK;
  s->materials = calloc(n, sizeof *s->materials);
  if (!s->materials)
    return sh__fail_at(c, "materials", SH_ERR_NOMEM, "out of memory");
  s->nmaterials = (int)n;
  sh__push_key(c, "materials");
  int i = 0;
  json_object_foreach(o, name, mo) {
    sh_material *m = &s->materials[i++];
    if ((st = sh__object(c, o, name, 1, &mo))) return st;
    sh__push_key(c, name);
    if (!(m->name = strdup(name)))
      return sh__fail(c, SH_ERR_NOMEM, "out of memory");
    if ((st = sh__check_keys(c, mo, SH__KEYS(material_keys), "a material")) ||
        (st = sh__vec3(c, mo, "diffuse", 0, sh_v3s(0), sh__ge0, &m->diffuse)) ||
        (st = sh__vec3(c, mo, "specular", 0, sh_v3s(0), sh__ge0,
                       &m->specular)) ||
        (st = sh__number(c, mo, "shininess", 0, 32, sh__ge0, &m->shininess)) ||
        (st = sh__vec3(c, mo, "reflect", 0, sh_v3s(0), sh__ge0, &m->reflect)) ||
        (st = sh__vec3(c, mo, "transmit", 0, sh_v3s(0), sh__ge0,
                       &m->transmit)) ||
        (st = sh__number(c, mo, "ior", 0, 1, sh__gt0, &m->ior)) ||
        (st = sh__vec3(c, mo, "emission", 0, sh_v3s(0), sh__quantity,
                       &m->emission)) ||
        (st = sh__boolean(c, mo, "casts_soft_shadows", 0, 1,
                          &m->casts_soft_shadows)) ||
        (st = sh__boolean(c, mo, "receives_soft_shadows", 0, 1,
                          &m->receives_soft_shadows)))
      return st;
    sh__pop(c);
  }
  sh__pop(c);
  return SH_OK;
}

/* ---- Render settings (the project's own keys) ---- */

/* A renderer's key as option text (sh_render_param). */
static char *option_text(const json_t *v) {
  char buf[512];
  size_t n = 0;
  buf[0] = '\0';
  if (json_is_string(v)) return strdup(json_string_value(v));
  if (json_is_boolean(v)) return strdup(json_is_true(v) ? "true" : "false");
  if (json_is_number(v)) {
    sh__fmt_num(json_number_value(v), buf, sizeof buf);
    return strdup(buf);
  }
  if (json_is_array(v)) {
    for (size_t i = 0; i < json_array_size(v) && n < sizeof buf; i++) {
      const json_t *e = json_array_get(v, i);
      char num[40] = "?";
      if (json_is_number(e)) sh__fmt_num(json_number_value(e), num, sizeof num);
      n += (size_t)snprintf(buf + n, sizeof buf - n, "%s%s", i ? " " : "", num);
    }
    return strdup(buf);
  }
  return strdup(json_is_object(v) ? "an object" : "null");
}

/* The keys gl_shafts and the light meshes method own, kept with their
 * places for the renderer to check. */
static sh_status keep_render_params(sh__pctx *c, json_t *o,
                                    sh_render_settings *r) {
  static const char *const own[] = {"spp", "max_depth", "seed", "exposure",
                                    NULL};
  const char *key;
  json_t *v;
  size_t n = json_object_size(o);
  r->params = n ? calloc(n, sizeof *r->params) : NULL;
  if (n && !r->params) return sh__fail(c, SH_ERR_NOMEM, "out of memory");
  json_object_foreach(o, key, v) {
    int core = 0;
    for (int i = 0; own[i]; i++) core |= !strcmp(key, own[i]);
    if (core) continue;
    sh_render_param *q = &r->params[r->nparams++];
    q->key = strdup(key);
    q->text = option_text(v);
    q->json = json_dumps(v, JSON_COMPACT | JSON_ENCODE_ANY);
    if (!q->key || !q->text || !q->json)
      return sh__fail(c, SH_ERR_NOMEM, "out of memory");
    sh__jseg path[2] = {{"render", 0}, {key, 0}};
    size_t at;
    if (c->text && sh__json_locate(c->text, c->len, path, 2, 0, &at))
      sh__json_linecol(c->text, at, &q->line, &q->column);
  }
  return SH_OK;
}

static sh_status parse_render(sh__parser *p, json_t *root) {
  sh__pctx *c = &p->c;
  sh_render_settings *r = &p->scene->render;
  json_t *o;
  long long spp = 16, depth = 5, seed = 0;
  sh_status st;
  r->spp = 16;
  r->max_depth = 5;
  r->seed = 0;
  r->exposure = 0;
  if ((st = sh__object(c, root, "render", 0, &o)) || !o) return st;
  sh__push_key(c, "render");
  if ((st = sh__check_keys(c, o, SH__KEYS(render_keys),
                           "the render settings")) ||
      (st = sh__integer(c, o, "spp", 0, 16, 1, INT_MAX, &spp)) ||
      (st = sh__integer(c, o, "max_depth", 0, 5, 0, 100, &depth)) ||
      (st = sh__integer(c, o, "seed", 0, 0, 0, 4294967295LL, &seed)) ||
      (st = sh__number(c, o, "exposure", 0, 0, sh__any, &r->exposure)))
    return st;
  r->spp = (int)spp;
  r->max_depth = (int)depth;
  r->seed = (unsigned)seed;
  if ((st = keep_render_params(c, o, r))) return st;
  sh__pop(c);
  return SH_OK;
}

/* ---- The whole scene ---- */

static sh_status parse_root(sh__parser *p, json_t *root) {
  sh__pctx *c = &p->c;
  sh_scene *s = p->scene;
  json_t *v;
  const char *fmt;
  sh_status st;
  if (!json_is_object(root))
    return sh__wrong(c, root, "an object (a shafts scene) at the top level");
  /* The format and version come first, so that another kind of JSON file
   * is named as such rather than by its first unknown key. */
  if ((v = json_object_get(root, "format"))) {
    if ((st = sh__string(c, root, "format", 1, &fmt))) return st;
    if (strcmp(fmt, "shafts-scene") != 0)
      return sh__fail_at(c, "format", SH_ERR_SCENE,
                         "expected \"shafts-scene\", found \"%s\": this is "
                         "not a shafts scene file",
                         fmt);
  }
  if ((v = json_object_get(root, "version"))) {
    char num[40];
    if (!json_is_number(v)) {
      sh__push_key(c, "version");
      return sh__wrong(c, v, "the number 1");
    }
    if (json_number_value(v) != 1) {
      sh__fmt_num(json_number_value(v), num, sizeof num);
      return sh__fail_at(c, "version", SH_ERR_SCENE,
                         "unsupported scene format version %s; this program "
                         "reads version 1",
                         num);
    }
  }
  if ((st = sh__check_keys(c, root, SH__KEYS(top_keys), "the top level")))
    return st;
  if (!json_object_get(root, "format"))
    return sh__missing(c, "format", "\"shafts-scene\"");
  if (!json_object_get(root, "version"))
    return sh__missing(c, "version", "the number 1");
  if ((st = sh__parse_camera(p, root)) ||
      (st = sh__vec3(c, root, "background", 0, sh_v3s(0), sh__quantity,
                     &s->background)) ||
      (st = sh__vec3(c, root, "ambient", 0, sh_v3s(0), sh__quantity, &s->ambient)) ||
      (st = sh__parse_medium(p, root)) || (st = parse_materials(p, root)) ||
      (st = parse_lights_and_shapes(p, root)) ||
      (st = parse_render(p, root)))
    return st;
  return SH_OK;
}

/* Turns jansson's report of text it could not read into an sh_error. A
 * number too large for a double (1e999) is valid JSON that breaks the
 * format's "every number is finite": an SH_ERR_SCENE at the number. */
sh_status sh__syntax_error(const char *text, size_t len, const char *name,
                           const json_error_t *je, sh_error *err) {
  enum json_error_code code = json_error_code(je);
  size_t pos = je->position > 0 ? (size_t)je->position : 0;
  if (code == json_error_out_of_memory)
    return sh_error_set(err, SH_ERR_NOMEM,
                        "out of memory while reading the scene");
  if (pos > len) pos = len;
  if (code == json_error_numeric_overflow) {
    size_t start = pos;
    while (start > 0 && strchr("0123456789+-.eE", text[start - 1]) &&
           text[start - 1])
      start--;
    int is_real = 0;
    for (size_t i = start; i < pos; i++)
      is_real |= text[i] == '.' || text[i] == 'e' || text[i] == 'E';
    if (is_real)
      sh_error_set(err, SH_ERR_SCENE,
                   "expected a finite number, found %.*s, which is too large "
                   "for a double",
                   (int)(pos - start), text + start);
    else
      sh_error_set(err, SH_ERR_SCENE,
                   "the integer %.*s is too large; write large numbers with "
                   "an exponent (such as 1e20)",
                   (int)(pos - start), text + start);
    sh__json_linecol(text, start, &err->line, &err->column);
  } else {
    sh_error_set(err, SH_ERR_SYNTAX, "invalid JSON: %s", je->text);
    err->line = je->line > 0 ? je->line : 1;
    err->column = je->column > 0 ? je->column : 1;
  }
  sh_error_set_file(err, name);
  /* When the offending token is a closing bracket, the path is the one
   * inside the container it fails to close. */
  if (pos > 0 && (strstr(je->text, "near '}'") || strstr(je->text, "near ']'")))
    pos--;
  char *key = sh__json_path_at(text, len, pos);
  if (key) sh_error_set_key(err, "%s", key);
  free(key);
  return err->status;
}

/* Checks the caller's in-memory meshes: names given and distinct. */
static sh_status check_meshes(const sh_mesh_data *meshes, int nmeshes,
                              sh_error *err) {
  if (nmeshes < 0 || (nmeshes > 0 && !meshes))
    return sh_error_set(err, SH_ERR_ARG,
                        "sh_scene_parse_ex: %d meshes and no array", nmeshes);
  for (int i = 0; i < nmeshes; i++) {
    if (!meshes[i].name || !meshes[i].name[0])
      return sh_error_set(err, SH_ERR_ARG,
                          "sh_scene_parse_ex: mesh %d has no name", i);
    for (int j = 0; j < i; j++)
      if (strcmp(meshes[i].name, meshes[j].name) == 0)
        return sh_error_set(err, SH_ERR_ARG,
                            "sh_scene_parse_ex: two meshes are named '%s'",
                            meshes[i].name);
  }
  return SH_OK;
}

static sh_status parse_text(const char *text, size_t len, const char *name,
                            const char *base_dir, const sh_mesh_data *meshes,
                            int nmeshes, int absolute_ok, sh_scene **out,
                            sh_error *err) {
  json_error_t je;
  sh_status st;
  if (out) *out = NULL;
  if (!text || !out)
    return sh_error_set(err, SH_ERR_ARG, "sh_scene_parse: no text or output");
  if ((st = check_meshes(meshes, nmeshes, err))) return st;
  if (!name) name = "<scene>";
  json_t *root = json_loadb(text, len, JSON_REJECT_DUPLICATES, &je);
  if (!root) return sh__syntax_error(text, len, name, &je, err);
  sh__parser p;
  memset(&p, 0, sizeof p);
  p.c.text = text;
  p.c.len = len;
  p.c.name = name;
  p.c.err = err;
  p.base_dir = base_dir;
  p.absolute_ok = absolute_ok;
  p.meshes = meshes;
  p.nmeshes = nmeshes;
  sh_scene *s = p.scene = calloc(1, sizeof *s);
  if (!s || !(s->file = strdup(name)) ||
      (base_dir && base_dir[0] && !(s->base_dir = strdup(base_dir)))) {
    sh_scene_free(s);
    json_decref(root);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  }
  s->camera.up = sh_v3(0, 1, 0);
  st = parse_root(&p, root);
  json_decref(root);
  if (st != SH_OK) {
    sh_scene_free(s);
    return st;
  }
  sh_error_clear(err);
  *out = s;
  return SH_OK;
}

static sh_status parse_buffer(const char *text, size_t len, const char *name,
                              const char *base_dir, const sh_mesh_data *meshes,
                              int nmeshes, int absolute_ok, sh_scene **out,
                              sh_error *err) {
  sh_error local = SH_ERROR_INIT;
  sh_status st = parse_text(text, len, name, base_dir, meshes, nmeshes,
                            absolute_ok, out, err ? err : &local);
  sh_error_clear(&local);
  return st;
}

sh_status sh_scene_parse_ex(const char *text, const char *name,
                            const char *base_dir, const sh_mesh_data *meshes,
                            int nmeshes, sh_scene **out, sh_error *err) {
  return parse_buffer(text, text ? strlen(text) : 0, name, base_dir, meshes,
                      nmeshes, 1, out, err);
}

sh_status sh_scene_parse_arrays(const char *text, const char *name,
                                const char *base_dir, int nmeshes,
                                const char *const *names,
                                const float *const *positions,
                                const int *nvertices,
                                const int *const *indices,
                                const int *ntriangles, sh_scene **out,
                                sh_error *err) {
  if (out) *out = NULL;
  if (nmeshes < 0 || (nmeshes > 0 && (!names || !positions || !nvertices ||
                                      !indices || !ntriangles)))
    return sh_error_set(err, SH_ERR_ARG,
                        "sh_scene_parse_arrays: %d meshes and no arrays",
                        nmeshes);
  sh_mesh_data *m = calloc((size_t)(nmeshes ? nmeshes : 1), sizeof *m);
  if (!m) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  for (int i = 0; i < nmeshes; i++)
    m[i] = (sh_mesh_data){names[i], positions[i], nvertices[i], indices[i],
                          ntriangles[i]};
  sh_status st =
      sh_scene_parse_ex(text, name, base_dir, m, nmeshes, out, err);
  free(m);
  return st;
}

sh_status sh_scene_parse(const char *text, const char *name,
                         const char *base_dir, sh_scene **out, sh_error *err) {
  return sh_scene_parse_ex(text, name, base_dir, NULL, 0, out, err);
}

sh_status sh_scene_load(const char *path, sh_scene **out, sh_error *err) {
  if (out) *out = NULL;
  if (!path || !out)
    return sh_error_set(err, SH_ERR_ARG, "sh_scene_load: no path or output");
  FILE *f = sh_file_open_read(path);
  if (!f) {
    int e = errno;
    sh_error_set(err, SH_ERR_IO, "cannot open the scene file: %s", strerror(e));
    sh_error_set_file(err, path);
    return SH_ERR_IO;
  }
  /* Only a regular file: /dev/zero or a FIFO would be read until memory
   * runs out or forever. And no more than SH_SCENE_MAX_BYTES, checked on
   * the bytes read too (the file may grow while read). */
  struct stat sb;
  int too_big = 0;
  if (fstat(fileno(f), &sb) == 0 &&
      (!S_ISREG(sb.st_mode) || sb.st_size > SH_SCENE_MAX_BYTES)) {
    fclose(f);
    if (!S_ISREG(sb.st_mode))
      sh_error_set(err, SH_ERR_IO,
                   "cannot read the scene file: it is %s, not a regular file",
                   sh_file_kind(sb.st_mode));
    else
      sh_error_set(err, SH_ERR_SCENE,
                   "the scene file has %lld bytes, more than the %d MiB a "
                   "scene may have (SH_SCENE_MAX_BYTES, docs/scene-format.md)",
                   (long long)sb.st_size, SH_SCENE_MAX_BYTES >> 20);
    sh_error_set_file(err, path);
    return S_ISREG(sb.st_mode) ? SH_ERR_SCENE : SH_ERR_IO;
  }
  size_t cap = 1 << 16, len = 0;
  char *buf = malloc(cap + 1);
  sh_status st = SH_OK;
  while (buf) {
    size_t got = fread(buf + len, 1, cap - len, f);
    len += got;
    if (len > SH_SCENE_MAX_BYTES) {
      free(buf);
      buf = NULL;
      too_big = 1;
      break;
    }
    if (len < cap) break;
    char *bigger = cap < SIZE_MAX / 4 ? realloc(buf, 2 * cap + 1) : NULL;
    if (!bigger) {
      free(buf);
      buf = NULL;
      break;
    }
    buf = bigger;
    cap *= 2;
  }
  if (too_big) {
    st = sh_error_set(err, SH_ERR_SCENE,
                      "the scene file grew beyond the %d MiB a scene may "
                      "have while it was read (SH_SCENE_MAX_BYTES)",
                      SH_SCENE_MAX_BYTES >> 20);
  } else if (!buf) {
    st = sh_error_set(err, SH_ERR_NOMEM, "out of memory reading the scene");
  } else if (ferror(f)) {
    int e = errno;
    st = sh_error_set(err, SH_ERR_IO, "cannot read the scene file: %s",
                      strerror(e));
  }
  fclose(f);
  if (st != SH_OK) {
    sh_error_set_file(err, path);
    free(buf);
    return st;
  }
  buf[len] = '\0';
  /* The scene's directory: everything before the last slash. */
  char *dir = strdup(path);
  if (!dir) {
    free(buf);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  }
  char *slash = strrchr(dir, '/');
  if (!slash)
    strcpy(dir, ".");
  else if (slash == dir)
    dir[1] = '\0';
  else
    *slash = '\0';
  st = parse_buffer(buf, len, path, dir, NULL, 0, 0, out, err);
  free(dir);
  free(buf);
  return st;
}
