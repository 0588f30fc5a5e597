/* The camera as GL sees it: the scene's pinhole camera (sh_camera.h) as a
 * reversed-Z, infinite-far projection, of the whole image or of a crop
 * window of it (an off-axis sub-frustum: the window's pixels are the
 * whole image's). Pixel (i, j) of GL's framebuffer, rows counted from the
 * bottom, samples the ray of image pixel (x0 + i, y1 - 1 - j) through its
 * centre, as the reference renderer does, where [x0, x1) x [y0, y1) is the
 * window (the whole image without a crop). View depth z is the distance
 * along the forward axis: the pixel's ray is eye + z * d with
 * d . forward = 1. */
#ifndef GS_VIEW_H
#define GS_VIEW_H

#include "gs_polytope.h"
#include "sh_camera.h"
#include "sh_scene.h"

typedef struct gs__view {
  sh_camera_frame frame; /* origin, forward, right, up, tan_half_x/y */
  int width, height;     /* the pixels drawn: the window's size */
  sh_crop win;           /* the window in the camera's image */
  /* The window on the plane one unit ahead of the eye: view directions
   * with x_v / z in [cx - sx, cx + sx] and y_v / z in [cy - sy, cy + sy]
   * (y up). The whole image: cx = cy = 0, sx = tan_half_x, sy =
   * tan_half_y. NDC (the window's, [-1, 1]^2) maps to x_v / z = cx + sx x,
   * and likewise for y. */
  double cx, cy, sx, sy;
  double znear; /* the near plane's view depth */
  /* GL sees every point as p - anchor (the "anchored" space): positions go
   * to GL in single precision, whose ulp grows with the distance from the
   * origin, so a scene a million units from the origin would keep a
   * sixteenth of a unit. The anchor is the origin sh_frame_fit gives the
   * scene's bounds (sh_scene_bounds): near their centre, and quantised, so
   * that it seldom moves when the scene changes. */
  sh_vec3 anchor;
  /* GL sees view depths relative to zref, as zeta = z - zref, and a pixel's
   * ray as org + zref (d - forward) + zeta d (org and zref (d - forward) in
   * the anchored space, both small where the scene is): from the eye, a
   * camera 5e5 units from a scene 4 across kept depths and eye-relative
   * points only to ulp(5e5) = 1/32 unit in single precision, and their
   * differences cancelled (44% off). zref is the scene's near end (the
   * least view depth of its bounds' corners) when the scene lies wholly
   * beyond the near plane, else 0 (the camera in the scene: depths are the
   * eye's own); org is the point of the view axis at that depth, eye + zref
   * forward - anchor, computed in double. */
  double zref;
  sh_vec3 org;
  /* The depth buffer holds (depth_b - depth_a zeta) / z, 1 at the near
   * plane. With the camera in the scene, depth_a = 0 and depth_b = znear:
   * reversed Z, znear / z, of relative precision. With the scene beyond
   * the near plane (which is then at zref), the depth falls to 0 at zref +
   * twice the scene's depth span s: depth_b = zref, depth_a = zref / (2 s),
   * nearly linear in zeta for a camera far away, so that surfaces keep
   * about 1e-7 of s apart at any distance (znear / z kept 1e-7 of z: a
   * camera 1e8 units from a scene 4 across could not tell its surfaces
   * apart). */
  double depth_a, depth_b;
} gs__view;

/* The scene's camera, of the window `crop` (NULL or all zero: the whole
 * image; it must have passed sh_crop_check); the near plane is set tiny
 * against the scene's size (1e-10 of its bounds' diagonal: float depth
 * with reversed Z keeps its relative precision), or at the scene's near end when all of it lies beyond that;
 * the anchor, zref, org and the depth mapping. */
void gs__view_init(gs__view *v, const sh_scene *scene, const sh_crop *crop);

/* A world point or box corner in the anchored space. */
sh_vec3 gs__anchored(const gs__view *v, sh_vec3 p);

/* m (of world points) as a matrix of anchored points: m T(anchor). */
sh_mat4 gs__anchored_mat(const gs__view *v, const sh_mat4 *m);

/* An exact sphere's object space, centred on the sphere, from the
 * anchored space: T(-centre) inv T(anchor) (the shape's own object space
 * holds the world's offset when it has no transform). */
sh_mat4 gs__sphere_from_anchored(const gs__view *v, const sh_shape *sphere);

/* Anchored space to clip space: clip = ((x_v - cx z) / sx, (y_v - cy z) / sy,
 * depth_b - depth_a zeta, z), so the stored depth is (depth_b - depth_a
 * zeta) / z (1 at the near plane; 0 at infinity or, for a scene beyond the
 * near plane, at twice its depth span behind its near end). */
sh_mat4 gs__view_proj(const gs__view *v);

/* The unnormalised direction (d . forward = 1) of the ray through a point
 * of the window's NDC. */
sh_vec3 gs__view_ray(const gs__view *v, double x, double y);

/* The ray origin of a pixel at zeta = 0 is org + zref (d - forward): this is
 * d - forward = right (cx + sx x) + up (cy + sy y) of the window's NDC. */
sh_vec3 gs__view_ray_offset(const gs__view *v, double x, double y);

/* View depth of a world point. */
double gs__view_depth(const gs__view *v, sh_vec3 p);

/* Normalised device coordinates (the window's) of a world point in front
 * of the camera. */
void gs__view_ndc(const gs__view *v, sh_vec3 p, double *x, double *y);

/* The window's frustum: its four sides and the near plane as half-spaces. */
void gs__view_frustum(const gs__view *v, gs__halfspace out[5]);

#endif
