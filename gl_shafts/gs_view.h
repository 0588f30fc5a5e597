/* The camera as GL sees it: the scene's pinhole camera (sh_camera.h) as a
 * reversed-Z, infinite-far projection. Pixel (i, j) of GL's framebuffer,
 * rows counted from the bottom, samples the ray of image pixel
 * (i, height - 1 - j) through its centre, as the reference renderer does.
 * View depth z is the distance along the forward axis: the pixel's ray is
 * eye + z * d with d . forward = 1. */
#ifndef GS_VIEW_H
#define GS_VIEW_H

#include "gs_polytope.h"
#include "sh_camera.h"
#include "sh_scene.h"

typedef struct gs__view {
  sh_camera_frame frame; /* origin, forward, right, up, tan_half_x/y */
  int width, height;
  double znear; /* the near plane's view depth */
} gs__view;

/* The scene's camera; the near plane is set tiny against the scene's size
 * (float depth with reversed Z keeps its precision). */
void gs__view_init(gs__view *v, const sh_scene *scene);

/* World to clip space: clip = (x_v / tan_x, y_v / tan_y, znear, z), so the
 * stored depth is znear / z (1 at the near plane, 0 at infinity). */
sh_mat4 gs__view_proj(const gs__view *v);

/* View depth of a world point. */
double gs__view_depth(const gs__view *v, sh_vec3 p);

/* Normalised device coordinates of a world point in front of the camera. */
void gs__view_ndc(const gs__view *v, sh_vec3 p, double *x, double *y);

/* The frustum's four sides and near plane as half-spaces. */
void gs__view_frustum(const gs__view *v, gs__halfspace out[5]);

#endif
