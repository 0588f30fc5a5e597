/* Benchmark of the light meshes method (run by lmm_tracer/bench.sh; not a
 * test). Prints, as tables:
 *  1. time and error of LMM against RRTA as the number of lights (1, 4, 16,
 *     64) and the image size grow: where LMM gets faster than RRTA;
 *  2. soft-shadow quality: LMM against stochastic area-light sampling at
 *     equal error against a converged area-light image, and their times;
 *  3. rays per second of both against the Embree ceiling on this machine
 *     (single and stream queries, coherent camera and shadow rays).
 * Every figure of a run is measured in that run, so ratios compare like
 * with like on a shared, noisy machine. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lmm_area.h"
#include "lmm_method.h"
#include "sh_camera.h"
#include "sh_cli.h"
#include "sh_compare.h"
#include "sh_parse.h"
#include "sh_time.h"
#include "sh_reference.h"

/* The seed's fig. 3 scene (tabletop, hanging cylinder, bar) with n point
 * lights on a ring above it, of equal total intensity. */
static sh_scene *table_scene(int nlights, int size) {
  size_t cap = 4096 + 160 * (size_t)nlights;
  char *json = malloc(cap);
  size_t k = (size_t)snprintf(json, cap,
      "{\"format\": \"shafts-scene\", \"version\": 1,"
      " \"camera\": {\"position\": [2.0, 2.5, 3.4], \"look_at\": [0, 1.05, 0],"
      "  \"fov_y_deg\": 45, \"width\": %d, \"height\": %d},"
      " \"ambient\": [0.03, 0.03, 0.03], \"lights\": [", size, size);
  for (int i = 0; i < nlights; i++) {
    double a = 2.0 * SH_PI * i / nlights + 2.3;
    k += (size_t)snprintf(json + k, cap - k,
                          "%s{\"type\": \"point\", \"position\": [%.4f, 3.2, "
                          "%.4f], \"intensity\": [%.4f, %.4f, %.4f]}",
                          i ? ", " : "", 1.9 * cos(a), 1.9 * sin(a),
                          30.0 / nlights, 30.0 / nlights, 30.0 / nlights);
  }
  snprintf(json + k, cap - k,
      "], \"materials\": {\"top\": {\"diffuse\": [0.62, 0.45, 0.3]},"
      "  \"cyl\": {\"diffuse\": [0.35, 0.5, 0.75], \"specular\": [0.3, 0.3, 0.3],"
      "   \"shininess\": 40},"
      "  \"bar\": {\"diffuse\": [0.75, 0.25, 0.18]}},"
      " \"shapes\": ["
      "  {\"type\": \"box\", \"min\": [-1.6, 0.66, -1.1], \"max\": [1.6, 0.72, 1.1],"
      "   \"material\": \"top\"},"
      "  {\"type\": \"cylinder\", \"base\": [0, 1.15, 0], \"top\": [0, 1.85, 0],"
      "   \"radius\": 0.3, \"material\": \"cyl\"},"
      "  {\"type\": \"box\", \"min\": [0.1, 1.38, -0.07], \"max\": [0.95, 1.52, 0.07],"
      "   \"material\": \"bar\"}]}");
  sh_scene *s = NULL;
  sh_error err = SH_ERROR_INIT;
  if (sh_scene_parse(json, "bench.json", ".", &s, &err) != SH_OK) {
    char *text = sh_error_text(&err);
    fprintf(stderr, "lmm_bench: %s\n", text ? text : err.message);
    free(text);
  }
  sh_error_clear(&err);
  free(json);
  return s;
}

/* The table scene and its tracer in *rt; the benchmark stops when either
 * cannot be made. */
static sh_scene *traced_table(int nlights, int size, sh_rt **rt) {
  sh_scene *s = table_scene(nlights, size);
  *rt = NULL;
  if (!s || sh_rt_create(s, rt, NULL) != SH_OK) exit(1);
  return s;
}

typedef struct run {
  double seconds;
  uint64_t rays;
  double fraction; /* LMM: mesh points computed */
} run;

