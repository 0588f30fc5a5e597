#include "gs_gl.h"

#include "sh_time.h"

#include <stdio.h>
#include <string.h>

_Thread_local const gs__gl_api *gs__gl_current;

sh_status gs__gl_load(gs__gl_getproc getproc, void *user, gs__gl_api *api,
                      sh_error *err) {
  memset(api, 0, sizeof *api);
#define GS__GL_LOAD(type, name)                                              \
  api->name = (type)getproc(user, "gl" #name);                               \
  if (!api->name)                                                            \
    return sh_error_set(err, SH_ERR_DEVICE,                                  \
                        "the OpenGL library has no gl" #name                 \
                        "; gl_shafts needs OpenGL 4.5");
  GS__GL_FUNCS(GS__GL_LOAD)
#undef GS__GL_LOAD
  return SH_OK;
}

static const char *error_name(GLenum e) {
  switch (e) {
  case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
  case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
  case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
  case GL_INVALID_FRAMEBUFFER_OPERATION:
    return "GL_INVALID_FRAMEBUFFER_OPERATION";
  case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
  case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
  case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
  default: return "an unknown GL error";
  }
}

double gs__gl_lap(double *t) {
  glFinish();
  double now = sh_seconds(), d = now - *t;
  *t = now;
  return d;
}

sh_status gs__gl_check(const char *what, sh_error *err) {
  GLenum e = glGetError();
  if (e == GL_NO_ERROR) return SH_OK;
  GLenum first = e;
  char names[256] = "";
  size_t used = 0;
  /* Drain the queue (bounded: a lost context can report forever). */
  for (int n = 0; e != GL_NO_ERROR && n < 8; n++, e = glGetError()) {
    const char *s = error_name(e);
    size_t len = strlen(s);
    if (used + len + 3 < sizeof names) {
      if (used) {
        memcpy(names + used, ", ", 2);
        used += 2;
      }
      memcpy(names + used, s, len + 1);
      used += len;
    }
  }
  return sh_error_set(err, first == GL_OUT_OF_MEMORY ? SH_ERR_NOMEM : SH_ERR_DEVICE,
                      "OpenGL reported %s while %s", names, what);
}

sh_status gs__gl_setup(char *renderer, size_t renderer_size, char *vendor,
                       size_t vendor_size, char *version, size_t version_size,
                       sh_error *err) {
  const char *r = (const char *)glGetString(GL_RENDERER);
  const char *d = (const char *)glGetString(GL_VENDOR);
  const char *v = (const char *)glGetString(GL_VERSION);
  snprintf(renderer, renderer_size, "%s", r ? r : "unknown");
  snprintf(vendor, vendor_size, "%s", d ? d : "unknown");
  snprintf(version, version_size, "%s", v ? v : "unknown");
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  return gs__gl_check("setting up the GL context", err);
}
