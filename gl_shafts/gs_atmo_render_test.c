/* The atmosphere drawn by gl_shafts (gs_atmo_render.h) against the
 * independent quadrature of atmo_quad.h (double precision, Gauss-Legendre
 * along each ray, the sun's optical depth integrated at every node) over
 * a lattice of pixels: the sky from 1 m above the ground at sunset, towards
 * the sun and away from it (the planet's shadow rising at dusk), the sky
 * under a high sun, and the planet from 30 000 km with the terminator in
 * view. `ctest -R gs_atmo_render -V` prints the errors; a failure writes
 * the images and their difference (gl_shafts_atmo_*.exr).
 * Measured (relative RMS, sh_image_compare, 192 pixels a view at offsets
 * that vary, so that they do not all fall on lattice points): at 64x48
 * with the layers at full resolution (12 planes, 6 spheres) 0.041%,
 * 0.218%, 0.013% and 0.082%, bound 0.3%; on a lattice of step 4 at
 * 192x144 0.66%, 0.34%, 0.12% and 0.24%, bound 1.5% (the step is 1.25
 * degrees there; docs/gl_shafts.md gives the errors at 640x480).
 * `gs_atmo_render_test
 * W H STEP PLANES SPHERES LATTICE` renders one size and prints the errors
 * (bound 100%); with
 * ATMO_WRITE=DIR it writes the images there as PNG. */
#include <stdio.h>
#include <stdlib.h>

#include "atmo_quad.h"
#include "gs_atmo_render.h"
#include "gs_context.h"
#include "gs_gl.h"
#include "sh_camera.h"
#include "sh_time.h"
#include "test_util.h"


typedef struct view_case {
  const char *name;
  double eye[3], look[3], fov;
  double sun_elev_deg, sun_azim_deg; /* the sun's direction from the eye */
  gs__atmo_settings set;
  double bound;
} view_case;

/* Renders one case and compares every `step`-th pixel with the quadrature.
 * Returns the error. */
static double run(gs__context *ctx, const gs__atmo *a, const view_case *vc, int w,
                  int h, int step, double *ms) {
  (void)ctx;
  double el = vc->sun_elev_deg * SH_PI / 180, az = vc->sun_azim_deg * SH_PI / 180;
  sh_vec3 to_sun = sh_v3(cos(el) * cos(az), sin(el), cos(el) * sin(az));
  char json[1024];
  snprintf(json, sizeof json,
           "{\"format\": \"shafts-scene\", \"version\": 1,"
           " \"camera\": {\"position\": [%.17g, %.17g, %.17g],"
           "  \"look_at\": [%.17g, %.17g, %.17g], \"fov_y_deg\": %g,"
           "  \"width\": %d, \"height\": %d},"
           " \"lights\": [{\"type\": \"directional\", \"direction\": [%.17g, %.17g, %.17g],"
           "  \"irradiance\": [20, 20, 20]}]}",
           vc->eye[0], vc->eye[1], vc->eye[2], vc->look[0], vc->look[1], vc->look[2],
           vc->fov, w, h, -to_sun.x, -to_sun.y, -to_sun.z);
  sh_scene *s = tu_scene(json);
  if (!s) return 1e9;
  gs__view view;
  gs__view_init(&view, s, NULL);
  gs__programs progs = {0};
  gs__params params = {0};
  gs__frame fr = {s, &view, &progs, &params, 1};
  gs__target t;
  gs__atmo_gl g;
  sh_error err = SH_ERROR_INIT;
  gs__atmo_source src = {aq_depth, a};
  double err_out = 1e9;
  float *rgba = malloc((size_t)w * h * 4 * sizeof *rgba);
  if (gs__target_create(&t, w, h, &err) != SH_OK ||
      gs__atmo_gl_init(&g, a, &src, &err) != SH_OK) {
    fprintf(stderr, "%s: %s\n", vc->name, err.message);
    return 1e9;
  }
  gs__atmo_counts counts;
  sh_status st = gs__atmo_render(&g, &fr, &t, &vc->set, &counts, &err);
  if (st == SH_OK) { /* the timed frame: programs built */
    glFinish();
    double t0 = sh_seconds();
    st = gs__atmo_render(&g, &fr, &t, &vc->set, &counts, &err);
    glFinish();
    *ms = 1e3 * (sh_seconds() - t0);
  }
  if (st != SH_OK) {
    fprintf(stderr, "%s: %s\n", vc->name, err.message);
  } else {
    glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, rgba);
    const char *dir = getenv("ATMO_WRITE"); /* for looking at the images */
    if (dir) {
      float *rgb = malloc((size_t)w * h * 3 * sizeof *rgb);
      for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
          for (int c = 0; c < 3; c++)
            rgb[3 * ((size_t)y * w + x) + c] = rgba[4 * ((size_t)(h - 1 - y) * w + x) + c];
      char path[1024];
      snprintf(path, sizeof path, "%s/atmo_%s.png", dir, vc->name);
      sh_image_write_rgb(path, w, h, rgb, vc->eye[1] > 100 ? 0 : -2, NULL);
      free(rgb);
    }
    int nx = (w + step - 1) / step, ny = (h + step - 1) / step;
    sh_image got = {0}, want = {0};
    sh_image_alloc(&got, nx, ny, NULL);
    sh_image_alloc(&want, nx, ny, NULL);
    sh_camera_frame f;
    sh_camera_frame_init(&s->camera, &f);
    sh_vec3 eye = s->camera.position, sun_dir = sh_neg(to_sun);
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++) {
        /* Offsets that vary from pixel to pixel, so that the pixels
         * compared do not all fall on lattice points. */
        int x = i * step + (i * 7 + 3) % step, y = j * step + (j * 5 + 2) % step;
        if (x >= w) x = w - 1;
        if (y >= h) y = h - 1;
        const float *px = rgba + 4 * ((size_t)(h - 1 - y) * w + x);
        sh_vec3 d = sh_camera_dir(&f, x + 0.5, y + 0.5);
        sh_vec3 L = aq_radiance(a, eye, d, sun_dir, sh_v3s(20), s->background, 24);
        float *o = got.rgb + 3 * ((size_t)j * nx + i), *r = want.rgb + 3 * ((size_t)j * nx + i);
        for (int c = 0; c < 3; c++) {
          o[c] = px[c];
          r[c] = (float)sh_vget(L, c);
        }
      }
    char name[128];
    snprintf(name, sizeof name, "atmo_%s", vc->name);
    err_out = tu_error(&got, &want);
    tu_check(tu_check_close(name, &got, &want, vc->bound), name);
    printf("%s: %d planes, %d spheres, frame %.1f ms at %dx%d\n", vc->name,
           counts.planes, counts.spheres, *ms, w, h);
    sh_image_free(&got);
    sh_image_free(&want);
  }
  free(rgba);
  gs__atmo_gl_free(&g);
  gs__target_free(&t);
  gs__programs_free(&progs);
  gs__params_free(&params);
  sh_scene_free(s);
  sh_error_clear(&err);
  return err_out;
}

