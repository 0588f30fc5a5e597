/* The off-screen OpenGL context: an OSMesa (llvmpipe) OpenGL 4.5 core
 * context. It renders only into framebuffer objects; the 1x1 OSMesa buffer
 * exists because OSMesa needs one to make a context current. */
#ifndef GS_CONTEXT_H
#define GS_CONTEXT_H

#include "sh_error.h"

typedef struct gs__context gs__context;

/* Creates a context, makes it current on the calling thread and loads the
 * GL entry points (gs_gl.h). SH_ERR_DEVICE if OSMesa cannot give OpenGL
 * 4.5 core. */
sh_status gs__context_create(gs__context **out, sh_error *err);

/* Makes the context current on the calling thread (a context is current on
 * one thread at a time). */
sh_status gs__context_make_current(gs__context *ctx, sh_error *err);

/* The GL_RENDERER and GL_VERSION strings, for statistics. */
const char *gs__context_renderer(const gs__context *ctx);
const char *gs__context_version(const gs__context *ctx);

/* Destroys the context; NULL is allowed. */
void gs__context_free(gs__context *ctx);

#endif
