/* Filter cards reproduce the scene format's light-map mapping: a shadow ray
 * from a lit point towards the light crosses the card where the card's
 * texture coordinates (x, y) are the map coordinates (s, 1 - t) that
 * sh_light_map_value uses, for spots and for windows; a window's card lies
 * outside the scene's bounding sphere, upstream, and its wall holds the
 * sphere's whole shadow. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "se_geom.h"
#include "sh_light.h"
#include "sh_test.h"

static double rnd(uint64_t *s) {
  *s = *s * 6364136223846793005ull + 1442695040888963407ull;
  return (double)(*s >> 11) / 9007199254740992.0;
}

/* Where the segment from p along d (unit) meets the card's plane, in the
 * card's (x, y); returns the distance along d. */
static double hit(const se_card *c, sh_vec3 p, sh_vec3 d, double *x, double *y) {
  double t = sh_dot(sh_sub(c->origin, p), c->normal) / sh_dot(d, c->normal);
  sh_vec3 q = sh_sub(sh_madd(p, d, t), c->origin);
  double uu = sh_dot(c->ex, c->ex), uv = sh_dot(c->ex, c->ey), vv = sh_dot(c->ey, c->ey);
  double qu = sh_dot(q, c->ex), qv = sh_dot(q, c->ey), det = uu * vv - uv * uv;
  *x = (qu * vv - qv * uv) / det;
  *y = (qv * uu - qu * uv) / det;
  return t;
}

/* A 2x2 map whose texels differ, so that a wrong orientation shows. */
static void small_map(sh_light *l) {
  static float px[12] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f,
                         0.7f, 0.8f, 0.9f, 0.25f, 0.35f, 0.45f};
  l->has_map = 1;
  l->map.width = l->map.height = 2;
  l->map.rgb = px;
}

static void spot(void) {
  sh_light l;
  memset(&l, 0, sizeof l);
  l.type = SH_LIGHT_SPOT;
  l.position = sh_v3(0.3, 3.0, -0.2);
  l.direction = sh_v3(0.2, -1.0, 0.3);
  l.intensity = sh_v3s(1.0);
  l.outer_deg = l.inner_deg = 30;
  small_map(&l);
  l.map_up = sh_v3(0, 0, -1);
  SH_CHECK(sh_light_prepare(&l, sh_v3(0, 1, 0), 1, NULL) == SH_OK);
  se_card c = se_spot_card(&l, 0.01);
  uint64_t s = 1;
  int tested = 0;
  for (int k = 0; k < 2000; k++) {
    sh_vec3 p = sh_v3(4 * rnd(&s) - 2, 3 * rnd(&s) - 1, 4 * rnd(&s) - 2);
    sh_vec3 v = sh_sub(p, l.position);
    double z = sh_dot(v, l.direction);
    if (z <= 0.02) continue;
    double mx = sh_dot(v, l.map_right) / (z * l.tan_outer);
    double my = sh_dot(v, l.map_up) / (z * l.tan_outer);
    if (fabs(mx) > 1 || fabs(my) > 1) continue;
    double x, y;
    sh_vec3 d = sh_normalize(sh_sub(l.position, p));
    double t = hit(&c, p, d, &x, &y);
    SH_CHECK(t > 0 && t < sh_length(v)); /* between the point and the light */
    SH_CHECK_NEAR(x, 0.5 * (mx + 1), 0, 1e-9);
    SH_CHECK_NEAR(y, 1.0 - 0.5 * (1 - my), 0, 1e-9);
    /* And the texel there is the map's value. */
    sh_vec3 m = sh_light_map_value(&l, p);
    float tex[3];
    sh_image_lookup(&l.map, x, 1.0 - y, tex);
    SH_CHECK_NEAR(tex[0], m.x, 0, 1e-6);
    SH_CHECK_NEAR(tex[2], m.z, 0, 1e-6);
    tested++;
  }
  SH_CHECK(tested > 100);
}

static void window(void) {
  sh_light l;
  memset(&l, 0, sizeof l);
  l.type = SH_LIGHT_DIRECTIONAL;
  l.direction = sh_v3(0.5, -1.0, -0.3);
  l.irradiance = sh_v3s(1.0);
  small_map(&l);
  l.map_origin = sh_v3(-2.8, 3.4, -1.2);
  l.map_u = sh_v3(2.4, 0, 0.3);
  l.map_v = sh_v3(0, -0.2, 2.4);
  SH_CHECK(sh_light_prepare(&l, sh_v3(0, 1, 0), 0, NULL) == SH_OK);
  sh_vec3 center = sh_v3(0, 1.5, 0);
  double radius = 5.0;
  se_window w = se_window_card(&l, center, radius);
  uint64_t s = 7;
  int inside = 0, outside = 0;
  for (int k = 0; k < 2000; k++) {
    sh_vec3 p = sh_madd(center, sh_v3(2 * rnd(&s) - 1, 2 * rnd(&s) - 1, 2 * rnd(&s) - 1),
                        radius / sqrt(3.0));
    double x, y;
    double t = hit(&w.card, p, sh_neg(l.direction), &x, &y);
    /* The card is upstream of the whole sphere, the light beyond it. */
    SH_CHECK(t > 2 * radius && t < w.light_distance - radius);
    /* Inside the wall. */
    SH_CHECK(x > w.wall_lo_x && x < w.wall_hi_x && y > w.wall_lo_y && y < w.wall_hi_y);
    sh_vec3 m = sh_light_map_value(&l, p);
    if (x >= 0 && x <= 1 && y >= 0 && y <= 1) {
      float tex[3];
      sh_image_lookup(&l.map, x, 1.0 - y, tex);
      SH_CHECK_NEAR(tex[1], m.y, 0, 1e-6);
      inside++;
    } else {
      SH_CHECK(sh_is_black(m)); /* blocked outside the window */
      outside++;
    }
  }
  SH_CHECK(inside > 20 && outside > 20);
}

int main(void) {
  spot();
  window();
  SH_TEST_DONE();
}
