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

/* A map's depths are a function of what it was drawn from: its kind and
 * size, each face's projection and winding, which shapes cast, and the
 * triangles (the exact spheres' uniforms change with them). The geometry
 * is keyed by a version that the renderer bumps whenever its triangles
 * change (gs_renderer_sync); the rest is compared. */
typedef struct gs__shadow_key {
  int valid;                  /* 0: draw at the next update */
  unsigned long geom_version;
  int nfaces;
  sh_mat4 face_vp[6];
  int light_front[6];
  int ncasts;
  unsigned char *casts;       /* ncasts bytes, owned */
} gs__shadow_key;

typedef struct gs__shadow_map {
  gs__shadow_kind kind;
  int res;
  GLuint tex, fbo;
  GLuint depth_sampler; /* tex read as depths (common.glsl, shadow_behind) */
  gs__shadow_key key;         /* what the texture holds */
} gs__shadow_map;

/* Renders the light's shadow map into sm, (re)allocating its texture when
 * the kind or size changes. Leaves the viewport and framebuffer changed. */
sh_status gs__shadow_render(gs__shadow_map *sm, const gs__frame *fr,
                            const gs__light_setup *ls, int res,
                            const gs__geometry *geom, sh_error *err);

/* gs__shadow_render unless the map already holds what it would draw: the
 * same key with the geometry at `geom_version`. *drawn says whether it
 * drew (then the viewport and framebuffer changed). */
sh_status gs__shadow_update(gs__shadow_map *sm, const gs__frame *fr,
                            const gs__light_setup *ls, int res,
                            const gs__geometry *geom, unsigned long geom_version,
                            int *drawn, sh_error *err);

/* Binds the map to its texture unit (1 for 2D, 2 for cube maps). */
void gs__shadow_bind(const gs__shadow_map *sm);

void gs__shadow_free(gs__shadow_map *sm);

#endif
