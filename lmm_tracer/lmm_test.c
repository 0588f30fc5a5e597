/* The light meshes method against the properties Debelov et al. claim and
 * the ones we require: (a) away from shadow edges it equals the RRTA, (b)
 * hard edges become soft, (c) it converges to the RRTA as h falls with kl
 * fixed; no light leaks; semitransparent shadows are t^2 of the light; and
 * under refract-both a lens sphere focuses light where a separate
 * ray-traced computation puts the focus. */
#include <string.h>

#include "lmm_caustic.h"
#include "lmm_method.h"
#include "sh_camera.h"
#include "sh_parse.h"
#include "sh_reference.h"
#include "sh_test.h"

/* Parses a test scene and builds its tracer into *rt; NULL (a failed
 * check) when the scene does not parse. */
static sh_scene *open_scene(const char *json, sh_rt **rt) {
  sh_scene *s = sh_test_parse(json, "lmm_test.json");
  SH_CHECK(s != NULL);
  *rt = NULL;
  if (s) SH_CHECK(sh_rt_create(s, rt, NULL) == SH_OK);
  return s;
}

/* Renders with the tracer; h > 0 selects the light meshes method. */
static void render(const sh_scene *s, const sh_rt *rt, double h, double kl,
                   lmm_scheme scheme, sh_image *img, lmm_stats *stats) {
  sh_reference_options opt = sh_reference_defaults(s);
  opt.threads = 2;
  opt.rt = rt;
  opt.refract = scheme != LMM_SCHEME_STRAIGHT;
  lmm *method = NULL;
  if (h > 0) {
    lmm_options lo = {h, kl, scheme, 200000, 0, 1, 0, NULL, NULL, NULL};
    SH_CHECK(lmm_create(s, rt, &lo, opt.threads, &method, NULL) == SH_OK);
    opt.hook = lmm_hook(method);
  }
  SH_CHECK(sh_render_reference(s, &opt, img, NULL, NULL) == SH_OK);
  if (method && stats) lmm_get_stats(method, stats);
  lmm_free(method);
}

/* A floor under a point light with a floating box: the seed's fig. 3 in
 * small. The camera looks down at the floor. */
static const char *FLOOR_BOX =
    "{\"format\": \"shafts-scene\", \"version\": 1,"
    " \"camera\": {\"position\": [0, 6, 0.01], \"look_at\": [0, 0, 0],"
    "  \"fov_y_deg\": 60, \"width\": 72, \"height\": 72},"
    " \"lights\": [{\"type\": \"point\", \"position\": [0.3, 4, 0.2],"
    "  \"intensity\": [20, 20, 20]}],"
    " \"materials\": {\"m\": {\"diffuse\": [0.8, 0.8, 0.8]}},"
    " \"shapes\": [{\"type\": \"quad\", \"material\": \"m\","
    "  \"corner\": [-3, 0, 3], \"u\": [6, 0, 0], \"v\": [0, 0, -6]},"
    "  {\"type\": \"box\", \"material\": \"m\", \"min\": [-0.6, 1.5, -0.6],"
    "   \"max\": [0.6, 1.7, 0.6]}]}";

/* The floor point a pixel sees (y = 0), and the unshadowed radiance. */
static sh_vec3 floor_point(const sh_camera_frame *f, int x, int y) {
  sh_vec3 d = sh_camera_dir(f, x + 0.5, y + 0.5);
  return sh_madd(f->origin, d, -f->origin.y / d.y);
}

static double unshadowed(const sh_scene *s, sh_vec3 p) {
  sh_vec3 to = sh_sub(s->lights[0].position, p);
  double r2 = sh_dot(to, to);
  return 0.8 / SH_PI * s->lights[0].intensity.x * (to.y / sqrt(r2)) / r2;
}

