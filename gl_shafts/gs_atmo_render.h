/* Drawing an atmosphere (gs_atmo.h) under directional suns, by the method
 * of Dobashi, Yamamoto and Nishita 2002 (seed 003, slides 31-50):
 * - the optical depths towards the sun and towards the eye from the
 *   precomputed table (gs_atmo_table.h), a texture;
 * - the eye inside the atmosphere (the sky from the ground): sampling
 *   planes, parallel to the screen, at view depths in geometric progression
 *   from the eye to the farthest air in view, each adding the single
 *   scattering of its slab (atmo_sky.frag);
 * - the eye above the top (the planet from space): sampling spheres about
 *   the planet's centre, at radii in equal steps of the Rayleigh density
 *   as the slides space them, each adding its shell (atmo_space.frag);
 * - the ground, an opaque Lambert sphere lit through the air, and the
 *   background through the air (atmo_base.frag).
 * Every pass is drawn in the eye's coordinates from quantities computed in
 * double precision (atmo.glsl), so a planet of radius 6360 km with the eye
 * 1 m above it, or seen from 30 000 km, keeps its precision.
 * The context must be current for every call. */
#ifndef GS_ATMO_RENDER_H
#define GS_ATMO_RENDER_H

#include "gs_atmo.h"
#include "gs_atmo_table.h"
#include "gs_params.h"
#include "gs_target.h"

/* Defaults: the table's size (gs_atmo_table_test measures its error), the
 * planes of the sky and the spheres of space. */
#define GS__ATMO_TABLE_R 64
#define GS__ATMO_TABLE_MU 256
#define GS__ATMO_PLANES 32
#define GS__ATMO_SPHERES 16

typedef struct gs__atmo_gl {
  gs__atmo atmo;
  gs__atmo_table table;
  GLuint tex; /* the table, RGBA32F, n_mu x n_r, linear filtering */
} gs__atmo_gl;

/* Builds the table from src (gs__atmo_source_medium for a scene's medium)
 * and uploads it. */
sh_status gs__atmo_gl_init(gs__atmo_gl *g, const gs__atmo *a,
                           const gs__atmo_source *src, sh_error *err);
void gs__atmo_gl_free(gs__atmo_gl *g);

/* What a frame of the atmosphere drew. */
typedef struct gs__atmo_counts {
  int planes, spheres; /* sampling planes or spheres drawn (over all suns) */
  int eye_outside;     /* 1: spheres (the eye above the top) */
} gs__atmo_counts;

/* Draws the atmosphere seen by fr's camera into t's image (replacing what
 * it held) under the scene's directional lights (the others are not
 * drawn: the caller refuses them), with `planes` sampling planes when the
 * eye is inside the atmosphere and `spheres` sampling spheres when it is
 * above the top (each >= 1). */
sh_status gs__atmo_render(const gs__atmo_gl *g, const gs__frame *fr,
                          const gs__target *t, int planes, int spheres,
                          gs__atmo_counts *counts, sh_error *err);

/* The view depths of the sky's planes: z[0] = 0 < z[1] < ... < z[n] =
 * zmax, z[1] = zmax * first and the rest in geometric progression. */
void gs__atmo_plane_depths(double zmax, double first, int n, double *z);

/* The radii of the sampling spheres: r[0] = R_g < ... < r[n] = R_t, the
 * Rayleigh density exp(-h / H_R) falling in n equal steps. */
void gs__atmo_sphere_radii(const gs__atmo *a, int n, double *r);

#endif
