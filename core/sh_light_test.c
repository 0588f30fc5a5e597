/* Light profiles and the irradiance lights deliver. */
#include "sh_light.h"
#include "sh_test.h"

static double smooth(double u) {
  u = u < 0 ? 0 : u > 1 ? 1 : u;
  return 3 * u * u - 2 * u * u * u;
}

int main(void) {
  sh_light l = {0};
  l.type = SH_LIGHT_SPOT;
  l.position = sh_v3(0, 2, 0);
  l.direction = sh_v3(0, -1, 0);
  l.intensity = sh_v3(10, 20, 30);
  l.outer_deg = 30;
  l.inner_deg = 20;
  l.exponent = 2;
  SH_CHECK(sh_light_prepare(&l, sh_v3(0, 1, 0), 0, NULL) == SH_OK);
  const double angles[] = {0, 10, 19.9, 20, 22, 25, 29, 29.99, 30, 45, 120};
  for (int i = 0; i < 11; i++) {
    double th = angles[i] * SH_PI / 180, c = cos(th);
    double expect = pow(c, 2) * smooth((c - cos(30 * SH_PI / 180)) /
                                       (cos(20 * SH_PI / 180) -
                                        cos(30 * SH_PI / 180)));
    if (angles[i] > 30) expect = 0;
    SH_CHECK_NEAR(sh_spot_profile(&l, c), expect, 1e-12, 1e-15);
  }
  /* A hard edge when inner equals outer. */
  l.inner_deg = 30;
  l.exponent = 0;
  sh_light_prepare(&l, sh_v3(0, 1, 0), 0, NULL);
  SH_CHECK(sh_spot_profile(&l, cos(29.9 * SH_PI / 180)) == 1.0);
  SH_CHECK(sh_spot_profile(&l, cos(30.1 * SH_PI / 180)) == 0.0);

  /* Irradiance: I * profile / r^2, direction towards the light. */
  sh_vec3 wi;
  double dist;
  sh_vec3 e = sh_light_incident(&l, sh_v3(0, 0, 0), &wi, &dist);
  SH_CHECK_NEAR(dist, 2.0, 1e-12, 0);
  SH_CHECK_NEAR(wi.y, 1.0, 1e-12, 0);
  SH_CHECK_NEAR(e.x, 10.0 / 4.0, 1e-12, 0);
  SH_CHECK_NEAR(e.z, 30.0 / 4.0, 1e-12, 0);
  e = sh_light_incident(&l, sh_v3(2, 0, 0), &wi, &dist); /* 45 degrees off */
  SH_CHECK(sh_is_black(e));

  sh_light p = {0};
  p.type = SH_LIGHT_POINT;
  p.position = sh_v3(1, 1, 1);
  p.intensity = sh_v3s(3);
  e = sh_light_incident(&p, sh_v3(1, 1, 4), &wi, &dist);
  SH_CHECK_NEAR(e.y, 3.0 / 9.0, 1e-12, 0);
  SH_CHECK_NEAR(wi.z, -1.0, 1e-12, 0);

  sh_light d = {0};
  d.type = SH_LIGHT_DIRECTIONAL;
  d.direction = sh_v3(0, -2, 0);
  d.irradiance = sh_v3s(5);
  sh_light_prepare(&d, sh_v3(0, 1, 0), 0, NULL);
  e = sh_light_incident(&d, sh_v3(7, -3, 2), &wi, &dist);
  SH_CHECK_NEAR(e.x, 5.0, 1e-12, 0);
  SH_CHECK_NEAR(wi.y, 1.0, 1e-12, 0);
  SH_CHECK(isinf(dist));

  /* A directional light map: a 2x1 image, left half red, right half blue,
   * on the window [0,2] x [0,1] at y = 5, light going down. */
  float px[6] = {1, 0, 0, 0, 0, 1};
  d.has_map = 1;
  d.map.width = 2;
  d.map.height = 1;
  d.map.rgb = px;
  d.map_origin = sh_v3(0, 5, 0);
  d.map_u = sh_v3(2, 0, 0);
  d.map_v = sh_v3(0, 0, 1);
  SH_CHECK(sh_light_prepare(&d, sh_v3(0, 1, 0), 0, NULL) == SH_OK);
  sh_vec3 m = sh_light_map_value(&d, sh_v3(0.25, -3, 0.5));
  SH_CHECK_NEAR(m.x, 1.0, 1e-6, 0);
  SH_CHECK_NEAR(m.z, 0.0, 0, 1e-6);
  m = sh_light_map_value(&d, sh_v3(1.75, 0, 0.5));
  SH_CHECK_NEAR(m.z, 1.0, 1e-6, 0);
  m = sh_light_map_value(&d, sh_v3(2.5, 0, 0.5)); /* outside the window */
  SH_CHECK(sh_is_black(m));

  /* The sun's disk: irradiance / (2 pi (1 - cos(half angle))) inside the
   * cone around the direction the light comes from, 0 outside, the map
   * playing no part. */
  d.angular_diameter_deg = 4;
  SH_CHECK(sh_light_prepare(&d, sh_v3(0, 1, 0), 0, NULL) == SH_OK);
  double omega = 2 * SH_PI * (1 - cos(2 * SH_PI / 180));
  SH_CHECK_NEAR(d.disk_solid_angle, omega, 1e-12, 0);
  e = sh_light_disk_radiance(&d, sh_v3(0, 1, 0));
  SH_CHECK_NEAR(e.x, 5.0 / omega, 1e-12, 0);
  double in = 1.99 * SH_PI / 180, out = 2.01 * SH_PI / 180;
  e = sh_light_disk_radiance(&d, sh_v3(sin(in), cos(in), 0));
  SH_CHECK_NEAR(e.z, 5.0 / omega, 1e-12, 0);
  SH_CHECK(sh_is_black(sh_light_disk_radiance(&d, sh_v3(0, 0, 1))));
  SH_CHECK(sh_is_black(
      sh_light_disk_radiance(&d, sh_v3(0, cos(out), sin(out)))));
  SH_CHECK(sh_is_black(sh_light_disk_radiance(&d, sh_v3(0, -1, 0))));
  /* The Sun's 0.53 degrees: the small-angle form keeps its digits. */
  d.angular_diameter_deg = 0.53;
  sh_light_prepare(&d, sh_v3(0, 1, 0), 0, NULL);
  double th = 0.265 * SH_PI / 180;
  SH_CHECK_NEAR(d.disk_solid_angle,
                SH_PI * th * th * (1 - th * th / 12 + pow(th, 4) / 360), 1e-13, 0);
  /* No disk without a diameter, and none for other lights. */
  d.angular_diameter_deg = 0;
  sh_light_prepare(&d, sh_v3(0, 1, 0), 0, NULL);
  SH_CHECK(sh_is_black(sh_light_disk_radiance(&d, sh_v3(0, 1, 0))));
  SH_CHECK(sh_is_black(sh_light_disk_radiance(&p, sh_v3(0, 0, -1))));

  /* The background a ray sees: the scene's plus every disk. */
  sh_light two[2] = {d, d};
  two[0].angular_diameter_deg = 4;
  two[1].angular_diameter_deg = 6;
  two[1].irradiance = sh_v3s(2);
  sh_light_prepare(&two[0], sh_v3(0, 1, 0), 0, NULL);
  sh_light_prepare(&two[1], sh_v3(0, 1, 0), 0, NULL);
  sh_scene sc;
  memset(&sc, 0, sizeof sc);
  sc.background = sh_v3(0.1, 0.2, 0.3);
  sc.nlights = 2;
  sc.lights = two;
  double omega6 = 2 * SH_PI * (1 - cos(3 * SH_PI / 180));
  e = sh_scene_background_radiance(&sc, sh_v3(0, 1, 0));
  SH_CHECK_NEAR(e.y, 0.2 + 5.0 / omega + 2.0 / omega6, 1e-12, 0);
  double mid = 2.5 * SH_PI / 180; /* in the wider disk only */
  e = sh_scene_background_radiance(&sc, sh_v3(sin(mid), cos(mid), 0));
  SH_CHECK_NEAR(e.z, 0.3 + 2.0 / omega6, 1e-12, 0);
  e = sh_scene_background_radiance(&sc, sh_v3(1, 0, 0));
  SH_CHECK_NEAR(e.x, 0.1, 1e-15, 0);
  SH_TEST_DONE();
}
