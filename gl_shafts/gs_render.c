#include "gs_render.h"

#include "sh_medium.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gs_atmo_light.h"
#include "gs_atmo_render.h"
#include "gs_context.h"
#include "gs_geometry.h"
#include "gs_gl.h"
#include "gs_lattice.h"
#include "gs_medium.h"
#include "gs_lightvol.h"
#include "gs_named.h"
#include "gs_program.h"
#include "gs_shadow.h"
#include "gs_surface.h"
#include "gs_sweep.h"
#include "gs_target.h"
#include "gs_view.h"
#include "sh_time.h"
#include "shafts.h"

struct gs_renderer {
  const sh_scene *scene;
  gs_options opt;
  gs__context *ctx;
  gs__view view;
  gs__programs progs;
  gs__params params;
  gs__geometry geom;
  gs__target target;
  gs__sweep sweep;
  int nlights;
  GLuint *maps;               /* light-map textures, 0 if none */
  unsigned long long *map_hash; /* what each was uploaded from */
  gs__light_setup *lights;
  int lights_stale;           /* work the light setups out at the next draw */
  unsigned long geom_version; /* bumped when the triangles change */
  gs__shadow_map *shadows;    /* kept across draws while their key holds */
  gs__lattice *lattices;
  float *readback;            /* width * height * 4 */
  gs__atmo_gl *atmo;          /* an atmosphere's table: drawn by gs_atmo_render */
  long built_reported;        /* progs.built at the end of the last draw */
};

/* The size of the image drawn: the crop's, else the camera's. */
static void image_size(const gs_renderer *r, int *w, int *h) {
  sh_crop win = sh_crop_window(&r->opt.crop, &r->scene->camera);
  *w = win.x1 - win.x0;
  *h = win.y1 - win.y0;
}

/* Checks the crop against the image and the options against the GL
 * implementation's limits. */
static sh_status check_limits(const gs_renderer *r, sh_error *err) {
  GLint max2d = 0, max3d = 0, maxcube = 0, maxview[2] = {0, 0};
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max2d);
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
  glGetIntegerv(GL_MAX_CUBE_MAP_TEXTURE_SIZE, &maxcube);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, maxview);
  const gs_options *o = &r->opt;
  sh_status st = sh_crop_check(&o->crop, &r->scene->camera, err);
  if (st != SH_OK) return st;
  int w, h;
  image_size(r, &w, &h);
  if (w > max2d || h > max2d || w > maxview[0] || h > maxview[1])
    return sh_error_set(err, SH_ERR_ARG,
                        "the image (%dx%d) is larger than this GL renders (%dx%d)",
                        w, h, maxview[0] < max2d ? maxview[0] : max2d,
                        maxview[1] < max2d ? maxview[1] : max2d);
  for (int t = 0; t < 3; t++) {
    int res = gs_light_shadow_map_res(o, (sh_light_type)t);
    if (res > max2d || res > maxcube)
      return sh_error_set(err, SH_ERR_ARG,
                          "shadow_map_res %d is larger than this GL allows (%d)", res,
                          max2d < maxcube ? max2d : maxcube);
  }
  if (o->light_map_res > max2d)
    return sh_error_set(err, SH_ERR_ARG,
                        "light_map_res %d is larger than this GL allows (%d)",
                        o->light_map_res, max2d);
  int maxplanes = gs_light_planes(o, SH_LIGHT_DIRECTIONAL);
  if (gs_light_planes(o, SH_LIGHT_SPOT) > maxplanes)
    maxplanes = gs_light_planes(o, SH_LIGHT_SPOT);
  if (o->xi == GS_XI_LATTICE &&
      (o->lattice_u > max3d || o->lattice_v > max3d || maxplanes + 1 > max3d))
    return sh_error_set(err, SH_ERR_ARG,
                        "with xi on the lattice, the lattice (%dx%d) and planes "
                        "+ 1 (%d) must be at most %d, this GL's largest 3D "
                        "texture; use fewer planes or xi exact",
                        o->lattice_u, o->lattice_v, maxplanes + 1, max3d);
  for (int i = 0; i < r->scene->nlights; i++) {
    const sh_light *l = &r->scene->lights[i];
    if (l->has_map && o->light_map_res == 0 &&
        (l->map.width > max2d || l->map.height > max2d))
      return sh_error_set(err, SH_ERR_ARG,
                          "light %d's light map (%dx%d) is larger than this GL "
                          "allows (%d); give a light_map_res",
                          i, l->map.width, l->map.height, max2d);
  }
  return SH_OK;
}

