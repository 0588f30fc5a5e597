/* The GLSL physics functions of common.glsl against their C twins in core,
 * on a grid of inputs: phase() against sh_phase_eval (isotropic,
 * Henyey-Greenstein at several g, Nishita hazy and murky, Rayleigh),
 * spot_profile() against sh_spot_profile (hard and smooth edges, the
 * exponent classes 0, 1 and other, narrow cones down to 0.005 degrees;
 * the shader takes the angle as its versine 1 - cos), box_clip() against sh_box_clip
 * (rays from inside and outside, axis-parallel ones, bounded and unbounded
 * intervals), and medium.glsl's optical_depth() and sigma_s_at() against
 * sh_medium_optical_depth and sh_medium_sigma_s_at, for a homogeneous
 * medium and height fog (segments from inside and outside the box, level
 * and nearly level ones among them, where the closed form takes its
 * series). Each runs in both kinds of program (baked and live).
 *
 * A tiny fragment shader (TWIN below) calls the function with inputs it
 * fetches from float textures, one input per pixel, and writes the result
 * into the RGBA32F image, which is read back. The parameters the shader
 * sees (g, the cone's cosines, the box) are floats, so the C twin is given
 * the same float values, and the difference is the function's own float
 * arithmetic: it must stay within TOL = 1e-5 relative to the C value,
 * where a value near 0 is measured against a floor, since it carries the
 * absolute rounding of the larger terms it is made of: for the phase
 * functions relative to max(|C|, 1e-4 * the largest C value on the grid);
 * for the spot profile to max(|C|, 1e-2 * the largest), as the compiler
 * may evaluate (vo - v) / w as vo / w - v / w (v the versine), whose
 * cancellation at the cone's edge costs about 1e-6 absolute (measured:
 * 7e-5 relative at a profile of 1e-4); for the ray's interval
 * relative to max(|t|, the box's size); for optical depth relative to
 * max(|C|, 1e-2 * the largest C value), as the clipped interval's rounding
 * (relative to the box's size, above) carries into a short chord's
 * optical depth (measured: 1.5e-5 relative to a chord of 1e-3 of the
 * largest); for sigma_s at a point relative to max(|C|, 1e-4 * the
 * largest). The worst difference of each function is printed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gs_context.h"
#include "gs_params.h"
#include "gs_target.h"
#include "sh_light.h"
#include "sh_medium.h"
#include "test_util.h"

#define W 64
#define H 16
#define N (W * H)
#define TOL 1e-5

/* TWIN 0: phase(in0.x); 1: spot_profile(in0.x), in0.x a versine; 2: box_clip(in0.xyz,
 * in1.xyz, in0.w, in1.w) in .xy; 3: optical_depth(in0.xyz, in1.xyz) in .xyz;
 * 4: sigma_s_at(in0.xyz) in .xyz. */
static const gs__glsl TWIN = {
    "twin.frag",
    "layout(binding = GS_UNIT_FREE) uniform sampler2D u_in0;\n"
    "layout(binding = GS_UNIT_FREE + 1) uniform sampler2D u_in1;\n"
    "layout(location = 0) out vec4 o_color;\n"
    "void main() {\n"
    "  vec4 a = texelFetch(u_in0, ivec2(gl_FragCoord.xy), 0);\n"
    "  vec4 b = texelFetch(u_in1, ivec2(gl_FragCoord.xy), 0);\n"
    "#if TWIN == 0\n"
    "  o_color = vec4(phase(a.x), 0.0, 0.0, 1.0);\n"
    "#elif TWIN == 1\n"
    "  o_color = vec4(spot_profile(a.x), 0.0, 0.0, 1.0);\n"
    "#elif TWIN == 2\n"
    "  o_color = vec4(box_clip(a.xyz, b.xyz, a.w, b.w), 0.0, 1.0);\n"
    "#elif TWIN == 3\n"
    "  o_color = vec4(optical_depth(a.xyz, b.xyz), 1.0);\n"
    "#else\n"
    "  o_color = vec4(sigma_s_at(a.xyz), 1.0);\n"
    "#endif\n"
    "}\n"};

typedef struct twins {
  sh_scene *scene;
  gs__view view;
  gs__params params;
  gs__programs progs;
  gs__target target;
  GLuint in[2];
} twins;

/* Runs TWIN `which` on the inputs for light l (the scene's light 0), baked
 * or live, into out (N RGBA). */
