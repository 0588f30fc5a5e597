#include "gs_view.h"

/* How near the eye the nearest surface may be (gs__view_init's anchor): for a sphere its distance
 * from the surface, for other shapes from their world box (from inside,
 * from the box's nearest face). INFINITY without shapes. */
static double eye_clearance(const sh_scene *scene, sh_vec3 eye) {
  double d = INFINITY;
  for (int i = 0; i < scene->nshapes; i++) {
    const sh_shape *s = &scene->shapes[i];
    if (s->type == SH_SHAPE_SPHERE) {
      /* In object space, along the centre's direction scaled to the world
       * (a transformed sphere's distance, near enough). */
      sh_vec3 e = sh_sub(sh_xform_point(&s->inv, eye), s->center);
      double er = sh_length(e);
      double k = er > 0 ? sh_length(sh_xform_vector(&s->xform, sh_scale(e, 1.0 / er))) : 1.0;
      d = fmin(d, fabs(er - s->radius) * k);
      continue;
    }
    sh_vec3 lo, hi;
    if (!sh_shape_bounds(s, &lo, &hi)) continue;
    double out = 0, in = INFINITY;
    for (int k = 0; k < 3; k++) {
      double x = sh_vget(eye, k), a = sh_vget(lo, k), b = sh_vget(hi, k);
      double o = fmax(fmax(a - x, x - b), 0.0);
      out += o * o;
      in = fmin(in, fmin(x - a, b - x));
    }
    d = fmin(d, out > 0 ? sqrt(out) : in);
  }
  return d;
}

void gs__view_init(gs__view *v, const sh_scene *scene, const sh_crop *crop) {
  const sh_camera *cam = &scene->camera;
  sh_camera_frame_init(cam, &v->frame);
  v->win = sh_crop_window(crop, cam);
  v->width = v->win.x1 - v->win.x0;
  v->height = v->win.y1 - v->win.y0;
  /* The window's edges on the unit plane; the whole image's are exactly
   * +-tan_half, so that its centre is 0 and its half size tan_half. */
  double tx = v->frame.tan_half_x, ty = v->frame.tan_half_y;
  double left = (2.0 * v->win.x0 / cam->width - 1.0) * tx;
  double right = (2.0 * v->win.x1 / cam->width - 1.0) * tx;
  double top = (1.0 - 2.0 * v->win.y0 / cam->height) * ty;
  double bottom = (1.0 - 2.0 * v->win.y1 / cam->height) * ty;
  v->cx = 0.5 * (left + right);
  v->sx = 0.5 * (right - left);
  v->cy = 0.5 * (top + bottom);
  v->sy = 0.5 * (top - bottom);
  sh_vec3 lo, hi;
  sh_scene_bounds(scene, &lo, &hi);
  double size = sh_length(sh_sub(hi, lo));
  /* znear / z keeps its relative precision at any znear: tiny against the
   * scene (1e-5 of a planet's bounds was 180 m, and an eye 1 m above the
   * ground saw nothing of it). */
  v->znear = 1e-10 * (size > 0 ? size : 1.0);
  double unit;
  sh_frame_fit(lo, hi, &v->anchor, &unit);
  /* An eye so near a surface that the anchored space's ulp there exceeds
   * 1e-3 of the distance (an eye 1 m above a planet's ground, 6.4e6 m from
   * the anchor, had 0.5 m: the lit ground's edge moved by rows) gets an
   * anchor of its own: the eye quantised to the power of two at or above
   * 1024 times that distance, so that it moves once the eye has travelled
   * about that far (the triangles are then uploaded again). */
  sh_vec3 eye = v->frame.origin;
  double clear = eye_clearance(scene, eye);
  if (isfinite(clear) && sh_length(sh_sub(eye, v->anchor)) > 1.6e4 * clear) {
    double g = exp2(ceil(log2(fmax(clear, 1e-30 * (size > 0 ? size : 1.0)) * 1024.0)));
    v->anchor = sh_v3(g * round(eye.x / g), g * round(eye.y / g), g * round(eye.z / g));
  }
  /* The bounds' depth range, as the corners' offsets from the anchor's
   * depth (no cancellation for a camera far away). */
  double za = gs__view_depth(v, v->anchor), c0 = INFINITY, c1 = -INFINITY;
  for (int i = 0; i < 8; i++) {
    sh_vec3 c = sh_v3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    double dc = sh_dot(sh_sub(c, v->anchor), v->frame.forward);
    c0 = fmin(c0, dc);
    c1 = fmax(c1, dc);
  }
  v->zref = 0;
  v->depth_a = 0;
  v->depth_b = v->znear;
  if (za + c0 > v->znear) {
    v->zref = za + c0;
    v->znear = v->zref;
    double span = fmax(c1 - c0, v->znear * 1e-6);
    v->depth_a = v->zref / (2.0 * span);
    v->depth_b = v->zref;
  }
  v->org = sh_madd(sh_sub(v->frame.origin, v->anchor), v->frame.forward, v->zref);
}

