/* lmm_tracer: the project's ray tracer. In reference mode it is the ground
 * truth the other renderers are judged against; in whitted mode it is the
 * RRTA baseline of Debelov et al. 2008; in lmm mode it renders soft shadows
 * by the light meshes method. The command-line face of lmm_render.h: the
 * renderer's options are set by name (lmm_render_options_set), so their
 * limits and choices are the renderer's own. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lmm_render.h"
#include "sh_cli.h"
#include "sh_parse.h"
#include "sh_progress.h"

#define TOOL_NAME "lmm_tracer"
static const char *const TOOL = TOOL_NAME;

#define RENDERER(name, key, meta, text)                                       \
  {name, 0, SH_CLI_SETTER, meta, 0, 0, 0, 0, 0, 0, NULL, key, NULL, NULL, text}

/* The renderer's options go to lmm_render_options_set by name, checked
 * while parsing on a scratch set. */
static lmm_render_options scratch;
static sh_status set_option(void *target, const char *key, const char *value,
                            sh_error *err) {
  return lmm_render_options_set(target, key, value, err);
}

static const sh_cli_option options[] = {
    SH_CLI_RENDER_OPTIONS,
    RENDERER("mode", "mode", NULL,
             "reference (default): the converged reference renderer; "
             "whitted: the same tracer as the RRTA baseline; lmm: the light "
             "meshes method"),
    RENDERER("scheme", "scheme", NULL,
             "where refraction is followed (refract-both: lmm only; "
             "default: render.scheme, else refract-trace)"),
    {"local", 0, SH_CLI_SETTER, NULL, 0, 0, 0, 0, 0, 0, NULL, "local", "1",
     NULL, "formula 1: no mirror rays, no refraction"},
    RENDERER("mesh-step", "mesh_step", "H",
             "lmm: mesh step (default: render.mesh_step, else 1/100 of the "
             "shapes' diagonal)"),
    RENDERER("kl", "kl", "KL",
             "lmm: interpolation radius r = H * KL (default: render.kl, else "
             "2)"),
    RENDERER("caustic-rays", "caustic_rays", "N",
             "lmm, refract-both: rays per light and shape (default 200000)"),
    {"refined", 0, SH_CLI_SETTER, NULL, 0, 0, 0, 0, 0, 0, NULL, "refined", "1",
     NULL, "lmm, refract-both: the refined variant of section 5"},
    RENDERER("lmm-volume", "volume", NULL,
             "lmm with a medium: mesh (default) interpolates the volumetric "
             "shadows from the mesh; exact traces them"),
    RENDERER("area-radius", "area_radius", "R",
             "whitted: point and spot lights become spheres of radius R, "
             "sampled by shadow rays"),
    RENDERER("area-samples", "area_samples", "N",
             "whitted with --area-radius: shadow rays per light (default 16)"),
    RENDERER("spp", "spp", "N",
             "in-scattering samples per ray segment and light (default: the "
             "scene's render.spp, else 16)"),
    RENDERER("max-depth", "max_depth", "N",
             "reflection/refraction depth (default: render.max_depth, else "
             "5)"),
    RENDERER("seed", "seed", "S", "random seed (default: render.seed, else 0)"),
    RENDERER("threads", "threads", "N",
             "worker threads (default: one per CPU)"),
};

static const sh_cli_tool tool = {
    TOOL_NAME, "SCENE.json -o OUT.exr|OUT.png [options]",
    "Renders a scene (docs/scene-format.md) by Whitted ray tracing with "
    "single\nscattering in the medium; lmm mode softens shadows by the "
    "light meshes\nmethod (docs/lmm.md).",
    options, (int)(sizeof options / sizeof *options), 1, 1, NULL, NULL,
    set_option, &scratch, lmm_render_option_choices, NULL};

/* The settings a render used (the EXR header's shafts:settings). */
static char *settings_json(const lmm_render_stats *st, const sh_crop *crop) {
  static const char *const schemes[] = {"default", "straight", "refract-trace",
                                        "refract-both"};
  sh_stats *s = sh_stats_new();
  sh_stats_str(s, "scheme", schemes[st->scheme]);
  sh_stats_num(s, "width", st->width);
  sh_stats_num(s, "height", st->height);
  sh_stats_num(s, "spp", st->spp);
  sh_stats_num(s, "max_depth", st->max_depth);
  sh_stats_num(s, "seed", (double)st->seed);
  sh_stats_crop(s, crop);
  if (st->has_lmm) {
    sh_stats_num(s, "mesh_step", st->mesh_step);
    sh_stats_num(s, "kl", st->kl);
  }
  char *text = sh_stats_text(s);
  sh_stats_free(s);
  return text;
}

static const char *mode_name(lmm_mode mode) {
  return mode == LMM_MODE_REFERENCE ? "reference"
         : mode == LMM_MODE_LMM     ? "lmm"
                                    : "whitted";
}