/* method: 0 RRTA, 1 LMM (h, kl), 2 area lights (radius, samples). */
static run render(const sh_scene *s, const sh_rt *rt, int method, double a,
                  double b, sh_image *img) {
  sh_reference_options opt = sh_reference_defaults(s);
  opt.threads = sh_reference_threads(0);
  opt.rt = rt;
  opt.max_depth = 0;
  run r = {0, 0, 0};
  double t0 = sh_seconds();
  lmm *L = NULL;
  lmm_area *A = NULL;
  if (method == 1) {
    lmm_options lo = {a, b, LMM_SCHEME_REFRACT_TRACE, 0, 0, 1, 0, NULL, NULL, NULL};
    lmm_create(s, rt, &lo, opt.threads, &L, NULL);
    opt.hook = lmm_hook(L);
  } else if (method == 2) {
    lmm_area_create(s, rt, a, (int)b, &A, NULL);
    opt.hook = lmm_area_hook(A);
  }
  sh_reference_stats st;
  sh_render_reference(s, &opt, img, &st, NULL);
  r.seconds = sh_seconds() - t0;
  r.rays = st.closest_rays + st.occlusion_rays;
  if (L) {
    lmm_stats ls;
    lmm_get_stats(L, &ls);
    r.fraction = (double)ls.mesh.points_computed / ls.mesh.points_total;
  }
  lmm_free(L);
  lmm_area_free(A);
  return r;
}

static double rel_error(const sh_image *a, const sh_image *ref) {
  sh_image_error e;
  sh_image_compare(a, ref, 0.01, &e, NULL, NULL);
  return e.rel_rms;
}

static void scaling(const int *sizes, int nsizes) {
  const int lights[] = {1, 4, 16, 64};
  printf("## LMM against RRTA as lights and image size grow\n\n");
  printf("h = 0.04 (1/100 of the scene), kl = 2; camera rays only (no "
         "recursion); times in seconds, %d threads\n\n",
         sh_reference_threads(0));
  printf("| lights | image | RRTA s | LMM s | LMM / RRTA | LMM error vs RRTA "
         "| mesh points computed |\n|---|---|---|---|---|---|---|\n");
  for (int si = 0; si < nsizes; si++)
    for (int li = 0; li < 4; li++) {
      sh_rt *rt;
      sh_scene *s = traced_table(lights[li], sizes[si], &rt);
      sh_image a = {0}, b = {0};
      run ra = render(s, rt, 0, 0, 0, &a);
      run rb = render(s, rt, 1, 0.04, 2.0, &b);
      printf("| %d | %d^2 | %.3f | %.3f | %.2f | %.2f%% | %.2f%% |\n",
             lights[li], sizes[si], ra.seconds, rb.seconds,
             rb.seconds / ra.seconds, 100 * rel_error(&b, &a),
             100 * rb.fraction);
      fflush(stdout);
      sh_image_free(&a);
      sh_image_free(&b);
      sh_rt_free(rt);
      sh_scene_free(s);
    }
  printf("\n");
}

static void area_quality(int size) {
  printf("## Soft shadows: LMM against area-light sampling (%d^2, 1 light)\n\n",
         size);
  sh_rt *rt;
  sh_scene *s = traced_table(1, size, &rt);
  sh_image lm = {0};
  run rl = render(s, rt, 1, 0.04, 2.0, &lm);
  /* The sphere light whose converged image is closest to LMM's. */
  const double radii[] = {0.05, 0.1, 0.15, 0.2, 0.3, 0.4};
  double best_r = radii[0], best_e = INFINITY;
  sh_image conv = {0};
  for (int i = 0; i < 6; i++) {
    sh_image img = {0};
    render(s, rt, 2, radii[i], 256, &img);
    double e = rel_error(&lm, &img);
    printf("sphere light radius %.2f: LMM differs from it by %.2f%%\n",
           radii[i], 100 * e);
    if (e < best_e) {
      best_e = e;
      best_r = radii[i];
    }
    sh_image_free(&img);
  }
  run rc = render(s, rt, 2, best_r, 1024, &conv);
  double lmm_err = rel_error(&lm, &conv);
  printf("\nmatching radius %.2f; converged image: 1024 shadow rays, %.2f s\n\n",
         best_r, rc.seconds);
  printf("| method | shadow rays per light | seconds | error vs converged "
         "area light |\n|---|---|---|---|\n");
  printf("| LMM h = 0.04, kl = 2 | - | %.3f | %.2f%% |\n", rl.seconds,
         100 * lmm_err);
  double equal_time = -1;
  for (int n = 1; n <= 256; n *= 4) {
    sh_image img = {0};
    run ra = render(s, rt, 2, best_r, n, &img);
    double e = rel_error(&img, &conv);
    printf("| area sampling | %d | %.3f | %.2f%% |\n", n, ra.seconds, 100 * e);
    if (equal_time < 0 && e <= lmm_err) equal_time = ra.seconds;
    sh_image_free(&img);
  }
  if (equal_time > 0)
    printf("\nAt LMM's error, area sampling takes %.3f s: %.2fx LMM's time.\n"
           "(LMM's error against the area light is a bias: it does not fall "
           "with more work at this h.)\n\n", equal_time, equal_time / rl.seconds);
  else
    printf("\nArea sampling did not reach LMM's error within 256 rays.\n\n");
  sh_image_free(&lm);
  sh_image_free(&conv);
  sh_rt_free(rt);
  sh_scene_free(s);
}

