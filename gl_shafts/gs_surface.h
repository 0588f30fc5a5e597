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

/* The sun's disks (docs/scene-format.md, "The sun's disk"), as the
 * reference sees them (sh_light_disk_radiance), for a pass that draws what
 * rays leaving the scene see: declares one (u_sun_dirN, u_sun_radianceN)
 * pair per directional light with a disk (per directional light when
 * `live`, so that a scene patch turning a disk on or off builds no
 * program) and defines SUN_DISKS(d), their radiance in the unit direction
 * d (common.glsl). u_sun_dirN holds the direction the light comes from
 * and 4 sin^2(half angle / 2), the squared chord |d - s|^2 at the disk's
 * edge, which keeps its digits in single precision for a 0.5 degree disk
 * where 1 - cos does not. */
void gs__sun_disks(gs__params *p, const sh_scene *scene, int live);

#endif