static int is_atmosphere(const sh_scene *scene) {
  return gs__medium_is_atmosphere(&scene->medium);
}

/* The atmosphere's table, built (again) from the scene's medium when it
 * is one and differs from the table's. */
static sh_status sync_atmosphere(gs_renderer *r, sh_error *err) {
  if (!is_atmosphere(r->scene)) return SH_OK;
  gs__atmo a;
  gs__atmo_from_medium(&r->scene->medium, &a);
  if (r->atmo && memcmp(&a, &r->atmo->atmo, sizeof a) == 0) return SH_OK;
  if (!r->atmo && !(r->atmo = calloc(1, sizeof *r->atmo)))
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  gs__atmo_gl_free(r->atmo);
  gs__atmo_source src = gs__atmo_source_medium(&r->scene->medium);
  return gs__atmo_gl_init(r->atmo, &a, &src, err);
}

/* A hash (FNV-1a over 32-bit words) of a light map's size and pixels:
 * whether a sync must upload it again. */
static unsigned long long map_hash(const sh_image *img) {
  unsigned long long h = 1469598103934665603ULL;
  h = (h ^ (unsigned)img->width) * 1099511628211ULL;
  h = (h ^ (unsigned)img->height) * 1099511628211ULL;
  size_t n = img->rgb ? (size_t)img->width * img->height * 3 : 0;
  for (size_t i = 0; i < n; i++) {
    uint32_t w;
    memcpy(&w, &img->rgb[i], sizeof w);
    h = (h ^ w) * 1099511628211ULL;
  }
  return h;
}

/* The light map as a float texture, at its own size or resampled to R x R
 * bilinearly (sh_image_lookup), sampled bilinearly with edge clamping as
 * sh_light_map_value samples it. */
static sh_status upload_map(const sh_light *l, int res, GLuint *out, sh_error *err) {
  const sh_image *img = &l->map;
  int w = res ? res : img->width, h = res ? res : img->height;
  /* RGBA: llvmpipe samples four-channel float textures faster than RGB. */
  float *rgba = malloc((size_t)w * h * 4 * sizeof *rgba);
  if (!rgba) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  for (int y = 0; y < h; y++)
    for (int x = 0; x < w; x++) {
      float *o = rgba + 4 * ((size_t)y * w + x);
      if (res)
        sh_image_lookup(img, (x + 0.5) / w, (y + 0.5) / h, o);
      else
        memcpy(o, img->rgb + 3 * ((size_t)y * w + x), 3 * sizeof *o);
      o[3] = 1.0f;
    }
  GLuint t;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, GL_RGBA32F, w, h);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  /* Row 0 (the image's top) at t = 0, as sh_image_lookup reads it. */
  glTextureSubImage2D(t, 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, rgba);
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  free(rgba);
  *out = t;
  return gs__gl_check("uploading a light map", err);
}

/* Uploads the light maps that differ from the textures' (all at first),
 * deletes the textures of lights that lost their map. */
static sh_status sync_maps(gs_renderer *r, sh_error *err) {
  sh_status st = SH_OK;
  for (int i = 0; i < r->nlights && st == SH_OK; i++) {
    const sh_light *l = &r->scene->lights[i];
    unsigned long long h = l->has_map ? map_hash(&l->map) : 0;
    if (r->maps[i] && (!l->has_map || h != r->map_hash[i])) {
      glDeleteTextures(1, &r->maps[i]);
      r->maps[i] = 0;
    }
    if (l->has_map && !r->maps[i]) {
      st = upload_map(l, r->opt.light_map_res, &r->maps[i], err);
      r->map_hash[i] = h;
    }
  }
  return st;
}

