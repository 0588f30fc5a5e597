#include "sh_camera.h"

#include <math.h>
#include <stdio.h>

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

int sh_crop_given(const sh_crop *c) {
  return c && (c->x0 || c->y0 || c->x1 || c->y1);
}

sh_crop sh_crop_window(const sh_crop *c, const sh_camera *cam) {
  if (sh_crop_given(c)) return *c;
  sh_crop whole = {0, 0, cam->width, cam->height};
  return whole;
}

sh_status sh_crop_check(const sh_crop *c, const sh_camera *cam,
                        sh_error *err) {
  if (!sh_crop_given(c)) return SH_OK;
  const char *why = NULL;
  char buf[96];
  if (c->x0 < 0 || c->y0 < 0)
    why = c->x0 < 0 ? "x0 is negative" : "y0 is negative";
  else if (c->x1 <= c->x0 || c->y1 <= c->y0)
    why = c->x1 <= c->x0 ? "x1 must be greater than x0"
                         : "y1 must be greater than y0";
  else if (c->x1 > cam->width || c->y1 > cam->height) {
    snprintf(buf, sizeof buf, "%s = %d is beyond the image's %s %d",
             c->x1 > cam->width ? "x1" : "y1",
             c->x1 > cam->width ? c->x1 : c->y1,
             c->x1 > cam->width ? "width" : "height",
             c->x1 > cam->width ? cam->width : cam->height);
    why = buf;
  }
  if (!why) return SH_OK;
  sh_status st = sh_error_set(
      err, SH_ERR_ARG,
      "%s: the crop x0 y0 x1 y1 = %d %d %d %d must lie in the %dx%d image "
      "(pixels [x0, x1) x [y0, y1), y down from the top)",
      why, c->x0, c->y0, c->x1, c->y1, cam->width, cam->height);
  sh_error_set_key(err, "crop");
  return st;
}
