/* The OSMesa backend (gs_context.h): Mesa's off-screen library, loaded with
 * dlopen so that gl_shafts builds without it (Mesa 25.1 removed it). The
 * few declarations it needs are copied here from Mesa's <GL/osmesa.h>,
 * which may be absent. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

#include "gs_context.h"

typedef struct osmesa_context *OSMesaContext;
typedef void (*OSMESAproc)(void);
#define OSMESA_RGBA 0x1908 /* GL_RGBA */
#define OSMESA_FORMAT 0x22
#define OSMESA_DEPTH_BITS 0x30
#define OSMESA_STENCIL_BITS 0x31
#define OSMESA_ACCUM_BITS 0x32
#define OSMESA_PROFILE 0x33
#define OSMESA_CORE_PROFILE 0x34
#define OSMESA_CONTEXT_MAJOR_VERSION 0x36
#define OSMESA_CONTEXT_MINOR_VERSION 0x37

typedef OSMesaContext (*create_context_attribs_fn)(const int *, OSMesaContext);
typedef unsigned char (*make_current_fn)(OSMesaContext, void *, GLenum, GLsizei,
                                         GLsizei);
typedef OSMesaContext (*get_current_context_fn)(void);
typedef void (*destroy_context_fn)(OSMesaContext);
typedef OSMESAproc (*get_proc_address_fn)(const char *);

#define OSMESA_FUNCS(X)                                                      \
  X(create_context_attribs_fn, CreateContextAttribs)                         \
  X(make_current_fn, MakeCurrent)                                            \
  X(get_current_context_fn, GetCurrentContext)                               \
  X(destroy_context_fn, DestroyContext)                                      \
  X(get_proc_address_fn, GetProcAddress)

static struct {
#define OSMESA_MEMBER(type, name) type name;
  OSMESA_FUNCS(OSMESA_MEMBER)
#undef OSMESA_MEMBER
} osmesa;
static char load_error[512];

static void load(void) {
  static const char *const names[] = {"libOSMesa.so.8", "libOSMesa.so.6", NULL};
  void *h = gs__context_dlopen(names, load_error, sizeof load_error);
  if (!h) return;
#define OSMESA_LOAD(type, name)                                              \
  if (!(osmesa.name = (type)gs__context_dlsym(h, names[0], "OSMesa" #name,   \
                                              load_error,                    \
                                              sizeof load_error)))           \
    return;
  OSMESA_FUNCS(OSMESA_LOAD)
#undef OSMESA_LOAD
}

typedef struct osmesa_impl {
  OSMesaContext ctx;
  unsigned char pixel[4]; /* the 1x1 buffer OSMesa needs to be current */
} osmesa_impl;

static sh_status make_current(void *impl, sh_error *err) {
  osmesa_impl *o = impl;
  if (!osmesa.MakeCurrent(o->ctx, o->pixel, 0x1401 /* GL_UNSIGNED_BYTE */, 1, 1))
    return sh_error_set(err, SH_ERR_DEVICE,
                        "OSMesa could not make the GL context current");
  return SH_OK;
}

static void release(void *impl) {
  (void)impl;
  osmesa.MakeCurrent(NULL, NULL, 0, 0, 0);
}

static sh_status create(void **out, sh_error *err) {
  static pthread_once_t once = PTHREAD_ONCE_INIT;
  pthread_once(&once, load);
  if (load_error[0]) return sh_error_set(err, SH_ERR_DEVICE, "%s", load_error);
  osmesa_impl *o = calloc(1, sizeof *o);
  if (!o) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA,
                         OSMESA_DEPTH_BITS, 0,
                         OSMESA_STENCIL_BITS, 0,
                         OSMESA_ACCUM_BITS, 0,
                         OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, 4,
                         OSMESA_CONTEXT_MINOR_VERSION, 5,
                         0};
  o->ctx = osmesa.CreateContextAttribs(attribs, NULL);
  if (!o->ctx) {
    free(o);
    return sh_error_set(err, SH_ERR_DEVICE,
                        "OSMesa could not create an OpenGL 4.5 core context "
                        "(Mesa 20 or newer has one)");
  }
  sh_status st = make_current(o, err);
  if (st != SH_OK) {
    osmesa.DestroyContext(o->ctx);
    free(o);
    return st;
  }
  *out = o;
  return SH_OK;
}

static gs__gl_proc get_proc(void *impl, const char *name) {
  (void)impl;
  return (gs__gl_proc)osmesa.GetProcAddress(name);
}

static void destroy(void *impl) {
  osmesa_impl *o = impl;
  if (!o) return;
  if (osmesa.GetCurrentContext() == o->ctx) release(o);
  osmesa.DestroyContext(o->ctx);
  free(o);
}

const gs__context_backend gs__context_osmesa = {
    "osmesa", create, make_current, release, get_proc, destroy};