sh_vec3 gs__anchored(const gs__view *v, sh_vec3 p) { return sh_sub(p, v->anchor); }

sh_mat4 gs__anchored_mat(const gs__view *v, const sh_mat4 *m) {
  return sh_mat4_mul(*m, sh_mat4_translate(v->anchor));
}

sh_mat4 gs__sphere_from_anchored(const gs__view *v, const sh_shape *sphere) {
  sh_mat4 m = gs__anchored_mat(v, &sphere->inv);
  return sh_mat4_mul(sh_mat4_translate(sh_neg(sphere->center)), m);
}

sh_mat4 gs__view_proj(const gs__view *v) {
  const sh_camera_frame *f = &v->frame;
  sh_vec3 eye = gs__anchored(v, f->origin);
  sh_vec3 rows[3] = {sh_scale(sh_madd(f->right, f->forward, -v->cx), 1.0 / v->sx),
                     sh_scale(sh_madd(f->up, f->forward, -v->cy), 1.0 / v->sy),
                     f->forward};
  sh_mat4 m = {{{0}}};
  for (int r = 0; r < 2; r++) {
    m.m[r][0] = rows[r].x;
    m.m[r][1] = rows[r].y;
    m.m[r][2] = rows[r].z;
    m.m[r][3] = -sh_dot(rows[r], eye);
  }
  /* clip z = depth_b - depth_a zeta, zeta = forward . (p - org); w = z =
   * zref + zeta. */
  for (int c = 0; c < 3; c++) m.m[2][c] = -v->depth_a * sh_vget(f->forward, c);
  m.m[2][3] = v->depth_b + v->depth_a * sh_dot(f->forward, v->org);
  m.m[3][0] = rows[2].x;
  m.m[3][1] = rows[2].y;
  m.m[3][2] = rows[2].z;
  m.m[3][3] = v->zref - sh_dot(rows[2], v->org);
  return m;
}

sh_vec3 gs__view_ray(const gs__view *v, double x, double y) {
  const sh_camera_frame *f = &v->frame;
  return sh_madd(sh_madd(f->forward, f->right, v->cx + x * v->sx), f->up,
                 v->cy + y * v->sy);
}

sh_vec3 gs__view_ray_offset(const gs__view *v, double x, double y) {
  const sh_camera_frame *f = &v->frame;
  return sh_madd(sh_scale(f->right, v->cx + x * v->sx), f->up, v->cy + y * v->sy);
}

double gs__view_depth(const gs__view *v, sh_vec3 p) {
  return sh_dot(sh_sub(p, v->frame.origin), v->frame.forward);
}

void gs__view_ndc(const gs__view *v, sh_vec3 p, double *x, double *y) {
  const sh_camera_frame *f = &v->frame;
  sh_vec3 d = sh_sub(p, f->origin);
  double z = sh_dot(d, f->forward);
  *x = (sh_dot(d, f->right) - v->cx * z) / (z * v->sx);
  *y = (sh_dot(d, f->up) - v->cy * z) / (z * v->sy);
}

void gs__view_frustum(const gs__view *v, gs__halfspace out[5]) {
  const sh_camera_frame *f = &v->frame;
  /* x_v <= (cx + sx) z: (right - (cx + sx) forward) . (p - eye) <= 0, and
   * so on. */
  out[0] = gs__halfspace_at(sh_madd(f->right, f->forward, -(v->cx + v->sx)), f->origin);
  out[1] = gs__halfspace_at(sh_madd(sh_neg(f->right), f->forward, v->cx - v->sx), f->origin);
  out[2] = gs__halfspace_at(sh_madd(f->up, f->forward, -(v->cy + v->sy)), f->origin);
  out[3] = gs__halfspace_at(sh_madd(sh_neg(f->up), f->forward, v->cy - v->sy), f->origin);
  out[4] = gs__halfspace_at(sh_neg(f->forward), sh_madd(f->origin, f->forward, v->znear));
}