static int run(twins *t, int which, int bake, const float *in0, const float *in1,
               float *out) {
  gs__light_setup ls = {.light = &t->scene->lights[0]};
  gs__frame fr = {.scene = t->scene, .view = &t->view, .progs = &t->progs,
                  .params = &t->params, .bake = bake};
  char extra[32];
  snprintf(extra, sizeof extra, "#define TWIN %d\n", which);
  gs__params *p = gs__params_begin(&fr, &ls, extra);
  gs__param_f(p, "u_depth", 0.0);
  GLuint prog;
  sh_error err = SH_ERROR_INIT;
  if (gs__program_use(&t->progs, &gs__glsl_screen_vert, &TWIN, p, &prog, &err) != SH_OK) {
    printf("FAIL: the twin program: %s\n", err.message);
    return 0;
  }
  glTextureSubImage2D(t->in[0], 0, 0, 0, W, H, GL_RGBA, GL_FLOAT, in0);
  glTextureSubImage2D(t->in[1], 0, 0, 0, W, H, GL_RGBA, GL_FLOAT, in1);
  glBindTextureUnit(GS_UNIT_FREE, t->in[0]);
  glBindTextureUnit(GS_UNIT_FREE + 1, t->in[1]);
  glBindFramebuffer(GL_FRAMEBUFFER, t->target.fbo);
  gs__target_draw_buffers(&t->target, 1);
  glViewport(0, 0, W, H);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  static const float FULL[8] = {-1, -1, 1, -1, 1, 1, -1, 1};
  gs__target_draw_polygon(&t->target, FULL, 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, out);
  sh_error_clear(&err);
  return gs__gl_check("reading the twin's image", &err) == SH_OK;
}

/* Compares out[4 i + channel] with want[i] (both runs), printing the worst
 * difference. */
static void compare_channel(const char *what, const float *got_baked, const float *got_live,
                            const double *want, const float *in0, double floor,
                            int channel) {
  double top = 0, worst = 0;
  int at = 0, live = 0;
  for (int i = 0; i < N; i++) top = fmax(top, fabs(want[i]));
  for (int k = 0; k < 2; k++) {
    const float *got = k ? got_live : got_baked;
    for (int i = 0; i < N; i++) {
      double e = fabs(got[4 * i + channel] - want[i]) / fmax(fabs(want[i]), floor * top);
      if (!(e <= worst)) worst = e, at = i, live = k;
    }
  }
  char msg[200];
  snprintf(msg, sizeof msg, "%s: worst relative difference %.2g (at input %.9g, %s) <= %g",
           what, worst, in0[4 * at], live ? "live" : "baked", TOL);
  tu_check(worst <= TOL, msg);
}

static void compare(const char *what, const float *got_baked, const float *got_live,
                    const double *want, const float *in0, double floor) {
  compare_channel(what, got_baked, got_live, want, in0, floor, 0);
}

static float in0[4 * N], in1[4 * N], outb[4 * N], outl[4 * N];
static double want[N];

static void test_phase(twins *t) {
  for (int i = 0; i < N; i++) in0[4 * i] = (float)(-1.0 + 2.0 * i / (N - 1));
  sh_medium *m = &t->scene->medium;
  static const struct { sh_phase_type type; double g; const char *name; } cases[] = {
      {SH_PHASE_ISOTROPIC, 0, "isotropic"},
      {SH_PHASE_HENYEY_GREENSTEIN, -0.6, "Henyey-Greenstein g = -0.6"},
      {SH_PHASE_HENYEY_GREENSTEIN, 0.3, "Henyey-Greenstein g = 0.3"},
      {SH_PHASE_HENYEY_GREENSTEIN, 0.8, "Henyey-Greenstein g = 0.8"},
      {SH_PHASE_NISHITA_HAZY, 0, "Nishita hazy"},
      {SH_PHASE_NISHITA_MURKY, 0, "Nishita murky"},
      {SH_PHASE_RAYLEIGH, 0, "Rayleigh"}};
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    m->phase.type = cases[c].type;
    m->phase.g = (float)cases[c].g;
    for (int i = 0; i < N; i++) want[i] = sh_phase_eval(&m->phase, in0[4 * i]);
    char what[80];
    snprintf(what, sizeof what, "phase, %s", cases[c].name);
    if (run(t, 0, 1, in0, in1, outb) && run(t, 0, 0, in0, in1, outl))
      compare(what, outb, outl, want, in0, 1e-4);
    else
      tu_check(0, what);
  }
}

