/* Shapes in an atmosphere (docs/gl_shafts.md, "Shapes and lights in the
 * atmosphere"): what the sky's passes (gs_atmo_render.h, atmo.glsl) add
 * for a scene with shapes, the shaders' side being atmo_shapes.glsl.
 * - The surfaces are drawn first by the surface pass (gs_surface.h), lit
 *   through the air (medium.glsl's optical depth of an atmosphere, from
 *   the table) with their shadow maps, and seen through it; they write the
 *   view depth. The sky's compose pass then draws only where no surface
 *   is, and every layer's stretch of a ray ends at the surface.
 * - A sun with casters has an orthographic shadow map over the shapes'
 *   bounds (gs__medium_shadow_bounds); the air and the ground are shadowed
 *   by it, the air sampled along each layer's stretch where it can be in
 *   a shadow at one sample per texel the stretch crosses.
 * The context must be current. */
#ifndef GS_ATMO_SHAPES_H
#define GS_ATMO_SHAPES_H

#include "gs_lightvol.h"
#include "gs_params.h"
#include "gs_shadow.h"

/* Appends what atmo_shapes.glsl reads to p, a pass of the sky for the
 * light whose setup is ls and shadow map sm (NULL: none): SURFACES (1 if
 * the scene has shapes), u_eye and u_shadow_res (the map's size, 0
 * without one). */
void gs__atmo_shapes_params(gs__params *p, const gs__frame *fr,
                            const gs__light_setup *ls, const gs__shadow_map *sm);

#endif
