#include "gs_surface.h"

#include "shaders/gs_shared.h"

static const float FULL_SCREEN[8] = {-1, -1, 1, -1, 1, 1, -1, 1};

static sh_status background(const gs__frame *fr, const gs__target *t,
                            sh_error *err) {
  gs__params *p = gs__params_begin(fr, NULL, "");
  gs__param_v3(p, "u_background", fr->scene->background);
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
  sh_mat4 vp = gs__view_proj(fr->view);
  int passes = scene->nlights > 0 ? scene->nlights : 1;
  for (int pass = 0; pass < passes && geom->nverts > 0; pass++) {
    const gs__light_setup *ls = scene->nlights > 0 ? &lights[pass] : NULL;
    if (pass == 0) {
      gs__target_draw_buffers(t, 2);
      glDisable(GL_BLEND);
      glDepthFunc(GL_GREATER);
      glDepthMask(GL_TRUE);
    } else {
      gs__target_draw_buffers(t, 1);
      glEnable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE);
      glDepthFunc(GL_EQUAL);
      glDepthMask(GL_FALSE);
    }
    if (ls) {
      if (ls->shadow != GS__SHADOW_NONE) gs__shadow_bind(&shadows[pass]);
      if (maps[pass]) glBindTextureUnit(GS_UNIT_MAP, maps[pass]);
    }
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
          sh_status st = gs__program_use(fr->progs, &gs__glsl_surface_vert,
                                         &gs__glsl_surface_frag, p, &prog, err);
          if (st != SH_OK) return st;
        }
        const sh_material *m = &scene->materials[s->material];
        if (sphere) {
          /* Both sides of the covering mesh would give the same sphere
           * point (added twice in the blended passes): draw the side that
           * faces the camera, the inside if the camera is in the sphere. */
          const sh_shape *sh = &scene->shapes[i];
          sh_vec3 eye = sh_xform_point(&sh->inv, fr->view->frame.origin);
          int inside = sh_length(sh_sub(eye, sh->center)) < sh->radius;
          glEnable(GL_CULL_FACE);
          glCullFace(inside != s->mirrored ? GL_FRONT : GL_BACK);
          sh_mat4 obj_inv = gs__sphere_from_anchored(fr->view, sh);
          gs__uniform_mat4(prog, "u_obj_inv", &obj_inv);
          gs__uniform_v3(prog, "u_center", sh_v3s(0.0)); /* centred space */
          gs__uniform_f(prog, "u_radius", sh->radius);
          gs__uniform_v3(prog, "u_inflate_center", gs__anchored(fr->view, s->center));
          gs__uniform_f(prog, "u_inflate", s->inflate);
        }
        gs__uniform_v3(prog, "u_kd", m->diffuse);
        gs__uniform_v3(prog, "u_ks", m->specular);
        gs__uniform_f(prog, "u_shininess", m->shininess);
        gs__uniform_v3(prog, "u_base",
                       pass == 0 ? sh_add(m->emission, sh_mul(scene->ambient, m->diffuse))
                                 : sh_v3s(0));
        glDrawArrays(GL_TRIANGLES, s->first, s->count);
        glDisable(GL_CULL_FACE);
      }
    }
    sh_status st = gs__gl_check("shading the surfaces", err);
    if (st != SH_OK) return st;
  }
  return background(fr, t, err);
}
