#include "gs_context.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct gs__context {
  const gs__context_backend *backend;
  void *impl;
  pthread_mutex_t lock; /* held from make_current to release */
  gs__gl_api gl;
  char renderer[128], vendor[128], version[128];
};

void *gs__context_dlopen(const char *const *names, char *why, size_t why_size) {
  const char *reason = "no library named";
  for (int i = 0; names[i]; i++) {
    void *h = dlopen(names[i], RTLD_NOW | RTLD_LOCAL);
    if (h) return h;
    const char *e = dlerror();
    if (e) reason = e;
  }
  snprintf(why, why_size, "%s could not be loaded (%s)", names[0], reason);
  return NULL;
}

void *gs__context_dlsym(void *h, const char *lib, const char *symbol,
                        char *why, size_t why_size) {
  void *p = dlsym(h, symbol);
  if (!p) snprintf(why, why_size, "%s has no %s", lib, symbol);
  return p;
}

static gs__gl_proc get_proc(void *user, const char *name) {
  gs__context *ctx = user;
  return ctx->backend->get_proc(ctx->impl, name);
}

/* Creates the context on one backend, leaving it current (and locked). */
static sh_status create_on(const gs__context_backend *b, gs__context *ctx,
                           sh_error *err) {
  pthread_mutex_lock(&ctx->lock);
  sh_status st = b->create(&ctx->impl, err);
  if (st != SH_OK) {
    pthread_mutex_unlock(&ctx->lock);
    return st;
  }
  ctx->backend = b;
  st = gs__gl_load(get_proc, ctx, &ctx->gl, err);
  if (st == SH_OK) {
    gs__gl_current = &ctx->gl;
    st = gs__gl_setup(ctx->renderer, sizeof ctx->renderer, ctx->vendor,
                      sizeof ctx->vendor, ctx->version, sizeof ctx->version, err);
  }
  if (st != SH_OK) {
    gs__context_release(ctx);
    b->destroy(ctx->impl);
    ctx->impl = NULL;
    ctx->backend = NULL;
  }
  return st;
}

/* GS_BACKEND_AUTO narrowed by SHAFTS_GL_BACKEND. */
static sh_status resolve(gs_backend asked, gs_backend *out, sh_error *err) {
  *out = asked;
  const char *env = getenv("SHAFTS_GL_BACKEND");
  if (asked != GS_BACKEND_AUTO || !env || !*env || !strcmp(env, "auto"))
    return SH_OK;
  if (!strcmp(env, "egl")) *out = GS_BACKEND_EGL;
  else if (!strcmp(env, "osmesa")) *out = GS_BACKEND_OSMESA;
  else
    return sh_error_set(err, SH_ERR_ARG,
                        "the environment variable SHAFTS_GL_BACKEND must be "
                        "auto, egl or osmesa, not '%s'", env);
  return SH_OK;
}

sh_status gs__context_create(gs_backend asked, gs__context **out, sh_error *err) {
  *out = NULL;
  gs_backend want;
  sh_status st = resolve(asked, &want, err);
  if (st != SH_OK) return st;
  if (want != GS_BACKEND_AUTO && want != GS_BACKEND_EGL && want != GS_BACKEND_OSMESA)
    return sh_error_set(err, SH_ERR_ARG, "backend must be auto, egl or osmesa (%d)",
                        (int)want);
  gs__context *ctx = calloc(1, sizeof *ctx);
  if (!ctx) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  pthread_mutex_init(&ctx->lock, NULL);
  sh_error egl_err = SH_ERROR_INIT, osmesa_err = SH_ERROR_INIT;
  st = SH_ERR_DEVICE;
  if (want != GS_BACKEND_OSMESA) st = create_on(&gs__context_egl, ctx, &egl_err);
  if (st != SH_OK && st != SH_ERR_NOMEM && want != GS_BACKEND_EGL)
    st = create_on(&gs__context_osmesa, ctx, &osmesa_err);
  if (st == SH_OK) {
    *out = ctx;
  } else {
    pthread_mutex_destroy(&ctx->lock);
    free(ctx);
  }
  if (st == SH_OK || st == SH_ERR_NOMEM) {
    sh_error_clear(&egl_err);
    sh_error_clear(&osmesa_err);
    return st == SH_OK ? SH_OK : sh_error_set(err, st, "out of memory");
  }
  if (want == GS_BACKEND_EGL)
    st = sh_error_set(err, st, "the egl backend cannot give an OpenGL 4.5 core "
                      "context: %s", egl_err.message);
  else if (want == GS_BACKEND_OSMESA)
    st = sh_error_set(err, st, "the osmesa backend cannot give an OpenGL 4.5 "
                      "core context: %s", osmesa_err.message);
  else
    st = sh_error_set(err, st, "no backend gives an OpenGL 4.5 core context "
                      "(gl_shafts needs Mesa 20 or newer, or a GPU driver "
                      "with EGL); egl: %s; osmesa: %s",
                      egl_err.message, osmesa_err.message);
  sh_error_set_key(err, "backend");
  sh_error_clear(&egl_err);
  sh_error_clear(&osmesa_err);
  return st;
}

sh_status gs__context_make_current(gs__context *ctx, sh_error *err) {
  pthread_mutex_lock(&ctx->lock);
  sh_status st = ctx->backend->make_current(ctx->impl, err);
  if (st == SH_OK) gs__gl_current = &ctx->gl;
  else pthread_mutex_unlock(&ctx->lock);
  return st;
}

void gs__context_release(gs__context *ctx) {
  ctx->backend->release(ctx->impl);
  gs__gl_current = NULL;
  pthread_mutex_unlock(&ctx->lock);
}

const char *gs__context_backend_name(const gs__context *ctx) {
  return ctx->backend->name;
}
const char *gs__context_renderer(const gs__context *ctx) {
  return ctx->renderer;
}
const char *gs__context_vendor(const gs__context *ctx) {
  return ctx->vendor;
}
const char *gs__context_version(const gs__context *ctx) {
  return ctx->version;
}

void gs__context_free(gs__context *ctx) {
  if (!ctx) return;
  if (ctx->backend) ctx->backend->destroy(ctx->impl);
  pthread_mutex_destroy(&ctx->lock);
  free(ctx);
}
