#include "sh_reference.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sh_camera.h"
#include "sh_inscatter.h"
#include "sh_light.h"
#include "sh_medium.h"
#include "sh_time.h"
#include "sh_rt.h"

typedef struct job {
  const sh_scene *scene;
  const sh_rt *rt;
  const sh_reference_options *opt;
  sh_camera_frame frame;
  sh_crop win;   /* the pixels rendered, in the whole image */
  sh_image *img; /* the window's size */
  long tiles_done; /* updated atomically */
  int next_tile;   /* claimed atomically */
  int tiles_x, tiles;
} job;

typedef struct worker {
  job *job;
  int index;
  pthread_t thread;
  sh_rt_counters counters;
  uint64_t samples, camera_rays;
  sh_vec3 *vis; /* per-light scratch for the shadow hook */
  double noise_sq, signal_sq; /* the noise estimate's sums */
  long noise_pixels;
} worker;

static sh_vec3 trace(worker *w, sh_vec3 o, sh_vec3 d, int depth, sh_rng *rng);

/* Light arriving at the hit's point p (normal n facing the viewer) from
 * every light, shaded with Lambert and Phong terms. */
static sh_vec3 direct_light(worker *w, const sh_material *mat, const sh_hit *h,
                            sh_vec3 n, sh_vec3 d) {
  sh_vec3 p = h->p;
  const sh_scene *scene = w->job->scene;
  sh_vec3 sum = sh_v3s(0.0);
  int has_spec = !sh_is_black(mat->specular);
  if (sh_is_black(mat->diffuse) && !has_spec) return sum;
  sh_vec3 origin = sh_rt_offset_hit(w->job->rt, h, n);
  const sh_shadow_hook *hook = w->job->opt->hook;
  int hooked = hook && hook->surface &&
               hook->surface(hook->user, w->index, h, n, w->vis,
                             &w->counters);
  for (int i = 0; i < scene->nlights; i++) {
    const sh_light *l = &scene->lights[i];
    sh_vec3 wi;
    double dist;
    sh_vec3 e = sh_light_incident(l, p, &wi, &dist);
    double cosl = sh_dot(n, wi);
    if (cosl <= 0 || sh_is_black(e)) continue;
    if (sh_medium_ground_blocks(&scene->medium, p, wi, dist)) continue;
    double tmax = isinf(dist) ? INFINITY : dist * (1.0 - 1e-7);
    sh_vec3 vis = hooked ? w->vis[i]
                         : sh_rt_visibility(w->job->rt, origin, wi, tmax,
                                            &w->counters);
    if (sh_is_black(vis)) continue;
    sh_vec3 tr = isinf(dist) ? sh_medium_transmittance_ray(&scene->medium, p, wi)
                             : sh_medium_transmittance(&scene->medium, p, l->position);
    e = sh_mul(sh_mul(e, vis), tr);
    sh_vec3 f = sh_scale(mat->diffuse, SH_INV_PI * cosl);
    if (has_spec) {
      double rv = sh_dot(sh_reflect(sh_neg(wi), n), sh_neg(d));
      if (rv > 0) f = sh_madd(f, mat->specular, pow(rv, mat->shininess));
    }
    sum = sh_add(sum, sh_mul(f, e));
  }
  return sum;
}

