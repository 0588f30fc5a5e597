/* gl_shafts_bench: renders scenes in-process and reports time per frame
 * (the GL context and scene upload counted apart, after a warm-up frame),
 * where the time goes, and the error against the converged reference
 * renderer, as a Markdown table. With --sweep-planes or --sweep-lattice it
 * measures how error and time move with the number of planes and lattice
 * points (the seed's figures 5 and 6). bench.sh runs the standard set.
 * For an atmosphere the planes column is its sampling planes (the eye in
 * the air) or spheres (from space), the lattice time its layers drawn on
 * the lattice of pixels, and the planes time its full-resolution passes
 * (gs_stats). */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "gs_named.h"
#include "gs_render.h"
#include "sh_cli.h"
#include "sh_compare.h"
#include "sh_file.h"
#include "sh_image.h"
#include "sh_parse.h"
#include "sh_progress.h"
#include "sh_reference.h"
#include "sh_str.h"

static const char *const TOOL = "gl_shafts_bench";

/* What sweeps override, per run: 0 (or xi DEFAULT) leaves the options. */
typedef struct sweep {
  int planes, lattice;
  gs_xi_mode xi;
} sweep;

typedef struct args {
  long size[2], frames, spp;
  const char *cache, *diffdir, *sweep_planes, *sweep_lattice;
  const char *compare[2];
  int sweep_xi;
} args;

#define FIELD(f) offsetof(args, f)
#define RENDERER(name, key, meta, n, fixed)                                    \
  {name, 0, SH_CLI_SETTER, meta, n, 0, 0, 0, 0, 0, NULL, key, fixed, NULL,     \
   "as gl_shafts"}
static const sh_cli_option options[] = {
    {"size", 0, SH_CLI_INT, "W H", 2, FIELD(size), 1, 16384, 0, 0, NULL, NULL,
     NULL, NULL, "render at W x H instead of the scene's size"},
    {"frames", 0, SH_CLI_INT, "N", 1, FIELD(frames), 1, 10000, 0, 0, NULL,
     NULL, NULL, "5", "timed frames after one warm-up frame"},
    {"ref-spp", 0, SH_CLI_INT, "N", 1, FIELD(spp), 0, 1 << 20, 0, 0, NULL,
     NULL, NULL, "1024", "reference samples; 0: no error column"},
    {"cache", 0, SH_CLI_TEXT, "DIR", 1, FIELD(cache), 0, 0, 0, 0, NULL, NULL,
     NULL, ".", "where references are kept"},
    RENDERER("planes", "planes", "N", 0, NULL),
    RENDERER("lattice", "lattice", "NU NV", 2, NULL),
    RENDERER("xi", "xi", NULL, 0, NULL),
    RENDERER("jitter", "jitter", NULL, 0, "1"),
    RENDERER("no-jitter", "jitter", NULL, 0, "0"),
    RENDERER("shadow-map-res", "shadow_map_res", "S", 0, NULL),
    RENDERER("light-map-res", "light_map_res", "R", 0, NULL),
    RENDERER("sub-angle", "sub_angle_deg", "DEG", 0, NULL),
    RENDERER("sub-texels", "sub_texels", "T", 0, NULL),
    RENDERER("backend", "backend", NULL, 0, NULL),
    {"sweep-planes", 0, SH_CLI_TEXT, "LIST", 1, FIELD(sweep_planes), 0, 0, 0,
     0, NULL, NULL, NULL, NULL, "comma-separated plane counts to measure in turn"},
    {"sweep-lattice", 0, SH_CLI_TEXT, "LIST", 1, FIELD(sweep_lattice), 0, 0,
     0, 0, NULL, NULL, NULL, NULL, "comma-separated lattice sizes (n for n x n)"},
    {"sweep-xi", 0, SH_CLI_FLAG, NULL, 0, FIELD(sweep_xi), 0, 0, 0, 1, NULL,
     NULL, NULL, NULL, "measure both xi lattice and xi exact"},
    {"diff", 0, SH_CLI_TEXT, "DIR", 1, FIELD(diffdir), 0, 0, 0, 0, NULL, NULL,
     NULL, NULL, "write each render and its difference to the reference"},
    {"compare", 0, SH_CLI_TEXT, "A B", 2, FIELD(compare), 0, 0, 0, 0, NULL,
     NULL, NULL, NULL, "only print the error of image A against reference B"},
};

