/* gl_shafts_bench: renders scenes in-process and reports time per frame
 * (the GL context and scene upload counted apart, after a warm-up frame),
 * where the time goes, and the error against the converged reference
 * renderer, as a Markdown table. With --sweep-planes or --sweep-lattice it
 * measures how error and time move with the number of planes and lattice
 * points (the seed's figures 5 and 6). bench.sh runs the standard set. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "gs_render.h"
#include "sh_cli.h"
#include "sh_compare.h"
#include "sh_file.h"
#include "sh_image.h"
#include "sh_parse.h"
#include "sh_progress.h"
#include "sh_reference.h"

static const char *const TOOL = "gl_shafts_bench";

static void usage(FILE *f) {
  fprintf(f,
"usage: gl_shafts_bench [options] SCENE.json...\n"
"\n"
"options:\n"
"  --size W H            render at W x H instead of the scene's size\n"
"  --frames N            timed frames after one warm-up frame (default 5)\n"
"  --ref-spp N           reference samples (default 1024); 0: no error column\n"
"  --cache DIR           where references are kept (default: .)\n"
"  --planes N, --lattice NU NV, --xi lattice|exact, --jitter, --no-jitter,\n"
"  --shadow-map-res S, --light-map-res R, --sub-angle DEG, --sub-texels T\n"
"                        as gl_shafts (default: its defaults)\n"
"  --backend auto|egl|osmesa  the GL context's backend (default auto)\n"
"  --sweep-planes LIST   comma-separated plane counts to measure in turn\n"
"  --sweep-lattice LIST  comma-separated lattice sizes (n for n x n)\n"
"  --sweep-xi            measure both xi lattice and xi exact\n"
"  --diff DIR            write each render and its difference to the reference\n"
"  --compare A B         only print the error of image A against reference B\n");
}

typedef struct config {
  long planes, lu, lv, smres, lmres;
  double sub_angle, sub_texels;
  sh_xi_mode xi;
  int jitter;
  gs_backend backend;
} config;

static int parse_list(const char *s, long *out, int max) {
  int n = 0;
  while (*s && n < max) {
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || v < 1) return -1;
    out[n++] = v;
    s = *end == ',' ? end + 1 : end;
    if (*end && *end != ',') return -1;
  }
  return n;
}

/* FNV-1a of a file's bytes (0 if it cannot be read): names the cached
 * references, so that an edited scene gets a new one. */
static unsigned long long file_hash(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  unsigned long long h = 1469598103934665603ULL;
  int c;
  while ((c = fgetc(f)) != EOF) h = (h ^ (unsigned)c) * 1099511628211ULL;
  fclose(f);
  return h;
}

/* The reference at the scene's (overridden) size: from the cache, or
 * rendered and cached. */
static sh_status reference(const sh_scene *scene, const char *path, int spp,
                           const char *cache, sh_image *ref, sh_error *err) {
  const char *base = strrchr(path, '/');
  base = base ? base + 1 : path;
  char name[1024];
  snprintf(name, sizeof name, "%s/%.*s_%dx%d_spp%d_%016llx.exr", cache,
           (int)(strlen(base) > 5 ? strlen(base) - 5 : strlen(base)), base,
           scene->camera.width, scene->camera.height, spp, file_hash(path));
  if (sh_image_read(name, ref, NULL) == SH_OK) return SH_OK;
  fprintf(stderr, "%s: rendering the reference %s (%d spp)...\n", TOOL, name, spp);
  sh_reference_options opt = sh_reference_defaults(scene);
  opt.spp = spp;
  sh_progress bar;
  sh_progress_init(&bar, "reference", 1);
  opt.progress = sh_progress_update;
  opt.progress_user = &bar;
  sh_status st = sh_render_reference(scene, &opt, ref, NULL, err);
  sh_progress_finish(&bar);
  if (st == SH_OK) st = sh_image_write(name, ref, 0, err);
  return st;
}