static void properties(void) {
  sh_rt *rt;
  sh_scene *s = open_scene(FLOOR_BOX, &rt);
  if (!s) return;
  sh_camera_frame f;
  sh_camera_frame_init(&s->camera, &f);
  double h = 0.1, kl = 2.0, r = h * kl;
  sh_image rrta = {0}, lm = {0};
  render(s, rt, 0, 0, LMM_SCHEME_REFRACT_TRACE, &rrta, NULL);
  lmm_stats st;
  render(s, rt, h, kl, LMM_SCHEME_REFRACT_TRACE, &lm, &st);
  SH_CHECK(st.mesh.bits == 1);
  SH_CHECK(st.mesh.points_computed > 0 &&
           st.mesh.points_computed < st.mesh.points_total / 5);

  /* (a) Where the light's visibility is the same at every point within
   * 1.5 r of P, the two images agree. */
  int away = 0, mismatched = 0, soft_lmm = 0, soft_rrta = 0;
  for (int y = 0; y < lm.height; y++)
    for (int x = 0; x < lm.width; x++) {
      sh_vec3 p = floor_point(&f, x, y);
      if (fabs(p.x) > 2.5 || fabs(p.z) > 2.5) continue;
      int lit = 0, total = 0;
      for (int k = 0; k < 27; k++) {
        sh_vec3 off = sh_v3(k % 3 - 1, (k / 3) % 3, k / 9 - 1);
        sh_vec3 q = sh_madd(p, sh_normalize(off), k == 3 + 1 ? 0 : 1.5 * r);
        if (sh_is_black(off)) q = p;
        q.y = fmax(q.y, 1e-4);
        sh_vec3 to = sh_sub(s->lights[0].position, q);
        double d = sh_length(to);
        lit += !sh_is_black(sh_rt_visibility(rt, q, sh_scale(to, 1 / d),
                                             d * 0.999999, NULL));
        total++;
      }
      double a = lm.rgb[3 * (y * lm.width + x)],
             b = rrta.rgb[3 * (y * lm.width + x)];
      if (lit == 0 || lit == total) {
        away++;
        if (fabs(a - b) > 1e-5 * fabs(b) + 1e-9) mismatched++;
      }
      /* (b) Penumbra: the fraction of the unshadowed radiance. */
      double u = unshadowed(s, p);
      soft_lmm += a > 0.1 * u && a < 0.9 * u;
      soft_rrta += b > 0.1 * u && b < 0.9 * u;
    }
  fprintf(stderr, "(a) %d pixels away from edges, %d differ; (b) penumbra "
                  "pixels: rrta %d, lmm %d\n", away, mismatched, soft_rrta,
          soft_lmm);
  SH_CHECK(away > lm.width * lm.height / 3);
  SH_CHECK(mismatched == 0);
  SH_CHECK(soft_lmm > 3 * soft_rrta + 20);

  /* (c) As h falls with kl fixed, the image converges to the RRTA's. */
  double prev = INFINITY;
  for (double hh = 0.2; hh > 0.02; hh /= 2) {
    sh_image img = {0};
    render(s, rt, hh, kl, LMM_SCHEME_REFRACT_TRACE, &img, NULL);
    double e = 0;
    for (int i = 0; i < img.width * img.height * 3; i++)
      e += (img.rgb[i] - rrta.rgb[i]) * (img.rgb[i] - rrta.rgb[i]);
    e = sqrt(e / (img.width * img.height * 3));
    fprintf(stderr, "(c) h = %.3f: rms difference from RRTA %.4g\n", hh, e);
    SH_CHECK(e < prev);
    prev = e;
    sh_image_free(&img);
  }
  sh_image_free(&rrta);
  sh_image_free(&lm);
  sh_rt_free(rt);
  sh_scene_free(s);
}

/* A thin plate (thinner than the mesh step) between the light and the
 * floor keeps the floor under it dark; a sheet with the light just behind
 * it near its edge stays dark on its front. */
