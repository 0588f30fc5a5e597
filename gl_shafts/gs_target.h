/* The frame's render targets: the image (RGBA32F, where surfaces are
 * written and the planes added), the surfaces' view depth (R32F, read by
 * the sweep), the depth buffer (32-bit float, reversed Z), and the per-light
 * ray intervals of the sweep (RGBA32F); plus a small dynamic buffer for
 * screen-space polygons. */
#ifndef GS_TARGET_H
#define GS_TARGET_H

#include "gs_gl.h"

typedef struct gs__target {
  int width, height;
  GLuint image, lindepth, depth, interval; /* textures */
  GLuint fbo;          /* image (0), lindepth (1), depth */
  GLuint interval_fbo; /* interval (0) */
  GLuint poly_vao, poly_vbo; /* 2D polygons (location 0), up to 64 points */
} gs__target;

sh_status gs__target_create(gs__target *t, int width, int height, sh_error *err);

/* Selects which of the image FBO's colour attachments are written:
 * 1 = the image only, 2 = the image and the view depth. */
void gs__target_draw_buffers(const gs__target *t, int n);

/* Draws a convex polygon of n <= 64 points (ndc x, y pairs) as a fan with
 * the currently bound program (screen.vert). */
void gs__target_draw_polygon(const gs__target *t, const float *xy, int n);

void gs__target_free(gs__target *t);

#endif
