/* The plane sweep for one light (Dobashi et al. 2000, section 5): virtual
 * planes parallel to the screen at regular view depths over the light's lit
 * volume, each drawn only over its screen polygon (the lit volume between
 * it and the next plane, projected), added to the image with float
 * blending. Each plane stands for its slab [z_k, z_k+1]; a fragment adds
 *   power * xi * pattern * visibility * dt
 * for the part of the slab its ray spends in the lit medium (the interval
 * pass works that out per pixel: box, spot cone or window prism, surface),
 * sampled at the middle of that part, or at a jittered depth in it. */
#ifndef GS_SWEEP_H
#define GS_SWEEP_H

#include "gs_lattice.h"
#include "gs_lightvol.h"
#include "gs_params.h"
#include "gs_shadow.h"
#include "gs_target.h"
#include "gs_view.h"
#include "sh_scene.h"

/* The largest optical-depth change one sample may stand for in a dense
 * medium (midpoint-rule error about its square / 24). */
#define GS__SUB_TAU 0.5

typedef struct gs__sweep {
  GLuint vao, vbo, query;
  float *verts;        /* 5 floats a vertex: ndc x, y, z front, z back, plane */
  size_t vcap;         /* vertices */
  GLint *first;
  GLsizei *count;
  size_t scap;         /* slabs */
} gs__sweep;

typedef struct gs__sweep_job {
  const gs__frame *frame;
  const gs__light_setup *light;
  const gs__shadow_map *shadow; /* used if the light's setup has a shadow */
  GLuint map;                   /* the light map texture, 0 if none */
  const gs__lattice *lattice;   /* NULL: xi exact */
  const double *lattice_map;    /* the lattice's texture-coordinate map */
  int planes, jitter;
  double sub_angle;             /* radians a sample may span, seen from a
                                   point or spot light */
  double sub_texels;            /* map texels a sample may span */
  int map_width, map_height;    /* the light map texture's size */
} gs__sweep_job;

/* Counts for statistics. */
typedef struct gs__sweep_counts {
  long planes;                 /* slabs drawn */
  double fragments_rasterized; /* pixels covered by their polygons */
  double fragments;            /* fragments that passed the depth test and
                                  lie in the lit interval */
} gs__sweep_counts;

sh_status gs__sweep_init(gs__sweep *sw, sh_error *err);

/* Adds one light's in-scattering to the target's image. */
sh_status gs__sweep_light(gs__sweep *sw, const gs__sweep_job *job,
                          const gs__target *target, gs__sweep_counts *counts,
                          sh_error *err);

void gs__sweep_free(gs__sweep *sw);

#endif
