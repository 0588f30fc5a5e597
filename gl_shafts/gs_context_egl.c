/* The EGL backend (gs_context.h): libEGL.so.1 (libglvnd's, which hands
 * each display to the vendor's driver: Mesa, NVIDIA...) loaded with dlopen.
 * Loading it at run time rather than linking it keeps the build free of
 * the library (only Khronos' headers are needed), lets the OSMesa fallback
 * work where libEGL is absent, and spares programs that never render (a
 * --help, a bad scene) its start-up cost.
 *
 * Displays are initialized and never terminated: eglGetPlatformDisplay
 * gives every caller in the process the same EGLDisplay for a device, so
 * eglTerminate could pull the display from under the application that
 * embeds gl_shafts (EGL_KHR_display_reference is not widely available). */
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EGL_NO_X11
#define EGL_EGL_PROTOTYPES 0
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "gs_context.h"

/* Core EGL 1.4/1.5 functions, looked up with dlsym; the extensions' with
 * eglGetProcAddress (NULL if absent). */
#define EGL_CORE(X)                                                          \
  X(PFNEGLGETPROCADDRESSPROC, GetProcAddress)                                \
  X(PFNEGLGETERRORPROC, GetError)                                            \
  X(PFNEGLQUERYSTRINGPROC, QueryString)                                      \
  X(PFNEGLINITIALIZEPROC, Initialize)                                        \
  X(PFNEGLBINDAPIPROC, BindAPI)                                              \
  X(PFNEGLQUERYAPIPROC, QueryAPI)                                            \
  X(PFNEGLCHOOSECONFIGPROC, ChooseConfig)                                    \
  X(PFNEGLCREATECONTEXTPROC, CreateContext)                                  \
  X(PFNEGLDESTROYCONTEXTPROC, DestroyContext)                                \
  X(PFNEGLMAKECURRENTPROC, MakeCurrent)                                      \
  X(PFNEGLGETCURRENTCONTEXTPROC, GetCurrentContext)                          \
  X(PFNEGLGETCURRENTDISPLAYPROC, GetCurrentDisplay)                          \
  X(PFNEGLGETCURRENTSURFACEPROC, GetCurrentSurface)
#define EGL_EXT(X)                                                           \
  X(PFNEGLQUERYDEVICESEXTPROC, QueryDevicesEXT)                              \
  X(PFNEGLQUERYDEVICESTRINGEXTPROC, QueryDeviceStringEXT)                    \
  X(PFNEGLGETPLATFORMDISPLAYEXTPROC, GetPlatformDisplayEXT)

static struct {
#define EGL_MEMBER(type, name) type name;
  EGL_CORE(EGL_MEMBER)
  EGL_EXT(EGL_MEMBER)
#undef EGL_MEMBER
} egl;
static char load_error[512];

static void load(void) {
  static const char *const names[] = {"libEGL.so.1", "libEGL.so", NULL};
  void *h = gs__context_dlopen(names, load_error, sizeof load_error);
  if (!h) return;
#define EGL_LOAD_CORE(type, name)                                            \
  if (!(egl.name = (type)gs__context_dlsym(h, names[0], "egl" #name,         \
                                           load_error, sizeof load_error)))  \
    return;
  EGL_CORE(EGL_LOAD_CORE)
#undef EGL_LOAD_CORE
#define EGL_LOAD_EXT(type, name) egl.name = (type)egl.GetProcAddress("egl" #name);
  EGL_EXT(EGL_LOAD_EXT)
#undef EGL_LOAD_EXT
}

