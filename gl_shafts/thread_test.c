/* The threading rule of gs_render.h: every gs_renderer_* call makes the
 * renderer's context current on entry and releases it on exit. Checked
 * here: a renderer created on one thread draws on another (as the Blender
 * add-on's worker thread draws), with the same image as on the creating
 * thread; two renderers draw at once on two threads (each thread has its
 * own current GL function table); two threads drawing with one renderer
 * take turns; after every call no GL context is
 * current on the calling thread (eglGetCurrentContext() == EGL_NO_CONTEXT
 * and OSMesaGetCurrentContext() == NULL); and, on EGL, a context the
 * caller had current before a call is current again after it, as
 * Blender's would be. Runs on the backend SHAFTS_GL_BACKEND names. */
#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EGL_NO_X11
#define EGL_EGL_PROTOTYPES 0
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "test_util.h"


/* The current context of a GL library the process has loaded (RTLD_NOLOAD:
 * a library not loaded has none). */
static void *egl_symbol(const char *name) {
  void *h = dlopen("libEGL.so.1", RTLD_NOW | RTLD_NOLOAD);
  return h ? dlsym(h, name) : NULL;
}

static int none_current(void) {
  PFNEGLBINDAPIPROC bind = (PFNEGLBINDAPIPROC)egl_symbol("eglBindAPI");
  PFNEGLQUERYAPIPROC query = (PFNEGLQUERYAPIPROC)egl_symbol("eglQueryAPI");
  PFNEGLGETCURRENTCONTEXTPROC current =
      (PFNEGLGETCURRENTCONTEXTPROC)egl_symbol("eglGetCurrentContext");
  if (bind && query && current) {
    EGLenum api = query();
    bind(EGL_OPENGL_API);
    EGLContext c = current();
    bind(api);
    if (c != EGL_NO_CONTEXT) return 0;
  }
  void *osmesa = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_NOLOAD);
  void *(*osmesa_current)(void) =
      osmesa ? (void *(*)(void))dlsym(osmesa, "OSMesaGetCurrentContext") : NULL;
  return !osmesa_current || osmesa_current() == NULL;
}

typedef struct job {
  gs_renderer *r;
  float *rgb;
  gs_stats stats;
  sh_status st;
  int released; /* no context current on the thread after the draw */
} job;

static job make_job(gs_renderer *r, float *rgb) {
  return (job){.r = r, .rgb = rgb, .st = SH_ERR_DEVICE};
}

static void *draw_job(void *arg) {
  job *j = arg;
  sh_error err = SH_ERROR_INIT;
  j->st = gs_renderer_draw(j->r, j->rgb, &j->stats, &err);
  if (j->st != SH_OK) fprintf(stderr, "draw: %s\n", err.message);
  j->released = none_current();
  sh_error_clear(&err);
  return NULL;
}

/* Runs two jobs at once, each on a thread of its own, and waits for both. */
static void draw_at_once(job *a, job *b) {
  pthread_t ta, tb;
  pthread_create(&ta, NULL, draw_job, a);
  pthread_create(&tb, NULL, draw_job, b);
  pthread_join(ta, NULL);
  pthread_join(tb, NULL);
}

static int same(const float *a, const float *b, size_t n) {
  return memcmp(a, b, n * sizeof *a) == 0;
}

/* On EGL: a surfaceless context of the test's own, current while the
 * renderer draws on the same thread, must be current again afterwards. */
