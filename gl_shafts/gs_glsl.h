/* The GLSL sources in gl_shafts/shaders, embedded in the library at build
 * time (embed_glsl.cmake): one per file, named after it. */
#ifndef GS_GLSL_H
#define GS_GLSL_H

typedef struct gs__glsl {
  const char *name; /* the file name, for error messages */
  const char *text;
} gs__glsl;

extern const gs__glsl gs__glsl_common_glsl, gs__glsl_gs_shared_h, gs__glsl_medium_glsl;
extern const gs__glsl gs__glsl_shadow_vert, gs__glsl_shadow_frag;
extern const gs__glsl gs__glsl_surface_vert, gs__glsl_surface_frag;
extern const gs__glsl gs__glsl_screen_vert, gs__glsl_background_frag;
extern const gs__glsl gs__glsl_interval_frag;
extern const gs__glsl gs__glsl_plane_vert, gs__glsl_plane_glsl;
extern const gs__glsl gs__glsl_plane_dir_frag, gs__glsl_plane_local_frag;

/* Every file, NULL-terminated: what `#include "NAME"` finds
 * (gs_program.h). */
extern const gs__glsl *const gs__glsl_all[];

#endif
