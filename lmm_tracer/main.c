/* lmm_tracer: the project's ray tracer. In reference mode it is the ground
 * truth the other renderers are judged against. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_cli.h"
#include "sh_file.h"
#include "sh_image.h"
#include "sh_parse.h"
#include "sh_reference.h"

static const char *const TOOL = "lmm_tracer";

static void usage(FILE *f) {
  fprintf(f,
"usage: lmm_tracer SCENE.json -o OUT.exr|OUT.png [options]\n"
"\n"
"Renders a scene (docs/scene-format.md) by Whitted ray tracing with single\n"
"scattering in the medium.\n"
"\n"
"options:\n"
"  -o, --output FILE   output image: .exr (linear 32-bit float radiance) or\n"
"                      .png (sRGB of radiance * 2^exposure, clamped);\n"
"                      repeat to write several formats from one render\n"
"  --mode MODE         reference (default): the converged reference renderer\n"
"  --spp N             in-scattering samples per ray segment and light\n"
"                      (default: the scene's render.spp, else 16)\n"
"  --max-depth N       reflection/refraction depth (default: render.max_depth, else 5)\n"
"  --seed S            random seed (default: render.seed, else 0)\n"
"  --threads N         worker threads (default: one per CPU)\n"
"  --exposure E        PNG exposure in stops (default: render.exposure, else 0)\n"
"  --stats FILE.json   write time, rays and samples as JSON\n"
"  -q, --quiet         no progress bar\n"
"  -h, --help          show this help\n"
"\n"
"Exit status: 0 on success, 2 for bad input (arguments, scene), 1 otherwise.\n");
}

#define MAX_OUTPUTS 8

typedef struct args {
  const char *scene, *stats, *mode;
  const char *outputs[MAX_OUTPUTS];
  int noutputs;
  long spp, max_depth, seed, threads;
  double exposure;
  int has_exposure, quiet;
} args;

/* Returns -1 to go on, else an exit status. */
static int parse_args(int argc, char **argv, args *a) {
  memset(a, 0, sizeof *a);
  a->spp = a->max_depth = a->seed = -1;
  a->mode = "reference";
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
    const char *v = i + 1 < argc ? argv[i + 1] : NULL;
    int ok = 1;
    if (!strcmp(o, "-h") || !strcmp(o, "--help")) {
      usage(stdout);
      return 0;
    } else if (!strcmp(o, "-q") || !strcmp(o, "--quiet")) {
      a->quiet = 1;
      continue;
    } else if (o[0] == '-' && o[1] != '\0' && !v) {
      fprintf(stderr, "%s: %s needs a value\n", TOOL, o);
      return 2;
    } else if (!strcmp(o, "-o") || !strcmp(o, "--output")) {
      if (a->noutputs == MAX_OUTPUTS) {
        fprintf(stderr, "%s: at most %d outputs\n", TOOL, MAX_OUTPUTS);
        return 2;
      }
      a->outputs[a->noutputs++] = v;
    } else if (!strcmp(o, "--stats")) {
      a->stats = v;
    } else if (!strcmp(o, "--mode")) {
      a->mode = v;
    } else if (!strcmp(o, "--spp")) {
      ok = sh_cli_int(TOOL, o, v, 1, 1 << 24, &a->spp);
    } else if (!strcmp(o, "--max-depth")) {
      ok = sh_cli_int(TOOL, o, v, 0, 64, &a->max_depth);
    } else if (!strcmp(o, "--seed")) {
      ok = sh_cli_int(TOOL, o, v, 0, 2147483647L, &a->seed);
    } else if (!strcmp(o, "--threads")) {
      ok = sh_cli_int(TOOL, o, v, 0, 1024, &a->threads);
    } else if (!strcmp(o, "--exposure")) {
      ok = sh_cli_double(TOOL, o, v, &a->exposure);
      a->has_exposure = 1;
    } else if (o[0] == '-' && o[1] != '\0') {
      fprintf(stderr, "%s: unknown option '%s' (see --help)\n", TOOL, o);
      return 2;
    } else if (!a->scene) {
      a->scene = o;
      continue;
    } else {
      fprintf(stderr, "%s: unexpected argument '%s' (see --help)\n", TOOL, o);
      return 2;
    }
    if (!ok) return 2;
    i++;
  }
  if (!a->scene || !a->noutputs) {
    fprintf(stderr, "%s: need a scene file and -o OUTPUT (see --help)\n", TOOL);
    return 2;
  }
  for (int k = 0; k < a->noutputs; k++) {
    char ext[16];
    sh_file_extension(a->outputs[k], ext, sizeof ext);
    if (strcmp(ext, "exr") && strcmp(ext, "png")) {
      fprintf(stderr, "%s: output '%s' must end in .exr or .png\n", TOOL,
              a->outputs[k]);
      return 2;
    }
  }
  if (strcmp(a->mode, "reference")) {
    fprintf(stderr, "%s: unknown --mode '%s'; this version has: reference\n",
            TOOL, a->mode);
    return 2;
  }
  return -1;
}