/* Whether the space-separated list `exts` has `name`. */
static int has_ext(const char *exts, const char *name) {
  size_t n = strlen(name);
  for (const char *p = exts; p && (p = strstr(p, name)); p += n)
    if ((p == exts || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return 1;
  return 0;
}

typedef struct egl_impl {
  EGLDisplay dpy;
  EGLContext ctx;
  /* The thread's EGL state before make_current, which release restores. */
  EGLenum prev_api;
  EGLDisplay prev_dpy;
  EGLSurface prev_draw, prev_read;
  EGLContext prev_ctx;
} egl_impl;

static sh_status make_current(void *impl, sh_error *err) {
  egl_impl *e = impl;
  e->prev_api = egl.QueryAPI();
  egl.BindAPI(EGL_OPENGL_API);
  e->prev_ctx = egl.GetCurrentContext();
  e->prev_dpy = egl.GetCurrentDisplay();
  e->prev_draw = egl.GetCurrentSurface(EGL_DRAW);
  e->prev_read = egl.GetCurrentSurface(EGL_READ);
  if (e->prev_ctx == e->ctx) e->prev_ctx = EGL_NO_CONTEXT;
  if (!egl.MakeCurrent(e->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, e->ctx)) {
    EGLint code = egl.GetError();
    egl.BindAPI(e->prev_api);
    return sh_error_set(err, SH_ERR_DEVICE,
                        "EGL could not make the GL context current (EGL error "
                        "0x%x%s)", (unsigned)code,
                        code == EGL_BAD_ACCESS
                            ? ": it is current on another thread, or the thread "
                              "has another API's context current"
                            : "");
  }
  return SH_OK;
}

static void release(void *impl) {
  egl_impl *e = impl;
  if (e->prev_ctx != EGL_NO_CONTEXT)
    egl.MakeCurrent(e->prev_dpy, e->prev_draw, e->prev_read, e->prev_ctx);
  else
    egl.MakeCurrent(e->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  egl.BindAPI(e->prev_api);
  e->prev_ctx = EGL_NO_CONTEXT;
}

/* Appends a formatted part to why, the failure message. */
static void note(char *why, size_t size, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static void note(char *why, size_t size, const char *fmt, ...) {
  size_t used = strlen(why);
  if (used + 3 >= size) return;
  if (used) {
    memcpy(why + used, "; ", 3);
    used += 2;
  }
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(why + used, size - used, fmt, ap);
  va_end(ap);
}

/* An OpenGL 4.5 core context on `dpy`, with no surface, made current. */
static int context_on(EGLDisplay dpy, const char *where, egl_impl *e, char *why,
                      size_t why_size) {
  EGLint major = 0, minor = 0;
  if (dpy == EGL_NO_DISPLAY) {
    note(why, why_size, "%s: no display (EGL error 0x%x)", where, (unsigned)egl.GetError());
    return 0;
  }
  if (!egl.Initialize(dpy, &major, &minor)) {
    note(why, why_size, "%s: eglInitialize failed (EGL error 0x%x)", where,
         (unsigned)egl.GetError());
    return 0;
  }
  const char *exts = egl.QueryString(dpy, EGL_EXTENSIONS);
  if (!has_ext(exts, "EGL_KHR_surfaceless_context")) {
    note(why, why_size, "%s: no EGL_KHR_surfaceless_context", where);
    return 0;
  }
  if (major == 1 && minor < 5 && !has_ext(exts, "EGL_KHR_create_context")) {
    note(why, why_size, "%s: EGL 1.4 without EGL_KHR_create_context", where);
    return 0;
  }
  EGLenum prev_api = egl.QueryAPI();
  if (!egl.BindAPI(EGL_OPENGL_API)) {
    note(why, why_size, "%s: no desktop OpenGL (EGL error 0x%x)", where,
         (unsigned)egl.GetError());
    return 0;
  }
  EGLConfig config = EGL_NO_CONFIG_KHR;
  EGLint nconfigs = 0;
  static const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                          EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                          EGL_NONE};
  if (!has_ext(exts, "EGL_KHR_no_config_context") &&
      (!egl.ChooseConfig(dpy, config_attribs, &config, 1, &nconfigs) ||
       nconfigs < 1)) {
    note(why, why_size, "%s: no OpenGL config (EGL error 0x%x)", where,
         (unsigned)egl.GetError());
    egl.BindAPI(prev_api);
    return 0;
  }
  static const EGLint context_attribs[] = {
      EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
      EGL_NONE};
  e->dpy = dpy;
  e->ctx = egl.CreateContext(dpy, config, EGL_NO_CONTEXT, context_attribs);
  EGLint code = egl.GetError();
  egl.BindAPI(prev_api);
  if (e->ctx == EGL_NO_CONTEXT) {
    note(why, why_size, "%s: no OpenGL 4.5 core context (EGL error 0x%x)", where,
         (unsigned)code);
    return 0;
  }
  sh_error err = SH_ERROR_INIT;
  if (make_current(e, &err) != SH_OK) {
    note(why, why_size, "%s: %s", where, err.message);
    sh_error_clear(&err);
    egl.DestroyContext(dpy, e->ctx);
    e->ctx = EGL_NO_CONTEXT;
    return 0;
  }
  return 1;
}

/* Tries the devices of EGL_EXT_platform_device, hardware ones first. */
static int try_devices(egl_impl *e, char *why, size_t why_size) {
  const char *client = egl.QueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_ext(client, "EGL_EXT_platform_device") || !egl.QueryDevicesEXT ||
      !egl.QueryDeviceStringEXT || !egl.GetPlatformDisplayEXT) {
    note(why, why_size, "device platform: no EGL_EXT_platform_device");
    return 0;
  }
  enum { MAX_DEVICES = 16 };
  EGLDeviceEXT devices[MAX_DEVICES];
  EGLint n = 0;
  if (!egl.QueryDevicesEXT(MAX_DEVICES, devices, &n) || n == 0) {
    note(why, why_size, "device platform: no devices (EGL error 0x%x)",
         (unsigned)egl.GetError());
    return 0;
  }
  for (int pass = 0; pass < 2; pass++)
    for (int i = 0; i < n; i++) {
      const char *exts = egl.QueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
      int software = has_ext(exts, "EGL_MESA_device_software");
      if (software != pass) continue;
      char where[64];
      snprintf(where, sizeof where, "device %d (%s)", i,
               software ? "software" : "hardware");
      EGLDisplay dpy = egl.GetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT,
                                                 devices[i], NULL);
      if (context_on(dpy, where, e, why, why_size)) return 1;
    }
  return 0;
}

static pthread_once_t load_once = PTHREAD_ONCE_INIT;

int gs__egl_devices(char *buf, size_t size) {
  pthread_once(&load_once, load);
  buf[0] = '\0';
  if (load_error[0]) {
    snprintf(buf, size, "no EGL: %s\n", load_error);
    return -1;
  }
  const char *client = egl.QueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  enum { MAX_DEVICES = 16 };
  EGLDeviceEXT devices[MAX_DEVICES];
  EGLint n = 0;
  if (!has_ext(client, "EGL_EXT_platform_device") || !egl.QueryDevicesEXT ||
      !egl.QueryDeviceStringEXT || !egl.QueryDevicesEXT(MAX_DEVICES, devices, &n)) {
    snprintf(buf, size, "no EGL device enumeration (EGL_EXT_device_enumeration)\n");
    return -1;
  }
  size_t used = 0;
  int hardware = 0;
  for (int i = 0; i < n && used < size; i++) {
    const char *exts = egl.QueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
    int software = has_ext(exts, "EGL_MESA_device_software");
    const char *node = has_ext(exts, "EGL_EXT_device_drm")
                           ? egl.QueryDeviceStringEXT(devices[i], EGL_DRM_DEVICE_FILE_EXT)
                           : NULL;
    hardware += !software;
    int k = snprintf(buf + used, size - used, "device %d: %s%s%s; extensions: %s\n", i,
                     software ? "software" : "hardware", node ? ", " : "",
                     node ? node : "", exts ? exts : "(none)");
    used += k > 0 ? (size_t)k : 0;
  }
  return hardware;
}

static int try_surfaceless(egl_impl *e, char *why, size_t why_size) {
  const char *client = egl.QueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_ext(client, "EGL_MESA_platform_surfaceless") ||
      !egl.GetPlatformDisplayEXT) {
    note(why, why_size, "surfaceless platform: no EGL_MESA_platform_surfaceless");
    return 0;
  }
  EGLDisplay dpy = egl.GetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA,
                                             EGL_DEFAULT_DISPLAY, NULL);
  return context_on(dpy, "surfaceless platform", e, why, why_size);
}

static sh_status create(void **out, sh_error *err) {
  pthread_once(&load_once, load);
  if (load_error[0]) return sh_error_set(err, SH_ERR_DEVICE, "%s", load_error);
  egl_impl *e = calloc(1, sizeof *e);
  if (!e) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  char why[768] = "";
  if (try_devices(e, why, sizeof why) || try_surfaceless(e, why, sizeof why)) {
    *out = e;
    return SH_OK;
  }
  free(e);
  return sh_error_set(err, SH_ERR_DEVICE, "%s", why);
}

static gs__gl_proc get_proc(void *impl, const char *name) {
  (void)impl;
  return (gs__gl_proc)egl.GetProcAddress(name);
}

static void destroy(void *impl) {
  egl_impl *e = impl;
  if (!e) return;
  EGLenum api = egl.QueryAPI();
  egl.BindAPI(EGL_OPENGL_API);
  if (egl.GetCurrentContext() == e->ctx)
    egl.MakeCurrent(e->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  egl.BindAPI(api);
  egl.DestroyContext(e->dpy, e->ctx);
  free(e);
}

const gs__context_backend gs__context_egl = {
    "egl", create, make_current, release, get_proc, destroy};