/* The light limit (GS_MAX_LIGHTS), at the scene's key "lights": checked
 * where a renderer is made and where a live one takes a changed scene. */
static sh_status check_light_count(const sh_scene *scene, sh_error *err) {
  if (scene->nlights <= GS_MAX_LIGHTS) return SH_OK;
  sh_status st = sh_error_set(err, SH_ERR_SCENE,
                              "%d lights: gl_shafts renders at most %d (each light "
                              "costs its own surface pass and plane sweep, and the "
                              "cost grows faster than the count: 100 point lights "
                              "took 1.9 s at 32x24, 1000 took 878 s; "
                              "docs/gl_shafts.md, 'Limits'); lmm_tracer has no such "
                              "limit",
                              scene->nlights, GS_MAX_LIGHTS);
  sh_error_set_file(err, scene->file);
  sh_error_set_key(err, "lights");
  return st;
}

sh_status gs_renderer_create(const sh_scene *scene, const gs_options *opt,
                             gs_renderer **out, sh_error *err) {
  *out = NULL;
  /* The scene's render keys are checked (with their places) even when the
   * caller's options replace them: a scene with a bad key is refused. */
  gs_options defaults;
  sh_status st = gs_options_from_scene(scene, &defaults, err);
  if (st != SH_OK) return st;
  if (!opt) opt = &defaults;
  if ((st = gs_options_check(opt, err)) != SH_OK ||
      (st = sh_crop_check(&opt->crop, &scene->camera, err)) != SH_OK ||
      (st = gs__medium_check(scene, err)) != SH_OK)
    return st;
  if ((st = check_light_count(scene, err)) != SH_OK) return st;
  gs_renderer *r = calloc(1, sizeof *r);
  if (!r) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  r->scene = scene;
  r->opt = *opt;
  r->nlights = scene->nlights;
  r->lights_stale = 1;
  size_t nl = (size_t)(scene->nlights ? scene->nlights : 1);
  r->maps = calloc(nl, sizeof *r->maps);
  r->map_hash = calloc(nl, sizeof *r->map_hash);
  r->lights = calloc(nl, sizeof *r->lights);
  r->shadows = calloc(nl, sizeof *r->shadows);
  r->lattices = calloc(nl, sizeof *r->lattices);
  int w, h;
  image_size(r, &w, &h);
  r->readback = malloc((size_t)w * h * 4 * sizeof *r->readback);
  if (!r->maps || !r->map_hash || !r->lights || !r->shadows || !r->lattices ||
      !r->readback) {
    gs_renderer_free(r);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  }
  st = gs__context_create(opt->backend, &r->ctx, err);
  if (st == SH_OK) st = check_limits(r, err);
  gs__view_init(&r->view, scene, &r->opt.crop);
  if (st == SH_OK) st = gs__geometry_build(scene, &r->view, &r->geom, err);
  if (st == SH_OK)
    st = gs__target_create(&r->target, w, h, err);
  if (st == SH_OK) st = gs__sweep_init(&r->sweep, err);
  if (st == SH_OK) st = sync_maps(r, err);
  if (st == SH_OK) st = sync_atmosphere(r, err);
  if (r->ctx) gs__context_release(r->ctx);
  if (st != SH_OK) {
    gs_renderer_free(r);
    return st;
  }
  *out = r;
  return SH_OK;
}