static void ceiling(int size) {
  printf("## Rays per second against the Embree ceiling (%d^2, 1 thread)\n\n",
         size);
  sh_rt *rt;
  sh_scene *s = traced_table(1, size, &rt);
  sh_camera_frame f;
  sh_camera_frame_init(&s->camera, &f);
  int n = size * size;
  sh_vec3 *o = malloc(sizeof *o * n), *d = malloc(sizeof *d * n);
  double *t = malloc(sizeof *t * n);
  int *shape = malloc(sizeof *shape * n);
  unsigned char *occ = malloc((size_t)n);
  for (int y = 0; y < size; y++)
    for (int x = 0; x < size; x++) {
      o[y * size + x] = f.origin;
      d[y * size + x] = sh_camera_dir(&f, x + 0.5, y + 0.5);
    }
  double t0 = sh_seconds();
  for (int i = 0; i < n; i++) {
    sh_hit h;
    if (!sh_rt_intersect(rt, o[i], d[i], 0, INFINITY, &h, NULL)) h.t = INFINITY;
    t[i] = h.t;
  }
  double single = n / (sh_seconds() - t0) / 1e6;
  t0 = sh_seconds();
  sh_rt_intersect_stream(rt, n, o, d, t, shape, 1, NULL);
  double stream = n / (sh_seconds() - t0) / 1e6;
  /* Shadow rays from the hit points to the light. */
  int m = 0;
  for (int i = 0; i < n; i++) {
    if (!isfinite(t[i])) continue;
    sh_vec3 p = sh_madd(o[i], d[i], t[i] * 0.9999);
    sh_vec3 to = sh_sub(s->lights[0].position, p);
    t[m] = sh_length(to) * 0.9999;
    d[m] = sh_normalize(to);
    o[m++] = p;
  }
  t0 = sh_seconds();
  for (int i = 0; i < m; i++)
    occ[i] = (unsigned char)sh_rt_occluded(rt, o[i], d[i], t[i], SH_RT_ALL, NULL);
  double shadow_single = m / (sh_seconds() - t0) / 1e6;
  t0 = sh_seconds();
  sh_rt_occluded_stream(rt, m, o, d, t, SH_RT_ALL, 1, occ, NULL);
  double shadow_stream = m / (sh_seconds() - t0) / 1e6;
  printf("| query | Mrays/s |\n|---|---|\n");
  printf("| camera rays, rtcIntersect1 | %.2f |\n", single);
  printf("| camera rays, rtcIntersect1M stream | %.2f |\n", stream);
  printf("| shadow rays, rtcOccluded1 | %.2f |\n", shadow_single);
  printf("| shadow rays, rtcOccluded1M stream | %.2f |\n", shadow_stream);
  free(o);
  free(d);
  free(t);
  free(shape);
  free(occ);
  sh_rt_free(rt);
  sh_scene_free(s);
  /* The tracers themselves, one thread, 16 lights. */
  s = traced_table(16, size, &rt);
  sh_image img = {0};
  for (int method = 0; method < 2; method++) {
    sh_reference_options opt = sh_reference_defaults(s);
    opt.threads = 1;
    opt.rt = rt;
    opt.max_depth = 0;
    lmm *L = NULL;
    if (method) {
      lmm_options lo = {0.04, 2.0, LMM_SCHEME_REFRACT_TRACE, 0, 0, 1, 0, NULL, NULL, NULL};
      lmm_create(s, rt, &lo, 1, &L, NULL);
      opt.hook = lmm_hook(L);
    }
    sh_reference_stats st;
    sh_render_reference(s, &opt, &img, &st, NULL);
    printf("| %s tracer, 16 lights, all rays incl. shading | %.2f |\n",
           method ? "LMM" : "RRTA",
           (st.closest_rays + st.occlusion_rays) / st.seconds / 1e6);
    lmm_free(L);
    sh_image_free(&img);
  }
  printf("\n");
  sh_rt_free(rt);
  sh_scene_free(s);
}

