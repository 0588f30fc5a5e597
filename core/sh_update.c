/* sh_scene_update (shafts.h): a patch of camera, lights, medium,
 * background, ambient and shape transforms, read by the scene parser's own
 * functions into a scratch scene, checked, and only then copied into the
 * scene, so that an error leaves the scene as it was. */
#include <jansson.h>
#include <stdlib.h>
#include <string.h>

#include "sh_light.h"
#include "sh_parse_int.h"

static const char *const patch_keys[] = {"camera",  "lights",     "medium",
                                         "background", "ambient",
                                         "transforms", NULL};

/* What the patch holds, read but not yet applied. */
typedef struct patch {
  sh_scene tmp; /* camera, lights, medium, background, ambient */
  int has_camera, has_lights, has_medium, has_background, has_ambient;
  sh_mat4 *xform, *inv; /* per shape; NULL if there are no transforms */
  char *given;          /* per shape: 1 where the patch has a transform */
} patch;

static void free_lights(sh_light *lights, int n) {
  for (int i = 0; i < n; i++) {
    free(lights[i].map_file);
    sh_image_free(&lights[i].map);
  }
  free(lights);
}

static int same_vec(sh_vec3 a, sh_vec3 b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

static int same_camera(const sh_camera *a, const sh_camera *b) {
  return same_vec(a->position, b->position) &&
         same_vec(a->look_at, b->look_at) && same_vec(a->up, b->up) &&
         a->fov_y_deg == b->fov_y_deg && a->width == b->width &&
         a->height == b->height;
}

static int same_atmosphere(const sh_atmosphere *a, const sh_atmosphere *b) {
  return same_vec(a->center, b->center) && a->ground_radius == b->ground_radius &&
         a->top_radius == b->top_radius &&
         same_vec(a->ground_albedo, b->ground_albedo) &&
         same_vec(a->rayleigh_sigma_s, b->rayleigh_sigma_s) &&
         a->rayleigh_H == b->rayleigh_H && a->has_mie == b->has_mie &&
         same_vec(a->mie_sigma_s, b->mie_sigma_s) &&
         same_vec(a->mie_sigma_a, b->mie_sigma_a) && a->mie_H == b->mie_H &&
         a->mie_phase.type == b->mie_phase.type &&
         a->mie_phase.g == b->mie_phase.g && a->has_ozone == b->has_ozone &&
         same_vec(a->ozone_sigma_a, b->ozone_sigma_a) &&
         a->ozone_height == b->ozone_height && a->ozone_width == b->ozone_width;
}

static int same_medium(const sh_medium *a, const sh_medium *b) {
  if (a->present != b->present) return 0;
  return !a->present ||
         (a->type == b->type && same_atmosphere(&a->atmo, &b->atmo) &&
          a->base_height == b->base_height &&
          a->scale_height == b->scale_height &&
          same_vec(a->sigma_s, b->sigma_s) && same_vec(a->sigma_a, b->sigma_a) &&
          a->phase.type == b->phase.type && a->phase.g == b->phase.g &&
          same_vec(a->bmin, b->bmin) && same_vec(a->bmax, b->bmax));
}

static int same_matrix(const sh_mat4 *a, const sh_mat4 *b) {
  return memcmp(a->m, b->m, sizeof a->m) == 0;
}

/* Reads "lights" and checks that it keeps the number and types. */
static sh_status read_lights(sh__parser *p, json_t *root, const sh_scene *s) {
  sh__pctx *c = &p->c;
  sh_status st;
  json_t *a = json_object_get(root, "lights");
  if (!json_is_array(a)) {
    sh__push_key(c, "lights");
    return sh__wrong(c, a, "an array (the scene's lights)");
  }
  if ((int)json_array_size(a) != s->nlights)
    return sh__fail_at(c, "lights", SH_ERR_SCENE,
                       "the patch has %d lights and the scene %d: a patch "
                       "keeps the number of lights; parse the scene again "
                       "to add or remove one",
                       (int)json_array_size(a), s->nlights);
  sh_scene *t = p->scene;
  t->lights = sh__parse_objects(p, root, "lights", "an object (a light)",
                                sizeof *t->lights, sh__parse_light,
                                &t->nlights, &st);
  if (st) return st;
  for (int i = 0; i < s->nlights; i++)
    if (p->scene->lights[i].type != s->lights[i].type) {
      static const char *const kind[] = {"point", "spot", "directional"};
      sh__push_key(c, "lights");
      sh__push_index(c, i);
      return sh__fail_at(c, "type", SH_ERR_SCENE,
                         "light %d is a %s light in the scene and a %s light "
                         "in the patch: a patch keeps each light's type; "
                         "parse the scene again to change it",
                         i, kind[s->lights[i].type],
                         kind[p->scene->lights[i].type]);
    }
  return SH_OK;
}

static sh_status read_transforms(sh__parser *p, json_t *root,
                                 const sh_scene *s, patch *pt) {
  sh__pctx *c = &p->c;
  sh_status st;
  json_t *a = json_object_get(root, "transforms");
  sh__push_key(c, "transforms");
  if (!json_is_array(a))
    return sh__wrong(c, a, "an array with one transform or null per shape");
  if ((int)json_array_size(a) != s->nshapes)
    return sh__fail(c, SH_ERR_SCENE,
                    "expected %d elements (one transform or null per shape), "
                    "found %d",
                    s->nshapes, (int)json_array_size(a));
  if (s->nshapes == 0) return SH_OK;
  size_t n = (size_t)s->nshapes;
  pt->xform = malloc(n * sizeof *pt->xform);
  pt->inv = malloc(n * sizeof *pt->inv);
  pt->given = calloc(n, 1);
  if (!pt->xform || !pt->inv || !pt->given)
    return sh__fail(c, SH_ERR_NOMEM, "out of memory");
  for (size_t i = 0; i < n; i++) {
    json_t *t = json_array_get(a, i);
    if (json_is_null(t)) continue;
    sh__push_index(c, (int)i);
    if ((st = sh__parse_transform(p, t, &pt->xform[i], &pt->inv[i])))
      return st;
    pt->given[i] = 1;
    sh__pop(c);
  }
  sh__pop(c);
  return SH_OK;
}

/* Reads every member of the patch into pt. */
static sh_status read_patch(sh__parser *p, json_t *root, const sh_scene *s,
                            patch *pt) {
  sh__pctx *c = &p->c;
  sh_scene *t = &pt->tmp;
  sh_status st;
  if (!json_is_object(root))
    return sh__wrong(c, root, "an object (a scene patch)");
  if ((st = sh__check_keys(c, root, SH__KEYS(patch_keys), "a scene patch")))
    return st;
  t->camera = s->camera;
  if ((pt->has_camera = json_object_get(root, "camera") != NULL)) {
    t->camera.up = sh_v3(0, 1, 0);
    if ((st = sh__parse_camera(p, root))) return st;
  }
  t->materials = s->materials;
  t->nmaterials = s->nmaterials;
  if ((pt->has_lights = json_object_get(root, "lights") != NULL) &&
      (st = read_lights(p, root, s)))
    return st;
  json_t *m = json_object_get(root, "medium");
  if ((pt->has_medium = m != NULL) && !json_is_null(m) &&
      (st = sh__parse_medium(p, root)))
    return st;
  if ((pt->has_background = json_object_get(root, "background") != NULL) &&
      (st = sh__vec3(c, root, "background", 1, sh_v3s(0), sh__ge0,
                     &t->background)))
    return st;
  if ((pt->has_ambient = json_object_get(root, "ambient") != NULL) &&
      (st = sh__vec3(c, root, "ambient", 1, sh_v3s(0), sh__ge0,
                     &t->ambient)))
    return st;
  if (json_object_get(root, "transforms") &&
      (st = read_transforms(p, root, s, pt)))
    return st;
  return SH_OK;
}

/* Copies what the patch holds into the scene; cannot fail. Returns the
 * SH_CHANGED_* bits. */
static unsigned apply(sh_scene *s, patch *pt) {
  sh_scene *t = &pt->tmp;
  unsigned changed = 0;
  if (pt->has_camera && !same_camera(&s->camera, &t->camera)) {
    changed |= SH_CHANGED_CAMERA;
    if (s->camera.width != t->camera.width ||
        s->camera.height != t->camera.height)
      changed |= SH_CHANGED_SIZE;
    s->camera = t->camera;
    /* A spot's map without an up of its own takes the camera's (as the
     * parser does), so a new camera up turns it. */
    for (int i = 0; i < s->nlights && !pt->has_lights; i++) {
      sh_light *l = &s->lights[i];
      if (l->type == SH_LIGHT_SPOT && l->has_map && !l->map_up_given) {
        sh_light_prepare(l, s->camera.up, 0, NULL);
        changed |= SH_CHANGED_LIGHTS;
      }
    }
  }
  if (pt->has_lights) {
    free_lights(s->lights, s->nlights);
    s->lights = t->lights;
    t->lights = NULL;
    t->nlights = 0;
    changed |= SH_CHANGED_LIGHTS;
  }
  if (pt->has_medium && !same_medium(&s->medium, &t->medium)) {
    s->medium = t->medium;
    changed |= SH_CHANGED_MEDIUM;
  }
  if ((pt->has_background && !same_vec(s->background, t->background)) ||
      (pt->has_ambient && !same_vec(s->ambient, t->ambient)))
    changed |= SH_CHANGED_ENVIRONMENT;
  if (pt->has_background) s->background = t->background;
  if (pt->has_ambient) s->ambient = t->ambient;
  for (int i = 0; pt->given && i < s->nshapes; i++) {
    if (!pt->given[i] || same_matrix(&s->shapes[i].xform, &pt->xform[i]))
      continue;
    s->shapes[i].xform = pt->xform[i];
    s->shapes[i].inv = pt->inv[i];
    changed |= SH_CHANGED_SHAPES;
  }
  return changed;
}

static sh_status update(sh_scene *scene, const char *text, const char *name,
                        unsigned *changed, sh_error *err) {
  json_error_t je;
  if (changed) *changed = 0;
  if (!scene || !text)
    return sh_error_set(err, SH_ERR_ARG, "sh_scene_update: no scene or patch");
  if (!name) name = "<patch>";
  size_t len = strlen(text);
  json_t *root = json_loadb(text, len, JSON_REJECT_DUPLICATES, &je);
  if (!root) return sh__syntax_error(text, len, name, &je, err);
  sh__parser p;
  patch pt;
  memset(&p, 0, sizeof p);
  memset(&pt, 0, sizeof pt);
  p.c.text = text;
  p.c.len = len;
  p.c.name = name;
  p.c.err = err;
  p.base_dir = scene->base_dir;
  p.scene = &pt.tmp;
  sh_status st = read_patch(&p, root, scene, &pt);
  json_decref(root);
  if (st == SH_OK) {
    unsigned bits = apply(scene, &pt);
    if (changed) *changed = bits;
    sh_error_clear(err);
  }
  free_lights(pt.tmp.lights, pt.tmp.nlights);
  free(pt.xform);
  free(pt.inv);
  free(pt.given);
  return st;
}

sh_status sh_scene_update(sh_scene *scene, const char *text, const char *name,
                          unsigned *changed, sh_error *err) {
  sh_error local = SH_ERROR_INIT;
  sh_status st = update(scene, text, name, changed, err ? err : &local);
  sh_error_clear(&local);
  return st;
}
