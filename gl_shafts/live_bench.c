/* gl_shafts_live_bench: what a viewport pays for a frame after an edit,
 * in-process, for baked programs (the default) and live ones
 * (gs_options.live). For each scene it keeps one renderer of each kind
 * warm and times, alternating the two so that the machine's load falls on
 * both alike:
 *   first   gs_renderer_create and the first draw (context, upload, every
 *           program built);
 *   warm    a draw with nothing changed;
 *   light   sh_scene_update moving the first light by 0.01 (a new position
 *           every time), gs_renderer_sync and a draw;
 *   power   the same with the first light's intensity (or irradiance)
 *           times 1.01;
 *   camera  the same with the camera moved by 0.01.
 * Each figure is the median over the frames of its row, wall-clock and
 * process CPU time (llvmpipe's threads included), with the programs built
 * per frame. Prints a Markdown table with live / baked ratios. Under
 * valgrind --tool=callgrind --instr-atstart=no, --count MODE measures the
 * instructions of the warm frames of one kind alone;
 * live_bench.sh runs the standard set and docs/gl_shafts.md ("Live mode")
 * quotes it. */
#include <jansson.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "gs_render.h"
#include "sh_cli.h"
#include "sh_parse.h"
#include "sh_time.h"
#include "shafts.h"

static const char *const TOOL = "gl_shafts_live_bench";

typedef struct args {
  long size[2], frames;
  int backend;
  int counting; /* -1: the table; 0 or 1: count baked or live frames */
} args;

static const sh_cli_choice backends[] = {{"auto", GS_BACKEND_AUTO},
                                         {"egl", GS_BACKEND_EGL},
                                         {"osmesa", GS_BACKEND_OSMESA},
                                         {NULL, 0}};
static const sh_cli_choice kinds[] = {{"baked", 0}, {"live", 1}, {NULL, 0}};

#define FIELD(f) offsetof(args, f)
static const sh_cli_option options[] = {
    {"size", 0, SH_CLI_INT, "W H", 2, FIELD(size), 1, 16384, 0, 0, NULL, NULL,
     NULL, "640 480", "render at W x H"},
    {"frames", 0, SH_CLI_INT, "N", 1, FIELD(frames), 1, 1000, 0, 0, NULL, NULL,
     NULL, "9", "frames timed per row"},
    {"backend", 0, SH_CLI_CHOICE, NULL, 0, FIELD(backend), 0, 0, 0, 0,
     backends, NULL, NULL, "auto", "where the GL context comes from"},
    {"count", 0, SH_CLI_CHOICE, NULL, 0, FIELD(counting), 0, 0, 0, 0, kinds,
     NULL, NULL, NULL,
     "only draw warm frames of that kind, instrumented for valgrind "
     "--tool=callgrind --instr-atstart=no"},
};

static const sh_cli_tool tool = {
    .name = TOOL,
    .synopsis = "[options] SCENE.json...",
    .description = "Times the frame a viewport pays after an edit, baked "
                   "programs against live\nones, as a Markdown table "
                   "(live_bench.sh; docs/gl_shafts.md, \"Live mode\").",
    .options = options,
    .noptions = (int)(sizeof options / sizeof *options),
    .min_operands = 1,
    .max_operands = SH_CLI_MAX_OPERANDS};

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, bench_cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

enum { FIRST, WARM, LIGHT, POWER, CAMERA, NROWS };
static const char *const ROW[NROWS] = {"first frame", "warm frame", "after a light move",
                                       "after an intensity change",
                                       "after a camera move"};

/* One renderer (baked or live) on its own copy of the scene. */
typedef struct side {
  sh_scene *scene;
  gs_renderer *r;
  float *rgb;
  double *wall[NROWS], *cpu[NROWS];
  int compiled[NROWS]; /* programs built over the row's frames */
} side;

/* Adds v to element k of a JSON array of numbers (or scales it, mul). */
static void nudge(json_t *a, size_t k, double v, int mul) {
  json_t *x = json_array_get(a, k);
  if (!json_is_number(x)) return;
  double d = json_number_value(x);
  json_array_set_new(a, k, json_real(mul ? d * v : d + v));
}

