/* The medium as gl_shafts sees it: the only C code of gl_shafts that looks
 * at the medium's kind (core/sh_medium.h answers everything else), the
 * shaders' medium.glsl being its GLSL side.
 * - Which kinds gl_shafts renders (homogeneous and height fog by the
 *   sweep, an atmosphere by gs_atmo_render.h), refusing others with
 *   sh_medium_require_kinds' located error.
 * - The kind as the shaders' MEDIUM switch (gs_shared.h), and the medium's
 *   parameters (u_sigma_s, u_sigma_t, u_bmin, u_bmax, u_g, u_fog; at the
 *   base height for height fog, positions in the anchored space of
 *   gs_view.h; an atmosphere's sphere and optical-depth table,
 *   atmo_table.glsl).
 * - The largest extinction in a light's lit volume, which decides how
 *   densely the sweep samples optical depth (gs_sweep.c). */
#ifndef GS_MEDIUM_H
#define GS_MEDIUM_H

#include "gs_polytope.h"
#include "gs_program.h"
#include "gs_view.h"
#include "sh_scene.h"

/* SH_OK if gl_shafts renders the scene's medium, else SH_ERR_SCENE located
 * at medium.type (or medium.phase.type), naming what it renders. */
sh_status gs__medium_check(const sh_scene *scene, sh_error *err);

/* Whether m is an atmosphere, which gs_atmo_render.h draws (its own
 * shaders, not the sweep's). */
int gs__medium_is_atmosphere(const sh_medium *m);

/* The MEDIUM switch's value for m (GS_MEDIUM_HOMOGENEOUS without one). */
int gs__medium_kind(const sh_medium *m);

/* The bounds a directional light's shadow map must hold in depth, into
 * lo and hi: the scene's (sh_scene_bounds), returning 0; for an
 * atmosphere its shapes' alone, returning 1: the air and the ground look
 * the map up with their depth clamped to its far end (atmo_shapes.glsl),
 * and the map then covers the shapes' bounds whole, not only the part in
 * view, as casters outside the view shadow the air in it. */
int gs__medium_shadow_bounds(const sh_scene *scene, sh_vec3 *lo, sh_vec3 *hi);

/* Appends the medium's parameters to p (zeros without a medium). */
void gs__medium_params(gs__params *p, const gs__view *view, const sh_medium *m);

/* The largest sigma_t (of the three channels) in the lit volume vol (world
 * coordinates): sh_medium_majorant_box over its bounding box. 0 for an
 * empty volume. */
double gs__medium_sigma_t_max(const sh_medium *m, const gs__poly *vol);

#endif
