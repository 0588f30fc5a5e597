/* The ray tracer's modes in one call: the reference renderer, the Whitted
 * baseline (RRTA of Debelov et al. 2008, optionally with sphere lights
 * sampled by shadow rays) and the light meshes method (lmm_method.h), with
 * the acceleration structure and the method's set-up (the refracted paths
 * of refract-both) built and freed inside the call. lmm_tracer's main and
 * the Python module (blender_addon/shafts_blender/shafts.py) both render
 * through lmm_render, so the modes' rules live here once.
 *
 * Options are a plain struct for C, and the same options are set by name
 * from text (lmm_render_options_set: one table of names, limits and
 * choices), which the command line and language bindings use. Statistics
 * are a plain struct, written as JSON by lmm_render_stats_json. Nothing
 * here prints; errors are sh_status with an sh_error. */
#ifndef LMM_RENDER_H
#define LMM_RENDER_H

#include <stddef.h>
#include <stdint.h>

#include "lmm_method.h"
#include "sh_camera.h"
#include "sh_error.h"
#include "sh_reference.h"
#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum lmm_mode {
  LMM_MODE_REFERENCE, /* the converged reference (the ground truth) */
  LMM_MODE_WHITTED,   /* the same tracer as the RRTA baseline */
  LMM_MODE_LMM        /* soft shadows by the light meshes method */
} lmm_mode;

/* A value of 0 (or -1 where said) means "not given": the scene's render
 * settings decide, else the built-in default. */
typedef struct lmm_render_options {
  lmm_mode mode;
  lmm_scheme scheme;   /* DEFAULT: render.scheme, else refract-trace */
  int local;              /* 1: formula 1 (no mirror rays, no refraction) */
  int refined;            /* lmm, refract-both: the refined variant */
  int volume_exact;       /* lmm in a medium: 1 traces the volumetric
                             shadows exactly, 0 interpolates the mesh */
  double mesh_step;       /* lmm: h, scene units; 0: render.mesh_step, else
                             lmm_default_step */
  double kl;              /* lmm: r = h * kl; 0: render.kl, else 2 */
  long long caustic_rays; /* lmm, refract-both: rays per light and shape;
                             0: 200000 */
  double area_radius;     /* whitted: point and spot lights become spheres
                             of this radius; -1: no */
  int area_samples;       /* with area_radius: shadow rays per light; 0: 16 */
  int spp;                /* in-scattering samples; 0: render.spp */
  int max_depth;          /* -1: render.max_depth */
  long long seed;         /* -1: render.seed */
  int threads;            /* 0: one per online CPU */
  sh_crop crop;           /* the pixels to render (sh_camera.h), each as in
                             the whole image to the bit; all zero: the
                             whole image */
  /* As in sh_reference_options: reports from the worker threads (NULL:
   * none) and a flag that stops the render (SH_ERR_CANCELLED). */
  void (*progress)(void *user, long done, long total);
  void *progress_user;
  volatile int *cancel;
} lmm_render_options;

typedef struct lmm_render_stats {
  lmm_mode mode;
  lmm_scheme scheme; /* the one used (never DEFAULT) */
  int width, height, spp, max_depth; /* width, height: the image rendered
                                        (the crop's) */
  int medium;            /* the scene has a medium (medium samples and the
                            noise estimate apply) */
  uint64_t seed;
  double seconds;        /* the whole call: set-up and render */
  /* The tracing's own (sh_reference.h): its seconds, threads, ray and
   * medium-sample counts and the image's noise, estimated (not in lmm and
   * sphere-light modes, whose hooks keep caches: noise_pixels 0). */
  sh_reference_stats trace;
  int has_lmm;           /* lmm mode: the fields below are filled */
  double mesh_step, kl;
  lmm_stats lmm;
} lmm_render_stats;

/* Every option "not given", mode reference, no callbacks. */
void lmm_render_options_init(lmm_render_options *opt);

/* Sets option `key` (the field's name: "mode", "scheme", "spp",
 * "mesh_step", ...; booleans take "0"/"1"/"true"/"false") from text,
 * checking its limits or choices: SH_ERR_ARG with a message naming the
 * key, the allowed values and what was given. */
sh_status lmm_render_options_set(lmm_render_options *opt, const char *key,
                                 const char *value, sh_error *err);

/* The names an option takes (NULL-terminated: "mode", "scheme",
 * "volume"), or NULL for an option that takes a number. */
const char *const *lmm_render_option_choices(const char *key);

/* The checks that need no scene: an option given where it does not apply
 * is refused (SH_ERR_ARG), not ignored. refined and caustic_rays need mode
 * lmm and scheme refract-both (when a scheme is given; lmm_render checks
 * the scene's); mesh_step, kl and volume exact need mode lmm; area_radius
 * needs mode whitted; area_samples needs area_radius. The error's key
 * (sh_error_key) is the option, and the message names options by key and
 * value ("area_radius needs mode whitted"), so that a command line can put
 * its own names in their place (sh_cli_option_names). lmm_render makes
 * these checks too. */
sh_status lmm_render_options_check(const lmm_render_options *opt,
                                   sh_error *err);

/* Renders `scene` into rgb: width * height * 3 floats (the camera's size,
 * or the crop's when one is given), linear radiance, rows from the top. A
 * crop outside the image is SH_ERR_ARG (sh_crop_check). `stats` may be NULL. On error (and
 * on cancel) rgb is left as it was, and everything the call made is
 * freed. */
sh_status lmm_render(const sh_scene *scene, const lmm_render_options *opt,
                     float *rgb, lmm_render_stats *stats, sh_error *err);

/* Writes the statistics as a JSON object into buf (size bytes, NUL
 * terminated, cut short if too small) and returns the length the whole
 * text needs, as snprintf does (0 if out of memory). */
size_t lmm_render_stats_json(const lmm_render_stats *stats, char *buf,
                             size_t size);

/* For bindings that keep the structs opaque: options on the heap (set by
 * name; callbacks with lmm_render_options_set_callbacks), and the size of
 * a stats buffer. */
lmm_render_options *lmm_render_options_new(void);
void lmm_render_options_free(lmm_render_options *opt);
void lmm_render_options_set_callbacks(lmm_render_options *opt,
                                      void (*progress)(void *, long, long),
                                      void *progress_user,
                                      volatile int *cancel);
size_t lmm_render_stats_size(void);

#ifdef __cplusplus
}
#endif
#endif