/* The images (with their provenance) and the --stats record: lmm_render's
 * statistics with the tool and scene. */
static sh_status write_outputs(const sh_cli_render *r,
                               const sh_image *img, double exposure,
                               const lmm_render_stats *st, sh_error *err) {
  char *settings = settings_json(st, &r->crop);
  sh_status status = sh_cli_write_images(TOOL, r->files, &r->outputs, img,
                                         exposure,
                                         mode_name(st->mode), settings,
                                         r->scene, err);
  free(settings);
  if (status != SH_OK) return status;
  if (!r->stats) return sh_outputs_publish(r->files, err);
  size_t n = lmm_render_stats_json(st, NULL, 0);
  char *text = n ? malloc(n + 1) : NULL;
  if (!text) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  lmm_render_stats_json(st, text, n + 1);
  sh_stats *s = sh_stats_from_json(text);
  sh_stats_str(s, "tool", TOOL);
  sh_stats_str(s, "scene", r->scene);
  sh_stats_crop(s, &r->crop);
  status = sh_stats_write(s, r->files, r->stats, err);
  sh_stats_free(s);
  free(text);
  if (status == SH_OK) status = sh_outputs_publish(r->files, err);
  return status;
}

/* The reference is judged against at 1% (docs/validation.md): a noisier
 * reference measures its own noise. */
#define NOISE_WARNING 0.01

static void warn_noise(const lmm_render_stats *st) {
  if (st->mode != LMM_MODE_REFERENCE || st->trace.noise_rel_rms <= NOISE_WARNING)
    return;
  double ratio = st->trace.noise_rel_rms / (NOISE_WARNING / 2);
  fprintf(stderr,
          "%s: warning: this reference's own noise is about %.2g%% (relative "
          "RMS, estimated from %ld pixels rendered twice); errors measured "
          "against it below about that level are its noise; --spp %.0f "
          "brings it to %.2g%% or less (it falls at least as 1/sqrt(spp))\n",
          TOOL, 100 * st->trace.noise_rel_rms, st->trace.noise_pixels,
          ceil(st->spp * ratio * ratio), 100 * NOISE_WARNING / 2);
}

/* An error about the renderer's options, which name them by key
 * ("area_radius needs mode whitted"), with the command line's names
 * ("--area-radius needs --mode whitted"). */
static int report_options(sh_error *err) {
  char *text = sh_cli_option_names(&tool, err->message);
  sh_cli_error(TOOL, "%s", text ? text : err->message);
  free(text);
  sh_error_clear(err);
  return SH_EXIT_BAD_INPUT;
}

int main(int argc, char **argv) {
  sh_error err = SH_ERROR_INIT;
  lmm_render_options opt;
  lmm_render_options_init(&opt);
  lmm_render_options_init(&scratch);
  sh_cli_render r;
  sh_cli_args parsed;
  sh_scene *scene;
  int rc = sh_cli_render_start(&tool, argc, argv, &r, &parsed, &scene);
  if (rc >= 0) return rc;
  if (lmm_render_options_check(&scratch, &err) != SH_OK) {
    report_options(&err);
    sh_cli_render_free(&r);
    sh_scene_free(scene);
    return SH_EXIT_BAD_INPUT;
  }
  sh_cli_apply(&tool, &parsed, &opt, &err); /* checked on scratch */
  sh_error_clear(&err);
  opt.crop = r.crop;
  double exposure = sh_cli_render_exposure(&r, scene);

  sh_progress bar;
  sh_progress_init(&bar, opt.mode == LMM_MODE_REFERENCE ? "reference" : "render",
                   !r.quiet);
  opt.progress = sh_progress_update;
  opt.progress_user = &bar;
  sh_image img = {0};
  lmm_render_stats st;
  sh_crop win = sh_crop_window(&r.crop, &scene->camera);
  sh_status status =
      sh_image_alloc(&img, win.x1 - win.x0, win.y1 - win.y0, &err);
  if (status == SH_OK) status = lmm_render(scene, &opt, img.rgb, &st, &err);
  sh_progress_finish(&bar);
  if (status == SH_OK)
    status = write_outputs(&r, &img, exposure, &st, &err);
  rc = SH_EXIT_OK;
  if (status == SH_ERR_ARG && !err.file[0] && err.path[0]) {
    /* An error about the options (the key is an option's): in the
     * command line's names. */
    rc = report_options(&err);
  } else if (status != SH_OK) {
    rc = sh_cli_report(TOOL, &err);
  } else {
    if (!r.quiet) warn_noise(&st);
    sh_cli_render_done(TOOL, &r, img.width, img.height, st.seconds, NULL);
  }
  sh_image_free(&img);
  sh_cli_render_free(&r);
  sh_scene_free(scene);
  return rc;
}