static void check_restores(gs_renderer *r, float *rgb) {
  PFNEGLGETPROCADDRESSPROC gpa =
      (PFNEGLGETPROCADDRESSPROC)egl_symbol("eglGetProcAddress");
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
      (PFNEGLGETPLATFORMDISPLAYEXTPROC)gpa("eglGetPlatformDisplayEXT");
  PFNEGLINITIALIZEPROC init = (PFNEGLINITIALIZEPROC)gpa("eglInitialize");
  PFNEGLBINDAPIPROC bind = (PFNEGLBINDAPIPROC)gpa("eglBindAPI");
  PFNEGLCREATECONTEXTPROC create = (PFNEGLCREATECONTEXTPROC)gpa("eglCreateContext");
  PFNEGLDESTROYCONTEXTPROC destroy = (PFNEGLDESTROYCONTEXTPROC)gpa("eglDestroyContext");
  PFNEGLMAKECURRENTPROC make = (PFNEGLMAKECURRENTPROC)gpa("eglMakeCurrent");
  PFNEGLGETCURRENTCONTEXTPROC current =
      (PFNEGLGETCURRENTCONTEXTPROC)gpa("eglGetCurrentContext");
  EGLDisplay dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
  EGLint major, minor;
  if (dpy == EGL_NO_DISPLAY || !init(dpy, &major, &minor)) {
    printf("skip: no surfaceless EGL display for the caller's own context\n");
    return;
  }
  bind(EGL_OPENGL_API);
  EGLContext mine = create(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, NULL);
  tu_check(mine != EGL_NO_CONTEXT && make(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, mine),
        "the caller's own EGL context is current");
  sh_error err = SH_ERROR_INIT;
  sh_status st = gs_renderer_draw(r, rgb, NULL, &err);
  tu_check(st == SH_OK, "draw while the caller has its own EGL context current");
  tu_check(current() == mine, "the caller's EGL context is current again after the draw");
  make(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  destroy(dpy, mine);
  sh_error_clear(&err);
}

int main(void) {
  sh_scene *scene = tu_scene(
      "{\"format\": \"shafts-scene\", \"version\": 1,"
      " \"camera\": {\"position\": [0, 1, 5], \"look_at\": [0, 0.5, 0],"
      "   \"fov_y_deg\": 45, \"width\": 48, \"height\": 36},"
      " \"medium\": {\"sigma_s\": [0.1, 0.1, 0.1],"
      "   \"bounds\": {\"min\": [-3, 0, -3], \"max\": [3, 3, 3]}},"
      " \"lights\": [{\"type\": \"spot\", \"position\": [0, 2.5, 0],"
      "   \"look_at\": [0, 0, 0], \"intensity\": [5, 5, 5], \"outer_angle_deg\": 30}],"
      " \"materials\": {\"grey\": {\"diffuse\": [0.5, 0.5, 0.5]}},"
      " \"shapes\": [{\"type\": \"quad\", \"material\": \"grey\", \"corner\": [-3, 0, 3],"
      "   \"u\": [6, 0, 0], \"v\": [0, 0, -6]},"
      "  {\"type\": \"sphere\", \"material\": \"grey\", \"center\": [0, 1, 0],"
      "   \"radius\": 0.3}]}");
  if (!scene) return 1;
  size_t n = (size_t)scene->camera.width * scene->camera.height * 3;
  float *here = calloc(n, sizeof *here), *there = calloc(n, sizeof *there);
  float *a = calloc(n, sizeof *a), *b = calloc(n, sizeof *b);
  gs_renderer *r = NULL, *r2 = NULL;
  sh_error err = SH_ERROR_INIT;
  sh_status st = gs_renderer_create(scene, NULL, &r, &err);
  if (st != SH_OK) {
    fprintf(stderr, "create: %s\n", err.message);
    return 1;
  }
  tu_check(none_current(), "no context current on the creating thread after create");
  gs_stats stats;
  st = gs_renderer_draw(r, here, &stats, &err);
  tu_check(st == SH_OK, "draw on the creating thread");
  tu_check(none_current(), "no context current on the creating thread after draw");
  printf("backend %s: %s (%s)\n", stats.backend, stats.renderer, stats.vendor);

  job j = make_job(r, there);
  pthread_t t;
  pthread_create(&t, NULL, draw_job, &j);
  pthread_join(t, NULL);
  tu_check(j.st == SH_OK, "draw on another thread");
  tu_check(j.released, "no context current on the drawing thread after draw");
  tu_check(same(here, there, n), "the other thread's image equals the creating thread's");
  tu_check(none_current(), "still no context current on the creating thread");

  /* Two renderers drawing at once, each on its own thread. */
  st = gs_renderer_create(scene, NULL, &r2, &err);
  tu_check(st == SH_OK, "a second renderer");
  if (st == SH_OK) {
    job j1 = make_job(r, a), j2 = make_job(r2, b);
    draw_at_once(&j1, &j2);
    tu_check(j1.st == SH_OK && j2.st == SH_OK, "two renderers draw at once on two threads");
    tu_check(j1.released && j2.released, "both threads have no context current after");
    tu_check(same(here, a, n) && same(here, b, n), "both images equal the first");
  }
  /* Two threads drawing at once with one renderer: the calls take turns. */
  job j3 = make_job(r, a), j4 = make_job(r, b);
  draw_at_once(&j3, &j4);
  tu_check(j3.st == SH_OK && j4.st == SH_OK && same(here, a, n) && same(here, b, n),
           "two threads drawing with one renderer take turns, same images");
  if (!strcmp(stats.backend, "egl")) check_restores(r, a);

  gs_renderer_free(r2);
  gs_renderer_free(r);
  tu_check(none_current(), "no context current after free");
  free(here);
  free(there);
  free(a);
  free(b);
  sh_scene_free(scene);
  sh_error_clear(&err);
  return tu_failures ? 1 : 0;
}
