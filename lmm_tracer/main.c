/* lmm_tracer: the project's ray tracer. In reference mode it is the ground
 * truth the other renderers are judged against; in whitted mode it is the
 * RRTA baseline of Debelov et al. 2008; in lmm mode it renders soft shadows
 * by the light meshes method. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lmm_area.h"
#include "lmm_method.h"
#include "sh_cli.h"
#include "sh_file.h"
#include "sh_image.h"
#include "sh_parse.h"
#include "sh_progress.h"
#include "sh_reference.h"

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

enum { MODE_REFERENCE, MODE_WHITTED, MODE_LMM };
static const char *const mode_names[] = {"reference", "whitted", "lmm", NULL};
static const char *const scheme_names[] = {"default", "straight",
                                           "refract-trace", "refract-both",
                                           NULL};

typedef struct args {
  const char *scene, *stats;
  const char *outputs[MAX_OUTPUTS];
  int noutputs;
  int mode, scheme, local, quiet, has_exposure, volume_exact, refined;
  long spp, max_depth, seed, threads, caustic_rays, area_samples;
  double exposure, mesh_step, kl, area_radius;
} args;

static int choice(const char *option, const char *v, const char *const *names,
                  int first, int *out) {
  for (int i = first; names[i]; i++)
    if (!strcmp(v, names[i])) {
      *out = i;
      return 1;
    }
  fprintf(stderr, "%s: %s: unknown value '%s'; expected one of:", TOOL, option,
          v);
  for (int i = first; names[i]; i++) fprintf(stderr, " %s", names[i]);
  fprintf(stderr, "\n");
  return 0;
}

static int positive(const char *option, const char *v, double *out) {
  if (!sh_cli_double(TOOL, option, v, out)) return 0;
  if (*out > 0) return 1;
  fprintf(stderr, "%s: %s expects a number > 0, got '%s'\n", TOOL, option, v);
  return 0;
}

/* Returns -1 to go on, else an exit status. */
static int parse_args(int argc, char **argv, args *a) {
  memset(a, 0, sizeof *a);
  a->spp = a->max_depth = a->seed = a->caustic_rays = a->area_samples = -1;
  a->area_radius = -1;
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
    } else if (!strcmp(o, "--local")) {
      a->local = 1;
      continue;
    } else if (!strcmp(o, "--refined")) {
      a->refined = 1;
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
      ok = choice(o, v, mode_names, 0, &a->mode);
    } else if (!strcmp(o, "--scheme")) {
      ok = choice(o, v, scheme_names, 1, &a->scheme);
    } else if (!strcmp(o, "--lmm-volume")) {
      static const char *const vols[] = {"mesh", "exact", NULL};
      ok = choice(o, v, vols, 0, &a->volume_exact);
    } else if (!strcmp(o, "--mesh-step")) {
      ok = positive(o, v, &a->mesh_step);
    } else if (!strcmp(o, "--kl")) {
      ok = positive(o, v, &a->kl);
    } else if (!strcmp(o, "--area-radius")) {
      ok = sh_cli_double(TOOL, o, v, &a->area_radius) && a->area_radius >= 0;
      if (!ok) fprintf(stderr, "%s: %s expects a number >= 0\n", TOOL, o);
    } else if (!strcmp(o, "--area-samples")) {
      ok = sh_cli_int(TOOL, o, v, 1, 1 << 20, &a->area_samples);
    } else if (!strcmp(o, "--caustic-rays")) {
      ok = sh_cli_int(TOOL, o, v, 1, 1L << 40, &a->caustic_rays);
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
    } else {
      const char **operands[] = {&a->scene};
      if (!sh_cli_operand(TOOL, o, operands, 1)) return 2;
      continue;
    }
    if (!ok) return 2;
    i++;
  }
  if (!sh_cli_check_render_outputs(TOOL, a->scene, a->outputs, a->noutputs))
    return 2;
  if (a->refined && a->mode != MODE_LMM) {
    fprintf(stderr, "%s: --refined needs --mode lmm --scheme refract-both\n",
            TOOL);
    return 2;
  }
  if (a->area_radius >= 0 && a->mode != MODE_WHITTED) {
    fprintf(stderr, "%s: --area-radius needs --mode whitted\n", TOOL);
    return 2;
  }
  return -1;
}

