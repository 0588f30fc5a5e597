/* The off-screen OpenGL 4.5 core context gl_shafts renders with, behind a
 * small backend interface (as libuv puts its platforms behind one set of
 * calls): gs_context.c chooses a backend and keeps what every backend
 * shares (the GL function table, the renderer strings); gs_context_egl.c
 * and gs_context_osmesa.c are the backends. Neither backend has a default
 * framebuffer that gl_shafts draws into: it renders only into framebuffer
 * objects (gs_target.h).
 *
 * Backends, in the order GS_BACKEND_AUTO tries them:
 *  - EGL (libEGL.so.1, libglvnd's, loaded with dlopen): the device platform
 *    (EGL_EXT_platform_device), a hardware device preferred over a software
 *    one (Mesa's llvmpipe device advertises EGL_MESA_device_software), then
 *    Mesa's surfaceless platform (EGL_MESA_platform_surfaceless); a context
 *    with no surface (EGL_KHR_surfaceless_context).
 *  - OSMesa (libOSMesa.so.8, loaded with dlopen): llvmpipe; it needs a
 *    buffer to make a context current, so it gets a 1x1 one.
 * Both libraries are loaded at run time, so gl_shafts builds with neither
 * installed and runs with either (Mesa 25.1 removed OSMesa).
 *
 * A context is current on at most one thread at a time. make_current takes
 * the context's lock (waiting while another thread has it current), makes
 * it current on the calling thread and points gs__gl_current (gs_gl.h) at
 * its function table; release undoes the three, restoring the EGL context
 * that was current on the thread before (if any), so a caller's own
 * context is left as it was. Every public gs_renderer_* call is bracketed
 * by the two, so calls on one renderer from several threads run one after
 * the other. */
#ifndef GS_CONTEXT_H
#define GS_CONTEXT_H

#include <stddef.h>

#include "gs_gl.h"
#include "gs_render.h"
#include "sh_error.h"

/* One backend: its entry points over its own state (`impl`). */
typedef struct gs__context_backend {
  const char *name; /* "egl", "osmesa": what gs_stats.backend reports */
  /* Creates a GL 4.5 core context and makes it current on the calling
   * thread (so that get_proc and the first GL calls work). Fills *impl.
   * SH_ERR_DEVICE with a message saying what was tried if there is none. */
  sh_status (*create)(void **impl, sh_error *err);
  sh_status (*make_current)(void *impl, sh_error *err);
  /* Leaves the context not current on the calling thread. */
  void (*release)(void *impl);
  gs__gl_proc (*get_proc)(void *impl, const char *name);
  /* Destroys the context (not current on any thread). */
  void (*destroy)(void *impl);
} gs__context_backend;

extern const gs__context_backend gs__context_egl;
extern const gs__context_backend gs__context_osmesa;

typedef struct gs__context gs__context;

/* Creates a context on the backend asked for (GS_BACKEND_AUTO: EGL, then
 * OSMesa; the environment variable SHAFTS_GL_BACKEND, "egl" or "osmesa",
 * narrows AUTO to one backend), loads its GL table and leaves it current on
 * the calling thread (release it when done). SH_ERR_DEVICE, with the key
 * "backend" and a message naming every backend tried and why it failed, if
 * none gives OpenGL 4.5 core. */
sh_status gs__context_create(gs_backend backend, gs__context **out, sh_error *err);

/* Makes the context current on the calling thread, first waiting for
 * another thread's release. */
sh_status gs__context_make_current(gs__context *ctx, sh_error *err);

/* Makes it not current on the calling thread. */
void gs__context_release(gs__context *ctx);

/* The backend's name, and the GL_RENDERER, GL_VENDOR and GL_VERSION
 * strings, for statistics. */
const char *gs__context_backend_name(const gs__context *ctx);
const char *gs__context_renderer(const gs__context *ctx);
const char *gs__context_vendor(const gs__context *ctx);
const char *gs__context_version(const gs__context *ctx);

/* Destroys the context; NULL is allowed. Call it with the context not
 * current on any other thread. */
void gs__context_free(gs__context *ctx);

/* One line per device EGL's device platform lists ("device 0: hardware,
 * /dev/dri/card0; extensions: ..."), for gpu_check.sh. Returns the number
 * of hardware devices (not EGL_MESA_device_software), or -1 with a line
 * saying why there is no list (no libEGL, no device enumeration). */
int gs__egl_devices(char *buf, size_t size);

/* dlopen of the first of `names` (a NULL-terminated list) that loads, for
 * a backend; on failure NULL, with a sentence naming the libraries and
 * dlerror's reason in why. */
void *gs__context_dlopen(const char *const *names, char *why, size_t why_size);

/* dlsym of `symbol` in the library h that gs__context_dlopen opened as
 * `lib`; on failure NULL, with "<lib> has no <symbol>" in why. */
void *gs__context_dlsym(void *h, const char *lib, const char *symbol,
                        char *why, size_t why_size);

#endif
