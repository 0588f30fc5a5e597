#include "gs_shadow.h"

#include <stdlib.h>
#include <string.h>

#include "shaders/gs_shared.h"

/* Texels an open caster's triangles grow by in its shadow map: the reach of
 * the bilinear lookup, whose farthest texel centre lies up to sqrt(2)
 * texels from the lookup across an edge. At 1 texel, a floor point a
 * quarter texel inside a wall's foot met an empty texel beyond it
 * diagonally (surface_room.json). */
#define GS__SHADOW_DILATE 1.5

/* Deletes the texture and framebuffer, keeping the key's storage. */
static void release_gl(gs__shadow_map *sm) {
  if (sm->fbo) glDeleteFramebuffers(1, &sm->fbo);
  if (sm->tex) glDeleteTextures(1, &sm->tex);
  if (sm->depth_sampler) glDeleteSamplers(1, &sm->depth_sampler);
  sm->fbo = sm->tex = sm->depth_sampler = 0;
  sm->res = 0;
  sm->kind = GS__SHADOW_NONE;
  sm->key.valid = 0;
}

/* The filtering and wrapping of a map's reads, set through a texture's or
 * a sampler object's setters (the same signatures): bilinear, and outside
 * a 2D map depth 0, infinitely far; `compare` adds the depth comparison. */
