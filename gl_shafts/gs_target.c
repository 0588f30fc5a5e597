#include "gs_target.h"

#include <string.h>

static GLuint texture(GLenum format, int w, int h) {
  GLuint t;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, format, w, h);
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

sh_status gs__target_create(gs__target *t, int w, int h, sh_error *err) {
  memset(t, 0, sizeof *t);
  t->width = w;
  t->height = h;
  t->image = texture(GL_RGBA32F, w, h);
  t->lindepth = texture(GL_R32F, w, h);
  t->depth = texture(GL_DEPTH_COMPONENT32F, w, h);
  t->interval = texture(GL_RGBA32F, w, h);
  glCreateFramebuffers(1, &t->fbo);
  glNamedFramebufferTexture(t->fbo, GL_COLOR_ATTACHMENT0, t->image, 0);
  glNamedFramebufferTexture(t->fbo, GL_COLOR_ATTACHMENT1, t->lindepth, 0);
  glNamedFramebufferTexture(t->fbo, GL_DEPTH_ATTACHMENT, t->depth, 0);
  gs__target_draw_buffers(t, 2);
  glNamedFramebufferReadBuffer(t->fbo, GL_COLOR_ATTACHMENT0);
  glCreateFramebuffers(1, &t->interval_fbo);
  glNamedFramebufferTexture(t->interval_fbo, GL_COLOR_ATTACHMENT0, t->interval, 0);
  glNamedFramebufferDrawBuffer(t->interval_fbo, GL_COLOR_ATTACHMENT0);
  glCreateVertexArrays(1, &t->poly_vao);
  glCreateBuffers(1, &t->poly_vbo);
  glNamedBufferData(t->poly_vbo, 64 * 2 * sizeof(float), NULL, GL_DYNAMIC_DRAW);
  glVertexArrayVertexBuffer(t->poly_vao, 0, t->poly_vbo, 0, 2 * sizeof(float));
  glEnableVertexArrayAttrib(t->poly_vao, 0);
  glVertexArrayAttribFormat(t->poly_vao, 0, 2, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(t->poly_vao, 0, 0);
  sh_status st = gs__gl_check("creating the render targets", err);
  if (st == SH_OK &&
      (glCheckNamedFramebufferStatus(t->fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE ||
       glCheckNamedFramebufferStatus(t->interval_fbo, GL_FRAMEBUFFER) !=
           GL_FRAMEBUFFER_COMPLETE))
    st = sh_error_set(err, SH_ERR_DEVICE,
                      "the GL driver cannot render into 32-bit float "
                      "framebuffers of %dx%d",
                      w, h);
  if (st != SH_OK) gs__target_free(t);
  return st;
}

void gs__target_draw_buffers(const gs__target *t, int n) {
  const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0,
                          n > 1 ? GL_COLOR_ATTACHMENT1 : GL_NONE};
  glNamedFramebufferDrawBuffers(t->fbo, 2, bufs);
}

void gs__target_draw_polygon(const gs__target *t, const float *xy, int n) {
  if (n < 3) return;
  if (n > 64) n = 64;
  glNamedBufferData(t->poly_vbo, (GLsizeiptr)(n * 2 * sizeof(float)), xy,
                    GL_DYNAMIC_DRAW);
  glBindVertexArray(t->poly_vao);
  glDrawArrays(GL_TRIANGLE_FAN, 0, n);
}

void gs__target_free(gs__target *t) {
  GLuint tex[4] = {t->image, t->lindepth, t->depth, t->interval};
  for (int i = 0; i < 4; i++)
    if (tex[i]) glDeleteTextures(1, &tex[i]);
  if (t->fbo) glDeleteFramebuffers(1, &t->fbo);
  if (t->interval_fbo) glDeleteFramebuffers(1, &t->interval_fbo);
  if (t->poly_vbo) glDeleteBuffers(1, &t->poly_vbo);
  if (t->poly_vao) glDeleteVertexArrays(1, &t->poly_vao);
  memset(t, 0, sizeof *t);
}
