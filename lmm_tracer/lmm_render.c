#include "lmm_render.h"

#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lmm_area.h"
#include "sh_json_out.h"
#include "sh_options.h"
#include "sh_reference.h"
#include "sh_render_params.h"
#include "sh_rt.h"
#include "sh_time.h"

/* ---- Options by name ---- */

static const char *const mode_names[] = {"reference", "whitted", "lmm", NULL};
/* In the order of lmm_scheme, after DEFAULT. */
static const char *const scheme_names[] = {"straight", "refract-trace",
                                           "refract-both", NULL};
static const char *const volume_names[] = {"mesh", "exact", NULL};

/* One row per option (sh_options.h): its name, where it lives, its kind
 * and limits or choices, and the value that means "not given". */
#define OPT(field) #field, offsetof(lmm_render_options, field)
static const sh__opt options[] = {
    {OPT(mode), SH__OPT_CHOICE, 0, 0, 0, mode_names, 0, 0, 0, 0},
    {OPT(scheme), SH__OPT_CHOICE, 0, 0, 0, scheme_names, 1, 1, LMM_SCHEME_DEFAULT, 0},
    {"volume", offsetof(lmm_render_options, volume_exact), SH__OPT_CHOICE, 0,
     0, 0, volume_names, 0, 0, 0, 0},
    {OPT(local), SH__OPT_BOOL, 0, 1, 0, NULL, 0, 0, 0, 0},
    {OPT(refined), SH__OPT_BOOL, 0, 1, 0, NULL, 0, 0, 0, 0},
    {OPT(mesh_step), SH__OPT_DOUBLE, 0, INFINITY, 1, NULL, 0, 1, 0, 0},
    {OPT(kl), SH__OPT_DOUBLE, 0, INFINITY, 1, NULL, 0, 1, 0, 0},
    {OPT(caustic_rays), SH__OPT_LLONG, 1, 1099511627776.0, 0, NULL, 0, 1, 0, 0},
    {OPT(area_radius), SH__OPT_DOUBLE, 0, INFINITY, 0, NULL, 0, 1, -1, 0},
    {OPT(area_samples), SH__OPT_INT, 1, 1 << 20, 0, NULL, 0, 1, 0, 0},
    {OPT(spp), SH__OPT_INT, 1, 1 << 24, 0, NULL, 0, 1, 0, 0},
    {OPT(max_depth), SH__OPT_INT, 0, 64, 0, NULL, 0, 1, -1, 0},
    {OPT(seed), SH__OPT_LLONG, 0, 4294967295.0, 0, NULL, 0, 1, -1, 0},
    {OPT(threads), SH__OPT_INT, 0, 1024, 0, NULL, 0, 0, 0, 0},
};
#undef OPT
enum { NOPTIONS = sizeof options / sizeof *options };

sh_status lmm_render_options_set(lmm_render_options *opt, const char *key,
                                 const char *value, sh_error *err) {
  return sh__options_set(options, NOPTIONS, opt, key, value, err);
}

const char *const *lmm_render_option_choices(const char *key) {
  const sh__opt *d = sh__options_find(options, NOPTIONS, key);
  return d ? d->choices : NULL;
}

void lmm_render_options_init(lmm_render_options *opt) {
  memset(opt, 0, sizeof *opt);
  opt->mode = LMM_MODE_REFERENCE;
  opt->area_radius = -1;
  opt->max_depth = -1;
  opt->seed = -1;
}

sh_status lmm_render_options_check(const lmm_render_options *opt,
                                   sh_error *err) {
  sh_status st = sh__options_check(options, NOPTIONS, opt, err);
  if (st != SH_OK) return st;
  /* An option that would not apply is refused, not ignored (as pbrt-v4
   * refuses an unused parameter). The error's key is the option; the
   * message names options by their keys and values ("needs mode lmm"), so
   * a command line can put its own names in their place. */
  int lmm = opt->mode == LMM_MODE_LMM;
  int other_scheme = opt->scheme && opt->scheme != LMM_SCHEME_REFRACT_BOTH;
  if (opt->refined && (!lmm || other_scheme))
    return sh__options_fail(err, "refined",
                            "refined needs mode lmm and scheme refract-both");
  if (opt->caustic_rays > 0 && (!lmm || other_scheme))
    return sh__options_fail(err, "caustic_rays", "caustic_rays needs mode "
                            "lmm and scheme refract-both");
  static const char *const lmm_only[] = {"mesh_step", "kl", "volume"};
  int given[] = {opt->mesh_step > 0, opt->kl > 0, opt->volume_exact};
  for (int i = 0; i < 3; i++)
    if (given[i] && !lmm)
      return sh__options_fail(err, lmm_only[i], "%s needs mode lmm",
                              lmm_only[i]);
  if (opt->area_radius >= 0 && opt->mode != LMM_MODE_WHITTED)
    return sh__options_fail(err, "area_radius",
                            "area_radius needs mode whitted");
  if (opt->area_samples > 0 && opt->area_radius < 0)
    return sh__options_fail(err, "area_samples",
                            "area_samples needs area_radius");
  return SH_OK;
}

