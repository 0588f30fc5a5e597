#include "gs_atmo_render.h"

#include "shaders/gs_shared.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

extern const gs__glsl gs__glsl_atmo_base_frag, gs__glsl_atmo_sky_frag,
    gs__glsl_atmo_space_frag;

static const float FULL_SCREEN[8] = {-1, -1, 1, -1, 1, 1, -1, 1};

sh_status gs__atmo_gl_init(gs__atmo_gl *g, const gs__atmo *a,
                           const gs__atmo_source *src, sh_error *err) {
  g->atmo = *a;
  g->tex = 0;
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
  g->tex = 0;
  gs__atmo_table_free(&g->table);
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

/* Starts a pass's parameters: the camera's (gs__params_begin) and the
 * atmosphere's, for the sun `l`. */
static gs__params *atmo_params(const gs__atmo_gl *g, const gs__frame *fr,
                               const eye_frame *e, const sh_light *l,
                               const char *extra) {
  const gs__atmo *a = &g->atmo;
  char defs[256];
  snprintf(defs, sizeof defs, "#define MIE_PHASE %d\n#define EYE_OUTSIDE %d\n%s",
           mie_phase(&a->mie_phase), e->re > a->shell.r_top, extra);
  gs__params *p = gs__params_begin(fr, NULL, defs);
  double rg = a->shell.r_ground, rt = a->shell.r_top;
  gs__param_v3(p, "u_up", e->up);
  gs__param_f(p, "u_re", e->re);
  gs__param_f(p, "u_ce", e->ce);
  gs__param_f(p, "u_rg", rg);
  gs__param_f(p, "u_rt", rt);
  gs__param_f(p, "u_hh", sqrt((rt - rg) * (rt + rg)));
  gs__param_v3(p, "u_ray_s", a->rayleigh_s);
  gs__param_f(p, "u_ray_h", a->rayleigh_h);
  gs__param_v3(p, "u_mie_s", a->mie_s);
  gs__param_f(p, "u_mie_h", a->mie_h);
  gs__param_f(p, "u_mie_g", a->mie_phase.g);
  gs__param_v3(p, "u_albedo", a->ground_albedo);
  gs__param_v3(p, "u_background", fr->scene->background);
  gs__param_2f(p, "u_table_size", g->table.n_mu, g->table.n_r);
  sh_vec3 to_sun = sh_normalize(sh_neg(l->direction));
  gs__param_v3(p, "u_lsun", to_sun);
  gs__param_v3(p, "u_esun", l->irradiance);
  gs__param_f(p, "u_depth", 0.0);
  return p;
}

sh_status gs__atmo_render(const gs__atmo_gl *g, const gs__frame *fr,
                          const gs__target *t, int planes, int spheres,
                          gs__atmo_counts *counts, sh_error *err) {
  const gs__atmo *a = &g->atmo;
  const sh_scene *scene = fr->scene;
  eye_frame e = eye_of(a, fr->view->frame.origin);
  int outside = e.re > a->shell.r_top;
  gs__atmo_counts c = {0, 0, outside};
  double *depth = malloc((size_t)((planes > spheres ? planes : spheres) + 1) * sizeof *depth);
  if (!depth) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  if (outside)
    gs__atmo_sphere_radii(a, spheres, depth);
  else {
    /* The farthest air in view lies no farther than the top seen along
     * the horizon; the first plane at a fiftieth of the smaller scale
     * height (the air's density changes little nearer). */
    double rg = a->shell.r_ground, rt = a->shell.r_top;
    double zmax = sqrt(fmax(e.ce, 0.0)) + sqrt((rt - rg) * (rt + rg));
    double first = fmin(0.02 * fmin(a->rayleigh_h, a->mie_h) / zmax, 0.5 / planes);
    gs__atmo_plane_depths(zmax, first, planes, depth);
  }

  glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
  gs__target_draw_buffers(t, 1);
  glViewport(0, 0, t->width, t->height);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glBindTextureUnit(GS_UNIT_ATMO, g->tex);
  glBlendFunc(GL_ONE, GL_ONE);
  glBlendEquation(GL_FUNC_ADD);
  sh_status st = SH_OK;
  int first_sun = 1;
  for (int i = 0; i < scene->nlights && st == SH_OK; i++) {
    const sh_light *l = &scene->lights[i];
    if (l->type != SH_LIGHT_DIRECTIONAL) continue;
    /* The ground and the background; the first pass replaces the image. */
    GLuint prog;
    gs__params *p = atmo_params(g, fr, &e, l, first_sun ? "#define FIRST 1\n"
                                                        : "#define FIRST 0\n");
    st = gs__program_use(fr->progs, &gs__glsl_screen_vert, &gs__glsl_atmo_base_frag,
                         p, &prog, err);
    if (st != SH_OK) break;
    if (first_sun) glDisable(GL_BLEND);
    else glEnable(GL_BLEND);
    gs__target_draw_polygon(t, FULL_SCREEN, 4);
    first_sun = 0;
    glEnable(GL_BLEND);
    /* The planes or spheres: one program, the slab or shell a uniform. */
    p = atmo_params(g, fr, &e, l, "");
    st = gs__program_use(fr->progs, &gs__glsl_screen_vert,
                         outside ? &gs__glsl_atmo_space_frag : &gs__glsl_atmo_sky_frag,
                         p, &prog, err);
    if (st != SH_OK) break;
    int n = outside ? spheres : planes;
    for (int k = 0; k < n; k++) {
      gs__uniform_2f(prog, outside ? "u_shell" : "u_slab", depth[k], depth[k + 1]);
      gs__target_draw_polygon(t, FULL_SCREEN, 4);
    }
    if (outside) c.spheres += n;
    else c.planes += n;
  }
  if (st == SH_OK && first_sun) {
    /* No sun: the background through the air alone. */
    static const sh_light dark = {.type = SH_LIGHT_DIRECTIONAL, .direction = {0, -1, 0}};
    GLuint prog;
    gs__params *p = atmo_params(g, fr, &e, &dark, "#define FIRST 1\n");
    st = gs__program_use(fr->progs, &gs__glsl_screen_vert, &gs__glsl_atmo_base_frag,
                         p, &prog, err);
    glDisable(GL_BLEND);
    if (st == SH_OK) gs__target_draw_polygon(t, FULL_SCREEN, 4);
  }
  glDisable(GL_BLEND);
  free(depth);
  if (counts) *counts = c;
  if (st != SH_OK) return st;
  return gs__gl_check("drawing the atmosphere", err);
}