static void no_leaks(void) {
  sh_rt *rt;
  sh_scene *s = open_scene(
      "{\"format\": \"shafts-scene\", \"version\": 1,"
      " \"camera\": {\"position\": [0, 0.25, 3], \"look_at\": [0, 0.25, 0],"
      "  \"fov_y_deg\": 20, \"width\": 48, \"height\": 32},"
      " \"lights\": [{\"type\": \"point\", \"position\": [0, 2, -0.3],"
      "  \"intensity\": [20, 20, 20]},"
      "  {\"type\": \"point\", \"position\": [1.05, 0.5, -0.02],"
      "  \"intensity\": [5, 5, 5]}],"
      " \"materials\": {\"m\": {\"diffuse\": [0.8, 0.8, 0.8]}},"
      " \"shapes\": [{\"type\": \"quad\", \"material\": \"m\","
      "  \"corner\": [-5, 0, 5], \"u\": [10, 0, 0], \"v\": [0, 0, -10]},"
      "  {\"type\": \"box\", \"material\": \"m\", \"min\": [-4, 0.3, -4],"
      "   \"max\": [4, 0.31, 4]},"
      "  {\"type\": \"quad\", \"material\": \"m\", \"corner\": [-1, 0.02, 0],"
      "   \"u\": [2, 0, 0], \"v\": [0, 0.26, 0]}]}",
      &rt);
  if (!s) return;
  sh_image img = {0};
  render(s, rt, 0.1, 2.0, LMM_SCHEME_REFRACT_TRACE, &img, NULL);
  /* Everything the camera sees is under the plate: the floor, lit by no
   * light, and the sheet's front, whose light is behind it. */
  double worst = 0;
  for (int i = 0; i < img.width * img.height * 3; i++)
    worst = fmax(worst, img.rgb[i]);
  fprintf(stderr, "no leaks: brightest pixel %.3g\n", worst);
  SH_CHECK(worst == 0);
  sh_image_free(&img);
  sh_rt_free(rt);
  sh_scene_free(s);
}

/* A sphere of transmit t over a floor: under the straight scheme its shadow
 * is t^2 of the light at the shadow's centre. Under refract-both a bright
 * focus appears below the sphere, where tracing rays through it puts the
 * focus. */
static const char *LENS =
    "{\"format\": \"shafts-scene\", \"version\": 1,"
    " \"camera\": {\"position\": [0, 6, 0.01], \"look_at\": [0, 0, 0],"
    "  \"fov_y_deg\": 30, \"width\": 64, \"height\": 64},"
    " \"lights\": [{\"type\": \"directional\", \"direction\": [0, -1, 0],"
    "  \"irradiance\": [3, 3, 3]}],"
    " \"materials\": {\"floor\": {\"diffuse\": [0.8, 0.8, 0.8]},"
    "  \"glass\": {\"transmit\": [0.6, 0.6, 0.6], \"ior\": 1.5}},"
    " \"shapes\": [{\"type\": \"quad\", \"material\": \"floor\","
    "  \"corner\": [-3, 0, 3], \"u\": [6, 0, 0], \"v\": [0, 0, -6]},"
    "  {\"type\": \"sphere\", \"material\": \"glass\", \"center\": [0, 2.5, 0],"
    "   \"radius\": 1}]}";

/* Where rays parallel to the axis at height a cross the axis after two
 * refractions through a sphere of radius 1 and index n centred at 0, as a
 * distance below the centre. */
static double axis_crossing(double a, double n) {
  double ti = asin(a), tt = asin(a / n);
  /* Inside, the ray turns by ti - tt; it leaves at angle 2 tt from the
   * entry point's radius, and bends again by ti - tt. */
  double dev = 2.0 * (ti - tt);   /* total deviation from the axis */
  /* The chord inside subtends pi - 2 tt: the exit point is the entry point
   * (sin ti, cos ti) turned on by that angle. */
  double px = sin(ti + SH_PI - 2.0 * tt);
  double py = cos(ti + SH_PI - 2.0 * tt);
  /* The ray leaves going down and towards the axis at angle dev. */
  double dx = -sin(dev), dy = -cos(dev);
  double t = -px / dx;
  return -(py + t * dy);
}