static sh_status sync(gs_renderer *r, unsigned changed, sh_error *err) {
  const sh_scene *scene = r->scene;
  sh_status st = SH_OK;
  if (changed & (SH_CHANGED_SIZE | SH_CHANGED_CAMERA | SH_CHANGED_LIGHTS))
    st = check_limits(r, err);
  int w, h;
  image_size(r, &w, &h);
  if (st == SH_OK && (w != r->target.width || h != r->target.height)) {
    float *rb = realloc(r->readback, (size_t)w * h * 4 * sizeof *rb);
    if (!rb) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
    r->readback = rb;
    gs__target_free(&r->target);
    st = gs__target_create(&r->target, w, h, err);
  }
  /* The near plane and the anchor follow the scene's bounds, which every
   * part moves (the anchor is quantised: it seldom moves, and then the
   * triangles are uploaded again). */
  if (changed && st == SH_OK) gs__view_init(&r->view, scene, &r->opt.crop);
  if (st == SH_OK && (changed & (SH_CHANGED_CAMERA | SH_CHANGED_SHAPES))) {
    int rebuilt, moved;
    st = gs__geometry_update(scene, &r->view, &r->geom, &rebuilt, &moved, err);
    if (moved) r->geom_version++;
  }
  /* The light setups follow the lights, the medium's box, the shapes and
   * the view (the lit volume is clipped to the frustum, a directional
   * light's map is fitted to it); the background and ambient leave them
   * as they are. The shadow maps are then kept unless their key changed. */
  if (changed & ~(unsigned)SH_CHANGED_ENVIRONMENT) r->lights_stale = 1;
  if (st == SH_OK && (changed & SH_CHANGED_LIGHTS)) st = sync_maps(r, err);
  if (st == SH_OK && (changed & SH_CHANGED_MEDIUM)) st = sync_atmosphere(r, err);
  return st;
}

sh_status gs_renderer_sync(gs_renderer *r, unsigned changed, sh_error *err) {
  sh_status lim = check_light_count(r->scene, err);
  if (lim != SH_OK) return lim;
  if (r->scene->nlights != r->nlights)
    return sh_error_set(err, SH_ERR_ARG,
                        "the scene's lights changed in number (%d, was %d): "
                        "make a new renderer",
                        r->scene->nlights, r->nlights);
  if (is_atmosphere(r->scene) != (r->atmo != NULL))
    return sh_error_set(err, SH_ERR_ARG,
                        "the scene's medium changed to or from an atmosphere: "
                        "make a new renderer");
  sh_status st = gs__medium_check(r->scene, err);
  if (st != SH_OK) return st;
  st = gs__context_make_current(r->ctx, err);
  if (st != SH_OK) return st;
  st = sync(r, changed, err);
  gs__context_release(r->ctx);
  return st;
}

/* Waits for GL and returns the time since *t, resetting it. */

static void to_rgb(const float *rgba, int w, int h, float *rgb) {
  /* GL's rows run bottom to top. */
  for (int y = 0; y < h; y++) {
    const float *src = rgba + 4 * (size_t)(h - 1 - y) * w;
    float *dst = rgb + 3 * (size_t)y * w;
    for (int x = 0; x < w; x++) {
      dst[3 * x] = src[4 * x];
      dst[3 * x + 1] = src[4 * x + 1];
      dst[3 * x + 2] = src[4 * x + 2];
    }
  }
}

