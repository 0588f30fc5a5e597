#include "se_geom.h"

#include <math.h>

void se_content_sphere(const sh_scene *scene, sh_vec3 *center,
                       double *radius) {
  sh_vec3 lo, hi;
  sh_scene_bounds(scene, &lo, &hi);
  *center = sh_scale(sh_add(lo, hi), 0.5);
  *radius = 0.5 * sh_length(sh_sub(hi, lo));
  if (!(*radius > 0)) *radius = sh_length(sh_sub(scene->camera.position, *center));
  if (!(*radius > 0)) *radius = 1.0;
}

int se_in_box(sh_vec3 p, sh_vec3 bmin, sh_vec3 bmax) {
  return p.x >= bmin.x && p.y >= bmin.y && p.z >= bmin.z && p.x <= bmax.x &&
         p.y <= bmax.y && p.z <= bmax.z;
}

sh_vec3 se_card_point(const se_card *card, double x, double y) {
  return sh_madd(sh_madd(card->origin, card->ex, x), card->ey, y);
}

se_card se_spot_card(const sh_light *light, double dist) {
  se_card c;
  double h = dist * light->tan_outer;
  sh_vec3 centre = sh_madd(light->position, light->direction, dist);
  c.ex = sh_scale(light->map_right, 2.0 * h);
  c.ey = sh_scale(light->map_up, 2.0 * h);
  c.origin = sh_madd(sh_madd(centre, light->map_right, -h), light->map_up, -h);
  c.normal = sh_normalize(sh_cross(c.ex, c.ey));
  return c;
}

/* The window coordinates (x, y) of p projected along d onto the plane
 * origin + x ex + y ey. */
static void project(const se_card *c, sh_vec3 d, sh_vec3 p, double *x,
                    double *y) {
  sh_vec3 n = c->normal;
  double lam = sh_dot(sh_sub(p, c->origin), n) / sh_dot(d, n);
  sh_vec3 q = sh_sub(sh_madd(p, d, -lam), c->origin);
  double uu = sh_dot(c->ex, c->ex), uv = sh_dot(c->ex, c->ey);
  double vv = sh_dot(c->ey, c->ey), qu = sh_dot(q, c->ex), qv = sh_dot(q, c->ey);
  double det = uu * vv - uv * uv;
  *x = (qu * vv - qv * uv) / det;
  *y = (qv * uu - qu * uv) / det;
}

se_window se_window_card(const sh_light *light, sh_vec3 center, double radius) {
  se_window w;
  sh_vec3 d = light->direction;
  /* The image's top-left corner is map_origin, its right map_u, its down
   * map_v: the bottom-left corner is origin + v and "up" is -v. */
  w.card.origin = sh_add(light->map_origin, light->map_v);
  w.card.ex = light->map_u;
  w.card.ey = sh_neg(light->map_v);
  w.card.normal = sh_normalize(sh_cross(w.card.ex, w.card.ey));
  /* The wall must hold the shadow of the sphere's bounding cube. */
  w.wall_lo_x = w.wall_lo_y = -0.05;
  w.wall_hi_x = w.wall_hi_y = 1.05;
  for (int k = 0; k < 8; k++) {
    sh_vec3 p = sh_add(center, sh_v3(k & 1 ? radius : -radius,
                                     k & 2 ? radius : -radius,
                                     k & 4 ? radius : -radius));
    double x, y;
    project(&w.card, d, p, &x, &y);
    w.wall_lo_x = fmin(w.wall_lo_x, x);
    w.wall_lo_y = fmin(w.wall_lo_y, y);
    w.wall_hi_x = fmax(w.wall_hi_x, x);
    w.wall_hi_y = fmax(w.wall_hi_y, y);
  }
  double sx = w.wall_hi_x - w.wall_lo_x, sy = w.wall_hi_y - w.wall_lo_y;
  w.wall_lo_x -= 0.1 * sx;
  w.wall_hi_x += 0.1 * sx;
  w.wall_lo_y -= 0.1 * sy;
  w.wall_hi_y += 0.1 * sy;
  /* Slide the window upstream: a point p of the sphere reaches the moved
   * plane after s = lam + dot(p - origin, n) / dot(d, n) along -d; make
   * every such s at least 2 radius (outside the sphere). */
  sh_vec3 n = w.card.normal;
  double dn = sh_dot(d, n), adn = fabs(dn);
  double qc = sh_dot(sh_sub(center, w.card.origin), n) / dn;
  double lam = 2.0 * radius + radius / adn - qc + 0.1 * radius;
  w.card.origin = sh_madd(w.card.origin, d, -lam);
  double smax = lam + qc + radius / adn;
  w.light_distance = smax + 2.0 * radius;
  return w;
}
