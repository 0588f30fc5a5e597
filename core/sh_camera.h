/* The pinhole camera of the scene format. */
#ifndef SH_CAMERA_H
#define SH_CAMERA_H

#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The camera's orthonormal frame and image-plane scale, derived once. */
typedef struct sh_camera_frame {
  sh_vec3 origin, forward, right, up;
  double tan_half_y, tan_half_x;
  int width, height;
} sh_camera_frame;

void sh_camera_frame_init(const sh_camera *cam, sh_camera_frame *f);

/* The unit direction of the ray through image position (x, y) in pixels,
 * x to the right and y downwards from the top-left corner: pixel (i, j) is
 * sampled at its centre (i + 0.5, j + 0.5). */
sh_vec3 sh_camera_dir(const sh_camera_frame *f, double x, double y);

/* A crop window: the pixels [x0, x1) x [y0, y1) of the camera's image, x
 * to the right and y downwards from the top-left corner, rendered at the
 * image's full resolution (every pixel as in the whole image, as pbrt-v4's
 * pixel bounds); the result holds the window alone, x1 - x0 by y1 - y0
 * pixels. All zero: no crop, the whole image. */
typedef struct sh_crop {
  int x0, y0, x1, y1;
} sh_crop;

/* Whether a crop is set (not all zero). */
int sh_crop_given(const sh_crop *crop);

/* The window a crop renders for this camera: the whole image when the
 * crop is NULL or not set. */
sh_crop sh_crop_window(const sh_crop *crop, const sh_camera *cam);

/* Checks a crop against the camera's image size: 0 <= x0 < x1 <= width
 * and 0 <= y0 < y1 <= height (an unset crop passes). SH_ERR_ARG with the
 * error's key "crop" and a message naming the bound that fails, the crop
 * and the image's size. */
sh_status sh_crop_check(const sh_crop *crop, const sh_camera *cam,
                        sh_error *err);

#ifdef __cplusplus
}
#endif
#endif
