#include "gs_named.h"

#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sh_json_out.h"
#include "sh_options.h"

/* In the order of sh_xi_mode after DEFAULT, and of gs_backend. */
static const char *const xi_names[] = {"lattice", "exact", NULL};
static const char *const backend_names[] = {"auto", "egl", "osmesa", NULL};

/* Kinds and choices only: the limits are gs_options_check's. */
#define OPT(field, kind) #field, offsetof(gs_options, field), kind, -INFINITY, INFINITY, 0
static const sh__opt options[] = {
    {OPT(planes, SH__OPT_INT), NULL, 0},
    {OPT(lattice_u, SH__OPT_INT), NULL, 0},
    {OPT(lattice_v, SH__OPT_INT), NULL, 0},
    {OPT(light_map_res, SH__OPT_INT), NULL, 0},
    {OPT(shadow_map_res, SH__OPT_INT), NULL, 0},
    {OPT(xi, SH__OPT_CHOICE), xi_names, SH_XI_LATTICE},
    {OPT(jitter, SH__OPT_BOOL), NULL, 0},
    {OPT(sub_angle_deg, SH__OPT_DOUBLE), NULL, 0},
    {OPT(sub_texels, SH__OPT_DOUBLE), NULL, 0},
    {OPT(backend, SH__OPT_CHOICE), backend_names, GS_BACKEND_AUTO},
    {OPT(live, SH__OPT_BOOL), NULL, 0},
};
#undef OPT

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
  sh_status st = sh__options_set(options, sizeof options / sizeof *options,
                                 &next, key, value, err);
  if (st == SH_OK && (st = gs_options_check(&next, err)) != SH_OK) {
    if (err) snprintf(err->path, sizeof err->path, "%s", key);
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
  sh__json_num(o, "lattice_seconds", s->lattice_seconds);
  sh__json_num(o, "plane_seconds", s->plane_seconds);
  sh__json_num(o, "readback_seconds", s->readback_seconds);
  sh__json_num(o, "lights_swept", s->lights_swept);
  sh__json_num(o, "shadow_maps", s->shadow_maps);
  sh__json_num(o, "planes", (double)s->planes);
  sh__json_num(o, "lattice_points", (double)s->lattice_points);
  sh__json_num(o, "fragments", s->fragments);
  sh__json_num(o, "fragments_rasterized", s->fragments_rasterized);
  sh__json_num(o, "triangles", (double)s->triangles);
  sh__json_num(o, "programs_compiled", s->programs_compiled);
  sh__json_num(o, "programs_cached", s->programs_cached);
  return sh__json_dump_to(o, buf, size);
}
