/* The Blender target's atmosphere data (se_blender_atmo.h), without
 * Blender: the ground mesh is a closed sphere of radius R_g seen from
 * outside, the air's container encloses the top sphere, and at every
 * height the lobes chosen per point give the exact in-scattering in
 * expectation while every choice keeps the exact extinction; for the two
 * canonical atmosphere scenes, in two frames (the scene's units, and 10^4
 * of them a unit, as the export's frame puts the Earth). */
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "se_blender_atmo.h"
#include "sh_parse.h"
#include "sh_test.h"

static double num(json_t *o, const char *key) { return json_number_value(json_object_get(o, key)); }

static sh_vec3 vec_at(json_t *a, size_t i) {
  return sh_v3(json_number_value(json_array_get(a, 3 * i)),
               json_number_value(json_array_get(a, 3 * i + 1)),
               json_number_value(json_array_get(a, 3 * i + 2)));
}

static sh_vec3 rgb(json_t *o, const char *key) { return vec_at(json_object_get(o, key), 0); }

/* Every triangle counter-clockwise seen from outside, every vertex at
 * `radius` (relative 1e-12), closed (V - E + F = 2 with E = 3F / 2); the
 * smallest distance from the centre to a triangle's plane. */
static double check_sphere(json_t *mesh, sh_vec3 c, double radius, int on_sphere) {
  json_t *v = json_object_get(mesh, "vertices"), *t = json_object_get(mesh, "triangles");
  size_t nv = json_array_size(v) / 3, nt = json_array_size(t) / 3;
  SH_CHECK(nv > 100 && nt > 100);
  SH_CHECK(2 * nv == nt + 4); /* V - E + F = 2, E = 3F / 2 */
  for (size_t i = 0; on_sphere && i < nv; i++)
    SH_CHECK_NEAR(sh_length(sh_sub(vec_at(v, i), c)), radius, 1e-12, 0);
  double nearest = INFINITY;
  int inward = 0;
  for (size_t k = 0; k < nt; k++) {
    sh_vec3 p[3];
    for (int j = 0; j < 3; j++)
      p[j] = vec_at(v, (size_t)json_integer_value(json_array_get(t, 3 * k + j)));
    sh_vec3 n = sh_normalize(sh_cross(sh_sub(p[1], p[0]), sh_sub(p[2], p[0])));
    double d = sh_dot(n, sh_sub(p[0], c));
    if (!(d > 0)) inward++;
    nearest = fmin(nearest, d);
  }
  SH_CHECK(inward == 0);
  return nearest;
}

/* The coefficients at height h (frame units) from the data: each part's
 * luminance share, the lobes' expected sigma_s, and each choice's
 * extinction, against the scene's own (frame units). */
