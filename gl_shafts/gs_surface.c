#include "gs_surface.h"

#include "shaders/gs_shared.h"

#include <math.h>
#include <stdio.h>

static const float FULL_SCREEN[8] = {-1, -1, 1, -1, 1, 1, -1, 1};

static int has_disk(const sh_light *l, int live) {
  return l->type == SH_LIGHT_DIRECTIONAL && (live || l->disk_solid_angle > 0);
}

void gs__sun_disks(gs__params *p, const sh_scene *scene, int live) {
  char name[2][32];
  int k = 0;
  for (int i = 0; i < scene->nlights; i++) {
    const sh_light *l = &scene->lights[i];
    if (!has_disk(l, live)) continue;
    double omega = l->disk_solid_angle;
    snprintf(name[0], sizeof name[0], "u_sun_dir%d", k);
    snprintf(name[1], sizeof name[1], "u_sun_radiance%d", k++);
    /* Omega = 4 pi sin^2(half / 2); -1: no direction is inside. */
    gs__param_4f(p, name[0], -l->direction.x, -l->direction.y,
                 -l->direction.z, omega > 0 ? omega / SH_PI : -1.0);
    gs__param_v3(p, name[1], omega > 0 ? sh_scale(l->irradiance, 1.0 / omega)
                                       : sh_v3s(0.0));
  }
  gs__params_text(p, "#define SUN_DISKS(d) (vec3(0.0)");
  for (int i = 0; i < k; i++) {
    char term[80];
    snprintf(term, sizeof term, " + sun_disk(d, u_sun_dir%d, u_sun_radiance%d)",
             i, i);
    gs__params_text(p, term);
  }
  gs__params_text(p, ")\n");
}

static sh_status background(const gs__frame *fr, const gs__target *t,
                            sh_error *err) {
  gs__params *p = gs__params_begin(fr, NULL, "");
  gs__param_v3(p, "u_background", fr->scene->background);
  gs__sun_disks(p, fr->scene, !fr->bake);
  gs__param_f(p, "u_depth", 0.0);
  GLuint prog;
  sh_status st = gs__program_use(fr->progs, &gs__glsl_screen_vert,
                                 &gs__glsl_background_frag, p, &prog, err);
  if (st != SH_OK) return st;
  /* Only where the depth buffer still holds its cleared 0. */
  gs__target_draw_buffers(t, 2);
  glDisable(GL_BLEND);
  glDepthFunc(GL_EQUAL);
  glDepthMask(GL_FALSE);
  gs__target_draw_polygon(t, FULL_SCREEN, 4);
  return gs__gl_check("drawing the background", err);
}

/* Draws every shape with the surface programs, shaded by light ls (NULL:
 * none) with its shadow map sm, with emission and ambient if base. */
static sh_status draw_shapes(const gs__frame *fr, const gs__geometry *geom,
                             const gs__light_setup *ls, const gs__shadow_map *sm,
                             int base, sh_error *err) {
  const sh_scene *scene = fr->scene;
  sh_mat4 vp = gs__view_proj(fr->view);
  glBindVertexArray(geom->vao);
  /* Meshes first, then exact spheres (another program). */
  for (int sphere = 0; sphere < 2; sphere++) {
    GLuint prog = 0;
    for (int i = 0; i < geom->nshapes; i++) {
      const gs__shape_draw *s = &geom->shape[i];
      if (s->count == 0 || s->exact_sphere != sphere) continue;
      if (!prog) {
        gs__params *p = gs__params_begin(fr, ls, sphere ? "#define SPHERE 1\n" : "");
        gs__param_mat4(p, "u_viewproj", &vp);
        gs__param_f(p, "u_near", fr->view->znear);
        gs__param_f(p, "u_lit", ls != NULL);
        gs__param_f(p, "u_shadow_texel",
                    ls && ls->shadow != GS__SHADOW_NONE && sm && sm->res > 0
                        ? ls->shadow_span / sm->res
                        : 0.0);
        sh_status st = gs__program_use(fr->progs, &gs__glsl_surface_vert,
                                       &gs__glsl_surface_frag, p, &prog, err);
        if (st != SH_OK) return st;
      }
      const sh_material *m = &scene->materials[s->material];
      if (sphere) {
        /* Both sides of the covering mesh would give the same sphere
         * point (added twice in the blended passes): draw the side that
         * faces the camera, the inside if the camera may be inside the
         * covering mesh (it lies up to r (inflate - 1) outside the sphere:
         * an eye 1 m above a planet's ground is inside it, and saw no
         * ground). The far side covers every pixel the sphere does, once. */
        const sh_shape *sh = &scene->shapes[i];
        sh_vec3 eye = sh_xform_point(&sh->inv, fr->view->frame.origin);
        double eye_r = sh_length(sh_sub(eye, sh->center));
        int inside = eye_r < sh->radius * s->inflate;
        glEnable(GL_CULL_FACE);
        glCullFace(inside != s->mirrored ? GL_FRONT : GL_BACK);
        sh_mat4 obj_inv = gs__sphere_from_anchored(fr->view, sh);
        /* |oc|^2 - r^2 at the rays' origin at depth zref (gs_view.h) in
         * double, of relative precision where the eye is near the surface
         * (in float, r^2 - |f|^2 of a planet's radius kept 4e6 of its
         * 1.3e7 m^2 for an eye 1 m above the ground); there surface.frag
         * solves with it, elsewhere about the ray's point nearest the
         * centre. */
        sh_vec3 oc0 = sh_xform_point(&obj_inv, fr->view->org);
        double r0 = sh_length(oc0);
        gs__uniform_f(prog, "u_sphere_c0", (r0 - sh->radius) * (r0 + sh->radius));
        gs__uniform_f(prog, "u_sphere_near", eye_r < 4.0 * sh->radius ? 1.0 : 0.0);
        gs__uniform_mat4(prog, "u_obj_inv", &obj_inv);
        gs__uniform_v3(prog, "u_center", sh_v3s(0.0)); /* centred space */
        gs__uniform_f(prog, "u_radius", sh->radius);
        gs__uniform_v3(prog, "u_inflate_center", gs__anchored(fr->view, s->center));
        gs__uniform_f(prog, "u_inflate", s->inflate);
      }
      /* An open shape drawn into this light's shadow map offsets its own
       * lookups (surface.frag). */
      gs__uniform_f(prog, "u_open",
                    ls && ls->shadow != GS__SHADOW_NONE && ls->casts[i] && !s->closed
                        ? 1.0
                        : 0.0);
      gs__uniform_v3(prog, "u_kd", m->diffuse);
      gs__uniform_v3(prog, "u_ks", m->specular);
      gs__uniform_f(prog, "u_shininess", m->shininess);
      gs__uniform_v3(prog, "u_base",
                     base ? sh_add(m->emission, sh_mul(scene->ambient, m->diffuse))
                          : sh_v3s(0));
      glDrawArrays(GL_TRIANGLES, s->first, s->count);
      glDisable(GL_CULL_FACE);
    }
  }
  return gs__gl_check("shading the surfaces", err);
}

