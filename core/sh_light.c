#include "sh_light.h"

#include <math.h>

sh_status sh_light_prepare(sh_light *light, sh_vec3 camera_up, int has_up,
                           sh_error *err) {
  light->direction = sh_normalize(light->direction);
  light->disk_cos_half = 2.0; /* no direction is inside */
  light->disk_solid_angle = 0.0;
  if (light->type == SH_LIGHT_DIRECTIONAL && light->angular_diameter_deg > 0) {
    double half = 0.5 * light->angular_diameter_deg * SH_PI / 180.0;
    double s = sin(0.5 * half);
    light->disk_cos_half = cos(half);
    light->disk_solid_angle = 4.0 * SH_PI * s * s;
  }
  if (light->type == SH_LIGHT_SPOT) {
    double ro = light->outer_deg * SH_PI / 180.0;
    double ri = light->inner_deg * SH_PI / 180.0;
    light->cos_outer = cos(ro);
    light->cos_inner = cos(ri);
    light->tan_outer = tan(ro);
    if (light->has_map) {
      /* The map's up is the given (or camera's) up projected onto the plane
       * normal to the axis. */
      sh_vec3 up = has_up ? light->map_up : camera_up;
      sh_vec3 a = light->direction;
      sh_vec3 pu = sh_sub(up, sh_scale(a, sh_dot(up, a)));
      if (sh_length(pu) < 1e-6 * sh_length(up)) {
        sh_vec3 t, b;
        if (has_up)
          return sh_error_set(err, SH_ERR_SCENE,
                              "the light map's up vector is parallel to the "
                              "spot's axis; give an \"up\" across the axis");
        sh_basis(a, &t, &b);
        pu = b;
      }
      light->map_up = sh_normalize(pu);
      light->map_right = sh_cross(a, light->map_up);
      /* Right-handed frame: looking along the axis with up up, right is
       * axis x up. */
    }
  } else if (light->type == SH_LIGHT_DIRECTIONAL && light->has_map) {
    sh_vec3 n = sh_cross(light->map_u, light->map_v);
    if (sh_length(n) == 0)
      return sh_error_set(err, SH_ERR_SCENE,
                          "the light map's u and v are parallel: the window "
                          "has no area");
    light->map_normal = sh_normalize(n);
    if (fabs(sh_dot(light->map_normal, light->direction)) < 1e-9)
      return sh_error_set(err, SH_ERR_SCENE,
                          "the light travels parallel to the light map's "
                          "window, so the pattern cannot be projected");
  }
  return SH_OK;
}

double sh_spot_profile(const sh_light *light, double c) {
  if (c < light->cos_outer) return 0.0;
  double f = 1.0;
  double w = light->cos_inner - light->cos_outer;
  if (w > 0 && c < light->cos_inner) {
    double u = (c - light->cos_outer) / w;
    f = u * u * (3.0 - 2.0 * u);
  }
  if (light->exponent != 0) f *= pow(c > 0 ? c : 0.0, light->exponent);
  return f;
}

static sh_vec3 map_sample(const sh_image *img, double s, double t) {
  float v[3];
  sh_image_lookup(img, s, t, v);
  return sh_v3(v[0], v[1], v[2]);
}

sh_vec3 sh_light_map_value(const sh_light *light, sh_vec3 p) {
  if (!light->has_map) return sh_v3s(1.0);
  if (light->type == SH_LIGHT_SPOT) {
    sh_vec3 d = sh_sub(p, light->position);
    double z = sh_dot(d, light->direction);
    if (z <= 0) return sh_v3s(0.0);
    double x = sh_dot(d, light->map_right) / (z * light->tan_outer);
    double y = sh_dot(d, light->map_up) / (z * light->tan_outer);
    if (x < -1 || x > 1 || y < -1 || y > 1) return sh_v3s(0.0);
    return map_sample(&light->map, 0.5 * (x + 1.0), 0.5 * (1.0 - y));
  }
  if (light->type == SH_LIGHT_DIRECTIONAL) {
    /* Project p along the direction onto the window's plane, then solve
     * q - origin = s u + t v in the plane. */
    sh_vec3 n = light->map_normal, d = light->direction;
    double lam = sh_dot(sh_sub(p, light->map_origin), n) / sh_dot(d, n);
    sh_vec3 q = sh_sub(sh_madd(p, d, -lam), light->map_origin);
    sh_vec3 u = light->map_u, v = light->map_v;
    double uu = sh_dot(u, u), uv = sh_dot(u, v), vv = sh_dot(v, v);
    double qu = sh_dot(q, u), qv = sh_dot(q, v);
    double det = uu * vv - uv * uv;
    double s = (qu * vv - qv * uv) / det, t = (qv * uu - qu * uv) / det;
    if (s < 0 || s > 1 || t < 0 || t > 1) return sh_v3s(0.0);
    /* s runs along u (image right), t along v (image down). */
    return map_sample(&light->map, s, t);
  }
  return sh_v3s(1.0);
}

sh_vec3 sh_light_incident(const sh_light *light, sh_vec3 p, sh_vec3 *wi,
                          double *dist) {
  if (light->type == SH_LIGHT_DIRECTIONAL) {
    *wi = sh_neg(light->direction);
    *dist = INFINITY;
    if (!light->has_map) return light->irradiance;
    return sh_mul(light->irradiance, sh_light_map_value(light, p));
  }
  sh_vec3 d = sh_sub(light->position, p);
  double r2 = sh_dot(d, d);
  double r = sqrt(r2);
  *dist = r;
  if (r == 0) {
    *wi = sh_v3(0, 1, 0);
    return sh_v3s(0.0);
  }
  *wi = sh_scale(d, 1.0 / r);
  sh_vec3 e = sh_scale(light->intensity, 1.0 / r2);
  if (light->type == SH_LIGHT_SPOT) {
    double c = -sh_dot(*wi, light->direction);
    double f = sh_spot_profile(light, c);
    if (f == 0) return sh_v3s(0.0);
    e = sh_scale(e, f);
    if (light->has_map) e = sh_mul(e, sh_light_map_value(light, p));
  }
  return e;
}

sh_vec3 sh_light_disk_radiance(const sh_light *light, sh_vec3 d) {
  if (light->type != SH_LIGHT_DIRECTIONAL || !(light->disk_solid_angle > 0) ||
      -sh_dot(d, light->direction) < light->disk_cos_half)
    return sh_v3s(0.0);
  return sh_scale(light->irradiance, 1.0 / light->disk_solid_angle);
}

sh_vec3 sh_scene_background_radiance(const sh_scene *scene, sh_vec3 d) {
  sh_vec3 L = scene->background;
  for (int i = 0; i < scene->nlights; i++)
    L = sh_add(L, sh_light_disk_radiance(&scene->lights[i], d));
  return L;
}