lmm_render_options *lmm_render_options_new(void) {
  lmm_render_options *o = malloc(sizeof *o);
  if (o) lmm_render_options_init(o);
  return o;
}

void lmm_render_options_free(lmm_render_options *opt) { free(opt); }

void lmm_render_options_set_callbacks(lmm_render_options *opt,
                                      void (*progress)(void *, long, long),
                                      void *progress_user,
                                      volatile int *cancel) {
  opt->progress = progress;
  opt->progress_user = progress_user;
  opt->cancel = cancel;
}

size_t lmm_render_stats_size(void) { return sizeof(lmm_render_stats); }

/* ---- Rendering ---- */

static int cancelled(const lmm_render_options *opt) {
  return opt->cancel && *opt->cancel;
}

sh_status lmm_render(const sh_scene *scene, const lmm_render_options *opt,
                     float *rgb, lmm_render_stats *stats, sh_error *err) {
  sh_status st;
  if (!scene || !opt || !rgb)
    return sh_error_set(err, SH_ERR_ARG, "lmm_render: no scene, options or image");
  if ((st = lmm_render_options_check(opt, err))) return st;
  /* Before the set-up, which can take seconds (the caustic pass). */
  if ((st = sh_crop_check(&opt->crop, &scene->camera, err))) return st;
  double start = sh_seconds();
  sh_reference_options ro = sh_reference_defaults(scene);
  if (opt->spp > 0) ro.spp = opt->spp;
  if (opt->max_depth >= 0) ro.max_depth = opt->max_depth;
  if (opt->seed >= 0) ro.seed = (uint64_t)opt->seed;
  ro.threads = sh_reference_threads(opt->threads);
  ro.local = opt->local;
  ro.progress = opt->progress;
  ro.progress_user = opt->progress_user;
  ro.cancel = opt->cancel;
  ro.crop = opt->crop;
  /* The scene's keys of the light meshes, through the options' table: a bad
   * one is refused with its place even when an option replaces it. */
  lmm_render_options keys;
  lmm_render_options_init(&keys);
  static const char *const render_keys[] = {"mesh_step", "kl", "scheme", NULL};
  if ((st = sh__render_params_apply(scene, options, NOPTIONS, &keys,
                                    render_keys, err)))
    return st;
  lmm_scheme scheme = opt->scheme ? opt->scheme : keys.scheme;
  if (scheme == LMM_SCHEME_DEFAULT) scheme = LMM_SCHEME_REFRACT_TRACE;
  ro.refract = scheme != LMM_SCHEME_STRAIGHT;
  if ((opt->refined || opt->caustic_rays > 0) &&
      scheme != LMM_SCHEME_REFRACT_BOTH)
    return sh__options_fail(err, opt->refined ? "refined" : "caustic_rays",
                            "%s needs scheme refract-both (render.scheme or "
                            "the default gives %s)",
                            opt->refined ? "refined" : "caustic_rays",
                            scheme_names[scheme - 1]);
  if (scheme == LMM_SCHEME_REFRACT_BOTH && opt->mode != LMM_MODE_LMM)
    return sh__options_fail(err, "scheme",
                            "scheme refract-both needs mode lmm: refracted "
                            "visibility comes from the light mesh");
  double h = opt->mesh_step > 0             ? opt->mesh_step
             : keys.mesh_step > 0          ? keys.mesh_step
                                           : lmm_default_step(scene);
  double kl = opt->kl > 0 ? opt->kl : keys.kl > 0 ? keys.kl : 2.0;

  sh_rt *rt = NULL;
  lmm *method = NULL;
  lmm_area *area = NULL;
  sh_image img = {0};
  sh_reference_stats rs;
  memset(&rs, 0, sizeof rs);
  st = sh_rt_create(scene, &rt, err);
  if (st == SH_OK && opt->mode == LMM_MODE_LMM) {
    lmm_options lo;
    memset(&lo, 0, sizeof lo);
    lo.h = h;
    lo.kl = kl;
    lo.scheme = scheme;
    lo.caustic_rays = opt->caustic_rays > 0 ? opt->caustic_rays : 200000;
    lo.volume = !opt->volume_exact;
    lo.refined = opt->refined;
    lo.cancel = opt->cancel;
    lo.progress = opt->progress; /* the refracted paths' pass */
    lo.progress_user = opt->progress_user;
    st = lmm_create(scene, rt, &lo, ro.threads, &method, err);
    if (st == SH_OK) ro.hook = lmm_hook(method);
  } else if (st == SH_OK && opt->mode == LMM_MODE_WHITTED &&
             opt->area_radius >= 0) {
    st = lmm_area_create(scene, rt, opt->area_radius,
                         opt->area_samples > 0 ? opt->area_samples : 16, &area,
                         err);
    if (st == SH_OK) ro.hook = lmm_area_hook(area);
  }
  if (st == SH_OK && cancelled(opt))
    st = sh_error_set(err, SH_ERR_CANCELLED, "rendering was cancelled");
  ro.rt = rt;
  if (st == SH_OK) st = sh_render_reference(scene, &ro, &img, &rs, err);
  if (st == SH_OK)
    memcpy(rgb, img.rgb, sizeof(float) * 3 * (size_t)img.width * img.height);
  if (st == SH_OK && stats) {
    memset(stats, 0, sizeof *stats);
    stats->mode = opt->mode;
    stats->scheme = scheme;
    stats->width = img.width;
    stats->height = img.height;
    stats->spp = ro.spp;
    stats->max_depth = ro.max_depth;
    stats->seed = ro.seed;
    stats->medium = scene->medium.present;
    stats->trace = rs;
    if (method) {
      stats->has_lmm = 1;
      stats->mesh_step = h;
      stats->kl = kl;
      lmm_get_stats(method, &stats->lmm);
    }
    stats->seconds = sh_seconds() - start;
  }
  sh_image_free(&img);
  lmm_free(method);
  lmm_area_free(area);
  sh_rt_free(rt);
  return st;
}

