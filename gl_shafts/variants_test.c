/* Every program variant the renderer can ask for compiles and links, on the
 * default backend, with the disk cache off (so every program is built).
 *
 * A variant is a pass's shader pair (background, surface, shadow,
 * interval, plane) and its #define lines (gs_params.c, gs_sweep.c). The
 * structural switches are taken in every combination: the light's kind
 * with the shadow maps it can have (point: none or cube; spot and
 * directional: none or 2D), a light map or none (spot, directional), the
 * spot's cone clipping, live or baked programs, no medium, a homogeneous
 * one or height fog (the MEDIUM switch). With
 * each combination, the switches that values decide (the phase function's
 * 6 types, grey or coloured sigma_t, the spot's edge and exponent class,
 * the light inside or outside the medium, XI_EXACT, JITTER and TAU_SUB)
 * go through ROWS rows so that each of their values meets each
 * combination; their full product with the structural ones (tens of
 * thousands of programs) would take hours on llvmpipe.
 *
 * The passes' own parameters (u_near, u_tau_rate, ...) are declared here
 * as the passes declare them: a pass that gains a parameter must add it
 * below, or this test fails naming the undeclared identifier. A failure
 * prints the pass, the variant's #define lines and the compile log. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gs_context.h"
#include "gs_params.h"
#include "test_util.h"

#define ROWS 6

static int failures, tried;

/* Prints the #define lines of a parameter block. */
static void print_defines(const char *text) {
  for (const char *l = text; l && *l;) {
    const char *eol = strchr(l, '\n');
    int len = eol ? (int)(eol - l) : (int)strlen(l);
    if (!strncmp(l, "#define", 7)) printf("    %.*s\n", len, l);
    l = eol ? eol + 1 : l + len;
  }
}

static void build(const gs__frame *fr, const char *pass, const gs__glsl *vs,
                  const gs__glsl *fs, gs__params *p) {
  GLuint prog = 0;
  sh_error err = SH_ERROR_INIT;
  tried++;
  if (gs__program_use(fr->progs, vs, fs, p, &prog, &err) == SH_OK) return;
  failures++;
  printf("FAIL: the %s pass (%s + %s) with\n", pass, vs->name, fs->name);
  print_defines(p->text);
  printf("  %s\n", err.message);
  sh_error_clear(&err);
}

/* Every pass a frame draws with light ls (and the unlit ones). */
static void build_passes(const gs__frame *fr, const gs__light_setup *ls, int row) {
  sh_mat4 id = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
  gs__params *p = gs__params_begin(fr, NULL, "");
  gs__param_v3(p, "u_background", fr->scene->background);
  gs__param_f(p, "u_depth", 0.0);
  build(fr, "background", &gs__glsl_screen_vert, &gs__glsl_background_frag, p);
  for (int lit = 0; lit < 2; lit++)
    for (int sphere = 0; sphere < 2; sphere++) {
      p = gs__params_begin(fr, lit ? ls : NULL, sphere ? "#define SPHERE 1\n" : "");
      gs__param_mat4(p, "u_viewproj", &id);
      gs__param_f(p, "u_near", fr->view->znear);
      gs__param_f(p, "u_lit", lit);
      gs__param_f(p, "u_shadow_texel", 0.01);
      build(fr, "surface", &gs__glsl_surface_vert, &gs__glsl_surface_frag, p);
    }
  if (ls->shadow != GS__SHADOW_NONE)
    for (int sphere = 0; sphere < 2; sphere++)
      build(fr, "shadow", &gs__glsl_shadow_vert, &gs__glsl_shadow_frag,
            gs__params_begin(fr, ls, sphere ? "#define SPHERE 1\n" : ""));
  p = gs__params_begin(fr, ls, "");
  gs__param_f(p, "u_depth", 0.0);
  build(fr, "interval", &gs__glsl_screen_vert, &gs__glsl_interval_frag, p);
  /* Live programs always sample by optical depth (gs_sweep.c). */
  int xi_exact = row & 1, jitter = (row >> 1) & 1, tau_sub = !fr->bake || row % 3 != 0;
  char extra[160];
  snprintf(extra, sizeof extra, "#define XI_EXACT %d\n#define JITTER %d\n#define TAU_SUB %d\n",
           xi_exact, jitter, tau_sub);
  p = gs__params_begin(fr, ls, extra);
  gs__param_f(p, "u_inv_sub_angle", 100.0);
  gs__param_f(p, "u_inv_sub_texels", 0.5);
  gs__param_2f(p, "u_map_size", 64, 64);
  gs__param_f(p, "u_shadow_res", 1024);
  gs__param_f(p, "u_tau_rate", 0.4);
  gs__param_4f(p, "u_xi_xy", 0.5, 0.5, 0.5, 0.5);
  gs__param_2f(p, "u_xi_z", 0.1, 0.0);
  build(fr, "plane", &gs__glsl_plane_vert,
        ls->light->type == SH_LIGHT_DIRECTIONAL ? &gs__glsl_plane_dir_frag
                                                : &gs__glsl_plane_local_frag,
        p);
}