static void test_spot(twins *t) {
  sh_light *l = &t->scene->lights[0];
  /* The last three are narrow cones (a laser), whose edges lie at versines
   * of 1.4e-5 down to 3.8e-9. */
  static const struct { double outer, inner, exponent; } cases[] = {
      {30, 30, 0},      {30, 20, 0},     {40, 10, 1},        {25, 25, 1},
      {50, 35, 2.5},    {60, 5, 8},      {0.3, 0.3, 0},      {0.3, 0.1, 1},
      {0.005, 0.002, 2.5}};
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    l->outer_deg = cases[c].outer;
    l->inner_deg = cases[c].inner;
    l->exponent = (float)cases[c].exponent;
    /* The shader is given the angles' versines 1 - cos as floats
     * (gs_params.c); the twin the cosines those floats stand for. */
    double so = sin(0.5 * l->outer_deg * SH_PI / 180.0);
    double si = sin(0.5 * l->inner_deg * SH_PI / 180.0);
    float vo = (float)(2.0 * so * so), vi = (float)(2.0 * si * si);
    l->cos_outer = 1.0 - vo;
    l->cos_inner = 1.0 - vi;
    /* The input is the versine: half the grid over [0, 2] (cos over [-1,
     * 1]), half over the edge. */
    for (int i = 0; i < N; i++) {
      double a = 0.5 * vi, b = 2.0 * vo - 0.5 * vi;
      in0[4 * i] = i < N / 2 ? (float)(2.0 * i / (N / 2 - 1))
                             : (float)(a + (b - a) * (i - N / 2) / (N / 2 - 1));
      want[i] = sh_spot_profile(l, 1.0 - (double)in0[4 * i]);
    }
    char what[80];
    snprintf(what, sizeof what, "spot profile, outer %g, inner %g, exponent %g",
             cases[c].outer, cases[c].inner, cases[c].exponent);
    if (run(t, 1, 1, in0, in1, outb) && run(t, 1, 0, in0, in1, outl))
      compare(what, outb, outl, want, in0, 1e-2);
    else
      tu_check(0, what);
  }
}

/* A deterministic uniform number in [-1, 1) (a linear congruential
 * sequence), so that every run sees the same rays. */
static double uniform(unsigned *s) {
  *s = *s * 1664525u + 1013904223u;
  return (*s >> 8) / 8388608.0 - 1.0;
}

static void test_box(twins *t) {
  sh_medium *m = &t->scene->medium;
  m->bmin = sh_v3(-1, -0.5, -2);
  m->bmax = sh_v3(1.5, 2, 0.75);
  unsigned s = 12345;
  static const float HI[3] = {3.0e38f, 1.0f, 4.0f};
  for (int i = 0; i < N; i++) {
    float *o = &in0[4 * i], *d = &in1[4 * i];
    for (int a = 0; a < 3; a++) {
      o[a] = (float)(2.5 * uniform(&s));
      d[a] = (float)uniform(&s);
    }
    if (i % 7 == 0) d[i % 3] = 0; /* parallel to a pair of faces */
    if (i % 11 == 0) d[0] = d[1] = 0;
    o[3] = i % 5 == 0 ? 0.5f : 0.0f;
    d[3] = HI[i % 3];
  }
  int ok = run(t, 2, 1, in0, in1, outb) && run(t, 2, 0, in0, in1, outl);
  tu_check(ok, "box clipping runs");
  if (!ok) return;
  double size = 4.0, worst = 0;
  int mismatched = 0, hits = 0;
  for (int k = 0; k < 2; k++) {
    const float *got = k ? outl : outb;
    for (int i = 0; i < N; i++) {
      const float *o = &in0[4 * i], *d = &in1[4 * i];
      double t0 = 0, t1 = 0;
      int hit = sh_box_clip(m->bmin, m->bmax, sh_v3(o[0], o[1], o[2]), sh_v3(d[0], d[1], d[2]),
                            o[3], d[3], &t0, &t1);
      int ghit = got[4 * i] < got[4 * i + 1];
      hits += hit;
      if (hit != ghit) {
        if (mismatched++ < 5)
          printf("  ray %d: C says %s, GLSL [%g, %g]\n", i, hit ? "hit" : "miss",
                 got[4 * i], got[4 * i + 1]);
        continue;
      }
      if (!hit) continue;
      worst = fmax(worst, fabs(got[4 * i] - t0) / fmax(fabs(t0), size));
      worst = fmax(worst, fabs(got[4 * i + 1] - t1) / fmax(fabs(t1), size));
    }
  }
  printf("box clipping: %d of %d rays (both runs) cross the box\n", hits, 2 * N);
  tu_check(hits > 2 * N / 5 && hits < 2 * N - 2 * N / 5, "the rays both hit and miss the box");
  tu_check(mismatched == 0, "box clipping: GLSL and C agree on which rays cross the box");
  char msg[120];
  snprintf(msg, sizeof msg, "box clipping: worst relative difference of t0, t1 %.2g <= %g",
           worst, TOL);
  tu_check(worst <= TOL, msg);
}

/* optical_depth() and sigma_s_at() of a homogeneous medium and of height
 * fog, against sh_medium_optical_depth and sh_medium_sigma_s_at. */
