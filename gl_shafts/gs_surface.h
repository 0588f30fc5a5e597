/* The surfaces' pass: every visible surface shaded as the reference shades
 * it (emission + ambient * diffuse + per light Lambert and Phong terms with
 * the light's transmittance and shadow-map visibility), attenuated by the
 * medium towards the eye, and the background, attenuated likewise, where no
 * surface is seen. One pass per light, added. The first, for the light
 * whose surface_rect (gs_lightvol.h) is largest, also adds emission and
 * ambient everywhere and writes the depth buffer and the view depth the
 * sweep reads; each other light's pass is cut (scissored) to its
 * surface_rect, the only pixels whose surfaces it can light (on the
 * five-spot stage 0.42 to 0.54 of the screen each).
 *
 * Limitation: surfaces are not mirrors and are not see-through here; the
 * `reflect`, `transmit` and `ior` of materials are ignored (gs_render.h). */
#ifndef GS_SURFACE_H
#define GS_SURFACE_H

#include "gs_geometry.h"
#include "gs_lightvol.h"
#include "gs_params.h"
#include "gs_shadow.h"
#include "gs_target.h"

/* Light i's setup is lights[i], its shadow map shadows[i] (used if its
 * setup asks for one) and its light map texture maps[i] (0 if none). */
sh_status gs__surface_render(const gs__frame *fr, const gs__geometry *geom,
                             const gs__light_setup *lights,
                             const gs__shadow_map *shadows, const GLuint *maps,
                             const gs__target *target, sh_error *err);

#endif
