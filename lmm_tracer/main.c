/* lmm_tracer: the project's ray tracer. In reference mode it is the ground
 * truth the other renderers are judged against; in whitted mode it is the
 * RRTA baseline of Debelov et al. 2008; in lmm mode it renders soft shadows
 * by the light meshes method. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lmm_render.h"
#include "sh_cli.h"
#include "sh_file.h"
#include "sh_image.h"
#include "sh_parse.h"
#include "sh_progress.h"

static const char *const TOOL = "lmm_tracer";

static void usage(FILE *f) {
  fprintf(f,
"usage: lmm_tracer SCENE.json -o OUT.exr|OUT.png [options]\n"
"\n"
"Renders a scene (docs/scene-format.md) by Whitted ray tracing with single\n"
"scattering in the medium; lmm mode softens shadows by the light meshes\n"
"method (docs/lmm.md).\n"
"\n"
"options:\n"
"  -o, --output FILE   output image: .exr (linear 32-bit float radiance) or\n"
"                      .png (sRGB of radiance * 2^exposure, clamped);\n"
"                      repeat to write several formats from one render\n"
"  --mode MODE         reference (default): the converged reference renderer;\n"
"                      whitted: the same tracer as the RRTA baseline;\n"
"                      lmm: the light meshes method\n"
"  --scheme S          straight | refract-trace (default) | refract-both:\n"
"                      where refraction is followed (refract-both: lmm only)\n"
"  --local             formula 1: no mirror rays, no refraction\n"
"  --mesh-step H       lmm: mesh step (default: render.mesh_step, else 1/100\n"
"                      of the shapes' diagonal)\n"
"  --kl KL             lmm: interpolation radius r = H * KL (default 2)\n"
"  --caustic-rays N    lmm, refract-both: rays per light and shape (200000)\n"
"  --refined           lmm, refract-both: the refined variant of section 5\n"
"  --lmm-volume M      lmm with a medium: mesh (default) interpolates the\n"
"                      volumetric shadows from the mesh; exact traces them\n"
"  --area-radius R     whitted: point and spot lights become spheres of\n"
"                      radius R, sampled by shadow rays\n"
"  --area-samples N    whitted with --area-radius: shadow rays per light (16)\n"
"  --spp N             in-scattering samples per ray segment and light\n"
"                      (default: the scene's render.spp, else 16)\n"
"  --max-depth N       reflection/refraction depth (default: render.max_depth, else 5)\n"
"  --seed S            random seed (default: render.seed, else 0)\n"
"  --threads N         worker threads (default: one per CPU)\n"
"  --exposure E        PNG exposure in stops (default: render.exposure, else 0)\n"
"  --stats FILE.json   write time, rays, samples and method statistics\n"
"  -q, --quiet         no progress bar\n"
"  -h, --help          show this help\n"
"\n"
"Exit status: 0 on success, 2 for bad input (arguments, scene), 1 otherwise.\n");
}

#define MAX_OUTPUTS 8

typedef struct args {
  const char *scene, *stats;
  const char *outputs[MAX_OUTPUTS];
  int noutputs;
  int quiet, has_exposure;
  double exposure;
  lmm_render_options render;
} args;

/* The command line's value options and the lmm_render option each sets
 * (its limits and choices are lmm_render_options_set's). */
static const char *const value_options[][2] = {
    {"--mode", "mode"},
    {"--scheme", "scheme"},
    {"--lmm-volume", "volume"},
    {"--mesh-step", "mesh_step"},
    {"--kl", "kl"},
    {"--caustic-rays", "caustic_rays"},
    {"--area-radius", "area_radius"},
    {"--area-samples", "area_samples"},
    {"--spp", "spp"},
    {"--max-depth", "max_depth"},
    {"--seed", "seed"},
    {"--threads", "threads"},
};

static const char *render_key(const char *flag) {
  for (size_t i = 0; i < sizeof value_options / sizeof *value_options; i++)
    if (!strcmp(flag, value_options[i][0])) return value_options[i][1];
  return NULL;
}

