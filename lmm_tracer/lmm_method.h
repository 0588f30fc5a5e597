/* The light meshes method (Debelov, Smirnova, Vasilyeva 2008) as a shadow
 * hook of the Whitted tracer (sh_reference.h): the visibility V(i, P) of
 * light i from a shaded point P is replaced by an average over the mesh
 * points near P, which turns hard shadows soft.
 *
 * Algorithm Psi: the interpolation set DLM(P) holds the mesh points x within
 * the sphere r = h * kl about P, on the front side of P's surface
 * ((N, x - P) > 0) and visible from P through opaque surfaces. Then
 *   V_LM(i, P) = xi(i, P) * (1/m) sum over x in DLM(P) of v(x, P) v(i, x)
 * (formula 7; formula 4 in opaque scenes, where v(x, P) = 1), with xi(i, P)
 * = 1 if the light is on the outer side of P's surface (the light-leak
 * guard) and v(x, P) the transmittance between P and x. An empty set falls
 * back to the exact visibility (formula 3); such points are counted.
 *
 * The user controls of the paper's conclusion are honoured: a light with
 * soft_shadows false keeps its exact visibility; a material with
 * receives_soft_shadows false is shaded with exact visibility; the shadows
 * of a material with casts_soft_shadows false stay sharp (the mesh ignores
 * it and its exact shadow multiplies in). In a medium, the volume hook
 * interpolates the mesh trilinearly along camera rays (soft shafts). */
#ifndef LMM_METHOD_H
#define LMM_METHOD_H

#include <stdint.h>

#include "lmm_mesh.h"
#include "sh_reference.h"

/* Which paths the light meshes method refracts (Debelov et al., fig. 4;
 * render.scheme, --scheme). */
typedef enum lmm_scheme {
  LMM_SCHEME_DEFAULT,
  LMM_SCHEME_STRAIGHT,      /* refraction ignored everywhere */
  LMM_SCHEME_REFRACT_TRACE, /* refraction in traced rays only */
  LMM_SCHEME_REFRACT_BOTH   /* refraction in traced rays and visibility */
} lmm_scheme;

typedef struct lmm_options {
  double h;              /* mesh step, scene units */
  double kl;             /* interpolation radius in steps */
  lmm_scheme scheme;  /* which paths refract */
  int64_t caustic_rays;  /* refract-both: rays per light and shape */
  int capacity_log2;     /* mesh table size (0: default) */
  int volume;            /* 1: the medium's visibility from the mesh too */
  /* refract-both: the refined variant of section 5, which replaces
   * xi(i, P) v(i, x) by V(i, x) xi(i, P) + alpha xi(P_j, P). */
  int refined;
  /* Optional: stops the refract-both pass early (SH_ERR_CANCELLED), and
   * reports its rays (done, total) from the calling thread. */
  volatile int *cancel;
  void (*progress)(void *user, long done, long total);
  void *progress_user;
} lmm_options;

typedef struct lmm_stats {
  lmm_mesh_stats mesh;
  int64_t shaded_points;  /* surface points shaded through the method */
  int64_t empty_sets;     /* points whose DLM(P) was empty (formula 3) */
  int64_t candidate_rays; /* visibility rays from P to mesh points */
  int64_t volume_lookups; /* medium points interpolated from the mesh */
  int64_t caustic_points; /* mesh points credited with refracted paths */
  double build_seconds;   /* time to trace the refracted paths */
} lmm_stats;

typedef struct lmm lmm;

/* Sets up the method for `threads` workers (sh_reference_threads). The
 * refract-both scheme traces the refracted paths here. Caller frees with
 * lmm_free; scene and rt must outlive it. */
sh_status lmm_create(const sh_scene *scene, const sh_rt *rt,
                     const lmm_options *opt, int threads, lmm **out,
                     sh_error *err);
void lmm_free(lmm *method);

/* The hook to put in sh_reference_options.hook; valid while `method` is. */
const sh_shadow_hook *lmm_hook(const lmm *method);

void lmm_get_stats(const lmm *method, lmm_stats *stats);

/* A mesh step for the scene when none is given: 1/100 of the diagonal of
 * the shapes' bounds. */
double lmm_default_step(const sh_scene *scene);

#endif
