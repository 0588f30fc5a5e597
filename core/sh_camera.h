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

#ifdef __cplusplus
}
#endif
#endif
