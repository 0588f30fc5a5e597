#include "sh_camera.h"

#include <math.h>

void sh_camera_frame_init(const sh_camera *cam, sh_camera_frame *f) {
  f->origin = cam->position;
  f->forward = sh_normalize(sh_sub(cam->look_at, cam->position));
  f->right = sh_normalize(sh_cross(f->forward, cam->up));
  f->up = sh_cross(f->right, f->forward);
  f->tan_half_y = tan(0.5 * cam->fov_y_deg * SH_PI / 180.0);
  f->tan_half_x = f->tan_half_y * (double)cam->width / (double)cam->height;
  f->width = cam->width;
  f->height = cam->height;
}

sh_vec3 sh_camera_dir(const sh_camera_frame *f, double x, double y) {
  double sx = (2.0 * x / f->width - 1.0) * f->tan_half_x;
  double sy = (1.0 - 2.0 * y / f->height) * f->tan_half_y;
  sh_vec3 d = sh_madd(sh_madd(f->forward, f->right, sx), f->up, sy);
  return sh_normalize(d);
}