/* Returns -1 to go on, else an exit status. */
static int parse_args(int argc, char **argv, args *a) {
  sh_error err;
  memset(a, 0, sizeof *a);
  lmm_render_options_init(&a->render);
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
    const char *v = i + 1 < argc ? argv[i + 1] : NULL;
    const char *key = render_key(o);
    if (!strcmp(o, "-h") || !strcmp(o, "--help")) {
      usage(stdout);
      return 0;
    } else if (!strcmp(o, "-q") || !strcmp(o, "--quiet")) {
      a->quiet = 1;
      continue;
    } else if (!strcmp(o, "--local") || !strcmp(o, "--refined")) {
      lmm_render_options_set(&a->render, o + 2, "1", NULL);
      continue;
    } else if (o[0] == '-' && o[1] != '\0' && !v) {
      fprintf(stderr, "%s: %s needs a value\n", TOOL, o);
      return 2;
    } else if (key) {
      if (lmm_render_options_set(&a->render, key, v, &err) != SH_OK) {
        fprintf(stderr, "%s: %s: %s\n", TOOL, o, err.message);
        return 2;
      }
    } else if (!strcmp(o, "-o") || !strcmp(o, "--output")) {
      if (a->noutputs == MAX_OUTPUTS) {
        fprintf(stderr, "%s: at most %d outputs\n", TOOL, MAX_OUTPUTS);
        return 2;
      }
      a->outputs[a->noutputs++] = v;
    } else if (!strcmp(o, "--stats")) {
      a->stats = v;
    } else if (!strcmp(o, "--exposure")) {
      if (!sh_cli_double(TOOL, o, v, &a->exposure)) return 2;
      a->has_exposure = 1;
    } else {
      const char **operands[] = {&a->scene};
      if (!sh_cli_operand(TOOL, o, operands, 1)) return 2;
      continue;
    }
    i++;
  }
  if (!sh_cli_check_render_outputs(TOOL, a->scene, a->outputs, a->noutputs))
    return 2;
  if (lmm_render_options_check(&a->render, &err) != SH_OK) {
    fprintf(stderr, "%s: %s\n", TOOL, err.message);
    return 2;
  }
  return -1;
}

/* The --stats file: lmm_render's statistics with the tool and scene. */
static sh_status write_stats(const args *a, const lmm_render_stats *st,
                             sh_error *err) {
  size_t n = lmm_render_stats_json(st, NULL, 0);
  char *text = n ? malloc(n + 1) : NULL;
  if (text) lmm_render_stats_json(st, text, n + 1);
  sh_stats *s = sh_stats_from_json(text);
  free(text);
  sh_stats_str(s, "tool", TOOL);
  sh_stats_str(s, "scene", a->scene);
  sh_status status = sh_stats_write(s, a->stats, err);
  sh_stats_free(s);
  return status;
}

int main(int argc, char **argv) {
  args a;
  int rc = parse_args(argc, argv, &a);
  if (rc >= 0) return rc;
  rc = 0;

  sh_error err;
  sh_scene *scene = NULL;
  if (sh_scene_load(a.scene, &scene, &err) != SH_OK)
    return sh_cli_report(TOOL, &err);
  if (scene->nlights == 0 && !a.quiet)
    fprintf(stderr, "%s: warning: the scene has no lights; the image is "
                    "black but for emission and background\n", TOOL);
  double exposure = a.has_exposure ? a.exposure : scene->render.exposure;

  sh_progress bar;
  sh_progress_init(&bar,
                   a.render.mode == LMM_MODE_REFERENCE ? "reference" : "render",
                   !a.quiet);
  a.render.progress = sh_progress_update;
  a.render.progress_user = &bar;
  sh_image img = {0};
  lmm_render_stats st;
  sh_status status =
      sh_image_alloc(&img, scene->camera.width, scene->camera.height, &err);
  if (status == SH_OK) status = lmm_render(scene, &a.render, img.rgb, &st, &err);
  sh_progress_finish(&bar);
  for (int k = 0; status == SH_OK && k < a.noutputs; k++)
    status = sh_image_write(a.outputs[k], &img, exposure, &err);
  if (status == SH_OK && a.stats) status = write_stats(&a, &st, &err);
  if (status != SH_OK) rc = sh_cli_report(TOOL, &err);
  if (rc == 0 && !a.quiet)
    for (int k = 0; k < a.noutputs; k++)
      fprintf(stderr, "%s: wrote %s (%dx%d, rendered in %.2f s)\n", TOOL,
              a.outputs[k], img.width, img.height, st.seconds);
  sh_image_free(&img);
  sh_scene_free(scene);
  return rc;
}