int main(int argc, char **argv) {
  args a;
  int rc = parse_args(argc, argv, &a);
  if (rc >= 0) return rc;

  sh_error err;
  sh_scene *scene = NULL;
  if (sh_scene_load(a.scene, &scene, &err) != SH_OK)
    return sh_cli_report(TOOL, &err);
  if (scene->nlights == 0 && !a.quiet)
    fprintf(stderr, "%s: warning: the scene has no lights; the image is "
                    "black but for emission and background\n", TOOL);

  sh_reference_options opt = sh_reference_defaults(scene);
  if (a.spp > 0) opt.spp = (int)a.spp;
  if (a.max_depth >= 0) opt.max_depth = (int)a.max_depth;
  if (a.seed >= 0) opt.seed = (uint64_t)a.seed;
  opt.threads = (int)a.threads;
  opt.progress = !a.quiet;
  double exposure = a.has_exposure ? a.exposure : scene->render.exposure;

  sh_image img = {0};
  sh_reference_stats st;
  rc = 0;
  sh_status status = sh_render_reference(scene, &opt, &img, &st, &err);
  for (int k = 0; status == SH_OK && k < a.noutputs; k++)
    status = sh_image_write(a.outputs[k], &img, exposure, &err);
  if (status != SH_OK) {
    rc = sh_cli_report(TOOL, &err);
  } else if (a.stats) {
    sh_stats *s = sh_stats_new();
    sh_stats_str(s, "tool", TOOL);
    sh_stats_str(s, "mode", a.mode);
    sh_stats_str(s, "scene", a.scene);
    sh_stats_num(s, "width", img.width);
    sh_stats_num(s, "height", img.height);
    sh_stats_num(s, "spp", opt.spp);
    sh_stats_num(s, "max_depth", opt.max_depth);
    sh_stats_num(s, "seed", (double)opt.seed);
    sh_stats_num(s, "threads", st.threads);
    sh_stats_num(s, "seconds", st.seconds);
    sh_stats_num(s, "camera_rays", (double)st.camera_rays);
    sh_stats_num(s, "closest_rays", (double)st.closest_rays);
    sh_stats_num(s, "occlusion_rays", (double)st.occlusion_rays);
    sh_stats_num(s, "medium_samples", (double)st.medium_samples);
    if (sh_stats_write(s, a.stats, &err) != SH_OK)
      rc = sh_cli_report(TOOL, &err);
    sh_stats_free(s);
  }
  if (rc == 0 && !a.quiet)
    for (int k = 0; k < a.noutputs; k++)
      fprintf(stderr, "%s: wrote %s (%dx%d, rendered in %.2f s)\n", TOOL,
              a.outputs[k], img.width, img.height, st.seconds);
  sh_image_free(&img);
  sh_scene_free(scene);
  return rc;
}