static sh_status set_option(void *target, const char *key, const char *value,
                            sh_error *err) {
  return gs_options_set(target, key, value, err);
}

static gs_options scratch;
static const sh_cli_tool tool = {
    TOOL, "[options] SCENE.json...",
    "Renders scenes in-process and reports time per frame, where it goes and "
    "the\nerror against the converged reference renderer, as a Markdown "
    "table.",
    options, (int)(sizeof options / sizeof *options), 0, SH_CLI_MAX_OPERANDS,
    NULL, NULL, set_option, &scratch, gs_option_choices, NULL};

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
  char *name = sh__printf_alloc(
      "%s/%.*s_%dx%d_spp%d_%016llx.exr", cache,
      (int)(strlen(base) > 5 ? strlen(base) - 5 : strlen(base)), base,
      scene->camera.width, scene->camera.height, spp, file_hash(path));
  if (!name) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  if (sh_image_read(name, ref, NULL) == SH_OK) {
    free(name);
    return SH_OK;
  }
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
  free(name);
  return st;
}

static sh_status run(const char *path, sh_scene *scene,
                     const sh_cli_args *parsed, const sweep *sw, int frames,
                     const sh_image *ref, const char *diffdir, sh_error *err) {
  gs_options o = gs_options_defaults(scene);
  sh_status st0 = sh_cli_apply(&tool, parsed, &o, err);
  if (st0 != SH_OK) return st0;
  if (sw->planes) o.planes = sw->planes;
  if (sw->lattice) o.lattice_u = o.lattice_v = sw->lattice;
  if (sw->xi != GS_XI_DEFAULT) o.xi = sw->xi;
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
    /* The planes a light sweeps; an atmosphere's own count (its sampling
     * planes or spheres, from the frame's stats). */
    char planes[32];
    if (m->spheres > 0) snprintf(planes, sizeof planes, "%ld spheres", m->spheres);
    else if (scene->medium.type == SH_MEDIUM_ATMOSPHERE)
      snprintf(planes, sizeof planes, "%ld", m->planes);
    else
      snprintf(planes, sizeof planes, "%d",
               scene->nlights ? gs_light_planes(&o, scene->lights[0].type) : o.planes);
    printf("| %s | %dx%d | %s | %dx%d | %s%s | %g | %g | %.1f (%.1f) | %.1f | %.1f | %.1f "
           "| %.1f / %.1f / %.1f / %.1f / %.1f | %.2f | %s | %s | %s: %s (%s) |\n",
           base, img.width, img.height, planes,
           o.lattice_u, o.lattice_v, gs_option_name("xi", o.xi),
           o.jitter ? " +jitter" : "", o.sub_angle_deg, o.sub_texels, 1000 * best, 1000 * med,
           1000 * cpu, 1000 * (setup + first), 1000 * setup, 1000 * m->shadow_seconds,
           1000 * m->surface_seconds, 1000 * m->lattice_seconds,
           1000 * m->plane_seconds, 1000 * m->readback_seconds,
           m->fragments / 1e6, err_col, bias_col, m->backend, m->renderer, m->vendor);
    fflush(stdout);
    if (diffdir && ref && st == SH_OK) {
      const char *xi = gs_option_name("xi", o.xi);
      int stem = (int)strlen(base) - 5;
      char *name = sh__printf_alloc("%s/%.*s_p%d_l%d_%s.exr", diffdir, stem, base,
                                    o.planes, o.lattice_u, xi);
      char *dif = sh__printf_alloc("%s/%.*s_p%d_l%d_%s_dif.exr", diffdir, stem,
                                   base, o.planes, o.lattice_u, xi);
      st = name && dif ? sh_image_write(name, &img, 0, err)
                       : sh_error_set(err, SH_ERR_NOMEM, "out of memory");
      if (st == SH_OK) st = sh_image_write(dif, &d, 0, err);
      free(name);
      free(dif);
    }
    sh_image_free(&d);
  }
  free(s);
  free(secs);
  sh_image_free(&img);
  gs_renderer_free(r);
  return st;
}

