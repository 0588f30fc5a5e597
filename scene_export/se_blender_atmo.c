#include "se_blender_atmo.h"

#include <math.h>

#include "se_cycles_phase.h"

/* A sphere as rings of latitude about a pole: the pole's vertex, rings at
 * polar angles theta_1 = theta0, theta_{k+1} = min(growth theta_k,
 * theta_k + max_step) below pi, nphi vertices each, and the antipode.
 * Dense near the pole (the point below the camera) and coarse beyond: a
 * chord between rings lies R dtheta^2 / 8 inside the sphere, which seen
 * from the pole's neighbourhood is an angle of about theta (growth -
 * 1)^2 / 8. Triangles are counter-clockwise seen from outside. */
typedef struct sphere_grid {
  double theta0, growth, max_step;
  int nphi;
} sphere_grid;

static void push(json_t *a, const se_frame *f, sh_vec3 p) {
  sh_vec3 v = se_frame_point(f, p);
  json_array_append_new(a, json_real(v.x));
  json_array_append_new(a, json_real(v.y));
  json_array_append_new(a, json_real(v.z));
}

static void push_tri(json_t *t, int a, int b, int c) {
  json_array_append_new(t, json_integer(a));
  json_array_append_new(t, json_integer(b));
  json_array_append_new(t, json_integer(c));
}

static void sphere_mesh(const se_frame *f, sh_vec3 c, double R, sh_vec3 pole,
                        const sphere_grid *g, json_t *v, json_t *t) {
  sh_vec3 u, w;
  sh_basis(pole, &u, &w);
  w = sh_cross(pole, u); /* (u, w, pole) right-handed */
  push(v, f, sh_madd(c, pole, R));
  int n = g->nphi, rings = 0;
  for (double th = g->theta0; th < SH_PI * (1.0 - 1e-9);
       th = fmin(th * g->growth, th + g->max_step), rings++) {
    for (int j = 0; j < n; j++) {
      double ph = 2.0 * SH_PI * j / n;
      sh_vec3 d = sh_add(sh_scale(pole, cos(th)),
                         sh_scale(sh_add(sh_scale(u, cos(ph)), sh_scale(w, sin(ph))), sin(th)));
      push(v, f, sh_madd(c, d, R));
    }
  }
  push(v, f, sh_madd(c, pole, -R));
  int antipode = 1 + rings * n;
  for (int j = 0; j < n; j++) push_tri(t, 0, 1 + j, 1 + (j + 1) % n);
  for (int k = 0; k + 1 < rings; k++) {
    int a = 1 + k * n, b = a + n;
    for (int j = 0; j < n; j++) {
      int j1 = (j + 1) % n;
      push_tri(t, a + j, b + j, b + j1);
      push_tri(t, a + j, b + j1, a + j1);
    }
  }
  int a = 1 + (rings - 1) * n;
  for (int j = 0; j < n; j++) push_tri(t, a + j, antipode, a + (j + 1) % n);
}

static json_t *rgb(sh_vec3 c) { return json_pack("[fff]", c.x, c.y, c.z); }

