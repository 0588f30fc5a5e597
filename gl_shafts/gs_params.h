/* What the shaders need to know about the scene: the #defines that select a
 * program variant for a light (common.glsl lists them) and the uniforms of
 * the camera, the medium and a light. */
#ifndef GS_PARAMS_H
#define GS_PARAMS_H

#include <stddef.h>

#include "gs_gl.h"
#include "gs_lightvol.h"
#include "gs_view.h"
#include "sh_scene.h"

/* Writes the variant's #define lines for light ls (NULL: no light) into
 * buf: LIGHT_TYPE, HAS_MAP, SHADOW, CONE_CLIP, PHASE, GREY_SIGMA,
 * SPOT_SMOOTH, SPOT_EXPONENT and LIGHT_INSIDE, then `extra`. */
void gs__defines(char *buf, size_t size, const sh_scene *scene,
                 const gs__light_setup *ls, const char *extra);

/* Sets the camera's and the medium's uniforms (u_eye ... u_g). Without a
 * medium the coefficients are 0. */
void gs__set_view_uniforms(GLuint prog, const gs__view *view,
                           const sh_scene *scene);

/* Sets a light's uniforms (u_lpos ... u_shadow_near). */
void gs__set_light_uniforms(GLuint prog, const gs__light_setup *ls);

#endif