static sh_vec3 shade(worker *w, const sh_hit *h, sh_vec3 d, int depth,
                     sh_rng *rng) {
  const sh_scene *scene = w->job->scene;
  const sh_material *mat = &scene->materials[scene->shapes[h->shape].material];
  int entering = sh_dot(h->ng, d) < 0;
  sh_vec3 n = entering ? h->ng : sh_neg(h->ng);
  sh_vec3 L = sh_add(mat->emission, sh_mul(scene->ambient, mat->diffuse));
  L = sh_add(L, direct_light(w, mat, h, n, d));
  const sh_reference_options *opt = w->job->opt;
  if (depth >= opt->max_depth) return L;
  sh_vec3 reflected = sh_reflect(d, n);
  if (!opt->local && !sh_is_black(mat->reflect))
    L = sh_add(L, sh_mul(mat->reflect, trace(w, sh_rt_offset_hit(w->job->rt, h, n),
                                             reflected, depth + 1, rng)));
  if (!sh_is_black(mat->transmit)) {
    /* Snell's law; the inside of a closed shape has index `ior`. Total
     * internal reflection sends the transmitted weight along the mirror
     * direction. */
    double eta = opt->local || !opt->refract ? 1.0
                 : entering             ? 1.0 / mat->ior
                                        : mat->ior;
    double ci = -sh_dot(n, d);
    double k = 1.0 - eta * eta * (1.0 - ci * ci);
    sh_vec3 dir, org;
    if (k < 0) {
      dir = reflected;
      org = sh_rt_offset_hit(w->job->rt, h, n);
    } else {
      dir = sh_normalize(sh_madd(sh_scale(d, eta), n, eta * ci - sqrt(k)));
      org = sh_rt_offset_hit(w->job->rt, h, sh_neg(n));
    }
    if (eta == 1.0) dir = d; /* straight on, exactly */
    L = sh_add(L, sh_mul(mat->transmit, trace(w, org, dir, depth + 1, rng)));
  }
  return L;
}

/* An atmosphere's ground at p (sh_medium.h): a Lambert sphere of
 * ground_albedo lit by every light through the air, with the shadows of
 * the scene's surfaces, and the ambient term as a surface gets it. Its
 * normal is exact (the sphere's radius direction), so a point on it needs
 * no offset for the planet's own shadow (sh_medium_ground_blocks). */
static sh_vec3 shade_ground(worker *w, sh_vec3 p) {
  const sh_scene *scene = w->job->scene;
  const sh_medium *m = &scene->medium;
  sh_vec3 albedo = m->atmo.ground_albedo;
  sh_vec3 n = sh_normalize(sh_sub(p, m->atmo.center));
  sh_vec3 L = sh_mul(scene->ambient, albedo);
  /* Not an Embree surface: only the point's rounding counts. */
  sh_vec3 origin = sh_rt_offset_by(w->job->rt, p, n, 0.0);
  for (int i = 0; i < scene->nlights; i++) {
    sh_vec3 wi;
    double dist;
    sh_vec3 e = sh_light_incident(&scene->lights[i], p, &wi, &dist);
    double cosl = sh_dot(n, wi);
    if (cosl <= 0 || sh_is_black(e) || sh_medium_ground_blocks(m, p, wi, dist))
      continue;
    double tmax = isinf(dist) ? INFINITY : dist * (1.0 - 1e-7);
    sh_vec3 vis = sh_rt_visibility(w->job->rt, origin, wi, tmax, &w->counters);
    if (sh_is_black(vis)) continue;
    sh_vec3 tr = isinf(dist) ? sh_medium_transmittance_ray(m, p, wi)
                             : sh_medium_transmittance(m, p, scene->lights[i].position);
    L = sh_add(L, sh_scale(sh_mul(sh_mul(albedo, e), sh_mul(vis, tr)),
                           SH_INV_PI * cosl));
  }
  return L;
}