static void write_stats(const args *a, const sh_reference_options *opt,
                        const sh_image *img, const sh_reference_stats *st,
                        const lmm *method, sh_lmm_scheme scheme, double h,
                        double kl, sh_error *err, int *rc) {
  sh_stats *s = sh_stats_new();
  sh_stats_str(s, "tool", TOOL);
  sh_stats_str(s, "mode", mode_names[a->mode]);
  sh_stats_str(s, "scheme", scheme_names[scheme]);
  sh_stats_str(s, "scene", a->scene);
  sh_stats_num(s, "width", img->width);
  sh_stats_num(s, "height", img->height);
  sh_stats_num(s, "spp", opt->spp);
  sh_stats_num(s, "max_depth", opt->max_depth);
  sh_stats_num(s, "seed", (double)opt->seed);
  sh_stats_num(s, "threads", st->threads);
  sh_stats_num(s, "seconds", st->seconds);
  sh_stats_num(s, "camera_rays", (double)st->camera_rays);
  sh_stats_num(s, "closest_rays", (double)st->closest_rays);
  sh_stats_num(s, "occlusion_rays", (double)st->occlusion_rays);
  sh_stats_num(s, "medium_samples", (double)st->medium_samples);
  if (method) {
    lmm_stats ls;
    lmm_get_stats(method, &ls);
    sh_stats_num(s, "mesh_step", h);
    sh_stats_num(s, "kl", kl);
    sh_stats_num(s, "mesh_points_total", (double)ls.mesh.points_total);
    sh_stats_num(s, "mesh_points_computed", (double)ls.mesh.points_computed);
    sh_stats_num(s, "mesh_points_uncached", (double)ls.mesh.points_uncached);
    sh_stats_num(s, "mesh_fraction_computed",
                 ls.mesh.points_total
                     ? (double)ls.mesh.points_computed / ls.mesh.points_total
                     : 0.0);
    sh_stats_str(s, "mesh_storage", ls.mesh.bits ? "bits" : "floats");
    sh_stats_num(s, "shaded_points", (double)ls.shaded_points);
    sh_stats_num(s, "empty_sets", (double)ls.empty_sets);
    sh_stats_num(s, "candidate_rays", (double)ls.candidate_rays);
    sh_stats_num(s, "volume_lookups", (double)ls.volume_lookups);
    sh_stats_num(s, "caustic_points", (double)ls.caustic_points);
    sh_stats_num(s, "caustic_seconds", ls.build_seconds);
  }
  if (sh_stats_write(s, a->stats, err) != SH_OK) *rc = sh_cli_report(TOOL, err);
  sh_stats_free(s);
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

  sh_reference_options opt = sh_reference_defaults(scene);
  if (a.spp > 0) opt.spp = (int)a.spp;
  if (a.max_depth >= 0) opt.max_depth = (int)a.max_depth;
  if (a.seed >= 0) opt.seed = (uint64_t)a.seed;
  opt.threads = sh_reference_threads((int)a.threads);
  opt.local = a.local;
  sh_lmm_scheme scheme = a.scheme ? (sh_lmm_scheme)a.scheme
                                  : scene->render.scheme;
  if (scheme == SH_SCHEME_DEFAULT) scheme = SH_SCHEME_REFRACT_TRACE;
  opt.refract = scheme != SH_SCHEME_STRAIGHT;
  double exposure = a.has_exposure ? a.exposure : scene->render.exposure;
  double h = a.mesh_step > 0 ? a.mesh_step
             : scene->render.mesh_step > 0 ? scene->render.mesh_step
                                           : lmm_default_step(scene);
  double kl = a.kl > 0 ? a.kl : scene->render.kl > 0 ? scene->render.kl : 2.0;

  sh_rt *rt = NULL;
  lmm *method = NULL;
  lmm_area *area = NULL;
  sh_image img = {0};
  sh_reference_stats st;
  sh_status status = SH_OK;
  if (a.refined && scheme != SH_SCHEME_REFRACT_BOTH)
    status = sh_error_set(&err, SH_ERR_ARG,
                          "--refined is a variant of the refract-both scheme");
  else if (scheme == SH_SCHEME_REFRACT_BOTH && a.mode != MODE_LMM)
    status = sh_error_set(&err, SH_ERR_ARG,
                          "the refract-both scheme needs --mode lmm: "
                          "refracted visibility comes from the light mesh");
  if (status == SH_OK) status = sh_rt_create(scene, &rt, &err);
  if (status == SH_OK && a.mode == MODE_LMM) {
    lmm_options lo;
    memset(&lo, 0, sizeof lo);
    lo.h = h;
    lo.kl = kl;
    lo.scheme = scheme;
    lo.caustic_rays = a.caustic_rays > 0 ? a.caustic_rays : 200000;
    lo.volume = !a.volume_exact;
    lo.refined = a.refined;
    status = lmm_create(scene, rt, &lo, opt.threads, &method, &err);
    if (status == SH_OK) opt.hook = lmm_hook(method);
  } else if (status == SH_OK && a.area_radius >= 0) {
    status = lmm_area_create(scene, rt, a.area_radius,
                             a.area_samples > 0 ? (int)a.area_samples : 16,
                             &area, &err);
    if (status == SH_OK) opt.hook = lmm_area_hook(area);
  }
  opt.rt = rt;
  sh_progress bar;
  sh_progress_init(&bar, a.mode == MODE_REFERENCE ? "reference" : "render",
                   !a.quiet);
  opt.progress = sh_progress_update;
  opt.progress_user = &bar;
  if (status == SH_OK)
    status = sh_render_reference(scene, &opt, &img, &st, &err);
  sh_progress_finish(&bar);
  for (int k = 0; status == SH_OK && k < a.noutputs; k++)
    status = sh_image_write(a.outputs[k], &img, exposure, &err);
  if (status != SH_OK)
    rc = sh_cli_report(TOOL, &err);
  else if (a.stats)
    write_stats(&a, &opt, &img, &st, method, scheme, h, kl, &err, &rc);
  if (rc == 0 && !a.quiet)
    for (int k = 0; k < a.noutputs; k++)
      fprintf(stderr, "%s: wrote %s (%dx%d, rendered in %.2f s)\n", TOOL,
              a.outputs[k], img.width, img.height, st.seconds);
  sh_image_free(&img);
  lmm_free(method);
  lmm_area_free(area);
  sh_rt_free(rt);
  sh_scene_free(scene);
  return rc;
}
