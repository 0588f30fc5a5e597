#include "gs_atmo_render.h"

#include "gs_atmo_shapes.h"

#include "shaders/gs_shared.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "sh_time.h"

extern const gs__glsl gs__glsl_atmo_layer_frag, gs__glsl_atmo_compose_frag;

static const float FULL_SCREEN[8] = {-1, -1, 1, -1, 1, 1, -1, 1};

sh_status gs__atmo_gl_init(gs__atmo_gl *g, const gs__atmo *a,
                           const gs__atmo_source *src, sh_error *err) {
  g->atmo = *a;
  g->tex = g->lat_tex = g->lat_fbo = 0;
  g->lat_w = g->lat_h = 0;
  sh_status st = gs__atmo_table_build(&g->table, src, &a->shell, GS__ATMO_TABLE_R,
                                      GS__ATMO_TABLE_MU, err);
  if (st != SH_OK) return st;
  glCreateTextures(GL_TEXTURE_2D, 1, &g->tex);
  glTextureStorage2D(g->tex, 1, GL_RGBA32F, g->table.n_mu, g->table.n_r);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTextureSubImage2D(g->tex, 0, 0, 0, g->table.n_mu, g->table.n_r, GL_RGBA,
                      GL_FLOAT, g->table.tau);
  glTextureParameteri(g->tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(g->tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(g->tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(g->tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return gs__gl_check("uploading the atmosphere's table", err);
}

void gs__atmo_gl_free(gs__atmo_gl *g) {
  if (g->tex) glDeleteTextures(1, &g->tex);
  if (g->lat_tex) glDeleteTextures(1, &g->lat_tex);
  if (g->lat_fbo) glDeleteFramebuffers(1, &g->lat_fbo);
  g->tex = g->lat_tex = g->lat_fbo = 0;
  gs__atmo_table_free(&g->table);
}

int gs__atmo_lattice_step(const sh_camera *cam) {
  double px = cam->fov_y_deg / cam->height; /* degrees a pixel, about */
  int step = (int)floor(GS__ATMO_LATTICE_DEG / px + 1e-9);
  return step < 1 ? 1 : step > GS__ATMO_LATTICE_MAX ? GS__ATMO_LATTICE_MAX : step;
}

void gs__atmo_plane_depths(double zmax, double first, int n, double *z) {
  z[0] = 0.0;
  double z1 = zmax * first;
  for (int k = 1; k <= n; k++)
    z[k] = n == 1 ? zmax : z1 * pow(zmax / z1, (double)(k - 1) / (n - 1));
  z[n] = zmax;
}

void gs__atmo_sphere_radii(const gs__atmo *a, int n, double *r) {
  double rg = a->shell.r_ground, top = a->shell.r_top - rg, H = a->rayleigh_h;
  double span = -expm1(-top / H); /* 1 - exp(-top / H) */
  for (int k = 0; k <= n; k++)
    r[k] = rg - H * log1p(-span * k / n);
  r[0] = rg;
  r[n] = a->shell.r_top;
}

/* The #define of Mie's phase function (atmo.glsl's ATMO_MIE_*). */
static int mie_phase(const sh_phase *ph) {
  switch (ph->type) {
  case SH_PHASE_ISOTROPIC: return 0;
  case SH_PHASE_HENYEY_GREENSTEIN: return 1;
  case SH_PHASE_CORNETTE_SHANKS: return 2;
  case SH_PHASE_NISHITA_HAZY: return 3;
  case SH_PHASE_NISHITA_MURKY: return 4;
  case SH_PHASE_RAYLEIGH: return 5;
  }
  return 0;
}

/* The eye in the planet's frame, in double precision. */
typedef struct eye_frame {
  sh_vec3 up;   /* unit vertical at the eye */
  double re;    /* distance from the centre */
  double ce;    /* re^2 - R_g^2 */
} eye_frame;

static eye_frame eye_of(const gs__atmo *a, sh_vec3 eye) {
  eye_frame e;
  sh_vec3 q = sh_sub(eye, a->shell.center);
  e.re = sh_length(q);
  e.up = e.re > 0 ? sh_scale(q, 1.0 / e.re) : sh_v3(0, 1, 0);
  e.ce = (e.re - a->shell.r_ground) * (e.re + a->shell.r_ground);
  return e;
}

/* Starts a pass's parameters: the camera's (gs__params_begin), the
 * atmosphere's and the shapes' (gs_atmo_shapes.h), for the sun `l` (NULL:
 * none) with its setup ls and shadow map sm (NULL: none); the caller adds u_depth
 * (screen.vert's). */
static gs__params *atmo_params(const gs__atmo_gl *g, const gs__frame *fr,
                               const eye_frame *e, const sh_light *l,
                               const gs__light_setup *ls, const gs__shadow_map *sm,
                               const char *extra) {
  const gs__atmo *a = &g->atmo;
  char defs[256];
  snprintf(defs, sizeof defs, "#define MIE_PHASE %d\n#define EYE_OUTSIDE %d\n%s",
           mie_phase(&a->mie_phase), e->re > a->shell.r_top, extra);
  gs__params *p = gs__params_begin(fr, ls, defs);
  gs__atmo_shapes_params(p, fr, ls, sm);
  gs__param_v3(p, "u_up", e->up);
  gs__param_f(p, "u_re", e->re);
  gs__param_f(p, "u_ce", e->ce);
  gs__param_v3(p, "u_ray_s", a->rayleigh_s);
  gs__param_f(p, "u_ray_h", a->rayleigh_h);
  gs__param_v3(p, "u_mie_s", a->mie_s);
  gs__param_f(p, "u_mie_h", a->mie_h);
  gs__param_f(p, "u_mie_g", a->mie_phase.g);
  gs__param_v3(p, "u_albedo", a->ground_albedo);
  gs__param_v3(p, "u_background", fr->scene->background);
  /* Without a sun (the background alone) any direction, no light. */
  sh_vec3 to_sun = l ? sh_normalize(sh_neg(l->direction)) : sh_v3(0, 1, 0);
  gs__param_v3(p, "u_lsun", to_sun);
  gs__param_v3(p, "u_esun", l ? l->irradiance : sh_v3s(0.0));
  /* The sun's disk (docs/scene-format.md, "The sun's disk"): the squared
   * chord |d - s|^2 at its edge, 4 sin^2(half angle / 2) = Omega / pi
   * (-1: no disk), and its radiance. */
  double omega = l ? l->disk_solid_angle : 0.0;
  gs__param_f(p, "u_disk_chord2", omega > 0 ? omega / SH_PI : -1.0);
  gs__param_v3(p, "u_disk_radiance",
               omega > 0 ? sh_scale(l->irradiance, 1.0 / omega) : sh_v3s(0.0));
  return p;
}

gs__params *gs__atmo_pass_params(const gs__atmo_gl *g, const gs__frame *fr,
                                 const sh_light *l, const gs__light_setup *ls,
                                 const gs__shadow_map *sm, const char *extra) {
  eye_frame e = eye_of(&g->atmo, fr->view->frame.origin);
  return atmo_params(g, fr, &e, l, ls, sm, extra);
}

/* The lattice's texture and framebuffer, at the size the image needs. */
static sh_status lattice_fit(gs__atmo_gl *g, int w, int h, sh_error *err) {
  if (g->lat_tex && g->lat_w == w && g->lat_h == h) return SH_OK;
  if (g->lat_fbo) glDeleteFramebuffers(1, &g->lat_fbo);
  if (g->lat_tex) glDeleteTextures(1, &g->lat_tex);
  glCreateTextures(GL_TEXTURE_2D, 1, &g->lat_tex);
  glTextureStorage2D(g->lat_tex, 1, GL_RGBA32F, w, h);
  glCreateFramebuffers(1, &g->lat_fbo);
  glNamedFramebufferTexture(g->lat_fbo, GL_COLOR_ATTACHMENT0, g->lat_tex, 0);
  glNamedFramebufferDrawBuffer(g->lat_fbo, GL_COLOR_ATTACHMENT0);
  g->lat_w = w;
  g->lat_h = h;
  if (glCheckNamedFramebufferStatus(g->lat_fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    return sh_error_set(err, SH_ERR_DEVICE,
                        "the GL driver cannot render into a 32-bit float "
                        "framebuffer of %dx%d", w, h);
  return gs__gl_check("creating the sky's lattice", err);
}

/* Sets the layers' bounds (layer[0..n]: depths or radii) for the bound
 * program prog (atmo.glsl's u_layers, u_nlayers). */
static void set_layers(GLuint prog, const double *layer, int n) {
  gs__uniform_i(prog, "u_nlayers", n);
  for (int k = 0; k <= n; k++) {
    char name[32];
    snprintf(name, sizeof name, "u_layers[%d]", k);
    gs__uniform_f(prog, name, layer[k]);
  }
}

/* One sun's passes (l NULL: the background alone): with a lattice, the
 * layers drawn on it, then the image composed (what the rays end on, the
 * lattice interpolated, the pixels it cannot serve integrated over the
 * layers); without, the image composed of what the rays end on, then the
 * layers drawn at full resolution. The first sun's compose pass replaces
 * the image. */
static sh_status draw_sun(gs__atmo_gl *g, const gs__frame *fr, const gs__target *t,
                          const eye_frame *e, const sh_light *l,
                          const gs__light_setup *ls, const gs__shadow_map *sm,
                          int first, const double *layer, int n, int step,
                          gs__atmo_counts *c, double *clock, sh_error *err) {
  GLuint layers = 0, prog;
  sh_status st;
  gs__params *p;
  if (!l) step = 1;
  if (step > 1) {
    int lw = (t->width + step - 1) / step, lh = (t->height + step - 1) / step;
    if ((st = lattice_fit(g, lw, lh, err)) != SH_OK) return st;
    p = atmo_params(g, fr, e, l, ls, sm, "");
    gs__param_f(p, "u_depth", 0.0);
    st = gs__program_use(fr->progs, &gs__glsl_screen_vert, &gs__glsl_atmo_layer_frag, p,
                         &layers, err);
    if (st != SH_OK) return st;
    glBindFramebuffer(GL_FRAMEBUFFER, g->lat_fbo);
    glViewport(0, 0, lw, lh);
    glDisable(GL_BLEND);
    gs__uniform_f(layers, "u_lat_scale", step);
    set_layers(layers, layer, n);
    gs__target_draw_polygon(t, FULL_SCREEN, 4);
    c->lattice_seconds += gs__gl_lap(clock);
    glBindTextureUnit(GS_UNIT_ATMO_LATTICE, g->lat_tex);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
  glViewport(0, 0, t->width, t->height);
  for (int fix = 0; fix <= (step > 1); fix++) {
    char defs[80];
    snprintf(defs, sizeof defs, "#define FIRST %d\n#define LATTICE %d\n#define FIXUP %d\n",
             first, step > 1, fix);
    p = atmo_params(g, fr, e, l, ls, sm, defs);
    gs__param_f(p, "u_depth", fix ? 1.0 : 0.0);
    st = gs__program_use(fr->progs, &gs__glsl_screen_vert, &gs__glsl_atmo_compose_frag, p,
                         &prog, err);
    if (st != SH_OK) return st;
    gs__uniform_f(prog, "u_lat_scale", 1.0);
    gs__uniform_f(prog, "u_lat_step", step);
    if (fix) set_layers(prog, layer, n);
    if (first && !fix) glDisable(GL_BLEND);
    else glEnable(GL_BLEND);
    /* The compose pass marks the pixels the lattice cannot serve at depth
     * 1; the fixup pass, drawn at depth 1, runs on them alone. */
    if (step > 1) {
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(fix ? GL_EQUAL : GL_ALWAYS);
      glDepthMask(fix ? GL_FALSE : GL_TRUE);
    } else if (fr->scene->nshapes > 0) {
      /* Where no surface was drawn (gs_atmo_shapes.h). */
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_EQUAL);
    }
    gs__target_draw_polygon(t, FULL_SCREEN, 4);
    if (fix) c->fixup_seconds += gs__gl_lap(clock);
    else c->compose_seconds += gs__gl_lap(clock);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
  }
  if (step > 1 || !l) return SH_OK;
  p = atmo_params(g, fr, e, l, ls, sm, "");
  gs__param_f(p, "u_depth", 0.0);
  st = gs__program_use(fr->progs, &gs__glsl_screen_vert, &gs__glsl_atmo_layer_frag, p,
                       &layers, err);
  if (st != SH_OK) return st;
  /* Added to the image's colour; its alpha (the layers' ray class) left. */
  glEnable(GL_BLEND);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
  gs__uniform_f(layers, "u_lat_scale", 1.0);
  set_layers(layers, layer, n);
  gs__target_draw_polygon(t, FULL_SCREEN, 4);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  c->layer_seconds += gs__gl_lap(clock);
  return SH_OK;
}

sh_status gs__atmo_render(gs__atmo_gl *g, const gs__frame *fr, const gs__target *t,
                          const gs__atmo_settings *set, gs__atmo_counts *counts,
                          sh_error *err) {
  const gs__atmo *a = &g->atmo;
  const sh_scene *scene = fr->scene;
  eye_frame e = eye_of(a, fr->view->frame.origin);
  int outside = e.re > a->shell.r_top;
  int n = outside ? set->spheres : set->planes;
  if (n < 1 || n > GS_ATMO_MAX_LAYERS)
    return sh_error_set(err, SH_ERR_ARG, "the atmosphere takes 1 to %d %s, not %d",
                        GS_ATMO_MAX_LAYERS, outside ? "sampling spheres" : "sampling planes", n);
  gs__atmo_counts c = {0, 0, outside, 0, 0, 0, 0};
  double clock = sh_seconds();
  double *layer = malloc((size_t)(n + 1) * sizeof *layer);
  if (!layer) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  if (outside)
    gs__atmo_sphere_radii(a, n, layer);
  else {
    /* The farthest air in view lies no farther than the top seen along
     * the horizon; the first plane at a fiftieth of the smaller scale
     * height (the air's density changes little nearer). */
    double rg = a->shell.r_ground, rt = a->shell.r_top;
    double zmax = sqrt(fmax(e.ce, 0.0)) + sqrt((rt - rg) * (rt + rg));
    double first = fmin(0.02 * fmin(a->rayleigh_h, a->mie_h) / zmax, 0.5 / n);
    gs__atmo_plane_depths(zmax, first, n, layer);
  }
  gs__target_draw_buffers(t, 1);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glBindTextureUnit(GS_UNIT_ATMO, g->tex);
  glBlendFunc(GL_ONE, GL_ONE);
  glBlendEquation(GL_FUNC_ADD);
  sh_status st = SH_OK;
  int first = 1;
  for (int i = 0; i < scene->nlights && st == SH_OK; i++) {
    const sh_light *l = &scene->lights[i];
    if (l->type != SH_LIGHT_DIRECTIONAL) continue;
    const gs__light_setup *ls = set->lights ? &set->lights[i] : NULL;
    const gs__shadow_map *sm = ls && ls->shadow != GS__SHADOW_NONE ? &set->shadows[i] : NULL;
    if (sm) gs__shadow_bind(sm);
    st = draw_sun(g, fr, t, &e, l, ls, sm, first, layer, n, set->lattice_step, &c, &clock,
                  err);
    first = 0;
    if (outside) c.spheres += n;
    else c.planes += n;
  }
  /* No sun: the background through the air alone. */
  if (st == SH_OK && first)
    st = draw_sun(g, fr, t, &e, NULL, NULL, NULL, 1, layer, n, 1, &c, &clock, err);
  glDisable(GL_BLEND);
  free(layer);
  if (counts) *counts = c;
  if (st != SH_OK) return st;
  return gs__gl_check("drawing the atmosphere", err);
}
