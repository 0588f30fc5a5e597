/* The reference renderer: Whitted ray tracing (direct light with hard
 * shadows through semitransparent surfaces, mirror reflection, refraction
 * weighted by k_t as in formula 2 of Debelov et al. 2008) plus single
 * scattering in the medium (homogeneous, height fog or atmosphere) along
 * every ray segment, seen directly and through reflection and refraction.
 * The medium answers for optical depth, transmittance and the coefficients
 * and phase at each sample (sh_medium.h); the transmittances are exact
 * (closed forms) for homogeneous media and height fog, and within 1e-8
 * relative (Gauss-Legendre panels, sh_atmosphere.h) for an atmosphere. An
 * atmosphere's ground is an opaque Lambert sphere intersected in double
 * precision before the scene's surfaces, lit through the air, and it
 * shadows the air and every surface (the planet's shadow).
 *
 * Every pixel is sampled at its centre. The in-scattering integral is
 * estimated per ray segment and light with `spp` stratified samples:
 * equiangular sampling over the part of the segment inside a spot's cone
 * for point and spot lights (the 1/r^2 cancels), sampling by the mean
 * channel's extinction and transmittance for directional lights
 * (sh_medium_sample_distance). Accumulation is in double precision and
 * every pixel seeds its own random stream, so the image depends only on the
 * scene, spp and seed, not on the thread count. */
#ifndef SH_REFERENCE_H
#define SH_REFERENCE_H

#include <stdint.h>

#include "sh_camera.h"
#include "sh_error.h"
#include "sh_image.h"
#include "sh_rt.h"
#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sh_reference_options {
  int spp;           /* in-scattering samples per segment and light, >= 1 */
  int max_depth;     /* reflection/refraction recursion limit, >= 0 */
  uint64_t seed;
  int threads;       /* 0: one per online CPU */
  /* Optional: called from the worker threads as the work advances, with
   * the finished and the total units (tiles of the image), at most once
   * per unit. Calls from different threads may overlap and arrive out of
   * order (keep the largest `done`); keep it cheap. NULL: no reports. The
   * library never prints: the tools install a terminal bar here. */
  void (*progress)(void *user, long done, long total);
  void *progress_user;
  /* Optional: when *cancel becomes non-zero the workers stop after their
   * current tile and the call returns SH_ERR_CANCELLED with nothing
   * allocated. Read without locks from every worker. */
  volatile int *cancel;
  /* 1 (default): transmitted rays refract by Snell's law; 0: they go on
   * straight, as OpenGL shows semitransparent surfaces. */
  int refract;
  /* 1: the local illumination model with shadows (formula 1 of Debelov et
   * al.): no mirror rays; transmitted rays go on straight. Default 0. */
  int local;
  /* Optional: render the window alone (sh_camera.h): `out` is the
   * window's size, and each of its pixels is the same pixel of the whole
   * image to the bit (its ray and its random stream are the whole image's).
   * All zero: the whole image. */
  sh_crop crop;
  const sh_rt *rt;            /* optional: a prebuilt sh_rt of the scene */
  const sh_shadow_hook *hook; /* optional */
} sh_reference_options;

typedef struct sh_reference_stats {
  double seconds;
  uint64_t camera_rays, closest_rays, occlusion_rays, medium_samples;
  int threads;
  /* An estimate of the image's own noise, as the relative RMS error that
   * sh_image_compare would measure between this image and the converged
   * one: one pixel in every NOISE_STRIDE x NOISE_STRIDE block (its centre)
   * is rendered a second time with independent random numbers, and
   * sqrt(sum |a - b|^2 / 2 / sum |a|^2) over those pixels estimates the
   * per-pixel standard deviation relative to the signal (the difference of
   * two independent estimates has twice the variance of one). It costs
   * 1/64 more work, and the second renders count in no other statistic.
   * Not made (0, noise_pixels 0) with a shadow hook, whose caches the
   * second render would change. Halving it takes 4x the spp. */
  double noise_rel_rms;
  long noise_pixels; /* the pixels rendered twice */
} sh_reference_stats;

/* The block size of the noise estimate (one pixel rendered twice a block). */
#define SH_REFERENCE_NOISE_STRIDE 8

/* The number of worker threads `threads` resolves to (0: one per CPU). */
int sh_reference_threads(int threads);

/* Options from the scene's render settings, with threads = 0, no progress
 * callback, refraction on. */
sh_reference_options sh_reference_defaults(const sh_scene *scene);

/* Renders `scene` into `out`, which the call allocates at the camera's size
 * (caller frees with sh_image_free). `stats` may be NULL. */
sh_status sh_render_reference(const sh_scene *scene,
                              const sh_reference_options *opt, sh_image *out,
                              sh_reference_stats *stats, sh_error *err);

#ifdef __cplusplus
}
#endif
#endif