/* The pixels of an ndc rectangle, a pixel wider on every side, as a scissor
 * box; 0 if the rectangle is empty. */
static int scissor_box(const double r[4], const gs__target *t, GLint box[4]) {
  if (!(r[2] >= r[0] && r[3] >= r[1])) return 0;
  int x0 = (int)floor((r[0] + 1.0) * 0.5 * t->width) - 1;
  int y0 = (int)floor((r[1] + 1.0) * 0.5 * t->height) - 1;
  int x1 = (int)ceil((r[2] + 1.0) * 0.5 * t->width) + 1;
  int y1 = (int)ceil((r[3] + 1.0) * 0.5 * t->height) + 1;
  x0 = x0 < 0 ? 0 : x0;
  y0 = y0 < 0 ? 0 : y0;
  x1 = x1 > t->width ? t->width : x1;
  y1 = y1 > t->height ? t->height : y1;
  if (x1 <= x0 || y1 <= y0) return 0;
  box[0] = x0;
  box[1] = y0;
  box[2] = x1 - x0;
  box[3] = y1 - y0;
  return 1;
}

sh_status gs__surface_render(const gs__frame *fr, const gs__geometry *geom,
                             const gs__light_setup *lights,
                             const gs__shadow_map *shadows, const GLuint *maps,
                             const gs__target *t, sh_error *err) {
  const sh_scene *scene = fr->scene;
  glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
  glViewport(0, 0, t->width, t->height);
  gs__target_draw_buffers(t, 2);
  const float zero[4] = {0, 0, 0, 0}, far[4] = {3.0e38f, 0, 0, 0};
  glDepthMask(GL_TRUE); /* clears obey the depth mask */
  glClearNamedFramebufferfv(t->fbo, GL_COLOR, 0, zero);
  glClearNamedFramebufferfv(t->fbo, GL_COLOR, 1, far);
  glClearNamedFramebufferfv(t->fbo, GL_DEPTH, 0, zero);
  glEnable(GL_DEPTH_TEST);
  sh_status st = SH_OK;
  /* The first pass writes emission and ambient, the view depth and the
   * light that reaches most of the screen; each other light adds its own
   * within the screen rectangle it can reach. */
  int first = -1;
  double most = -1;
  for (int i = 0; i < scene->nlights; i++) {
    const double *r = lights[i].surface_rect;
    double area = r[2] >= r[0] && r[3] >= r[1] ? (r[2] - r[0]) * (r[3] - r[1]) : 0;
    if (area > most) most = area, first = i;
  }
  for (int pass = -1; pass < scene->nlights && geom->nverts > 0 && st == SH_OK; pass++) {
    int light = pass < 0 ? first : pass;
    if (pass >= 0 && pass == first) continue;
    const gs__light_setup *ls = light >= 0 ? &lights[light] : NULL;
    if (pass < 0) {
      gs__target_draw_buffers(t, 2);
      glDisable(GL_BLEND);
      glDepthFunc(GL_GREATER);
      glDepthMask(GL_TRUE);
    } else {
      GLint box[4];
      if (!scissor_box(ls->surface_rect, t, box)) continue;
      glEnable(GL_SCISSOR_TEST);
      glScissor(box[0], box[1], box[2], box[3]);
      gs__target_draw_buffers(t, 1);
      glEnable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE);
      glDepthFunc(GL_EQUAL);
      glDepthMask(GL_FALSE);
    }
    if (ls) {
      if (ls->shadow != GS__SHADOW_NONE) gs__shadow_bind(&shadows[light]);
      if (maps[light]) glBindTextureUnit(GS_UNIT_MAP, maps[light]);
    }
    st = draw_shapes(fr, geom, ls, ls ? &shadows[light] : NULL, pass < 0, err);
    glDisable(GL_SCISSOR_TEST);
  }
  if (st != SH_OK) return st;
  return background(fr, t, err);
}