static sh_status run(const char *path, sh_scene *scene, const config *c,
                     int frames, const sh_image *ref, const char *diffdir,
                     sh_error *err) {
  gs_options o = gs_options_defaults(scene);
  if (c->planes) o.planes = (int)c->planes;
  if (c->lu) o.lattice_u = (int)c->lu, o.lattice_v = (int)c->lv;
  if (c->smres) o.shadow_map_res = (int)c->smres;
  if (c->lmres) o.light_map_res = (int)c->lmres;
  if (c->xi != SH_XI_DEFAULT) o.xi = c->xi;
  if (c->jitter >= 0) o.jitter = c->jitter;
  if (c->sub_angle > 0) o.sub_angle_deg = c->sub_angle;
  if (c->sub_texels > 0) o.sub_texels = c->sub_texels;
  o.backend = c->backend;
  double t0 = sh_seconds();
  gs_renderer *r = NULL;
  sh_status st = gs_renderer_create(scene, &o, &r, err);
  if (st != SH_OK) return st;
  double setup = sh_seconds() - t0;
  sh_image img = {0};
  st = sh_image_alloc(&img, scene->camera.width, scene->camera.height, err);
  gs_stats warm, *s = calloc((size_t)frames, sizeof *s);
  double *secs = calloc((size_t)frames, sizeof *secs);
  if (!s || !secs) st = sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  t0 = sh_seconds();
  if (st == SH_OK) st = gs_renderer_draw(r, img.rgb, &warm, err);
  double first = sh_seconds() - t0;
  double cpu0 = bench_cpu_seconds();
  CALLGRIND_START_INSTRUMENTATION;
  for (int i = 0; i < frames && st == SH_OK; i++) {
    st = gs_renderer_draw(r, img.rgb, &s[i], err);
    secs[i] = s[i].seconds;
  }
  CALLGRIND_STOP_INSTRUMENTATION;
  double cpu = (bench_cpu_seconds() - cpu0) / frames;
  if (st == SH_OK) {
    qsort(secs, (size_t)frames, sizeof *secs, bench_cmp_double);
    double med = secs[frames / 2], best = secs[0];
    /* The split of the median frame. */
    const gs_stats *m = &s[0];
    for (int i = 0; i < frames; i++)
      if (s[i].seconds == med) m = &s[i];
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    char err_col[64] = "", bias_col[64] = "";
    sh_image d = {0};
    if (ref) {
      sh_image_error e;
      st = sh_image_compare(&img, ref, 0.01, &e, diffdir ? &d : NULL, err);
      snprintf(err_col, sizeof err_col, "%.2f", 100 * e.rel_rms);
      snprintf(bias_col, sizeof bias_col, "%.2f", 100 * e.mean_rel);
    }
    printf("| %s | %dx%d | %d | %dx%d | %s%s | %g | %g | %.1f (%.1f) | %.1f | %.1f | %.1f "
           "| %.1f / %.1f / %.1f / %.1f / %.1f | %.2f | %s | %s | %s: %s (%s) |\n",
           base, img.width, img.height,
           scene->nlights ? gs_light_planes(&o, scene->lights[0].type) : o.planes,
           o.lattice_u, o.lattice_v, o.xi == SH_XI_EXACT ? "exact" : "lattice",
           o.jitter ? " +jitter" : "", o.sub_angle_deg, o.sub_texels, 1000 * best, 1000 * med,
           1000 * cpu, 1000 * (setup + first), 1000 * setup, 1000 * m->shadow_seconds,
           1000 * m->surface_seconds, 1000 * m->lattice_seconds,
           1000 * m->plane_seconds, 1000 * m->readback_seconds,
           m->fragments / 1e6, err_col, bias_col, m->backend, m->renderer, m->vendor);
    fflush(stdout);
    if (diffdir && ref && st == SH_OK) {
      char name[1024];
      snprintf(name, sizeof name, "%s/%.*s_p%d_l%d_%s.exr", diffdir,
               (int)strlen(base) - 5, base, o.planes, o.lattice_u,
               o.xi == SH_XI_EXACT ? "exact" : "lattice");
      st = sh_image_write(name, &img, 0, err);
      memcpy(name + strlen(name) - 4, "_dif.exr", 9);
      if (st == SH_OK) st = sh_image_write(name, &d, 0, err);
    }
    sh_image_free(&d);
  }
  free(s);
  free(secs);
  sh_image_free(&img);
  gs_renderer_free(r);
  return st;
}

