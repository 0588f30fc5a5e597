/* Drawing an atmosphere (gs_atmo.h) under directional suns, by the method
 * of Dobashi, Yamamoto and Nishita 2002 (seed 003, slides 31-50):
 * - the optical depths towards the sun and towards the eye from the
 *   precomputed table (gs_atmo_table.h), a texture;
 * - the eye inside the atmosphere (the sky from the ground): sampling
 *   planes, parallel to the screen, at view depths in geometric progression
 *   from the eye to the farthest air in view, each adding the single
 *   scattering of its slab (atmo_layer.frag);
 * - the eye above the top (the planet from space): sampling spheres about
 *   the planet's centre, at radii in equal steps of the Rayleigh density
 *   as the slides space them, each adding its shell (atmo_layer.frag);
 * - the layers drawn on a lattice of pixels and interpolated, as the
 *   slides evaluate the sun's light at lattice points, except across the
 *   horizon and the limb (atmo_compose.frag);
 * - the ground, an opaque Lambert sphere lit through the air, and the
 *   background and the sun's disk through the air (atmo_compose.frag).
 * Every pass is drawn in the eye's coordinates from quantities computed in
 * double precision (atmo.glsl), so a planet of radius 6360 km with the eye
 * 1 m above it, or seen from 30 000 km, keeps its precision.
 * The context must be current for every call. */
#ifndef GS_ATMO_RENDER_H
#define GS_ATMO_RENDER_H

#include "gs_atmo.h"
#include "gs_atmo_table.h"
#include "gs_params.h"
#include "gs_shadow.h"
#include "gs_target.h"
#include "shaders/gs_shared.h"

/* Defaults: the table's size (gs_atmo_table_test measures its error), the
 * planes of the sky and the spheres of space. */
#define GS__ATMO_TABLE_R 64
#define GS__ATMO_TABLE_MU 256
#define GS__ATMO_PLANES 12
#define GS__ATMO_SPHERES 6
/* The lattice's default step: the most pixels (at most 4) that fit in
 * half a degree of the camera's vertical field of view, at least 1. */
#define GS__ATMO_LATTICE_DEG 0.6
#define GS__ATMO_LATTICE_MAX 4

typedef struct gs__atmo_gl {
  gs__atmo atmo;
  gs__atmo_table table;
  GLuint tex; /* the table, RGBA32F, n_mu x n_r, linear filtering */
  GLuint lat_tex, lat_fbo; /* the lattice (RGBA32F), made at first use */
  int lat_w, lat_h;
} gs__atmo_gl;

/* How a frame is drawn. */
typedef struct gs__atmo_settings {
  int planes;  /* sampling planes, eye inside the atmosphere, 1 to
                  GS_ATMO_MAX_LAYERS (SH_ERR_ARG otherwise) */
  int spheres; /* sampling spheres, eye above the top, the same */
  /* The planes or spheres are drawn on a lattice of one pixel per
   * lattice_step x lattice_step block and interpolated (atmo_resolve.frag),
   * except where the horizon or the limb passes between lattice points,
   * drawn at full resolution; 1: every pixel at full resolution. */
  int lattice_step;
  /* The scene's light setups and shadow maps, by light (NULL: none): a
   * sun's map shadows the air and the ground (gs_atmo_shapes.h). With
   * shapes, the surfaces are drawn first (gs_surface.h), the rays end on
   * them, and lattice_step must be 1. */
  const gs__light_setup *lights;
  const gs__shadow_map *shadows;
} gs__atmo_settings;

/* The default lattice step for a camera (GS__ATMO_LATTICE_DEG). */
int gs__atmo_lattice_step(const sh_camera *cam);

/* Builds the table from src (gs__atmo_source_medium for a scene's medium)
 * and uploads it. */
sh_status gs__atmo_gl_init(gs__atmo_gl *g, const gs__atmo *a,
                           const gs__atmo_source *src, sh_error *err);
void gs__atmo_gl_free(gs__atmo_gl *g);

/* What a frame of the atmosphere drew, and where its time went: each pass
 * is ended by glFinish (gs__gl_lap), as gs_stats' stages are, so that
 * llvmpipe's shader time, anonymous JIT code to a profiler, is counted to
 * its pass. */
typedef struct gs__atmo_counts {
  int planes, spheres; /* sampling planes or spheres drawn (over all suns) */
  int eye_outside;     /* 1: spheres (the eye above the top) */
  double lattice_seconds; /* the layers drawn on the lattice */
  double compose_seconds; /* the full-resolution compose pass */
  double fixup_seconds;   /* the pixels the lattice cannot serve */
  double layer_seconds;   /* the layers at full resolution (no lattice) */
} gs__atmo_counts;

/* Draws the atmosphere seen by fr's camera into t's image (replacing what
 * it held) under the scene's
 * directional lights (the others are not drawn: the caller refuses them),
 * their disks included. */
sh_status gs__atmo_render(gs__atmo_gl *g, const gs__frame *fr, const gs__target *t,
                          const gs__atmo_settings *set, gs__atmo_counts *counts,
                          sh_error *err);

/* Starts the parameters of a pass that includes atmo.glsl (the sky's,
 * gs_atmo_light.h's) for light l (NULL: none) with its setup and shadow
 * map (NULL: none); the caller adds u_depth. */
gs__params *gs__atmo_pass_params(const gs__atmo_gl *g, const gs__frame *fr,
                                 const sh_light *l, const gs__light_setup *ls,
                                 const gs__shadow_map *sm, const char *extra);

/* The view depths of the sky's planes: z[0] = 0 < z[1] < ... < z[n] =
 * zmax, z[1] = zmax * first and the rest in geometric progression. */
void gs__atmo_plane_depths(double zmax, double first, int n, double *z);

/* The radii of the sampling spheres: r[0] = R_g < ... < r[n] = R_t, the
 * Rayleigh density exp(-h / H_R) falling in n equal steps. */
void gs__atmo_sphere_radii(const gs__atmo *a, int n, double *r);

#endif