static double luminance(sh_vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

/* A Volume Absorption of signed coefficient a (per unit length, before the
 * profile): colour 1 - a / D with density D = max |a|, so that Cycles'
 * (1 - colour) density is a; NULL for none. */
static json_t *absorption(sh_vec3 a, int profile, int part) {
  double d = fmax(fabs(a.x), fmax(fabs(a.y), fabs(a.z)));
  if (!(d > 0)) return NULL;
  return json_pack("{s:i, s:i, s:o, s:f}", "profile", profile, "part", part, "color",
                   rgb(sh_sub(sh_v3s(1.0), sh_scale(a, 1.0 / d))), "density", d);
}

double se_blender_atmo_clip_start(const sh_scene *scene) {
  const sh_atmosphere *a = &scene->medium.atmo;
  double r = sh_length(sh_sub(scene->camera.position, a->center));
  double h = fmin(fabs(r - a->ground_radius), fabs(r - a->top_radius));
  return fmax(1e-3 * h, 1e-9 * a->top_radius);
}

json_t *se_blender_atmosphere(const sh_scene *scene, const se_frame *f,
                              json_t *materials, json_t *meshes, se_notes *notes) {
  const sh_atmosphere *a = &scene->medium.atmo;
  sh_vec3 cam = sh_sub(scene->camera.position, a->center);
  double rc = sh_length(cam);
  sh_vec3 pole = rc > 0 ? sh_scale(cam, 1.0 / rc) : sh_v3(0, 1, 0);

  /* The ground: Lambert, smooth-shaded, fine below the camera: rings from
   * a twentieth of the camera's height (seen from there, no chord strays
   * more than about 1e-3 of its distance). */
  double hc = fmax(fabs(rc - a->ground_radius), 1e-9 * a->ground_radius);
  sphere_grid gg = {fmin(0.05 * hc / a->ground_radius, 0.02), 1.08, 0.02, 128};
  json_t *gv = json_array(), *gt = json_array();
  sphere_mesh(f, a->center, a->ground_radius, pole, &gg, gv, gt);
  sh_vec3 zero = sh_v3s(0.0);
  json_array_append_new(materials,
                        json_pack("{s:s, s:o, s:o, s:o, s:f, s:o}", "label", "ground",
                                  "diffuse", rgb(a->ground_albedo), "mirror", rgb(zero),
                                  "transmit", rgb(zero), "ior", 1.0, "emission", rgb(zero)));
  /* atmosphere_ground: the add-on's import takes the atmosphere's exact
   * ground sphere instead of this mesh (blender_build.py). */
  json_array_append_new(meshes, json_pack("{s:s, s:i, s:b, s:b, s:o, s:o}", "label", "ground",
                                          "material",
                                          (int)json_array_size(materials) - 1, "smooth",
                                          1, "atmosphere_ground", 1, "vertices", gv,
                                          "triangles", gt));

  /* The air's container: a uniform grid whose triangles (circumradius at
   * most 0.0274 of the radius) enclose the top sphere when its vertices lie
   * 1e-3 outside it. */
  double Rc = a->top_radius * (1.0 + 1e-3);
  sphere_grid cg = {SH_PI / 128.0, 1e9, SH_PI / 128.0, 128};
  json_t *cv = json_array(), *ct = json_array();
  sphere_mesh(f, a->center, Rc, pole, &cg, cv, ct);

  /* Profiles: 0 Rayleigh's, 1 Mie's, 2 the ozone's tent. Parts (the
   * scattering ones): Rayleigh, then Mie. */
  json_t *profiles = json_pack(
      "[{s:f}, {s:f}, {s:f, s:f}]", "scale_height", se_frame_length(f, a->rayleigh_H),
      "scale_height", se_frame_length(f, a->has_mie ? a->mie_H : a->rayleigh_H),
      "center_height", se_frame_length(f, a->ozone_height), "half_width",
      se_frame_length(f, 0.5 * (a->has_ozone ? a->ozone_width : 1.0)));
  sh_vec3 s0[2] = {se_frame_per_length(f, a->rayleigh_sigma_s),
                   se_frame_per_length(f, a->has_mie ? a->mie_sigma_s : zero)};
  sh_phase rayleigh = {SH_PHASE_RAYLEIGH, 0.0};
  const sh_phase *phases[2] = {&rayleigh, &a->mie_phase};
  double l[2] = {luminance(s0[0]), luminance(s0[1])};
  json_t *parts = json_array(), *scatter = json_array(), *absorb = json_array();
  int np = 0, index[2] = {-1, -1};
  for (int x = 0; x < 2; x++) {
    if (!(l[x] > 0)) continue;
    index[x] = np++;
    json_array_append_new(parts, json_pack("{s:i, s:f}", "profile", x, "luminance", l[x]));
  }
  for (int x = 0; x < 2; x++) {
    if (index[x] < 0) continue;
    int exact;
    double gs[SE_HG_MAX_LOBES], ws[SE_HG_MAX_LOBES];
    int n = se_phase_to_hg_weighted(phases[x], gs, ws, &exact);
    sh_vec3 c = sh_scale(s0[x], 1.0 / l[x]); /* the chosen lobe's sigma_s is c L */
    double m = sh_max3(c), from = 0.0;
    /* Lobe i owns the slice [from, to) of the part's interval, of length
     * its weight (the last ends at 1 exactly). */
    for (int i = 0; i < n; i++) {
      double to = i == n - 1 ? 1.0 : from + ws[i];
      json_array_append_new(scatter,
                            json_pack("{s:i, s:f, s:f, s:f, s:o, s:f}", "part", index[x],
                                      "from", from, "to", to, "anisotropy", gs[i], "color",
                                      rgb(sh_scale(c, 1.0 / m)), "density", m));
      from = to;
    }
    /* The extinction the chosen lobe leaves out (or adds), per other part. */
    for (int y = 0; y < 2; y++) {
      if (y == x || index[y] < 0) continue;
      json_t *ab = absorption(sh_sub(s0[y], sh_scale(c, l[y])), y, index[x]);
      if (ab) json_array_append_new(absorb, ab);
    }
    if (!exact) {
      double g1 = se_phase_to_hg(phases[x], &exact);
      if (n > 1 && phases[x]->type == SH_PHASE_CORNETTE_SHANKS)
        se_note(notes,
                "medium.%s: Cycles has no %s phase; it is a mixture of %d "
                "Henyey-Greenstein lobes fitted to it, g = %.4g and %.4g of weights %.4g "
                "and %.4g, one chosen per point.",
                x ? "mie.phase" : "rayleigh", se_phase_name(phases[x]->type), n, gs[0], gs[1],
                ws[0], ws[1]);
      else if (n > 1)
        se_note(notes,
                "medium.%s: Cycles has no %s phase; it is an equal-weight mixture of %d "
                "Henyey-Greenstein lobes fitted to it.",
                x ? "mie.phase" : "rayleigh", se_phase_name(phases[x]->type), n);
      else
        se_note_one_lobe(notes, x ? "medium.mie.phase" : "medium.rayleigh", "Cycles",
                         phases[x], g1, "");
    }
  }
  if (a->has_mie) {
    json_t *ab = absorption(se_frame_per_length(f, a->mie_sigma_a), 1, -1);
    if (ab) json_array_append_new(absorb, ab);
  }
  if (a->has_ozone) {
    json_t *ab = absorption(se_frame_per_length(f, a->ozone_sigma_a), 2, -1);
    if (ab) json_array_append_new(absorb, ab);
  }
  /* The choice of one lobe per point is exact in expectation (it adds
   * noise, no bias): no note. */

  /* Ray marching: steps of a fraction of the smallest scale height; enough
   * of them for the shell's longest chord (a ray grazing the ground). */
  double Hmin = fmin(a->rayleigh_H, a->has_mie ? a->mie_H : a->rayleigh_H);
  double step = se_frame_length(f, SE_ATMO_STEP_FRACTION * Hmin);
  double rate = step / (0.1 * se_frame_length(f, 2.0 * Rc));
  double chord = 2.0 * sqrt(Rc * Rc - a->ground_radius * a->ground_radius);
  double steps = ceil(1.1 * se_frame_length(f, chord) / step);
  if (steps > 65536.0)
    se_note(notes,
            "medium: the shell's longest chord needs %.0f steps of %g scene units and "
            "Cycles takes at most 65536: longer steps there.",
            steps, SE_ATMO_STEP_FRACTION * Hmin);

  sh_vec3 lo = se_frame_point(f, sh_sub(a->center, sh_v3s(Rc)));
  sh_vec3 hi = se_frame_point(f, sh_add(a->center, sh_v3s(Rc)));
  json_t *atmo = json_pack(
      "{s:o, s:f, s:f, s:{s:o, s:o}, s:o, s:o, s:o, s:o, s:f, s:i}", "center",
      rgb(se_frame_point(f, a->center)), "ground_radius",
      se_frame_length(f, a->ground_radius), "top_radius", se_frame_length(f, a->top_radius),
      "container", "vertices", cv, "triangles", ct, "profiles", profiles, "parts", parts,
      "scatter", scatter, "absorption", absorb, "step_rate", rate, "max_steps",
      (int)fmin(65536.0, steps));
  return json_pack("{s:o, s:o, s:o, s:o}", "min", rgb(sh_vmin(lo, hi)), "max",
                   rgb(sh_vmax(lo, hi)), "sigma_t",
                   rgb(se_frame_per_length(f, scene->medium.sigma_t)), "atmosphere", atmo);
}