static void check_mixture(const sh_atmosphere *a, const se_frame *f, json_t *atmo, double h) {
  json_t *profiles = json_object_get(atmo, "profiles"), *parts = json_object_get(atmo, "parts");
  double rho[8] = {0};
  for (size_t i = 0; i < json_array_size(profiles) && i < 8; i++) {
    json_t *p = json_array_get(profiles, i);
    if (json_object_get(p, "scale_height"))
      rho[i] = fmin(1.0, exp(-h / num(p, "scale_height")));
    else
      rho[i] = fmax(0.0, 1.0 - fabs(h - num(p, "center_height")) / num(p, "half_width"));
  }
  size_t np = json_array_size(parts);
  double L = 0, q[2] = {0};
  for (size_t x = 0; x < np; x++) {
    json_t *p = json_array_get(parts, x);
    L += num(p, "luminance") * rho[json_integer_value(json_object_get(p, "profile"))];
  }
  for (size_t x = 0; x < np && x < 2; x++) {
    json_t *p = json_array_get(parts, x);
    q[x] = num(p, "luminance") * rho[json_integer_value(json_object_get(p, "profile"))] / L;
  }
  /* The scene's coefficients at h, per frame unit. */
  double hs = h / f->scale; /* scene units */
  sh_vec3 sr = sh_scale(a->rayleigh_sigma_s, exp(-hs / a->rayleigh_H));
  sh_vec3 sm = a->has_mie ? sh_scale(a->mie_sigma_s, exp(-hs / a->mie_H)) : sh_v3s(0.0);
  sh_vec3 am = a->has_mie ? sh_scale(a->mie_sigma_a, exp(-hs / a->mie_H)) : sh_v3s(0.0);
  double tent = fmax(0.0, 1.0 - fabs(hs - a->ozone_height) / (0.5 * a->ozone_width));
  sh_vec3 ao = a->has_ozone ? sh_scale(a->ozone_sigma_a, tent) : sh_v3s(0.0);
  sh_vec3 want_s[2] = {se_frame_per_length(f, sr), se_frame_per_length(f, sm)};
  sh_vec3 want_t = se_frame_per_length(f, sh_add(sh_add(sr, sm), sh_add(am, ao)));
  json_t *scatter = json_object_get(atmo, "scatter"), *absorb = json_object_get(atmo, "absorption");
  sh_vec3 expected[2] = {sh_v3s(0.0), sh_v3s(0.0)};
  for (size_t k = 0; k < json_array_size(scatter); k++) {
    json_t *s = json_array_get(scatter, k);
    int x = (int)json_integer_value(json_object_get(s, "part"));
    double p = (num(s, "to") - num(s, "from")) * q[x];
    sh_vec3 ss = sh_scale(rgb(s, "color"), num(s, "density") * L);
    expected[x] = sh_madd(expected[x], ss, p);
    /* This lobe chosen: its sigma_s plus the absorption that goes with it. */
    sh_vec3 ext = ss;
    for (size_t j = 0; j < json_array_size(absorb); j++) {
      json_t *ab = json_array_get(absorb, j);
      int part = (int)json_integer_value(json_object_get(ab, "part"));
      if (part != -1 && part != x) continue;
      double d = num(ab, "density") * rho[json_integer_value(json_object_get(ab, "profile"))];
      ext = sh_add(ext, sh_scale(sh_sub(sh_v3s(1.0), rgb(ab, "color")), d));
    }
    for (int c = 0; c < 3; c++) SH_CHECK_NEAR(sh_vget(ext, c), sh_vget(want_t, c), 1e-12, 1e-300);
  }
  int x = 0;
  for (int part = 0; part < 2; part++) {
    if (!(sh_max3(want_s[part]) > 0)) continue;
    for (int c = 0; c < 3; c++)
      SH_CHECK_NEAR(sh_vget(expected[x], c), sh_vget(want_s[part], c), 1e-12, 1e-300);
    x++;
  }
}

static void check_scene(const char *path, double scale) {
  sh_scene *scene = NULL;
  sh_error err = {0};
  SH_CHECK(sh_scene_load(path, &scene, &err) == SH_OK);
  if (!scene) return;
  const sh_atmosphere *a = &scene->medium.atmo;
  se_frame f = se_frame_blender(scale, sh_v3s(0.0));
  json_t *materials = json_array(), *meshes = json_array();
  se_notes notes = {0};
  json_t *m = se_blender_atmosphere(scene, &f, materials, meshes, &notes);
  SH_CHECK(m != NULL && json_array_size(meshes) == 1 && json_array_size(materials) == 1);
  json_t *atmo = json_object_get(m, "atmosphere");
  sh_vec3 c = rgb(atmo, "center");
  double Rg = num(atmo, "ground_radius"), Rt = num(atmo, "top_radius");
  SH_CHECK_NEAR(Rg, a->ground_radius * scale, 1e-15, 0);
  SH_CHECK_NEAR(Rt, a->top_radius * scale, 1e-15, 0);
  check_sphere(json_array_get(meshes, 0), c, Rg, 1);
  /* The container holds the top sphere: no triangle's plane cuts it. */
  SH_CHECK(check_sphere(json_object_get(atmo, "container"), c, 0, 0) >= Rt);
  for (double h = 0; h <= 70.0; h += 2.5) check_mixture(a, &f, atmo, h * scale);
  /* Only the phases are approximated: Rayleigh's lobes, Cornette-Shanks'. */
  SH_CHECK(notes.count == 2);
  json_decref(m);
  json_decref(materials);
  json_decref(meshes);
  se_notes_free(&notes);
  sh_scene_free(scene);
}

int main(void) {
  const char *src = getenv("SHAFTS_SOURCE_DIR");
  if (!src) src = "../..";
  char path[1024];
  for (int i = 0; i < 2; i++) {
    snprintf(path, sizeof path, "%s/scenes/%s.json", src, i ? "earth_from_space" : "sky_sunset");
    check_scene(path, 1.0);
    check_scene(path, 1e-4);
  }
  SH_TEST_DONE();
}
