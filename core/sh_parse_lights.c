/* The scene parser's lights: point, spot and directional lights and their
 * light maps (docs/scene-format.md, "lights"). */
#include "sh_parse_int.h"

#include <stdlib.h>
#include <string.h>

#include "sh_light.h"

static const char *const light_keys[] = {"type", "soft_shadows", NULL};
static const char *const point_keys[] = {"position", "intensity", NULL};
static const char *const spot_keys[] = {
    "position",        "direction", "look_at",   "intensity", "outer_angle_deg",
    "inner_angle_deg", "exponent",  "light_map", NULL};
static const char *const directional_keys[] = {
    "direction", "irradiance", "angular_diameter_deg", "light_map", NULL};
static const char *const spot_map_keys[] = {"image", "up", NULL};
static const char *const directional_map_keys[] = {"image", "origin", "u", "v",
                                                   NULL};
/* In the order of sh_light_type. */
static const char *const light_names[] = {"point", "spot", "directional", NULL};

static sh_status parse_spot(sh__parser *p, json_t *o, sh_light *l) {
  sh__pctx *c = &p->c;
  sh_status st;
  int has_dir = json_object_get(o, "direction") != NULL;
  int has_look = json_object_get(o, "look_at") != NULL;
  if ((st = sh__vec3(c, o, "position", 1, sh_v3s(0), sh__any, &l->position)))
    return st;
  if (has_dir && has_look) {
    sh__push_key(c, "look_at");
    sh__fail_key(c, SH_ERR_SCENE,
                 "a spot light takes either direction or look_at, not both");
    sh__pop(c);
    return SH_ERR_SCENE;
  }
  if (!has_dir && !has_look)
    return sh__fail(c, SH_ERR_SCENE,
                    "missing required key 'direction' or 'look_at' (a spot "
                    "light needs the direction of its axis)");
  if (has_dir) {
    if ((st = sh__direction(c, o, "direction", 1, &l->direction, NULL)))
      return st;
  } else {
    sh_vec3 t;
    if ((st = sh__vec3(c, o, "look_at", 1, sh_v3s(0), sh__any, &t))) return st;
    l->direction = sh_sub(t, l->position);
    if (sh_is_black(l->direction))
      return sh__fail_at(c, "look_at", SH_ERR_SCENE,
                         "look_at equals position: the spot light has no "
                         "axis");
  }
  if ((st =
           sh__vec3(c, o, "intensity", 1, sh_v3s(0), sh__quantity,
                    &l->intensity)) ||
      (st = sh__number(c, o, "outer_angle_deg", 1, 0, (sh__range){0, 180, 1, 1},
                       &l->outer_deg)) ||
      (st = sh__number(c, o, "inner_angle_deg", 0, l->outer_deg,
                       (sh__range){0, 180, 0, 1}, &l->inner_deg)) ||
      (st = sh__number(c, o, "exponent", 0, 0, sh__ge0, &l->exponent)))
    return st;
  if (l->inner_deg > l->outer_deg) {
    char a[40], b[40];
    sh__fmt_num(l->inner_deg, a, sizeof a);
    sh__fmt_num(l->outer_deg, b, sizeof b);
    return sh__fail_at(c, "inner_angle_deg", SH_ERR_SCENE,
                       "expected inner_angle_deg <= outer_angle_deg (%s), "
                       "found %s",
                       b, a);
  }
  return SH_OK;
}

static sh_status parse_light_map(sh__parser *p, json_t *o, sh_light *l,
                                 int *has_up) {
  sh__pctx *c = &p->c;
  json_t *m;
  sh_status st;
  *has_up = 0;
  if ((st = sh__object(c, o, "light_map", 0, &m)) || !m) return st;
  if (l->type == SH_LIGHT_SPOT && l->outer_deg >= 90) {
    char a[40];
    sh__fmt_num(l->outer_deg, a, sizeof a);
    return sh__fail_at(c, "outer_angle_deg", SH_ERR_SCENE,
                       "a spot light with a light_map needs "
                       "outer_angle_deg < 90, found %s",
                       a);
  }
  sh__push_key(c, "light_map");
  if (l->type == SH_LIGHT_SPOT) {
    if ((st = sh__check_keys(c, m, SH__KEYS(spot_map_keys),
                             "a spot light's light_map")) ||
        (st = sh__direction(c, m, "up", 0, &l->map_up, has_up)))
      return st;
  } else {
    if ((st = sh__check_keys(c, m, SH__KEYS(directional_map_keys),
                             "a directional light's light_map")) ||
        (st =
             sh__vec3(c, m, "origin", 1, sh_v3s(0), sh__any, &l->map_origin)) ||
        (st = sh__direction(c, m, "u", 1, &l->map_u, NULL)) ||
        (st = sh__direction(c, m, "v", 1, &l->map_v, NULL)))
      return st;
    if (sh__parallel(l->map_u, l->map_v))
      return sh__fail_at(c, "v", SH_ERR_SCENE,
                         "u and v are parallel: the light map's window has "
                         "no area");
  }
  if ((st = sh__load_image(p, m, "image", 0, &l->map, &l->map_file))) return st;
  l->has_map = 1;
  l->map_up_given = *has_up;
  sh__pop(c);
  return SH_OK;
}

sh_status sh__parse_light(sh__parser *p, json_t *o, void *item) {
  sh_light *l = item;
  static const char *const *const type_keys[] = {point_keys, spot_keys,
                                                 directional_keys};
  static const char *const what[] = {"a point light", "a spot light",
                                     "a directional light"};
  sh__pctx *c = &p->c;
  sh_status st;
  int type, has_up = 0;
  sh_error e = SH_ERROR_INIT;
  if ((st = sh__choice(c, o, "type", 1, light_names, 0, "light type", &type)))
    return st;
  l->type = (sh_light_type)type;
  if ((st = sh__check_keys(c, o, SH__KEYS(light_keys, type_keys[type]),
                           what[type])) ||
      (st = sh__boolean(c, o, "soft_shadows", 0, 1, &l->soft_shadows)))
    return st;
  switch (l->type) {
  case SH_LIGHT_POINT:
    if ((st =
             sh__vec3(c, o, "position", 1, sh_v3s(0), sh__any, &l->position)) ||
        (st =
             sh__vec3(c, o, "intensity", 1, sh_v3s(0), sh__quantity,
                    &l->intensity)))
      return st;
    break;
  case SH_LIGHT_SPOT:
    if ((st = parse_spot(p, o, l))) return st;
    break;
  case SH_LIGHT_DIRECTIONAL:
    if ((st = sh__direction(c, o, "direction", 1, &l->direction, NULL)) ||
        (st = sh__vec3(c, o, "irradiance", 1, sh_v3s(0), sh__quantity,
                       &l->irradiance)) ||
        (st = sh__number(c, o, "angular_diameter_deg", 0, 0,
                         (sh__range){0, SH_SUN_DISK_MAX_DEG, 0, 0},
                         &l->angular_diameter_deg)))
      return st;
    break;
  }
  if (l->type != SH_LIGHT_POINT && (st = parse_light_map(p, o, l, &has_up)))
    return st;
  if (sh_light_prepare(l, p->scene->camera.up, has_up, &e) != SH_OK) {
    st = sh__fail_from(c, l->has_map ? "light_map" : NULL, &e, "");
    sh_error_clear(&e);
    return st;
  }
  return SH_OK;
}