/* The patch of event `row` number i (1, 2, ...), built from the scene
 * file's JSON; the camera keeps the bench's size. */
static char *patch(json_t *root, int row, int i, int w, int h) {
  json_t *p = json_object();
  if (row == CAMERA) {
    json_t *cam = json_deep_copy(json_object_get(root, "camera"));
    nudge(json_object_get(cam, "position"), 0, 0.01 * i, 0);
    json_object_set_new(cam, "width", json_integer(w));
    json_object_set_new(cam, "height", json_integer(h));
    json_object_set_new(p, "camera", cam);
  } else {
    json_t *lights = json_deep_copy(json_object_get(root, "lights"));
    json_t *l = json_array_get(lights, 0);
    if (row == LIGHT) {
      json_t *pos = json_object_get(l, "position");
      if (pos) nudge(pos, 0, 0.01 * i, 0);
      else nudge(json_object_get(l, "direction"), 0, 0.01 * i, 0);
    } else {
      const char *keys[2] = {"intensity", "irradiance"};
      for (int k = 0; k < 2; k++) {
        json_t *v = json_object_get(l, keys[k]);
        double f = 1.0;
        for (int j = 0; j < i; j++) f *= 1.01;
        if (json_is_array(v))
          for (size_t c = 0; c < json_array_size(v); c++) nudge(v, c, f, 1);
        else if (json_is_number(v))
          json_object_set_new(l, keys[k], json_real(json_number_value(v) * f));
      }
    }
    json_object_set_new(p, "lights", lights);
  }
  char *text = json_dumps(p, JSON_COMPACT);
  json_decref(p);
  return text;
}

/* Times one frame of side s: the update (patch, or none), sync and draw. */
static sh_status frame(side *s, const char *text, int row, int i, sh_error *err) {
  double t0 = sh_seconds(), c0 = bench_cpu_seconds();
  sh_status st = SH_OK;
  unsigned changed = 0;
  if (text) st = sh_scene_update(s->scene, text, "patch.json", &changed, err);
  if (st == SH_OK && changed) st = gs_renderer_sync(s->r, changed, err);
  gs_stats stats;
  if (st == SH_OK) st = gs_renderer_draw(s->r, s->rgb, &stats, err);
  s->wall[row][i] = sh_seconds() - t0;
  s->cpu[row][i] = bench_cpu_seconds() - c0;
  if (st == SH_OK) s->compiled[row] += stats.programs_compiled;
  return st;
}

static sh_status create(side *s, const char *path, int live, int w, int h,
                        gs_backend backend, sh_error *err) {
  sh_status st = sh_scene_load(path, &s->scene, err);
  if (st != SH_OK) return st;
  s->scene->camera.width = w;
  s->scene->camera.height = h;
  s->rgb = malloc((size_t)w * h * 3 * sizeof *s->rgb);
  if (!s->rgb) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  gs_options o = gs_options_defaults(s->scene);
  o.live = live;
  o.backend = backend;
  double t0 = sh_seconds(), c0 = bench_cpu_seconds();
  st = gs_renderer_create(s->scene, &o, &s->r, err);
  gs_stats stats;
  if (st == SH_OK) st = gs_renderer_draw(s->r, s->rgb, &stats, err);
  s->wall[FIRST][0] = sh_seconds() - t0;
  s->cpu[FIRST][0] = bench_cpu_seconds() - c0;
  if (st == SH_OK) s->compiled[FIRST] = stats.programs_compiled;
  return st;
}

static void side_free(side *s) {
  gs_renderer_free(s->r);
  sh_scene_free(s->scene);
  free(s->rgb);
  for (int k = 0; k < NROWS; k++) {
    free(s->wall[k]);
    free(s->cpu[k]);
  }
}

