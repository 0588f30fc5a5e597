#include "gs_view.h"

void gs__view_init(gs__view *v, const sh_scene *scene) {
  sh_camera_frame_init(&scene->camera, &v->frame);
  v->width = scene->camera.width;
  v->height = scene->camera.height;
  sh_vec3 lo, hi;
  sh_scene_bounds(scene, &lo, &hi);
  double size = sh_length(sh_sub(hi, lo));
  v->znear = 1e-5 * (size > 0 ? size : 1.0);
}

sh_mat4 gs__view_proj(const gs__view *v) {
  const sh_camera_frame *f = &v->frame;
  sh_vec3 rows[3] = {sh_scale(f->right, 1.0 / f->tan_half_x),
                     sh_scale(f->up, 1.0 / f->tan_half_y), f->forward};
  sh_mat4 m = {{{0}}};
  for (int r = 0; r < 2; r++) {
    m.m[r][0] = rows[r].x;
    m.m[r][1] = rows[r].y;
    m.m[r][2] = rows[r].z;
    m.m[r][3] = -sh_dot(rows[r], f->origin);
  }
  m.m[2][3] = v->znear;
  m.m[3][0] = rows[2].x;
  m.m[3][1] = rows[2].y;
  m.m[3][2] = rows[2].z;
  m.m[3][3] = -sh_dot(rows[2], f->origin);
  return m;
}

double gs__view_depth(const gs__view *v, sh_vec3 p) {
  return sh_dot(sh_sub(p, v->frame.origin), v->frame.forward);
}

void gs__view_ndc(const gs__view *v, sh_vec3 p, double *x, double *y) {
  const sh_camera_frame *f = &v->frame;
  sh_vec3 d = sh_sub(p, f->origin);
  double z = sh_dot(d, f->forward);
  *x = sh_dot(d, f->right) / (z * f->tan_half_x);
  *y = sh_dot(d, f->up) / (z * f->tan_half_y);
}

void gs__view_frustum(const gs__view *v, gs__halfspace out[5]) {
  const sh_camera_frame *f = &v->frame;
  /* x_v <= z tan_x: (right - tan_x forward) . (p - eye) <= 0, and so on. */
  out[0] = gs__halfspace_at(sh_madd(f->right, f->forward, -f->tan_half_x), f->origin);
  out[1] = gs__halfspace_at(sh_madd(sh_neg(f->right), f->forward, -f->tan_half_x), f->origin);
  out[2] = gs__halfspace_at(sh_madd(f->up, f->forward, -f->tan_half_y), f->origin);
  out[3] = gs__halfspace_at(sh_madd(sh_neg(f->up), f->forward, -f->tan_half_y), f->origin);
  out[4] = gs__halfspace_at(sh_neg(f->forward), sh_madd(f->origin, f->forward, v->znear));
}
