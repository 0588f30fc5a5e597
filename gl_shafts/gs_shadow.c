#include "gs_shadow.h"

static sh_status alloc_map(gs__shadow_map *sm, gs__shadow_kind kind, int res,
                           sh_error *err) {
  gs__shadow_free(sm);
  GLenum target = kind == GS__SHADOW_CUBE ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D;
  glCreateTextures(target, 1, &sm->tex);
  glTextureStorage2D(sm->tex, 1, GL_DEPTH_COMPONENT32F, res, res);
  glTextureParameteri(sm->tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(sm->tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(sm->tex, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTextureParameteri(sm->tex, GL_TEXTURE_COMPARE_FUNC, GL_GEQUAL);
  if (kind == GS__SHADOW_2D) {
    const float border[4] = {0, 0, 0, 0}; /* depth 0: infinitely far */
    glTextureParameteri(sm->tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
    glTextureParameteri(sm->tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
    glTextureParameterfv(sm->tex, GL_TEXTURE_BORDER_COLOR, border);
  } else {
    glTextureParameteri(sm->tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(sm->tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  glCreateFramebuffers(1, &sm->fbo);
  glNamedFramebufferDrawBuffer(sm->fbo, GL_NONE);
  glNamedFramebufferReadBuffer(sm->fbo, GL_NONE);
  sm->kind = kind;
  sm->res = res;
  return gs__gl_check("allocating a shadow map", err);
}

sh_status gs__shadow_render(gs__shadow_map *sm, const gs__light_setup *ls,
                            int res, const gs__geometry *geom,
                            gs__programs *progs, sh_error *err) {
  sh_status st = SH_OK;
  if (sm->kind != ls->shadow || sm->res != res || !sm->tex)
    st = alloc_map(sm, ls->shadow, res, err);
  GLuint prog = 0;
  if (st == SH_OK)
    st = gs__program_get(progs, &gs__glsl_shadow_vert, &gs__glsl_shadow_frag,
                         "", &prog, err);
  if (st != SH_OK) return st;
  glUseProgram(prog);
  glViewport(0, 0, res, res);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glBindFramebuffer(GL_FRAMEBUFFER, sm->fbo);
  /* Slope-scaled bias: stored depths pushed away from the light (reversed
   * depth: smaller), so that lit surfaces do not shadow themselves. Unlike
   * an offset along the normal, it leaves shadow edges where they are. The
   * factor was chosen by measurement (docs/gl_shafts.md). */
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(-16.0f, -1.0f);
  for (int f = 0; f < ls->nfaces; f++) {
    if (ls->shadow == GS__SHADOW_CUBE)
      glNamedFramebufferTextureLayer(sm->fbo, GL_DEPTH_ATTACHMENT, sm->tex, 0, f);
    else
      glNamedFramebufferTexture(sm->fbo, GL_DEPTH_ATTACHMENT, sm->tex, 0);
    if (glCheckNamedFramebufferStatus(sm->fbo, GL_FRAMEBUFFER) !=
        GL_FRAMEBUFFER_COMPLETE)
      return sh_error_set(err, SH_ERR_DEVICE,
                          "the shadow map's framebuffer is incomplete");
    const float zero = 0.0f;
    glClearNamedFramebufferfv(sm->fbo, GL_DEPTH, 0, &zero);
    gs__uniform_mat4(prog, "u_mvp", &ls->face_vp[f]);
    glBindVertexArray(geom->vao);
    for (int i = 0; i < geom->nshapes; i++)
      if (ls->casts[i]) glDrawArrays(GL_TRIANGLES, geom->shape[i].first, geom->shape[i].count);
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
  return gs__gl_check("rendering a shadow map", err);
}

void gs__shadow_bind(const gs__shadow_map *sm) {
  glBindTextureUnit(sm->kind == GS__SHADOW_CUBE ? 2 : 1, sm->tex);
}

void gs__shadow_free(gs__shadow_map *sm) {
  if (sm->fbo) glDeleteFramebuffers(1, &sm->fbo);
  if (sm->tex) glDeleteTextures(1, &sm->tex);
  sm->fbo = sm->tex = 0;
  sm->res = 0;
  sm->kind = GS__SHADOW_NONE;
}
