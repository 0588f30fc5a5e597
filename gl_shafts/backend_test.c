/* The context backends (gs_context.h): each backend present gives a GL 4.5
 * core context and reports itself in gs_stats; EGL and OSMesa give the same
 * images (bit for bit when both run the same llvmpipe, as here; within
 * 0.5% relative RMS when EGL reaches a GPU); bad backend requests are
 * refused with a message. With --egl-hidden (CTest runs it so with
 * __EGL_VENDOR_LIBRARY_FILENAMES=/dev/null, which leaves libglvnd with no
 * EGL driver): auto falls back to OSMesa, and egl fails with an error that
 * names the key "backend" and says what EGL lacked. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_parse.h"
#include "sh_test.h"
#include "test_util.h"


/* Renders with one backend; SH_OK or the failure, the error in *err. */
static sh_status render(const sh_scene *scene, gs_backend b, sh_image *out,
                        gs_stats *stats, sh_error *err) {
  gs_options o = gs_options_defaults(scene);
  o.backend = b;
  return gs_render(scene, &o, out, stats, err);
}

/* A canonical scene (scenes/FILE) at 160x120. */
static sh_scene *small(const char *file) {
  sh_scene *s = sh_test_load("scenes/%s", file);
  if (!s) return NULL;
  s->camera.width = 160;
  s->camera.height = 120;
  return s;
}

static void egl_hidden(void) {
  sh_scene *scene = small("teapot_spot.json");
  if (!scene) {
    tu_failures++;
    return;
  }
  sh_image img = {0};
  gs_stats st;
  sh_error err = SH_ERROR_INIT;
  sh_status s = render(scene, GS_BACKEND_AUTO, &img, &st, &err);
  tu_check(s == SH_OK, "auto renders with EGL hidden");
  if (s == SH_OK) {
    printf("auto chose %s: %s\n", st.backend, st.renderer);
    tu_check(!strcmp(st.backend, "osmesa"), "auto falls back to osmesa");
  }
  sh_image_free(&img);
  s = render(scene, GS_BACKEND_EGL, &img, &st, &err);
  char msg[2048];
  sh_error_format(&err, msg, sizeof msg);
  printf("egl asked for: %s\n", msg);
  tu_check(s == SH_ERR_DEVICE, "egl asked for fails with SH_ERR_DEVICE");
  tu_check(!strcmp(err.path, "backend"), "the error names the key 'backend'");
  tu_check(strstr(err.message, "egl backend") && strstr(err.message, "OpenGL 4.5 core"),
        "the message names the backend and what it could not give");
  tu_check(strstr(err.message, "device platform") != NULL,
        "the message says what EGL lacked");
  sh_scene_free(scene);
  sh_error_clear(&err);
}

int main(int argc, char **argv) {
  if (argc > 1 && !strcmp(argv[1], "--egl-hidden")) {
    egl_hidden();
    return tu_failures ? 1 : 0;
  }
  sh_scene *scene = small("teapot_spot.json");
  if (!scene) return 1;
  sh_error err = SH_ERROR_INIT;
  gs_options o = gs_options_defaults(scene);
  o.backend = (gs_backend)7;
  tu_check(gs_options_check(&o, &err) == SH_ERR_ARG, "backend 7 is refused");
  sh_image img = {0};
  setenv("SHAFTS_GL_BACKEND", "vulkan", 1);
  tu_check(render(scene, GS_BACKEND_AUTO, &img, NULL, &err) == SH_ERR_ARG &&
            strstr(err.message, "SHAFTS_GL_BACKEND"),
        "SHAFTS_GL_BACKEND=vulkan is refused, naming the variable");
  unsetenv("SHAFTS_GL_BACKEND");
  sh_scene_free(scene);

  const char *files[] = {"teapot_spot.json", "stage_5spots.json", "mountains_sun.json",
                         "stained_glass.json"};
  for (int f = 0; f < 4; f++) {
    scene = small(files[f]);
    if (!scene) return 1;
    sh_image egl = {0}, osmesa = {0};
    gs_stats se, so;
    sh_error ee = SH_ERROR_INIT, eo = SH_ERROR_INIT;
    sh_status a = render(scene, GS_BACKEND_EGL, &egl, &se, &ee);
    sh_status b = render(scene, GS_BACKEND_OSMESA, &osmesa, &so, &eo);
    if (a != SH_OK) printf("skip egl: %s\n", ee.message);
    if (b != SH_OK) printf("skip osmesa: %s\n", eo.message);
    if (a == SH_OK) tu_check(!strcmp(se.backend, "egl") && se.renderer[0] && se.vendor[0],
                          "egl reports itself, its renderer and vendor");
    if (b == SH_OK) tu_check(!strcmp(so.backend, "osmesa") && so.renderer[0] && so.vendor[0],
                          "osmesa reports itself, its renderer and vendor");
    if (a == SH_OK && b == SH_OK) {
      double maxdiff = 0;
      for (size_t i = 0; i < (size_t)egl.width * egl.height * 3; i++)
        maxdiff = fmax(maxdiff, fabs((double)egl.rgb[i] - osmesa.rgb[i]));
      int same_gl = !strcmp(se.renderer, so.renderer);
      printf("%s: egl (%s) vs osmesa (%s): largest difference %g\n", files[f],
             se.renderer, so.renderer, maxdiff);
      char name[64];
      snprintf(name, sizeof name, "backends_%.*s", (int)strlen(files[f]) - 5, files[f]);
      if (same_gl)
        tu_check(maxdiff == 0 || tu_check_close(name, &egl, &osmesa, 0),
              "the same GL on both backends gives the same image, bit for bit");
      else
        tu_check(tu_check_close(name, &egl, &osmesa, 0.005),
              "EGL's GPU and OSMesa agree within 0.5%");
    }
    sh_image_free(&egl);
    sh_image_free(&osmesa);
    sh_scene_free(scene);
    sh_error_clear(&ee);
    sh_error_clear(&eo);
  }
  sh_error_clear(&err);
  return tu_failures ? 1 : 0;
}