/* Sets the value switches of row `row` on the scene's light and medium
 * (medium 0: none, 1: homogeneous, 2: height fog). */
static void set_row(sh_scene *s, int row, int medium) {
  sh_medium *m = &s->medium;
  sh_light *l = &s->lights[0];
  m->present = medium > 0;
  m->type = medium == 2 ? SH_MEDIUM_HEIGHT_FOG : SH_MEDIUM_HOMOGENEOUS;
  m->base_height = 0.5;
  m->scale_height = 1.5;
  m->phase.type = (sh_phase_type)(row % 6);
  m->phase.g = m->phase.type == SH_PHASE_HENYEY_GREENSTEIN ||
                       m->phase.type == SH_PHASE_CORNETTE_SHANKS
                   ? 0.3
                   : 0.0;
  m->sigma_t = row & 1 ? sh_v3(0.2, 0.2, 0.2) : sh_v3(0.2, 0.3, 0.4);
  m->sigma_s = sh_scale(m->sigma_t, 0.9);
  l->position = (row >> 1) & 1 ? sh_v3(0, 2, 0) : sh_v3(0, 6, 0); /* in, out */
  l->exponent = row % 3 == 0 ? 0 : row % 3 == 1 ? 1 : 2.5;
  l->cos_outer = cos(30 * SH_PI / 180);
  l->cos_inner = row % 4 < 2 ? l->cos_outer : cos(20 * SH_PI / 180);
}

int main(void) {
  setenv("SHAFTS_PROGRAM_CACHE", "off", 1);
  sh_scene *scene = tu_scene(
      "{\"format\": \"shafts-scene\", \"version\": 1,"
      " \"camera\": {\"position\": [2.5, 2, 3], \"look_at\": [0, 0.6, 0],"
      "  \"fov_y_deg\": 45, \"width\": 16, \"height\": 12},"
      " \"medium\": {\"sigma_s\": [0.2, 0.2, 0.2], \"sigma_a\": [0.01, 0.01, 0.01],"
      "  \"bounds\": {\"min\": [-3, 0, -3], \"max\": [3, 4, 3]}},"
      " \"lights\": [{\"type\": \"spot\", \"position\": [0, 3, 0],"
      "  \"look_at\": [0, 0, 0], \"intensity\": [40, 40, 40],"
      "  \"outer_angle_deg\": 30, \"inner_angle_deg\": 20}],"
      " \"materials\": {\"grey\": {\"diffuse\": [0.6, 0.6, 0.6]}},"
      " \"shapes\": [{\"type\": \"sphere\", \"center\": [0, 0.6, 0], \"radius\": 0.5,"
      "   \"material\": \"grey\"}]}");
  if (!scene) return 1;
  gs__context *ctx = tu_context();
  if (!ctx) return 1;
  gs__view view;
  gs__view_init(&view, scene, NULL);
  gs__params params = {0};
  gs__programs progs = {0};
  sh_light *l = &scene->lights[0];
  long built = 0;
  static const sh_light_type kinds[3] = {SH_LIGHT_POINT, SH_LIGHT_SPOT, SH_LIGHT_DIRECTIONAL};
  for (int k = 0; k < 3; k++)
    for (int shadow = 0; shadow < 2; shadow++)
      for (int map = 0; map < 2; map++)
        for (int clip = 0; clip < 2; clip++)
          for (int live = 0; live < 2; live++)
            for (int medium = 0; medium < 3; medium++) {
              sh_light_type kind = kinds[k];
              if (kind == SH_LIGHT_POINT && map) continue;
              if (kind != SH_LIGHT_SPOT && clip) continue;
              l->type = kind;
              l->has_map = map;
              l->direction = sh_v3(0, -1, 0);
              l->irradiance = sh_v3(1, 1, 1);
              gs__light_setup ls = {.light = l, .cone_clip = clip};
              ls.shadow = !shadow ? GS__SHADOW_NONE
                          : kind == SH_LIGHT_POINT ? GS__SHADOW_CUBE
                                                   : GS__SHADOW_2D;
              for (int r = 0; r < 4; r++) ls.lookup.m[r][r] = 1;
              ls.shadow_near = 0.01;
              gs__frame fr = {.scene = scene, .view = &view, .progs = &progs,
                              .params = &params, .bake = !live};
              for (int row = 0; row < ROWS; row++) {
                set_row(scene, row, medium);
                build_passes(&fr, &ls, row);
              }
              /* Programs that differ only in baked values repeat; the
               * cache builds each text once. */
              built += progs.built;
              gs__programs_free(&progs);
              progs.built = 0;
            }
  printf("%d programs asked for, %ld built (distinct sources), %d failed\n", tried, built,
         failures);
  tu_check(failures == 0, "every variant compiles and links");
  tu_check(built > 100, "the variants were built, not found in a cache");
  gs__params_free(&params);
  gs__context_release(ctx);
  gs__context_free(ctx);
  sh_scene_free(scene);
  return tu_failures ? 1 : 0;
}
