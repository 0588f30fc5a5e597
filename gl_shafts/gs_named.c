#include "gs_named.h"

#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sh_json_out.h"
#include "sh_options.h"
#include "sh_render_params.h"

/* In the order of gs_xi_mode after DEFAULT, and of gs_backend. */
static const char *const xi_names[] = {"lattice", "exact", NULL};
static const char *const backend_names[] = {"auto", "egl", "osmesa", NULL};

/* Every option's one limit (sh_options.h): gs_options_set and
 * gs_options_check read this table. "lattice" sets lattice_u and
 * lattice_v together ("NU NV", or "N" for both). */
#define OPT(field) #field, offsetof(gs_options, field)
static const sh__opt options[] = {
    /* 0: by the light's kind (GS_DEFAULT_PLANES_*) */
    {OPT(planes), SH__OPT_INT, 1, 100000, 0, NULL, 0, 1, 0, 0},
    {OPT(lattice_u), SH__OPT_INT, 2, 4096, 0, NULL, 0, 0, 0, 0},
    {OPT(lattice_v), SH__OPT_INT, 2, 4096, 0, NULL, 0, 0, 0, 0},
    {"lattice", offsetof(gs_options, lattice_u), SH__OPT_INT, 2, 4096, 0, NULL,
     0, 0, 0, 2},
    /* 0: each map at its own size */
    {OPT(light_map_res), SH__OPT_INT, 1, 16384, 0, NULL, 0, 1, 0, 0},
    /* 0: by the light's kind (GS_DEFAULT_SHADOW_*) */
    {OPT(shadow_map_res), SH__OPT_INT, 1, 16384, 0, NULL, 0, 1, 0, 0},
    {OPT(xi), SH__OPT_CHOICE, 0, 0, 0, xi_names, GS_XI_LATTICE, 0, 0, 0},
    {OPT(jitter), SH__OPT_BOOL, 0, 1, 0, NULL, 0, 0, 0, 0},
    {OPT(sub_angle_deg), SH__OPT_DOUBLE, 0, 30, 1, NULL, 0, 0, 0, 0},
    {OPT(sub_texels), SH__OPT_DOUBLE, 0, 1e6, 1, NULL, 0, 0, 0, 0},
    {OPT(backend), SH__OPT_CHOICE, 0, 0, 0, backend_names, GS_BACKEND_AUTO, 0,
     0, 0},
    {OPT(live), SH__OPT_BOOL, 0, 1, 0, NULL, 0, 0, 0, 0},
};
#undef OPT
enum { NOPTIONS = sizeof options / sizeof *options };

/* The render keys gl_shafts owns (docs/scene-format.md, "render"); each is
 * the option of the same name. */
static const char *const render_keys[] = {"planes", "lattice", "light_map_res",
                                          "shadow_map_res", "xi", "jitter",
                                          NULL};

static gs_options builtin(void) {
  gs_options o;
  memset(&o, 0, sizeof o);
  o.lattice_u = o.lattice_v = GS_DEFAULT_LATTICE;
  o.xi = GS_DEFAULT_XI;
  o.jitter = GS_DEFAULT_JITTER;
  o.sub_angle_deg = GS_DEFAULT_SUB_ANGLE_DEG;
  o.sub_texels = GS_DEFAULT_SUB_TEXELS;
  return o;
}

sh_status gs_options_from_scene(const sh_scene *scene, gs_options *opt,
                                sh_error *err) {
  gs_options o = builtin();
  sh_status st = sh__render_params_apply(scene, options, NOPTIONS, &o,
                                         render_keys, err);
  if (st == SH_OK) *opt = o;
  return st;
}

gs_options gs_options_defaults(const sh_scene *scene) {
  gs_options o = builtin();
  /* Key by key, so that a bad one (which gs_options_from_scene and
   * gs_renderer_create report) leaves the others applied. */
  for (int k = 0; render_keys[k]; k++) {
    const char *one[] = {render_keys[k], NULL};
    sh__render_params_apply(scene, options, NOPTIONS, &o, one, NULL);
  }
  return o;
}