static void semitransparent(void) {
  sh_rt *rt;
  sh_scene *s = open_scene(LENS, &rt);
  if (!s) return;
  sh_camera_frame f;
  sh_camera_frame_init(&s->camera, &f);
  sh_image img = {0};
  render(s, rt, 0.1, 2.0, LMM_SCHEME_STRAIGHT, &img, NULL);
  /* The camera looks down through the sphere; straight, its rays reach the
   * floor at the shadow's centre after two crossings (weight 0.36), so
   * the pixel shows 0.36 * t^2 * the lit floor. */
  double lit = 0.8 / SH_PI * 3.0;
  int cx = img.width / 2, cy = img.height / 2;
  double centre = img.rgb[3 * (cy * img.width + cx)];
  fprintf(stderr, "straight: shadow centre %.5g, expected %.5g\n", centre,
          0.36 * 0.36 * lit);
  SH_CHECK_NEAR(centre, 0.36 * 0.36 * lit, 1e-3, 0);
  sh_image_free(&img);

  /* refract-both: the mesh values straight below the sphere, against the
   * crossings of paraxial and marginal rays. */
  lmm_options lo = {0.05, 2.0, LMM_SCHEME_REFRACT_BOTH, 200000, 0, 1, 0, NULL, NULL, NULL};
  double paraxial = 1.5 / (2.0 * 0.5); /* n R / (2 (n - 1)) from the centre */
  double marginal = axis_crossing(0.7, 1.5);
  fprintf(stderr, "focus expected between %.3f and %.3f below the centre "
                  "(rays at heights 0.7 and 0)\n", marginal, paraxial);
  SH_CHECK(marginal < paraxial);
  /* The light mesh's values along the axis below the sphere: formula 6,
   * the direct term plus the refracted paths, composed as the method does. */
  sh_vec3 vis[1];
  double best = 0, best_depth = 0;
  lmm_mesh *mesh = NULL;
  SH_CHECK(lmm_mesh_create(s, rt, lo.h, 0, &mesh, NULL) == SH_OK);
  lmm_caustics *caustics = NULL;
  const lmm_grid *grid = lmm_mesh_grid(mesh);
  volatile int stop = 1;
  lmm_caustics *none = (lmm_caustics *)1;
  lmm_caustics_control halt = {&stop, NULL, NULL};
  SH_CHECK(lmm_caustics_build(s, rt, grid, lo.caustic_rays, &halt, &none,
                              NULL) == SH_ERR_CANCELLED &&
           none == NULL);
  SH_CHECK(lmm_caustics_build(s, rt, grid, lo.caustic_rays, NULL, &caustics,
                              NULL) == SH_OK);
  lmm_mesh_set_direct_only(mesh);
  int ijk[3];
  for (double depth = 1.05; depth < 2.45; depth += lo.h) {
    lmm_grid_cell(grid, sh_v3(0.001, 2.5 - depth, 0.001), ijk);
    lmm_mesh_values(mesh, ijk[0], ijk[1], ijk[2], vis, NULL);
    vis[0] = sh_add(vis[0], lmm_caustics_at(caustics, ijk[0], ijk[1], ijk[2], 0));
    sh_vec3 x = lmm_grid_point(grid, ijk[0], ijk[1], ijk[2]);
    if (vis[0].x > best) {
      best = vis[0].x;
      best_depth = 2.5 - x.y;
    }
  }
  fprintf(stderr, "refract-both: brightest mesh point on the axis %.3g times "
                  "the light, %.3f below the centre\n", best, best_depth);
  SH_CHECK(best > 3.0);
  SH_CHECK(best_depth > marginal - 2 * lo.h && best_depth < paraxial + 2 * lo.h);
  lmm_mesh_free(mesh);
  lmm_caustics_free(caustics);

  /* The refined variant: on the floor every path's P_j (the lens's lower
   * surface) is on the outer side, so it agrees with formula 7 there. */
  sh_image plain = {0}, refined = {0};
  s->camera.width = s->camera.height = 24;
  for (int v = 0; v < 2; v++) {
    sh_reference_options opt = sh_reference_defaults(s);
    opt.rt = rt;
    lmm *method = NULL;
    lmm_options ro = {0.1, 2.0, LMM_SCHEME_REFRACT_BOTH, 50000, 0, 1, v, NULL, NULL, NULL};
    SH_CHECK(lmm_create(s, rt, &ro, 2, &method, NULL) == SH_OK);
    opt.threads = 2;
    opt.hook = lmm_hook(method);
    SH_CHECK(sh_render_reference(s, &opt, v ? &refined : &plain, NULL, NULL) ==
             SH_OK);
    lmm_free(method);
  }
  double diff = 0, total = 0;
  for (int i = 0; i < plain.width * plain.height * 3; i++) {
    diff += fabs(plain.rgb[i] - refined.rgb[i]);
    total += plain.rgb[i];
  }
  fprintf(stderr, "refined against formula 7 on the lens scene: %.3g%%\n",
          100 * diff / total);
  SH_CHECK(diff < 0.01 * total);
  sh_image_free(&plain);
  sh_image_free(&refined);
  sh_rt_free(rt);
  sh_scene_free(s);
}

