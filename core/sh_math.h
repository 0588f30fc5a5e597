/* Vector and matrix math: 3-vectors of doubles (points, directions and RGB
 * colours alike) and 4x4 affine matrices, row-major, acting on column
 * vectors. Everything is inline and allocation-free. */
#ifndef SH_MATH_H
#define SH_MATH_H

#include <math.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SH_PI 3.14159265358979323846
#define SH_INV_PI 0.31830988618379067154
#define SH_INV_4PI 0.07957747154594766788

typedef struct sh_vec3 {
  double x, y, z;
} sh_vec3;

typedef struct sh_mat4 {
  double m[4][4]; /* m[row][column] */
} sh_mat4;

static inline sh_vec3 sh_v3(double x, double y, double z) {
  sh_vec3 r = {x, y, z};
  return r;
}
static inline sh_vec3 sh_v3s(double s) { return sh_v3(s, s, s); }
static inline sh_vec3 sh_add(sh_vec3 a, sh_vec3 b) {
  return sh_v3(a.x + b.x, a.y + b.y, a.z + b.z);
}
static inline sh_vec3 sh_sub(sh_vec3 a, sh_vec3 b) {
  return sh_v3(a.x - b.x, a.y - b.y, a.z - b.z);
}
static inline sh_vec3 sh_mul(sh_vec3 a, sh_vec3 b) {
  return sh_v3(a.x * b.x, a.y * b.y, a.z * b.z);
}
static inline sh_vec3 sh_scale(sh_vec3 a, double s) {
  return sh_v3(a.x * s, a.y * s, a.z * s);
}
/* a + b * s */
static inline sh_vec3 sh_madd(sh_vec3 a, sh_vec3 b, double s) {
  return sh_v3(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s);
}
static inline double sh_dot(sh_vec3 a, sh_vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
static inline sh_vec3 sh_cross(sh_vec3 a, sh_vec3 b) {
  return sh_v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
               a.x * b.y - a.y * b.x);
}
static inline double sh_length(sh_vec3 a) { return sqrt(sh_dot(a, a)); }
static inline sh_vec3 sh_normalize(sh_vec3 a) {
  double l = sh_length(a);
  return l > 0 ? sh_scale(a, 1.0 / l) : a;
}
static inline sh_vec3 sh_neg(sh_vec3 a) { return sh_v3(-a.x, -a.y, -a.z); }
static inline double sh_max3(sh_vec3 a) {
  return fmax(a.x, fmax(a.y, a.z));
}
static inline double sh_min3(sh_vec3 a) {
  return fmin(a.x, fmin(a.y, a.z));
}
static inline sh_vec3 sh_vmin(sh_vec3 a, sh_vec3 b) {
  return sh_v3(fmin(a.x, b.x), fmin(a.y, b.y), fmin(a.z, b.z));
}
static inline sh_vec3 sh_vmax(sh_vec3 a, sh_vec3 b) {
  return sh_v3(fmax(a.x, b.x), fmax(a.y, b.y), fmax(a.z, b.z));
}
static inline sh_vec3 sh_vexp(sh_vec3 a) {
  return sh_v3(exp(a.x), exp(a.y), exp(a.z));
}
static inline int sh_is_black(sh_vec3 a) {
  return a.x == 0 && a.y == 0 && a.z == 0;
}
static inline double sh_vget(sh_vec3 a, int i) {
  return i == 0 ? a.x : i == 1 ? a.y : a.z;
}
static inline double sh_clamp(double x, double lo, double hi) {
  return x < lo ? lo : x > hi ? hi : x;
}
/* Mirror reflection of d about the normal n. */
static inline sh_vec3 sh_reflect(sh_vec3 d, sh_vec3 n) {
  return sh_sub(d, sh_scale(n, 2.0 * sh_dot(d, n)));
}
/* Builds two unit vectors that complete n (unit) to an orthonormal basis. */
static inline void sh_basis(sh_vec3 n, sh_vec3 *t, sh_vec3 *b) {
  double s = n.z >= 0 ? 1.0 : -1.0;
  double a = -1.0 / (s + n.z), c = n.x * n.y * a;
  *t = sh_v3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  *b = sh_v3(c, s + n.y * n.y * a, -n.y);
}

sh_mat4 sh_mat4_identity(void);
sh_mat4 sh_mat4_mul(sh_mat4 a, sh_mat4 b);
sh_mat4 sh_mat4_translate(sh_vec3 t);
sh_mat4 sh_mat4_scale(sh_vec3 s);
/* Rotation by `deg` degrees about axis 0 (X), 1 (Y) or 2 (Z), right-handed. */
sh_mat4 sh_mat4_rotate(int axis, double deg);
/* Inverse of an affine matrix; returns 0 if it is singular. */
int sh_mat4_inverse(sh_mat4 a, sh_mat4 *out);
sh_mat4 sh_mat4_transpose(sh_mat4 a);
sh_vec3 sh_xform_point(const sh_mat4 *m, sh_vec3 p);
sh_vec3 sh_xform_vector(const sh_mat4 *m, sh_vec3 v);
/* Transforms a normal by the inverse transpose; pass the inverse matrix. */
sh_vec3 sh_xform_normal(const sh_mat4 *inv, sh_vec3 n);

#ifdef __cplusplus
}
#endif
#endif