/* With a medium: volumetric shadows interpolated from the light mesh
 * against traced ones, both against the reference. */
static void volume(const char *path, int quick) {
  printf("## Volumetric shadows from the light mesh (%s)\n\n", path);
  sh_scene *s = NULL;
  if (sh_scene_load(path, &s, NULL) != SH_OK) {
    printf("cannot load %s\n\n", path);
    return;
  }
  if (quick) {
    s->camera.width /= 2;
    s->camera.height /= 2;
  }
  sh_rt *rt = NULL;
  if (sh_rt_create(s, &rt, NULL) != SH_OK) exit(1);
  sh_reference_options opt = sh_reference_defaults(s);
  opt.threads = sh_reference_threads(0);
  opt.rt = rt;
  sh_image ref = {0};
  opt.spp = 256;
  sh_reference_stats st;
  sh_render_reference(s, &opt, &ref, &st, NULL);
  printf("reference: spp 256, %.2f s\n\n", st.seconds);
  printf("| render | spp | seconds | error vs reference |\n|---|---|---|---|\n");
  opt.spp = 16;
  opt.seed = 1;
  for (int v = 0; v < 3; v++) {
    lmm *L = NULL;
    opt.hook = NULL;
    if (v > 0) {
      lmm_options lo = {lmm_default_step(s), 2.0, LMM_SCHEME_REFRACT_TRACE, 0,
                        0, v == 2, 0, NULL, NULL, NULL};
      lmm_create(s, rt, &lo, opt.threads, &L, NULL);
      opt.hook = lmm_hook(L);
    }
    sh_image img = {0};
    sh_render_reference(s, &opt, &img, &st, NULL);
    const char *name[] = {"reference (traced shadow rays)",
                          "LMM surfaces, traced volume shadows",
                          "LMM surfaces and volume shadows from the mesh"};
    printf("| %s | %d | %.2f | %.2f%% |\n", name[v], opt.spp, st.seconds,
           100 * rel_error(&img, &ref));
    sh_image_free(&img);
    lmm_free(L);
  }
  printf("\n");
  sh_image_free(&ref);
  sh_rt_free(rt);
  sh_scene_free(s);
}

static const sh_cli_option options[] = {
    {"quick", 0, SH_CLI_FLAG, NULL, 0, 0, 0, 0, 0, 1, NULL, NULL, NULL, NULL,
     "smaller images and sample counts: the tables quickly, not the "
     "published figures"},
};

static const sh_cli_tool tool = {
    "lmm_bench", "[options]",
    "Benchmarks the light meshes method: LMM against RRTA as lights and image "
    "size grow,\nsoft shadows against area-light sampling, rays per second "
    "against Embree's\nceiling, volumetric shadows from the mesh (run by "
    "lmm_tracer/bench.sh).",
    options, (int)(sizeof options / sizeof *options), 0, 0, NULL, NULL, NULL,
    NULL, NULL, NULL};

int main(int argc, char **argv) {
  int quick = 0;
  sh_cli_args parsed;
  int rc = sh_cli_parse(&tool, argc, argv, &quick, &parsed);
  if (rc >= 0) return rc;
  int sizes_full[] = {512, 1024}, sizes_quick[] = {128};
  printf("# lmm_bench%s\n\n", quick ? " (quick)" : "");
  if (quick)
    scaling(sizes_quick, 1);
  else
    scaling(sizes_full, 2);
  area_quality(quick ? 96 : 256);
  ceiling(quick ? 128 : 512);
  const char *src = getenv("SHAFTS_SOURCE_DIR");
  size_t n = strlen(src ? src : ".") + sizeof "/scenes/teapot_spot.json";
  char *path = malloc(n);
  if (!path) return 1;
  snprintf(path, n, "%s/scenes/teapot_spot.json", src ? src : ".");
  volume(path, quick);
  free(path);
  return 0;
}
