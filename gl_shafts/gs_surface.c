#include "gs_surface.h"

#include "gs_params.h"

static const float FULL_SCREEN[8] = {-1, -1, 1, -1, 1, 1, -1, 1};

static sh_status background(const sh_scene *scene, const gs__view *view,
                            const gs__target *t, gs__programs *progs,
                            sh_error *err) {
  char defs[512];
  gs__defines(defs, sizeof defs, scene, NULL, "");
  GLuint prog;
  sh_status st = gs__program_get(progs, &gs__glsl_screen_vert,
                                 &gs__glsl_background_frag, defs, &prog, err);
  if (st != SH_OK) return st;
  glUseProgram(prog);
  gs__set_view_uniforms(prog, view, scene);
  gs__uniform_v3(prog, "u_background", scene->background);
  gs__uniform_f(prog, "u_depth", 0.0);
  /* Only where the depth buffer still holds its cleared 0. */
  gs__target_draw_buffers(t, 2);
  glDisable(GL_BLEND);
  glDepthFunc(GL_EQUAL);
  glDepthMask(GL_FALSE);
  gs__target_draw_polygon(t, FULL_SCREEN, 4);
  return gs__gl_check("drawing the background", err);
}

sh_status gs__surface_render(const sh_scene *scene, const gs__view *view,
                             const gs__geometry *geom,
                             const gs__light_setup *lights,
                             const gs__shadow_map *shadows, const GLuint *maps,
                             const gs__target *t, gs__programs *progs,
                             sh_error *err) {
  glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
  glViewport(0, 0, t->width, t->height);
  gs__target_draw_buffers(t, 2);
  const float zero[4] = {0, 0, 0, 0}, far[4] = {3.0e38f, 0, 0, 0};
  glDepthMask(GL_TRUE); /* clears obey the depth mask */
  glClearNamedFramebufferfv(t->fbo, GL_COLOR, 0, zero);
  glClearNamedFramebufferfv(t->fbo, GL_COLOR, 1, far);
  glClearNamedFramebufferfv(t->fbo, GL_DEPTH, 0, zero);
  glEnable(GL_DEPTH_TEST);
  sh_mat4 vp = gs__view_proj(view);
  int passes = scene->nlights > 0 ? scene->nlights : 1;
  for (int pass = 0; pass < passes && geom->nverts > 0; pass++) {
    const gs__light_setup *ls = scene->nlights > 0 ? &lights[pass] : NULL;
    /* Two programs: meshes, and exact spheres. */
    GLuint progs2[2];
    for (int k = 0; k < 2; k++) {
      char defs[512];
      gs__defines(defs, sizeof defs, scene, ls, k ? "#define SPHERE 1\n" : "");
      sh_status st = gs__program_get(progs, &gs__glsl_surface_vert,
                                     &gs__glsl_surface_frag, defs, &progs2[k], err);
      if (st != SH_OK) return st;
      GLuint prog = progs2[k];
      gs__set_view_uniforms(prog, view, scene);
      gs__uniform_mat4(prog, "u_viewproj", &vp);
      gs__uniform_f(prog, "u_near", view->znear);
      gs__uniform_i(prog, "u_lit", ls != NULL);
      if (ls) gs__set_light_uniforms(prog, ls);
    }
    if (ls) {
      if (ls->shadow != GS__SHADOW_NONE) gs__shadow_bind(&shadows[pass]);
      if (maps[pass]) glBindTextureUnit(0, maps[pass]);
    }
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
    glBindVertexArray(geom->vao);
    for (int i = 0; i < geom->nshapes; i++) {
      const gs__shape_draw *s = &geom->shape[i];
      if (s->count == 0) continue;
      const sh_material *m = &scene->materials[s->material];
      GLuint prog = progs2[s->exact_sphere];
      glUseProgram(prog);
      if (s->exact_sphere) {
        const sh_shape *sh = &scene->shapes[i];
        gs__uniform_mat4(prog, "u_obj_inv", &sh->inv);
        gs__uniform_v3(prog, "u_center", sh->center);
        gs__uniform_f(prog, "u_radius", sh->radius);
        gs__uniform_v3(prog, "u_inflate_center", s->center);
        gs__uniform_f(prog, "u_inflate", s->inflate);
      }
      gs__uniform_v3(prog, "u_kd", m->diffuse);
      gs__uniform_v3(prog, "u_ks", m->specular);
      gs__uniform_f(prog, "u_shininess", m->shininess);
      gs__uniform_v3(prog, "u_base",
                     pass == 0 ? sh_add(m->emission, sh_mul(scene->ambient, m->diffuse))
                               : sh_v3s(0));
      glDrawArrays(GL_TRIANGLES, s->first, s->count);
    }
    sh_status st = gs__gl_check("shading the surfaces", err);
    if (st != SH_OK) return st;
  }
  return background(scene, view, t, progs, err);
}
