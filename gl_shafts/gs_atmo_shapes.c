#include "gs_atmo_shapes.h"

#include <stdio.h>

void gs__atmo_shapes_params(gs__params *p, const gs__frame *fr,
                            const gs__light_setup *ls, const gs__shadow_map *sm) {
  char defs[40];
  snprintf(defs, sizeof defs, "#define SURFACES %d\n", fr->scene->nshapes > 0);
  gs__params_text(p, defs);
  gs__param_v3(p, "u_eye", gs__anchored(fr->view, fr->view->frame.origin));
  gs__param_f(p, "u_shadow_res", ls && sm && ls->shadow != GS__SHADOW_NONE ? sm->res : 0);
}