/* ---- Statistics as JSON ---- */

size_t lmm_render_stats_json(const lmm_render_stats *s, char *buf,
                             size_t size) {
  json_t *o = json_object();
  if (!o) return 0;
  json_object_set_new(o, "mode", json_string(mode_names[s->mode]));
  json_object_set_new(o, "scheme",
                      json_string(s->scheme > 0 ? scheme_names[s->scheme - 1]
                                                : "default"));
  sh__json_num(o, "width", s->width);
  sh__json_num(o, "height", s->height);
  sh__json_num(o, "spp", s->spp);
  sh__json_num(o, "max_depth", s->max_depth);
  sh__json_num(o, "seed", (double)s->seed);
  const sh_reference_stats *t = &s->trace;
  sh__json_num(o, "threads", t->threads);
  sh__json_num(o, "seconds", s->seconds);
  sh__json_num(o, "render_seconds", t->seconds);
  sh__json_num(o, "camera_rays", (double)t->camera_rays);
  sh__json_num(o, "closest_rays", (double)t->closest_rays);
  sh__json_num(o, "occlusion_rays", (double)t->occlusion_rays);
  /* Only what applies: without a medium the tracer draws no random number
   * (no noise to estimate); the volume lookups and the caustic pass belong
   * to a medium and to refract-both. */
  if (s->medium) sh__json_num(o, "medium_samples", (double)t->medium_samples);
  if (s->medium && t->noise_pixels > 0) {
    sh__json_num(o, "noise_rel_rms_estimate", t->noise_rel_rms);
    sh__json_num(o, "noise_pixels", (double)t->noise_pixels);
  }
  if (s->has_lmm) {
    const lmm_stats *l = &s->lmm;
    sh__json_num(o, "mesh_step", s->mesh_step);
    sh__json_num(o, "kl", s->kl);
    sh__json_num(o, "mesh_points_total", (double)l->mesh.points_total);
    sh__json_num(o, "mesh_points_computed", (double)l->mesh.points_computed);
    sh__json_num(o, "mesh_points_uncached", (double)l->mesh.points_uncached);
    sh__json_num(o, "mesh_fraction_computed",
        l->mesh.points_total
            ? (double)l->mesh.points_computed / l->mesh.points_total
            : 0.0);
    json_object_set_new(o, "mesh_storage",
                        json_string(l->mesh.bits ? "bits" : "floats"));
    sh__json_num(o, "shaded_points", (double)l->shaded_points);
    sh__json_num(o, "empty_sets", (double)l->empty_sets);
    sh__json_num(o, "candidate_rays", (double)l->candidate_rays);
    if (s->medium) sh__json_num(o, "volume_lookups", (double)l->volume_lookups);
    if (s->scheme == LMM_SCHEME_REFRACT_BOTH) {
      sh__json_num(o, "caustic_points", (double)l->caustic_points);
      sh__json_num(o, "caustic_seconds", l->build_seconds);
    }
  }
  return sh__json_dump_to(o, buf, size);
}