static sh_vec3 trace(worker *w, sh_vec3 o, sh_vec3 d, int depth, sh_rng *rng) {
  const sh_scene *scene = w->job->scene;
  sh_hit h;
  int hit = sh_rt_intersect(w->job->rt, o, d, 0.0, INFINITY, &h, &w->counters);
  double tend = hit ? h.t : INFINITY;
  /* The medium ends on this side of the surface (sh_rt_free_end). */
  double tfree = hit ? sh_rt_free_end(w->job->rt, o, d, &h) : INFINITY;
  const sh_medium *m = &scene->medium;
  double tg;
  sh_vec3 L;
  if (sh_medium_ground_hit(m, o, d, tend, &tg)) {
    /* The ground (double precision about the planet's centre) is nearer
     * than every surface. */
    tfree = tg;
    L = shade_ground(w, sh_madd(o, d, tg));
  } else {
    L = hit ? shade(w, &h, d, depth, rng)
            : sh_scene_background_radiance(scene, d);
  }
  double t0, t1;
  if (sh_medium_clip(m, o, d, 0.0, tfree, &t0, &t1)) {
    L = sh_mul(L, sh_medium_transmittance_span(m, o, d, t0, t1));
    for (int i = 0; i < scene->nlights; i++)
      L = sh_add(L, sh_inscatter_light(scene, w->job->rt, w->job->opt->hook,
                                       w->index, &scene->lights[i], o,
                                       d, t0, t1, w->job->opt->spp, rng,
                                       &w->counters, &w->samples));
  }
  return L;
}

/* Pixels are rendered in square tiles, claimed one at a time, so that the
 * threads share the work evenly and each walks a compact part of the scene
 * (and of the light mesh's cache). */
enum { TILE = 16 };

/* The noise estimate's second render of a pixel (sh_reference_stats):
 * independent random numbers, counted in no statistic but its own. */
static void second_render(worker *w, sh_vec3 d, sh_vec3 L, uint64_t pixel) {
  sh_rt_counters counters = w->counters;
  uint64_t samples = w->samples;
  sh_rng rng;
  sh_rng_seed(&rng, w->job->opt->seed ^ 0x9e3779b97f4a7c15ULL,
              pixel ^ 0x5851f42d4c957f2dULL);
  sh_vec3 L2 = trace(w, w->job->frame.origin, d, 0, &rng);
  w->counters = counters;
  w->samples = samples;
  sh_vec3 diff = sh_sub(L, L2);
  double n = sh_dot(diff, diff), s = sh_dot(L, L);
  if (isfinite(n) && isfinite(s)) {
    w->noise_sq += 0.5 * n;
    w->signal_sq += s;
    w->noise_pixels++;
  }
}

static void *work(void *arg) {
  worker *w = arg;
  job *jb = w->job;
  /* Pixel (x, y) of the whole image: its index seeds its random stream. */
  const sh_crop *win = &jb->win;
  uint64_t width = (uint64_t)jb->frame.width;
  for (;;) {
    if (jb->opt->cancel && *jb->opt->cancel) break;
    int tile = __atomic_fetch_add(&jb->next_tile, 1, __ATOMIC_RELAXED);
    if (tile >= jb->tiles) break;
    int x0 = win->x0 + (tile % jb->tiles_x) * TILE;
    int y0 = win->y0 + (tile / jb->tiles_x) * TILE;
    for (int y = y0; y < y0 + TILE && y < win->y1; y++)
      for (int x = x0; x < x0 + TILE && x < win->x1; x++) {
        sh_rng rng;
        sh_rng_seed(&rng, jb->opt->seed, (uint64_t)y * width + x);
        sh_vec3 d = sh_camera_dir(&jb->frame, x + 0.5, y + 0.5);
        w->camera_rays++;
        sh_vec3 L = trace(w, jb->frame.origin, d, 0, &rng);
        if (!jb->opt->hook && x % SH_REFERENCE_NOISE_STRIDE == SH_REFERENCE_NOISE_STRIDE / 2 &&
            y % SH_REFERENCE_NOISE_STRIDE == SH_REFERENCE_NOISE_STRIDE / 2)
          second_render(w, d, L, (uint64_t)y * width + x);
        float *px = jb->img->rgb +
                    3 * ((size_t)(y - win->y0) * jb->img->width + (x - win->x0));
        px[0] = (float)L.x;
        px[1] = (float)L.y;
        px[2] = (float)L.z;
      }
    long done = __atomic_add_fetch(&jb->tiles_done, 1, __ATOMIC_RELAXED);
    if (jb->opt->progress)
      jb->opt->progress(jb->opt->progress_user, done, jb->tiles);
  }
  return NULL;
}

