#include "gs_context.h"

#include <GL/osmesa.h>
#include <stdlib.h>

#include "gs_gl_load.h"

struct gs__context {
  OSMesaContext osmesa;
  unsigned char pixel[4]; /* the 1x1 default framebuffer */
  char renderer[128], version[128];
};

static gs__gl_proc get_proc(const char *name) {
  return (gs__gl_proc)OSMesaGetProcAddress(name);
}

sh_status gs__context_create(gs__context **out, sh_error *err) {
  *out = NULL;
  gs__context *ctx = calloc(1, sizeof *ctx);
  if (!ctx) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA,
                         OSMESA_DEPTH_BITS, 0,
                         OSMESA_STENCIL_BITS, 0,
                         OSMESA_ACCUM_BITS, 0,
                         OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, 4,
                         OSMESA_CONTEXT_MINOR_VERSION, 5,
                         0};
  ctx->osmesa = OSMesaCreateContextAttribs(attribs, NULL);
  if (!ctx->osmesa) {
    free(ctx);
    return sh_error_set(err, SH_ERR_DEVICE,
                        "OSMesa could not create an OpenGL 4.5 core context "
                        "(gl_shafts needs Mesa's llvmpipe, Mesa 20 or newer)");
  }
  sh_status st = gs__context_make_current(ctx, err);
  if (st == SH_OK) st = gs__gl_load(get_proc, err);
  if (st == SH_OK)
    st = gs__gl_setup(ctx->renderer, sizeof ctx->renderer, ctx->version,
                      sizeof ctx->version, err);
  if (st != SH_OK) {
    gs__context_free(ctx);
    return st;
  }
  *out = ctx;
  return SH_OK;
}

sh_status gs__context_make_current(gs__context *ctx, sh_error *err) {
  if (!OSMesaMakeCurrent(ctx->osmesa, ctx->pixel, GL_UNSIGNED_BYTE, 1, 1))
    return sh_error_set(err, SH_ERR_DEVICE,
                        "OSMesa could not make the GL context current");
  return SH_OK;
}

const char *gs__context_renderer(const gs__context *ctx) {
  return ctx->renderer;
}
const char *gs__context_version(const gs__context *ctx) {
  return ctx->version;
}

void gs__context_free(gs__context *ctx) {
  if (!ctx) return;
  if (ctx->osmesa) {
    if (OSMesaGetCurrentContext() == ctx->osmesa)
      OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
    OSMesaDestroyContext(ctx->osmesa);
  }
  free(ctx);
}