/* --compare A B: the error of A against B. */
static int compare(const char *a_path, const char *b_path) {
  sh_error err = SH_ERROR_INIT;
  sh_image a = {0}, b = {0};
  sh_image_error e;
  int rc = 0;
  if (sh_image_read(a_path, &a, &err) != SH_OK ||
      sh_image_read(b_path, &b, &err) != SH_OK ||
      sh_image_compare(&a, &b, 0.01, &e, NULL, &err) != SH_OK)
    rc = sh_cli_report(TOOL, &err);
  else
    printf("error %.3f %%, mean relative %.3f %%, %ld lit pixels\n",
           100 * e.rel_rms, 100 * e.mean_rel, e.lit_pixels);
  sh_image_free(&a);
  sh_image_free(&b);
  return rc;
}

int main(int argc, char **argv) {
  args a = {{0, 0}, 5, 1024, ".", NULL, NULL, NULL, {NULL, NULL}, 0};
  sh_scene no_keys; /* options are checked on the built-in defaults */
  memset(&no_keys, 0, sizeof no_keys);
  scratch = gs_options_defaults(&no_keys);
  sh_cli_args parsed;
  int rc = sh_cli_parse(&tool, argc, argv, &a, &parsed);
  if (rc >= 0) return rc;
  if (a.compare[0]) return compare(a.compare[0], a.compare[1]);
  long sweep_p[32], sweep_l[32];
  int np = 0, nl = 0;
  if ((a.sweep_planes && (np = parse_list(a.sweep_planes, sweep_p, 32)) <= 0) ||
      (a.sweep_lattice && (nl = parse_list(a.sweep_lattice, sweep_l, 32)) <= 0)) {
    sh_cli_error(TOOL, "--sweep-planes, --sweep-lattice: expected "
                       "comma-separated counts >= 1");
    return SH_EXIT_BAD_INPUT;
  }
  if (!parsed.noperands) {
    sh_cli_help(&tool, stderr);
    return SH_EXIT_BAD_INPUT;
  }
  printf("| scene | size | planes | lattice | xi | sub-angle ° | sub-texels | ms/frame: best "
         "(median) | CPU ms/frame | first frame ms (with context) | context + upload ms | shadow / "
         "surface / lattice / planes / readback ms | Mfragments | error %% | "
         "mean rel. %% | backend: GL_RENDERER (GL_VENDOR) |\n");
  printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  rc = 0;
  for (int k = 0; k < parsed.noperands && rc == 0; k++) {
    sh_error err = SH_ERROR_INIT;
    sh_scene *scene = NULL;
    const char *path = parsed.operands[k];
    if ((rc = sh_cli_load_scene(TOOL, path, 1, &scene))) return rc;
    sh_cli_resize(scene, a.size[0], a.size[1]);
    sh_image ref = {0};
    if (a.spp > 0 && reference(scene, path, (int)a.spp, a.cache, &ref, &err) != SH_OK)
      rc = sh_cli_report(TOOL, &err);
    int nps = np ? np : 1, nls = nl ? nl : 1, nxs = a.sweep_xi ? 2 : 1;
    for (int p = 0; p < nps && rc == 0; p++)
      for (int l = 0; l < nls && rc == 0; l++)
        for (int x = 0; x < nxs && rc == 0; x++) {
          sweep sw = {np ? (int)sweep_p[p] : 0, nl ? (int)sweep_l[l] : 0,
                      a.sweep_xi ? (x ? GS_XI_EXACT : GS_XI_LATTICE)
                                 : GS_XI_DEFAULT};
          if (run(path, scene, &parsed, &sw, (int)a.frames,
                  a.spp > 0 ? &ref : NULL, a.diffdir, &err) != SH_OK)
            rc = sh_cli_report(TOOL, &err);
        }
    sh_image_free(&ref);
    sh_scene_free(scene);
  }
  return rc;
}