sh_reference_options sh_reference_defaults(const sh_scene *scene) {
  sh_reference_options o;
  memset(&o, 0, sizeof o);
  o.spp = scene->render.spp;
  o.max_depth = scene->render.max_depth;
  o.seed = scene->render.seed;
  o.refract = 1;
  return o;
}

int sh_reference_threads(int threads) {
  if (threads > 0) return threads;
  long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? (int)n : 1;
}

sh_status sh_render_reference(const sh_scene *scene,
                              const sh_reference_options *opt, sh_image *out,
                              sh_reference_stats *stats, sh_error *err) {
  if (opt->spp < 1 || opt->max_depth < 0 || opt->threads < 0)
    return sh_error_set(err, SH_ERR_ARG,
                        "spp must be >= 1, max_depth and threads >= 0");
  sh_status st = sh_crop_check(&opt->crop, &scene->camera, err);
  if (st != SH_OK) return st;
  double start = sh_seconds();
  job jb;
  memset(&jb, 0, sizeof jb);
  jb.win = sh_crop_window(&opt->crop, &scene->camera);
  st = sh_image_alloc(out, jb.win.x1 - jb.win.x0, jb.win.y1 - jb.win.y0, err);
  if (st != SH_OK) return st;
  jb.scene = scene;
  jb.opt = opt;
  jb.img = out;
  sh_camera_frame_init(&scene->camera, &jb.frame);
  sh_rt *rt = NULL;
  if (!opt->rt) {
    st = sh_rt_create(scene, &rt, err);
    if (st != SH_OK) {
      sh_image_free(out);
      return st;
    }
  }
  jb.rt = opt->rt ? opt->rt : rt;
  jb.tiles_x = (out->width + TILE - 1) / TILE;
  jb.tiles = jb.tiles_x * ((out->height + TILE - 1) / TILE);
  int nthreads = sh_reference_threads(opt->threads);
  if (nthreads > jb.tiles) nthreads = jb.tiles;
  worker *ws = calloc((size_t)nthreads, sizeof *ws);
  sh_vec3 *vis = calloc((size_t)nthreads * (scene->nlights + 1), sizeof *vis);
  if (!ws || !vis) {
    free(ws);
    free(vis);
    sh_rt_free(rt);
    sh_image_free(out);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  }
  int started = 0;
  for (int i = 0; i < nthreads; i++) {
    ws[i].job = &jb;
    ws[i].index = i;
    ws[i].vis = vis + (size_t)i * (scene->nlights + 1);
    if (i > 0 && pthread_create(&ws[i].thread, NULL, work, &ws[i]) != 0) break;
    started++;
  }
  work(&ws[0]);
  for (int i = 1; i < started; i++) pthread_join(ws[i].thread, NULL);
  if (stats) {
    double noise_sq = 0, signal_sq = 0;
    memset(stats, 0, sizeof *stats);
    for (int i = 0; i < started; i++) {
      stats->camera_rays += ws[i].camera_rays;
      stats->closest_rays += ws[i].counters.closest;
      stats->occlusion_rays += ws[i].counters.occlusion;
      stats->medium_samples += ws[i].samples;
      noise_sq += ws[i].noise_sq;
      signal_sq += ws[i].signal_sq;
      stats->noise_pixels += ws[i].noise_pixels;
    }
    stats->noise_rel_rms = signal_sq > 0 ? sqrt(noise_sq / signal_sq) : 0.0;
    stats->threads = started;
    stats->seconds = sh_seconds() - start;
  }
  free(ws);
  free(vis);
  sh_rt_free(rt);
  if (opt->cancel && *opt->cancel) {
    sh_image_free(out);
    return sh_error_set(err, SH_ERR_CANCELLED, "rendering was cancelled");
  }
  return SH_OK;
}