/* gs_renderer_draw with the context current. */
static sh_status draw(gs_renderer *r, float *rgb, gs_stats *stats, sh_error *err) {
  gs_stats s;
  memset(&s, 0, sizeof s);
  const sh_scene *scene = r->scene;
  const gs_options *o = &r->opt;
  sh_status st = SH_OK;
  gs__frame fr = {scene, &r->view, &r->progs, &r->params, !o->live};
  double start = sh_seconds(), t = start;
  /* An atmosphere's air is drawn by gs_atmo_render, not the sweep; its
   * shapes by the surface pass, with the shadow maps of every light. */
  int nsweep = r->atmo ? 0 : r->nlights;
  int local = 0;
  for (int i = 0; i < r->nlights; i++)
    local += scene->lights[i].type != SH_LIGHT_DIRECTIONAL;
  int nsetup = r->atmo && !scene->nshapes && !local ? 0 : r->nlights;
  /* The atmosphere's table: its surfaces and lights read it too. */
  if (r->atmo) glBindTextureUnit(GS_UNIT_ATMO, r->atmo->tex);

  /* Lights: their volumes (when a sync changed what they follow) and
   * shadow maps (when their key changed). */
  for (int i = 0; i < nsetup && st == SH_OK && r->lights_stale; i++) {
    gs__light_setup_free(&r->lights[i]);
    st = gs__light_setup_init(&r->lights[i], scene, i, &r->view, &r->geom, err);
  }
  if (st == SH_OK) r->lights_stale = 0;
  for (int i = 0; i < nsetup && st == SH_OK; i++) {
    if (r->lights[i].shadow == GS__SHADOW_NONE) continue;
    int drawn = 0;
    st = gs__shadow_update(&r->shadows[i], &fr, &r->lights[i],
                           gs_light_shadow_map_res(o, scene->lights[i].type),
                           &r->geom, r->geom_version, &drawn, err);
    s.shadow_maps += drawn;
  }
  if (st == SH_OK) s.shadow_seconds = gs__gl_lap(&t);

  if (st == SH_OK && (!r->atmo || scene->nshapes))
    st = gs__surface_render(&fr, &r->geom, r->lights, r->shadows, r->maps,
                            &r->target, err);
  if (st == SH_OK) s.surface_seconds = gs__gl_lap(&t);

  gs__sweep_counts counts = {0, 0, 0};
  for (int i = 0; i < nsweep && st == SH_OK; i++) {
    const gs__light_setup *ls = &r->lights[i];
    if (!ls->vol->nfaces) continue;
    s.lights_swept++;
    double map[6] = {0, 0, 0, 0, 0, 0};
    const sh_light *l = &scene->lights[i];
    int lmres = o->light_map_res, planes = gs_light_planes(o, l->type);
    gs__sweep_job job = {&fr, ls, &r->shadows[i], r->maps[i],
                         NULL, map, planes, o->jitter,
                         o->sub_angle_deg * SH_PI / 180.0,
                         o->sub_texels,
                         lmres ? lmres : l->map.width, lmres ? lmres : l->map.height};
    if (o->xi == GS_XI_LATTICE) {
      long points = 0;
      st = gs__lattice_eval(&r->lattices[i], scene, &r->view, ls, o->lattice_u,
                            o->lattice_v, planes, map, &points, err);
      s.lattice_points += points;
      job.lattice = &r->lattices[i];
      s.lattice_seconds += gs__gl_lap(&t);
    }
    if (st == SH_OK)
      st = gs__sweep_light(&r->sweep, &job, &r->target, &counts, err);
    s.plane_seconds += gs__gl_lap(&t);
  }
  if (st == SH_OK && r->atmo) {
    /* --planes gives the sampling planes or spheres; else their own
     * defaults (gs_atmo_render.h). */
    gs__atmo_settings set = {o->planes > 0 ? o->planes : GS__ATMO_PLANES,
                             o->planes > 0 ? o->planes : GS__ATMO_SPHERES,
                             gs__atmo_lattice_step(&scene->camera), NULL, NULL};
    if (nsetup) {
      /* The rays end on the surfaces (atmo_shapes.glsl). */
      glBindTextureUnit(GS_UNIT_LINDEPTH, r->target.lindepth);
      set.lattice_step = 1;
      set.lights = r->lights;
      set.shadows = r->shadows;
    }
    gs__atmo_counts ac;
    st = gs__atmo_render(r->atmo, &fr, &r->target, &set, &ac, err);
    s.spheres = ac.spheres;
    counts.planes += ac.planes;
    /* The suns' layers drawn on the lattice count as the lattice's time,
     * their full-resolution passes as the planes'. */
    gs__gl_lap(&t);
    s.lattice_seconds += ac.lattice_seconds;
    s.plane_seconds += ac.compose_seconds + ac.fixup_seconds + ac.layer_seconds;
    /* Point and spot lights: a pass each, as many angle steps as the sky
     * has planes. */
    for (int i = 0; i < r->nlights && st == SH_OK; i++) {
      if (scene->lights[i].type == SH_LIGHT_DIRECTIONAL) continue;
      st = gs__atmo_light_render(r->atmo, &fr, &r->target, &r->lights[i], &r->shadows[i],
                                 r->maps[i], o->planes > 0 ? o->planes
                                                           : GS__ATMO_LIGHT_INTERVALS,
                                 err);
      s.lights_swept++;
    }
    s.plane_seconds += gs__gl_lap(&t);
  }
  s.planes = counts.planes;
  s.fragments = counts.fragments;
  s.fragments_rasterized = counts.fragments_rasterized;

  if (st == SH_OK) {
    int w = r->target.width, h = r->target.height;
    glBindFramebuffer(GL_FRAMEBUFFER, r->target.fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, r->readback);
    st = gs__gl_check("reading the image back", err);
    if (st == SH_OK) to_rgb(r->readback, w, h, rgb);
    s.readback_seconds = gs__gl_lap(&t);
  }
  s.seconds = sh_seconds() - start;
  s.triangles = r->geom.triangles;
  s.width = r->target.width;
  s.height = r->target.height;
  snprintf(s.renderer, sizeof s.renderer, "%s", gs__context_renderer(r->ctx));
  snprintf(s.backend, sizeof s.backend, "%s", gs__context_backend_name(r->ctx));
  snprintf(s.vendor, sizeof s.vendor, "%s", gs__context_vendor(r->ctx));
  s.programs_compiled = (int)(r->progs.built - r->built_reported);
  s.programs_cached = r->progs.n;
  r->built_reported = r->progs.built;
  if (stats) *stats = s;
  return st;
}

