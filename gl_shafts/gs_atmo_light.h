/* Point and spot lights in an atmosphere (docs/gl_shafts.md, "Shapes and
 * lights in the atmosphere"): their single scattering in the air and
 * their light on the ground, added to the image after the sky's passes
 * (gs_atmo_render.h) by one full-screen pass a light (atmo_light.frag).
 * The light's 1 / r^2 is integrated exactly in the angle domain (dt / r^2
 * = dtheta / h, h the light's distance from the pixel's ray), the rest of
 * the integrand at 3 Gauss-Legendre nodes in each of `intervals` equal
 * steps of the angle; the air's optical depth from the sky's table
 * (medium.glsl's atmosphere), the shapes' shadows from the light's shadow
 * map, the ray ending on the surfaces (gs_atmo_shapes.h). The shapes
 * themselves are lit by the surface pass. The context must be current. */
#ifndef GS_ATMO_LIGHT_H
#define GS_ATMO_LIGHT_H

#include "gs_atmo_render.h"
#include "gs_lightvol.h"
#include "gs_shadow.h"
#include "gs_target.h"

/* The angle steps a light's pass takes by default. */
#define GS__ATMO_LIGHT_INTERVALS 16

/* Adds light ls->light (point or spot) to t's image: its shadow map sm
 * (used if ls has one), its light map texture map (0: none), `intervals`
 * >= 1 steps of the angle. */
sh_status gs__atmo_light_render(const gs__atmo_gl *g, const gs__frame *fr,
                                const gs__target *t, const gs__light_setup *ls,
                                const gs__shadow_map *sm, GLuint map, int intervals,
                                sh_error *err);

#endif