int gs_light_planes(const gs_options *o, sh_light_type type) {
  if (o->planes > 0) return o->planes;
  return type == SH_LIGHT_DIRECTIONAL ? GS_DEFAULT_PLANES_DIRECTIONAL
                                      : GS_DEFAULT_PLANES_LOCAL;
}

int gs_light_shadow_map_res(const gs_options *o, sh_light_type type) {
  if (o->shadow_map_res > 0) return o->shadow_map_res;
  return type == SH_LIGHT_DIRECTIONAL ? GS_DEFAULT_SHADOW_DIRECTIONAL
                                      : GS_DEFAULT_SHADOW_LOCAL;
}

sh_status gs_options_check(const gs_options *opt, sh_error *err) {
  return sh__options_check(options, NOPTIONS, opt, err);
}

const char *const *gs_option_choices(const char *key) {
  const sh__opt *d = sh__options_find(options, NOPTIONS, key);
  return d ? d->choices : NULL;
}

const char *gs_option_name(const char *key, int value) {
  const sh__opt *d = sh__options_find(options, NOPTIONS, key);
  return d ? sh__options_choice_name(d, value) : "?";
}

gs_options *gs_options_new(const sh_scene *scene) {
  gs_options *o = scene ? malloc(sizeof *o) : NULL;
  if (o) *o = gs_options_defaults(scene);
  return o;
}

void gs_options_free(gs_options *opt) { free(opt); }

sh_status gs_options_set(gs_options *opt, const char *key, const char *value,
                         sh_error *err) {
  if (!opt) return sh_error_set(err, SH_ERR_ARG, "gs_options_set: no options");
  gs_options next = *opt;
  sh_status st = sh__options_set(options, NOPTIONS, &next, key, value, err);
  if (st == SH_OK && (st = gs_options_check(&next, err)) != SH_OK) {
    sh_error_set_key(err, "%s", key);
    return st;
  }
  if (st == SH_OK) *opt = next;
  return st;
}

size_t gs_stats_size(void) { return sizeof(gs_stats); }

size_t gs_stats_json(const gs_stats *s, char *buf, size_t size) {
  json_t *o = json_object();
  if (!o) return 0;
  json_object_set_new(o, "backend", json_string(s->backend));
  json_object_set_new(o, "renderer", json_string(s->renderer));
  json_object_set_new(o, "vendor", json_string(s->vendor));
  sh__json_num(o, "width", s->width);
  sh__json_num(o, "height", s->height);
  sh__json_num(o, "seconds", s->seconds);
  sh__json_num(o, "setup_seconds", s->setup_seconds);
  sh__json_num(o, "shadow_seconds", s->shadow_seconds);
  sh__json_num(o, "surface_seconds", s->surface_seconds);
  if (s->lattice_points > 0 || s->lattice_seconds > 0) /* xi, an atmosphere's lattice */
    sh__json_num(o, "lattice_seconds", s->lattice_seconds);
  sh__json_num(o, "plane_seconds", s->plane_seconds);
  sh__json_num(o, "readback_seconds", s->readback_seconds);
  sh__json_num(o, "lights_swept", s->lights_swept);
  sh__json_num(o, "shadow_maps", s->shadow_maps);
  sh__json_num(o, "planes", (double)s->planes);
  if (s->spheres > 0) sh__json_num(o, "spheres", (double)s->spheres);
  if (s->lattice_points > 0)
    sh__json_num(o, "lattice_points", (double)s->lattice_points);
  sh__json_num(o, "fragments", s->fragments);
  sh__json_num(o, "fragments_rasterized", s->fragments_rasterized);
  sh__json_num(o, "triangles", (double)s->triangles);
  sh__json_num(o, "programs_compiled", s->programs_compiled);
  sh__json_num(o, "programs_cached", s->programs_cached);
  return sh__json_dump_to(o, buf, size);
}