sh_status gs_renderer_draw(gs_renderer *r, float *rgb, gs_stats *stats,
                           sh_error *err) {
  sh_status st = gs__context_make_current(r->ctx, err);
  if (st != SH_OK) return st;
  st = draw(r, rgb, stats, err);
  gs__context_release(r->ctx);
  return st;
}

void gs_renderer_free(gs_renderer *r) {
  if (!r) return;
  if (r->ctx && gs__context_make_current(r->ctx, NULL) == SH_OK) {
    for (int i = 0; i < r->nlights; i++) {
      if (r->maps && r->maps[i]) glDeleteTextures(1, &r->maps[i]);
      if (r->shadows) gs__shadow_free(&r->shadows[i]);
      if (r->lattices) gs__lattice_free(&r->lattices[i]);
    }
    if (r->atmo) gs__atmo_gl_free(r->atmo);
    gs__sweep_free(&r->sweep);
    gs__target_free(&r->target);
    gs__geometry_free(&r->geom);
    gs__programs_free(&r->progs);
    gs__params_free(&r->params);
    gs__context_release(r->ctx);
  }
  if (r->lights)
    for (int i = 0; i < r->nlights; i++) gs__light_setup_free(&r->lights[i]);
  gs__context_free(r->ctx);
  free(r->maps);
  free(r->map_hash);
  free(r->lights);
  free(r->shadows);
  free(r->lattices);
  free(r->readback);
  free(r->atmo);
  free(r);
}

sh_status gs_render(const sh_scene *scene, const gs_options *opt,
                    sh_image *out, gs_stats *stats, sh_error *err) {
  double start = sh_seconds();
  gs_renderer *r = NULL;
  sh_status st = gs_renderer_create(scene, opt, &r, err);
  if (st != SH_OK) return st;
  double setup = sh_seconds() - start;
  int w, h;
  image_size(r, &w, &h);
  st = sh_image_alloc(out, w, h, err);
  if (st == SH_OK) {
    st = gs_renderer_draw(r, out->rgb, stats, err);
    if (st != SH_OK) sh_image_free(out);
  }
  if (st == SH_OK && stats) stats->setup_seconds = setup;
  gs_renderer_free(r);
  return st;
}