static void test_medium(twins *t) {
  sh_medium *m = &t->scene->medium;
  m->bmin = sh_v3(-1, -0.5, -2);
  m->bmax = sh_v3(1.5, 2, 0.75);
  /* The parameters as the floats the shader sees. */
  m->sigma_s = sh_v3(0.3f, 0.45f, 0.6f);
  m->sigma_t = sh_v3(0.35f, 0.5f, 0.7f);
  m->base_height = 0.25f;
  m->scale_height = 1.0 / (double)(float)(1.0 / 0.7);
  unsigned s = 777;
  for (int i = 0; i < N; i++) {
    float *a = &in0[4 * i], *b = &in1[4 * i];
    for (int c = 0; c < 3; c++) {
      a[c] = (float)(2.5 * uniform(&s));
      b[c] = (float)(2.5 * uniform(&s));
    }
    if (i % 5 == 0) b[1] = a[1];                      /* level */
    if (i % 5 == 1) b[1] = a[1] + (float)(1e-3 * uniform(&s)); /* nearly */
  }
  static const struct { sh_medium_type type; const char *name; } kinds[] = {
      {SH_MEDIUM_HOMOGENEOUS, "homogeneous"}, {SH_MEDIUM_HEIGHT_FOG, "height fog"}};
  static double want_s[N];
  for (size_t k = 0; k < 2; k++) {
    m->type = kinds[k].type;
    for (int c = 0; c < 3; c++) {
      int inside = 0;
      for (int i = 0; i < N; i++) {
        const float *a = &in0[4 * i], *b = &in1[4 * i];
        sh_vec3 pa = sh_v3(a[0], a[1], a[2]), pb = sh_v3(b[0], b[1], b[2]);
        want[i] = sh_vget(sh_medium_optical_depth(m, pa, pb), c);
        inside += want[i] > 0;
        want_s[i] = sh_vget(sh_medium_sigma_s_at(m, pa), c);
      }
      char what[80];
      snprintf(what, sizeof what, "optical depth, %s, channel %d (%d of %d cross the box)",
               kinds[k].name, c, inside, N);
      if (run(t, 3, 1, in0, in1, outb) && run(t, 3, 0, in0, in1, outl))
        compare_channel(what, outb, outl, want, in0, 1e-2, c);
      else
        tu_check(0, what);
      snprintf(what, sizeof what, "sigma_s at a point, %s, channel %d", kinds[k].name, c);
      if (run(t, 4, 1, in0, in1, outb) && run(t, 4, 0, in0, in1, outl))
        compare_channel(what, outb, outl, want_s, in0, 1e-4, c);
      else
        tu_check(0, what);
    }
  }
  m->type = SH_MEDIUM_HOMOGENEOUS;
}

int main(void) {
  twins t = {0};
  t.scene = tu_scene(
      "{\"format\": \"shafts-scene\", \"version\": 1,"
      " \"camera\": {\"position\": [2.5, 2, 3], \"look_at\": [0, 0.6, 0],"
      "  \"fov_y_deg\": 45, \"width\": 64, \"height\": 16},"
      " \"medium\": {\"sigma_s\": [0.2, 0.2, 0.2], \"sigma_a\": [0.01, 0.01, 0.01],"
      "  \"bounds\": {\"min\": [-3, 0, -3], \"max\": [3, 4, 3]}},"
      " \"lights\": [{\"type\": \"spot\", \"position\": [0, 3, 0],"
      "  \"look_at\": [0, 0, 0], \"intensity\": [40, 40, 40],"
      "  \"outer_angle_deg\": 30, \"inner_angle_deg\": 20}],"
      " \"shapes\": []}");
  if (!t.scene) return 1;
  gs__context *ctx = tu_context();
  if (!ctx) return 1;
  sh_error err = SH_ERROR_INIT;
  gs__view_init(&t.view, t.scene, NULL);
  t.view.anchor = sh_v3s(0.0); /* the twins take world-space inputs */
  if (gs__target_create(&t.target, W, H, &err) != SH_OK) {
    printf("FAIL: the target: %s\n", err.message);
    return 1;
  }
  glCreateTextures(GL_TEXTURE_2D, 2, t.in);
  for (int i = 0; i < 2; i++) glTextureStorage2D(t.in[i], 1, GL_RGBA32F, W, H);
  test_phase(&t);
  test_spot(&t);
  test_box(&t);
  test_medium(&t);
  glDeleteTextures(2, t.in);
  gs__target_free(&t.target);
  gs__programs_free(&t.progs);
  gs__params_free(&t.params);
  gs__context_release(ctx);
  gs__context_free(ctx);
  sh_scene_free(t.scene);
  sh_error_clear(&err);
  return tu_failures ? 1 : 0;
}
