/* Loading the GL entry points: the part of gs_gl.h that the OSMesa side
 * (gs_context.c) can include next to <GL/osmesa.h>, whose <GL/gl.h> clashes
 * with the <GL/glcorearb.h> that gs_gl.h uses. */
#ifndef GS_GL_LOAD_H
#define GS_GL_LOAD_H

#include <stddef.h>

#include "sh_error.h"

/* Looks a GL function up by name ("glClear"); NULL if it does not exist. */
typedef void (*gs__gl_proc)(void);
typedef gs__gl_proc (*gs__gl_getproc)(const char *name);

/* Fills the table of gs_gl.h through getproc. Returns SH_ERR_DEVICE naming
 * the first missing function. Safe to call again (it reloads). */
sh_status gs__gl_load(gs__gl_getproc getproc, sh_error *err);

/* Sets the context-wide state gl_shafts relies on (depth in [0, 1] for
 * reversed-Z) and copies the GL_RENDERER and GL_VERSION strings. Call with
 * the context current, after gs__gl_load. */
sh_status gs__gl_setup(char *renderer, size_t renderer_size, char *version,
                       size_t version_size, sh_error *err);

#endif
