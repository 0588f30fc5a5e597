#include "sh_math.h"

sh_mat4 sh_mat4_identity(void) {
  sh_mat4 r = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
  return r;
}

sh_mat4 sh_mat4_mul(sh_mat4 a, sh_mat4 b) {
  sh_mat4 r;
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) {
      double s = 0;
      for (int k = 0; k < 4; k++) s += a.m[i][k] * b.m[k][j];
      r.m[i][j] = s;
    }
  return r;
}

sh_mat4 sh_mat4_translate(sh_vec3 t) {
  return (sh_mat4){{{1, 0, 0, t.x},
                    {0, 1, 0, t.y},
                    {0, 0, 1, t.z},
                    {0, 0, 0, 1}}};
}

sh_mat4 sh_mat4_scale(sh_vec3 s) {
  return (sh_mat4){{{s.x, 0, 0, 0},
                    {0, s.y, 0, 0},
                    {0, 0, s.z, 0},
                    {0, 0, 0, 1}}};
}

sh_mat4 sh_mat4_rotate(int axis, double deg) {
  sh_mat4 r = sh_mat4_identity();
  double a = deg * SH_PI / 180.0, c = cos(a), s = sin(a);
  int i = (axis + 1) % 3, j = (axis + 2) % 3;
  r.m[i][i] = c;
  r.m[i][j] = -s;
  r.m[j][i] = s;
  r.m[j][j] = c;
  return r;
}

sh_mat4 sh_mat4_transpose(sh_mat4 a) {
  sh_mat4 r;
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) r.m[i][j] = a.m[j][i];
  return r;
}

int sh_mat4_inverse(sh_mat4 a, sh_mat4 *out) {
  /* Gauss-Jordan elimination with partial pivoting on [a | I]. */
  double w[4][8];
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) {
      w[i][j] = a.m[i][j];
      w[i][j + 4] = i == j;
    }
  for (int c = 0; c < 4; c++) {
    int p = c;
    for (int r = c + 1; r < 4; r++)
      if (fabs(w[r][c]) > fabs(w[p][c])) p = r;
    if (fabs(w[p][c]) < 1e-300) return 0;
    for (int j = 0; j < 8; j++) {
      double t = w[c][j];
      w[c][j] = w[p][j];
      w[p][j] = t;
    }
    double inv = 1.0 / w[c][c];
    for (int j = 0; j < 8; j++) w[c][j] *= inv;
    for (int r = 0; r < 4; r++) {
      if (r == c) continue;
      double f = w[r][c];
      for (int j = 0; j < 8; j++) w[r][j] -= f * w[c][j];
    }
  }
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) out->m[i][j] = w[i][j + 4];
  return 1;
}

sh_vec3 sh_xform_point(const sh_mat4 *m, sh_vec3 p) {
  const double(*a)[4] = m->m;
  return sh_v3(a[0][0] * p.x + a[0][1] * p.y + a[0][2] * p.z + a[0][3],
               a[1][0] * p.x + a[1][1] * p.y + a[1][2] * p.z + a[1][3],
               a[2][0] * p.x + a[2][1] * p.y + a[2][2] * p.z + a[2][3]);
}

sh_vec3 sh_xform_vector(const sh_mat4 *m, sh_vec3 v) {
  const double(*a)[4] = m->m;
  return sh_v3(a[0][0] * v.x + a[0][1] * v.y + a[0][2] * v.z,
               a[1][0] * v.x + a[1][1] * v.y + a[1][2] * v.z,
               a[2][0] * v.x + a[2][1] * v.y + a[2][2] * v.z);
}

sh_vec3 sh_xform_normal(const sh_mat4 *inv, sh_vec3 n) {
  const double(*a)[4] = inv->m;
  return sh_v3(a[0][0] * n.x + a[1][0] * n.y + a[2][0] * n.z,
               a[0][1] * n.x + a[1][1] * n.y + a[2][1] * n.z,
               a[0][2] * n.x + a[1][2] * n.y + a[2][2] * n.z);
}
