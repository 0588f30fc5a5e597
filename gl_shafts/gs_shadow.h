/* Shadow maps: one depth texture per light that needs one (2D or cube,
 * 32-bit float, reversed depth: larger is nearer the light), rendered from
 * the scene's triangles and read in the shaders by hardware comparison
 * (GL_GEQUAL: lit when the point is at least as near as the stored depth)
 * with bilinear filtering of the comparisons. Texels outside a 2D map
 * compare as lit. */
#ifndef GS_SHADOW_H
#define GS_SHADOW_H

#include "gs_geometry.h"
#include "gs_lightvol.h"
#include "gs_params.h"

typedef struct gs__shadow_map {
  gs__shadow_kind kind;
  int res;
  GLuint tex, fbo;
} gs__shadow_map;

/* Renders the light's shadow map into sm, (re)allocating its texture when
 * the kind or size changes. Leaves the viewport and framebuffer changed. */
sh_status gs__shadow_render(gs__shadow_map *sm, const gs__frame *fr,
                            const gs__light_setup *ls, int res,
                            const gs__geometry *geom, sh_error *err);

/* Binds the map to its texture unit (1 for 2D, 2 for cube maps). */
void gs__shadow_bind(const gs__shadow_map *sm);

void gs__shadow_free(gs__shadow_map *sm);

#endif