/* --count: the warm frames of one kind, the only code instrumented. */
static sh_status count(const char *path, int live, int w, int h, int frames,
                       gs_backend backend, sh_error *err) {
  side s;
  memset(&s, 0, sizeof s);
  sh_status st = SH_OK;
  for (int k = 0; k < NROWS && st == SH_OK; k++) {
    s.wall[k] = calloc((size_t)frames, sizeof(double));
    s.cpu[k] = calloc((size_t)frames, sizeof(double));
    if (!s.wall[k] || !s.cpu[k]) st = sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  }
  if (st == SH_OK) st = create(&s, path, live, w, h, backend, err);
  CALLGRIND_START_INSTRUMENTATION;
  for (int i = 0; i < frames && st == SH_OK; i++) st = frame(&s, NULL, WARM, i, err);
  CALLGRIND_STOP_INSTRUMENTATION;
  side_free(&s);
  return st;
}

static sh_status bench(const char *path, int w, int h, int frames, gs_backend backend,
                       sh_error *err) {
  json_error_t jerr;
  json_t *root = json_load_file(path, 0, &jerr);
  if (!root)
    return sh_error_set(err, SH_ERR_IO, "%s:%d: %s", path, jerr.line, jerr.text);
  side sides[2];
  memset(sides, 0, sizeof sides);
  sh_status st = SH_OK;
  for (int m = 0; m < 2 && st == SH_OK; m++)
    for (int k = 0; k < NROWS && st == SH_OK; k++) {
      sides[m].wall[k] = calloc((size_t)frames, sizeof(double));
      sides[m].cpu[k] = calloc((size_t)frames, sizeof(double));
      if (!sides[m].wall[k] || !sides[m].cpu[k])
        st = sh_error_set(err, SH_ERR_NOMEM, "out of memory");
    }
  for (int m = 0; m < 2 && st == SH_OK; m++)
    st = create(&sides[m], path, m, w, h, backend, err);
  for (int row = WARM; row < NROWS && st == SH_OK; row++)
    for (int i = 0; i < frames && st == SH_OK; i++) {
      char *text = row == WARM ? NULL : patch(root, row, i + 1, w, h);
      for (int m = 0; m < 2 && st == SH_OK; m++) st = frame(&sides[m], text, row, i, err);
      free(text);
    }
  if (st == SH_OK) {
    const char *base = strrchr(path, '/');
    printf("\n%s at %dx%d, median of %d frames a row (first frame: one):\n\n",
           base ? base + 1 : path, w, h, frames);
    printf("| frame | baked ms | live ms | live / baked | baked CPU ms | live CPU ms |"
           " programs built, baked | live |\n");
    printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int row = 0; row < NROWS; row++) {
      int n = row == FIRST ? 1 : frames;
      double wb = 1e3 * median(sides[0].wall[row], n), wl = 1e3 * median(sides[1].wall[row], n);
      double cb = 1e3 * median(sides[0].cpu[row], n), cl = 1e3 * median(sides[1].cpu[row], n);
      printf("| %s | %.1f | %.1f | %.2f | %.1f | %.1f | %.1f | %.1f |\n", ROW[row], wb, wl,
             wl / wb, cb, cl, (double)sides[0].compiled[row] / n,
             (double)sides[1].compiled[row] / n);
    }
  }
  for (int m = 0; m < 2; m++) side_free(&sides[m]);
  json_decref(root);
  return st;
}

int main(int argc, char **argv) {
  args a = {{640, 480}, 9, GS_BACKEND_AUTO, -1};
  sh_cli_args parsed;
  int rc = sh_cli_parse(&tool, argc, argv, &a, &parsed);
  if (rc >= 0) return rc;
  int w = (int)a.size[0], h = (int)a.size[1], frames = (int)a.frames;
  gs_backend backend = (gs_backend)a.backend;
  const char *const *scenes = parsed.operands;
  int nscenes = parsed.noperands, counting = a.counting;
  rc = 0;
  for (int i = 0; i < nscenes && rc == 0; i++) {
    sh_error err = SH_ERROR_INIT;
    sh_status st = counting >= 0 ? count(scenes[i], counting, w, h, frames, backend, &err)
                                 : bench(scenes[i], w, h, frames, backend, &err);
    if (st != SH_OK) {
      sh_cli_error(TOOL, "%s: %s", scenes[i], err.message);
      rc = 1;
    }
    sh_error_clear(&err);
  }
  return rc;
}