int main(int argc, char **argv) {
  gs__context *ctx = tu_context();
  if (!ctx) return 1;
  gs__atmo a = aq_earth();
  int w = 64, h = 48, step = 4;
  if (argc > 2) {
    w = atoi(argv[1]);
    h = atoi(argv[2]);
    step = argc > 3 ? atoi(argv[3]) : 4;
  }
  int planes = argc > 4 ? atoi(argv[4]) : GS__ATMO_PLANES;
  int spheres = argc > 5 ? atoi(argv[5]) : GS__ATMO_SPHERES;
  int lat = argc > 6 ? atoi(argv[6]) : 1;
  double bound = argc > 2 ? 1.0 : 0.003;
  gs__atmo_settings set = {planes, spheres, lat, NULL, NULL};
  const view_case cases[] = {
      {"sunset_towards_sun", {0, 0.001, 0}, {1, 0.2, 0}, 60, 2, 0, set, bound},
      {"dusk_away", {0, 0.001, 0}, {-1, 0.3, 0.2}, 70, -1.5, 0, set, bound},
      {"high_sun", {0, 0.001, 0}, {0.3, 1, 0.5}, 90, 60, 30, set, bound},
      {"space", {30000, 1000, 0}, {0, -6360, 0}, 28, 10, 100, set, bound},
  };
  int n = (int)(sizeof cases / sizeof *cases);
  for (int i = 0; i < n; i++) {
    double ms = 0;
    run(ctx, &a, &cases[i], w, h, step, &ms);
  }
  /* The default lattice, at a size where its step is a finer angle. */
  if (argc <= 2)
    for (int i = 0; i < n; i++) {
      view_case vc = cases[i];
      vc.set.lattice_step = GS__ATMO_LATTICE_MAX;
      vc.bound = 0.015;
      double ms = 0;
      char name[64];
      snprintf(name, sizeof name, "%s_lattice", vc.name);
      vc.name = name;
      run(ctx, &a, &vc, 192, 144, 12, &ms);
    }
  gs__context_release(ctx);
  gs__context_free(ctx);
  return tu_failures ? 1 : 0;
}