int main(int argc, char **argv) {
  config base = {0, 0, 0, 0, 0, 0, 0, SH_XI_DEFAULT, -1, GS_BACKEND_AUTO};
  long w = 0, h = 0, frames = 5, spp = 1024;
  long sweep_p[32], sweep_l[32];
  int np = 0, nl = 0, sweep_xi = 0;
  const char *cache = ".", *diffdir = NULL;
  const char *scenes[64];
  int nscenes = 0;
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    const char *v2 = i + 2 < argc ? argv[i + 2] : NULL;
    int ok = 1;
    if (!strcmp(o, "-h") || !strcmp(o, "--help")) {
      usage(stdout);
      return 0;
    } else if (!strcmp(o, "--jitter") || !strcmp(o, "--no-jitter")) {
      base.jitter = !strcmp(o, "--jitter");
      continue;
    } else if (!strcmp(o, "--sweep-xi")) {
      sweep_xi = 1;
      continue;
    } else if (o[0] == '-' && !v) {
      fprintf(stderr, "%s: %s needs a value\n", TOOL, o);
      return 2;
    } else if (!strcmp(o, "--size")) {
      ok = sh_cli_int(TOOL, o, v, 1, 16384, &w) && sh_cli_int(TOOL, o, v2, 1, 16384, &h);
      i++;
    } else if (!strcmp(o, "--frames")) {
      ok = sh_cli_int(TOOL, o, v, 1, 10000, &frames);
    } else if (!strcmp(o, "--ref-spp")) {
      ok = sh_cli_int(TOOL, o, v, 0, 1 << 20, &spp);
    } else if (!strcmp(o, "--compare")) {
      sh_error err;
      sh_image a = {0}, b = {0};
      if (!v2) return 2;
      if (sh_image_read(v, &a, &err) != SH_OK || sh_image_read(v2, &b, &err) != SH_OK)
        return sh_cli_report(TOOL, &err);
      sh_image_error e;
      if (sh_image_compare(&a, &b, 0.01, &e, NULL, &err) != SH_OK)
        return sh_cli_report(TOOL, &err);
      printf("error %.3f %%, mean relative %.3f %%, %ld lit pixels\n",
             100 * e.rel_rms, 100 * e.mean_rel, e.lit_pixels);
      sh_image_free(&a);
      sh_image_free(&b);
      return 0;
    } else if (!strcmp(o, "--cache")) {
      cache = v;
    } else if (!strcmp(o, "--diff")) {
      diffdir = v;
    } else if (!strcmp(o, "--planes")) {
      ok = sh_cli_int(TOOL, o, v, 1, 100000, &base.planes);
    } else if (!strcmp(o, "--lattice")) {
      ok = sh_cli_int(TOOL, o, v, 2, 4096, &base.lu) &&
           sh_cli_int(TOOL, o, v2, 2, 4096, &base.lv);
      i++;
    } else if (!strcmp(o, "--shadow-map-res")) {
      ok = sh_cli_int(TOOL, o, v, 1, 16384, &base.smres);
    } else if (!strcmp(o, "--light-map-res")) {
      ok = sh_cli_int(TOOL, o, v, 1, 16384, &base.lmres);
    } else if (!strcmp(o, "--sub-texels")) {
      ok = sh_cli_double(TOOL, o, v, &base.sub_texels) && base.sub_texels > 0;
    } else if (!strcmp(o, "--sub-angle")) {
      ok = sh_cli_double(TOOL, o, v, &base.sub_angle) && base.sub_angle > 0;
    } else if (!strcmp(o, "--xi")) {
      base.xi = !strcmp(v, "exact") ? SH_XI_EXACT : SH_XI_LATTICE;
      ok = !strcmp(v, "exact") || !strcmp(v, "lattice");
    } else if (!strcmp(o, "--backend")) {
      ok = !strcmp(v, "auto") || !strcmp(v, "egl") || !strcmp(v, "osmesa");
      base.backend = !strcmp(v, "egl")      ? GS_BACKEND_EGL
                     : !strcmp(v, "osmesa") ? GS_BACKEND_OSMESA
                                            : GS_BACKEND_AUTO;
    } else if (!strcmp(o, "--sweep-planes")) {
      ok = (np = parse_list(v, sweep_p, 32)) > 0;
    } else if (!strcmp(o, "--sweep-lattice")) {
      ok = (nl = parse_list(v, sweep_l, 32)) > 0;
    } else if (o[0] == '-') {
      fprintf(stderr, "%s: unknown option '%s'\n", TOOL, o);
      return 2;
    } else {
      if (nscenes < 64) scenes[nscenes++] = o;
      continue;
    }
    if (!ok) {
      fprintf(stderr, "%s: bad value for %s\n", TOOL, o);
      return 2;
    }
    i++;
  }
  if (!nscenes) {
    usage(stderr);
    return 2;
  }
  printf("| scene | size | planes | lattice | xi | sub-angle ° | sub-texels | ms/frame: best "
         "(median) | CPU ms/frame | first frame ms (with context) | context + upload ms | shadow / "
         "surface / lattice / planes / readback ms | Mfragments | error %% | "
         "mean rel. %% | backend: GL_RENDERER (GL_VENDOR) |\n");
  printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  int rc = 0;
  for (int k = 0; k < nscenes && rc == 0; k++) {
    sh_error err;
    sh_scene *scene = NULL;
    if (sh_scene_load(scenes[k], &scene, &err) != SH_OK) return sh_cli_report(TOOL, &err);
    if (w) scene->camera.width = (int)w, scene->camera.height = (int)h;
    sh_image ref = {0};
    if (spp > 0 && reference(scene, scenes[k], (int)spp, cache, &ref, &err) != SH_OK)
      rc = sh_cli_report(TOOL, &err);
    int nps = np ? np : 1, nls = nl ? nl : 1, nxs = sweep_xi ? 2 : 1;
    for (int a = 0; a < nps && rc == 0; a++)
      for (int b = 0; b < nls && rc == 0; b++)
        for (int x = 0; x < nxs && rc == 0; x++) {
          config c = base;
          if (np) c.planes = sweep_p[a];
          if (nl) c.lu = c.lv = sweep_l[b];
          if (sweep_xi) c.xi = x ? SH_XI_EXACT : SH_XI_LATTICE;
          if (run(scenes[k], scene, &c, (int)frames, spp > 0 ? &ref : NULL,
                  diffdir, &err) != SH_OK)
            rc = sh_cli_report(TOOL, &err);
        }
    sh_image_free(&ref);
    sh_scene_free(scene);
  }
  return rc;
}
