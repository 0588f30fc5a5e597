#include "gs_atmo_light.h"

#include "shaders/gs_shared.h"

extern const gs__glsl gs__glsl_atmo_light_frag;

static const float FULL_SCREEN[8] = {-1, -1, 1, -1, 1, 1, -1, 1};

sh_status gs__atmo_light_render(const gs__atmo_gl *g, const gs__frame *fr,
                                const gs__target *t, const gs__light_setup *ls,
                                const gs__shadow_map *sm, GLuint map, int intervals,
                                sh_error *err) {
  if (intervals < 1) return sh_error_set(err, SH_ERR_ARG, "intervals must be >= 1");
  int shadowed = ls->shadow != GS__SHADOW_NONE;
  gs__params *p = gs__atmo_pass_params(g, fr, ls->light, ls, shadowed ? sm : NULL, "");
  gs__param_f(p, "u_depth", 0.0);
  GLuint prog;
  sh_status st = gs__program_use(fr->progs, &gs__glsl_screen_vert,
                                 &gs__glsl_atmo_light_frag, p, &prog, err);
  if (st != SH_OK) return st;
  gs__uniform_f(prog, "u_lat_scale", 1.0);
  gs__uniform_i(prog, "u_intervals", intervals);
  if (shadowed) gs__shadow_bind(sm);
  glBindTextureUnit(GS_UNIT_ATMO, g->tex);
  if (map) glBindTextureUnit(GS_UNIT_MAP, map);
  glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
  glViewport(0, 0, t->width, t->height);
  gs__target_draw_buffers(t, 1);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glBlendEquation(GL_FUNC_ADD);
  gs__target_draw_polygon(t, FULL_SCREEN, 4);
  glDisable(GL_BLEND);
  return gs__gl_check("drawing a light in the atmosphere", err);
}