static void set_reads(PFNGLTEXTUREPARAMETERIPROC seti, PFNGLTEXTUREPARAMETERFVPROC setfv,
                      GLuint obj, gs__shadow_kind kind, int compare) {
  seti(obj, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  seti(obj, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  seti(obj, GL_TEXTURE_COMPARE_MODE, compare ? GL_COMPARE_REF_TO_TEXTURE : GL_NONE);
  if (compare) seti(obj, GL_TEXTURE_COMPARE_FUNC, GL_GEQUAL);
  GLint wrap = kind == GS__SHADOW_2D ? GL_CLAMP_TO_BORDER : GL_CLAMP_TO_EDGE;
  seti(obj, GL_TEXTURE_WRAP_S, wrap);
  seti(obj, GL_TEXTURE_WRAP_T, wrap);
  const float border[4] = {0, 0, 0, 0};
  if (kind == GS__SHADOW_2D) setfv(obj, GL_TEXTURE_BORDER_COLOR, border);
}

static sh_status alloc_map(gs__shadow_map *sm, gs__shadow_kind kind, int res,
                           sh_error *err) {
  release_gl(sm);
  GLenum target = kind == GS__SHADOW_CUBE ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D;
  glCreateTextures(target, 1, &sm->tex);
  glTextureStorage2D(sm->tex, 1, GL_DEPTH_COMPONENT32F, res, res);
  /* Bilinear filtering of the comparisons (2x2 percentage-closer
   * filtering) measured closer to the reference's hard shadows than
   * nearest-texel comparison (docs/gl_shafts.md). */
  set_reads(glTextureParameteri, glTextureParameterfv, sm->tex, kind, 1);
  /* The same texture read as filtered depths, with no comparison
   * (common.glsl, shadow_behind). */
  glCreateSamplers(1, &sm->depth_sampler);
  set_reads(glSamplerParameteri, glSamplerParameterfv, sm->depth_sampler, kind, 0);
  glCreateFramebuffers(1, &sm->fbo);
  glNamedFramebufferDrawBuffer(sm->fbo, GL_NONE);
  glNamedFramebufferReadBuffer(sm->fbo, GL_NONE);
  sm->kind = kind;
  sm->res = res;
  return gs__gl_check("allocating a shadow map", err);
}

sh_status gs__shadow_render(gs__shadow_map *sm, const gs__frame *fr,
                            const gs__light_setup *ls, int res,
                            const gs__geometry *geom, sh_error *err) {
  const sh_scene *scene = fr->scene;
  sh_status st = SH_OK;
  if (sm->kind != ls->shadow || sm->res != res || !sm->tex)
    st = alloc_map(sm, ls->shadow, res, err);
  GLuint prog[2] = {0, 0}; /* meshes, exact spheres */
  for (int k = 0; k < 2 && st == SH_OK; k++)
    st = gs__program_use(fr->progs, &gs__glsl_shadow_vert, &gs__glsl_shadow_frag,
                         gs__params_begin(fr, ls, k ? "#define SPHERE 1\n" : ""),
                         &prog[k], err);
  if (st != SH_OK) return st;
  /* Two depths far apart along each texel's ray, for the exact spheres:
   * the near plane and the scene's diagonal away for perspective maps (the
   * near plane is 1e-10 of it, gs_lightvol.c: a thousand near distances
   * were 1e-7 of the scene, and the ray's direction between two points
   * that near the light was lost in float), both ends of an orthographic
   * one. */
  sh_vec3 lo, hi;
  sh_scene_bounds(fr->scene, &lo, &hi);
  double size = sh_length(sh_sub(hi, lo));
  double d0 = 1.0, d1 = ls->shadow == GS__SHADOW_2D && ls->light->type == SH_LIGHT_DIRECTIONAL
                            ? 0.0
                            : ls->shadow_near / (size > 0 ? size : 1.0);
  glViewport(0, 0, res, res);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glBindFramebuffer(GL_FRAMEBUFFER, sm->fbo);
  for (int f = 0; f < ls->nfaces; f++) {
    if (ls->shadow == GS__SHADOW_CUBE)
      glNamedFramebufferTextureLayer(sm->fbo, GL_DEPTH_ATTACHMENT, sm->tex, 0, f);
    else
      glNamedFramebufferTexture(sm->fbo, GL_DEPTH_ATTACHMENT, sm->tex, 0);
    if (glCheckNamedFramebufferStatus(sm->fbo, GL_FRAMEBUFFER) !=
        GL_FRAMEBUFFER_COMPLETE)
      return sh_error_set(err, SH_ERR_DEVICE,
                          "the shadow map's framebuffer is incomplete");
    const float zero = 0.0f;
    glClearNamedFramebufferfv(sm->fbo, GL_DEPTH, 0, &zero);
    sh_mat4 inv, mvp = gs__anchored_mat(fr->view, &ls->face_vp[f]);
    if (!sh_mat4_inverse(mvp, &inv))
      return sh_error_set(err, SH_ERR_DEVICE, "a shadow map's projection is singular");
    for (int k = 0; k < 2; k++) {
      gs__uniform_mat4(prog[k], "u_mvp", &mvp);
      gs__uniform_mat4(prog[k], "u_mvp_inv", &inv);
      gs__uniform_2f(prog[k], "u_texel_ndc", 2.0 / res, 2.0 / res);
      gs__uniform_2f(prog[k], "u_ray_depths", d0, d1);
    }
    glBindVertexArray(geom->vao);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, geom->vbo);
    for (int i = 0; i < geom->nshapes; i++) {
      const gs__shape_draw *s = &geom->shape[i];
      if (!ls->casts[i]) continue;
      glUseProgram(prog[s->exact_sphere]);
      if (s->exact_sphere) {
        const sh_shape *sh = &scene->shapes[i];
        sh_mat4 obj_inv = gs__sphere_from_anchored(fr->view, sh);
        gs__uniform_mat4(prog[1], "u_obj_inv", &obj_inv);
        gs__uniform_v3(prog[1], "u_center", sh_v3s(0.0)); /* centred space */
        gs__uniform_f(prog[1], "u_radius", sh->radius);
        gs__uniform_v3(prog[1], "u_inflate_center", gs__anchored(fr->view, s->center));
        gs__uniform_f(prog[1], "u_inflate", s->inflate);
      }
      if (s->closed) {
        /* A closed caster is stored by its far side (the sides facing the
         * light culled): its lit front is always nearer the light than the
         * stored depth, and its shadow's edges stay exact, with no bias. */
        glDisable(GL_POLYGON_OFFSET_FILL);
        glEnable(GL_CULL_FACE);
        glCullFace(ls->light_front[f] != s->mirrored ? GL_FRONT : GL_BACK);
      } else {
        /* An open one (quads, heightfields, open meshes) is stored as it
         * is, with no bias: a point of the medium just behind it is then
         * behind at least one of the four texels its filtered lookup
         * meets (the depth of a plane is affine in the map), and the
         * sweep counts a point lit only when all four are (common.glsl,
         * shadow_volume). Pushed away from the light (the usual bias
         * against a surface shadowing itself), a zero-thickness wall let
         * light through a layer behind it as thick as its slope was steep:
         * the fog of a closed room lit up to 28% of a shaft's peak. A
         * surface's own lookup is offset instead (surface.frag). Each
         * triangle is also grown by GS__SHADOW_DILATE texels in the map,
         * its depth extended along its plane (shadow.vert): a floor's
         * lookup within a texel of its edge under a wall's foot met the
         * empty texels beyond that edge, where the filter found light
         * (closed_room.json at 96x72: one pixel, 3.9e-4, now 0). */
        glDisable(GL_CULL_FACE);
        glDisable(GL_POLYGON_OFFSET_FILL);
      }
      if (!s->exact_sphere)
        gs__uniform_f(prog[0], "u_dilate", s->closed ? 0.0 : GS__SHADOW_DILATE * 2.0 / res);
      glDrawArrays(GL_TRIANGLES, s->first, s->count);
    }
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_CULL_FACE);
  return gs__gl_check("rendering a shadow map", err);
}

/* Whether sm->key equals the key of drawing ls at this size and version. */
static int key_matches(const gs__shadow_map *sm, const gs__light_setup *ls, int res,
                       int nshapes, unsigned long geom_version) {
  const gs__shadow_key *k = &sm->key;
  if (!k->valid || !sm->tex || sm->kind != ls->shadow || sm->res != res ||
      k->geom_version != geom_version || k->nfaces != ls->nfaces ||
      k->ncasts != nshapes)
    return 0;
  if (memcmp(k->face_vp, ls->face_vp, (size_t)ls->nfaces * sizeof ls->face_vp[0]) ||
      memcmp(k->light_front, ls->light_front,
             (size_t)ls->nfaces * sizeof ls->light_front[0]))
    return 0;
  return !nshapes || !memcmp(k->casts, ls->casts, (size_t)nshapes);
}

sh_status gs__shadow_update(gs__shadow_map *sm, const gs__frame *fr,
                            const gs__light_setup *ls, int res,
                            const gs__geometry *geom, unsigned long geom_version,
                            int *drawn, sh_error *err) {
  *drawn = 0;
  int n = geom->nshapes;
  if (key_matches(sm, ls, res, n, geom_version)) return SH_OK;
  gs__shadow_key *k = &sm->key;
  k->valid = 0;
  if (k->ncasts != n) {
    unsigned char *c = realloc(k->casts, (size_t)(n ? n : 1));
    if (!c) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
    k->casts = c;
    k->ncasts = n;
  }
  sh_status st = gs__shadow_render(sm, fr, ls, res, geom, err);
  if (st != SH_OK) return st;
  *drawn = 1;
  k->geom_version = geom_version;
  k->nfaces = ls->nfaces;
  memcpy(k->face_vp, ls->face_vp, sizeof k->face_vp);
  memcpy(k->light_front, ls->light_front, sizeof k->light_front);
  if (n) memcpy(k->casts, ls->casts, (size_t)n);
  k->valid = 1;
  return SH_OK;
}

void gs__shadow_bind(const gs__shadow_map *sm) {
  int cube = sm->kind == GS__SHADOW_CUBE;
  glBindTextureUnit(cube ? GS_UNIT_SHADOW_CUBE : GS_UNIT_SHADOW_2D, sm->tex);
  GLuint depth_unit = cube ? GS_UNIT_SHADOW_DEPTH_CUBE : GS_UNIT_SHADOW_DEPTH_2D;
  glBindTextureUnit(depth_unit, sm->tex);
  glBindSampler(depth_unit, sm->depth_sampler);
}

void gs__shadow_free(gs__shadow_map *sm) {
  release_gl(sm);
  free(sm->key.casts);
  memset(&sm->key, 0, sizeof sm->key);
}
