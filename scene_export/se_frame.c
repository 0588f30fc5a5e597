#include "se_frame.h"

se_frame se_frame_pov(double scale, sh_vec3 origin) {
  se_frame f = {{0, 1, 2}, {1, 1, -1}, scale, origin};
  return f;
}

se_frame se_frame_blender(double scale, sh_vec3 origin) {
  se_frame f = {{0, 2, 1}, {1, -1, 1}, scale, origin};
  return f;
}

sh_vec3 se_frame_dir(const se_frame *f, sh_vec3 d) {
  return sh_v3(f->sign[0] * sh_vget(d, f->axis[0]),
               f->sign[1] * sh_vget(d, f->axis[1]),
               f->sign[2] * sh_vget(d, f->axis[2]));
}

sh_vec3 se_frame_point(const se_frame *f, sh_vec3 p) {
  return sh_scale(se_frame_dir(f, sh_sub(p, f->origin)), f->scale);
}

double se_frame_length(const se_frame *f, double length) {
  return length * f->scale;
}

sh_vec3 se_frame_per_length(const se_frame *f, sh_vec3 coefficient) {
  return sh_scale(coefficient, 1.0 / f->scale);
}

sh_vec3 se_frame_intensity(const se_frame *f, sh_vec3 intensity) {
  return sh_scale(intensity, f->scale * f->scale);
}

double se_frame_matrix(const se_frame *f, const sh_mat4 *m, int row, int col) {
  int a = f->axis[row];
  double v = m->m[a][col];
  if (col == 3) v -= sh_vget(f->origin, a); /* the translation */
  return f->sign[row] * f->scale * v;
}
