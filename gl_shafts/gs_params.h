/* What the shaders need to know about the scene: the #defines that select a
 * program variant for a light (common.glsl lists them) and the parameters
 * (gs_program.h) of the camera, the medium and a light. */
#ifndef GS_PARAMS_H
#define GS_PARAMS_H

#include "gs_lightvol.h"
#include "gs_program.h"
#include "gs_view.h"
#include "sh_scene.h"

/* What the passes of a frame share. */
typedef struct gs__frame {
  const sh_scene *scene;
  const gs__view *view;
  gs__programs *progs;
  gs__params *params; /* reused by every draw */
  int bake;           /* bake parameters into programs (gs_program.h);
                         0: live programs (gs_options.live) */
} gs__frame;

/* Starts the frame's parameter block for a draw with light ls (NULL: no
 * light):
 * resets it, then appends the variant's #define lines (LIGHT_TYPE, HAS_MAP,
 * SHADOW, CONE_CLIP, PHASE, GREY_SIGMA, SPOT_SMOOTH, SPOT_EXPONENT,
 * LIGHT_INSIDE and MEDIUM; live programs take SPOT_SMOOTH 2, which holds for any
 * cone), `extra` lines, and the
 * camera's, the medium's and the
 * light's parameters (u_org ..., the medium's of gs_medium.h, u_lpos ...
 * u_shadow_near). Without a medium its coefficients are 0. */
gs__params *gs__params_begin(const gs__frame *fr, const gs__light_setup *ls,
                             const char *extra);

#endif