/* Writes text with its first `from` replaced by `to` into buf. */
static const char *edit(char *buf, size_t size, const char *text,
                        const char *from, const char *to) {
  const char *at = strstr(text, from);
  SH_CHECK(at != NULL);
  if (!at) return text;
  snprintf(buf, size, "%.*s%s%s", (int)(at - text), text, to,
           at + strlen(from));
  return buf;
}

/* The user controls of the paper's conclusion: each of them, applied to the
 * only light, caster or receiver, gives back the RRTA's hard shadows. */
static void controls(void) {
  char tmp[8192], base[8192], text[8192];
  edit(tmp, sizeof tmp, FLOOR_BOX, "{\"type\": \"box\", \"material\": \"m\"",
       "{\"type\": \"box\", \"material\": \"b\"");
  edit(base, sizeof base, tmp, "\"materials\": {",
       "\"materials\": {\"b\": {\"diffuse\": [0.8, 0.8, 0.8]}, ");
  const char *variants[3][2] = {
      {"\"intensity\": [20, 20, 20]}", "\"intensity\": [20, 20, 20], "
                                        "\"soft_shadows\": false}"},
      {"\"b\": {\"diffuse\": [0.8, 0.8, 0.8]}",
       "\"b\": {\"diffuse\": [0.8, 0.8, 0.8], \"casts_soft_shadows\": false}"},
      {"\"m\": {\"diffuse\": [0.8, 0.8, 0.8]}",
       "\"m\": {\"diffuse\": [0.8, 0.8, 0.8], \"receives_soft_shadows\": "
       "false}"}};
  const char *names[3] = {"light soft_shadows false",
                          "caster casts_soft_shadows false",
                          "receiver receives_soft_shadows false"};
  for (int v = 0; v < 3; v++) {
    sh_rt *rt;
    sh_scene *s = open_scene(
        edit(text, sizeof text, base, variants[v][0], variants[v][1]), &rt);
    if (!s) continue;
    sh_image a = {0}, b = {0};
    render(s, rt, 0, 0, LMM_SCHEME_REFRACT_TRACE, &a, NULL);
    render(s, rt, 0.1, 2.0, LMM_SCHEME_REFRACT_TRACE, &b, NULL);
    double worst = 0;
    for (int i = 0; i < a.width * a.height * 3; i++)
      worst = fmax(worst, fabs(a.rgb[i] - b.rgb[i]));
    fprintf(stderr, "%s: largest difference from RRTA %.3g\n", names[v],
            worst);
    SH_CHECK(worst < 1e-6);
    sh_image_free(&a);
    sh_image_free(&b);
    sh_rt_free(rt);
    sh_scene_free(s);
  }
}

int main(void) {
  properties();
  controls();
  no_leaks();
  semitransparent();
  SH_TEST_DONE();
}
