#include "gs_lattice.h"

#include "shaders/gs_shared.h"

#include <stdlib.h>
#include <string.h>

#include "sh_medium.h"

sh_vec3 gs__xi_r2(const sh_scene *scene, const sh_light *l, sh_vec3 eye,
                  sh_vec3 p) {
  const sh_medium *m = &scene->medium;
  sh_vec3 wi, tau;
  if (l->type == SH_LIGHT_DIRECTIONAL) {
    wi = sh_neg(l->direction);
    tau = sh_medium_optical_depth_ray(m, p, wi);
  } else {
    wi = sh_normalize(sh_sub(l->position, p));
    tau = sh_medium_optical_depth(m, p, l->position);
  }
  sh_vec3 view = sh_normalize(sh_sub(p, eye));
  double ph = sh_phase_eval(sh_medium_phase_at(m, p), sh_dot(wi, view));
  tau = sh_add(tau, sh_medium_optical_depth(m, eye, p));
  sh_vec3 tr = sh_vexp(sh_neg(tau));
  return sh_scale(sh_mul(sh_medium_sigma_s_at(m, p), tr), ph);
}

sh_status gs__lattice_eval(gs__lattice *lat, const sh_scene *scene,
                           const gs__view *view, const gs__light_setup *ls,
                           int nu, int nv, int planes, double map[6],
                           long *points, sh_error *err) {
  /* The seed's lattice lies on the planes; with few planes (and samples
   * between them) it gets layers between them too. */
  int nw = (planes > nu ? (planes > nv ? planes : nv) : (nu > nv ? nu : nv)) + 1;
  size_t n = (size_t)nu * nv * nw * 4;
  if (n > lat->cap) {
    float *d = realloc(lat->data, n * sizeof *d);
    if (!d) return sh_error_set(err, SH_ERR_NOMEM, "out of memory for the lattice");
    lat->data = d;
    lat->cap = n;
  }
  const sh_camera_frame *f = &view->frame;
  double x0 = ls->rect[0], y0 = ls->rect[1], x1 = ls->rect[2], y1 = ls->rect[3];
  if (!(x1 > x0)) x1 = x0 + 1e-6;
  if (!(y1 > y0)) y1 = y0 + 1e-6;
  double dz = (ls->zmax - ls->zmin) / (nw - 1);
  float *o = lat->data;
  for (int k = 0; k < nw; k++) {
    double z = ls->zmin + k * dz;
    for (int j = 0; j < nv; j++) {
      double y = y0 + (y1 - y0) * j / (nv - 1);
      for (int i = 0; i < nu; i++) {
        double x = x0 + (x1 - x0) * i / (nu - 1);
        sh_vec3 d = gs__view_ray(view, x, y);
        sh_vec3 xi = gs__xi_r2(scene, ls->light, f->origin, sh_madd(f->origin, d, z));
        o[0] = (float)xi.x;
        o[1] = (float)xi.y;
        o[2] = (float)xi.z;
        o[3] = 1.0f;
        o += 4;
      }
    }
  }
  if (!lat->tex || lat->nu != nu || lat->nv != nv || lat->nw != nw) {
    if (lat->tex) glDeleteTextures(1, &lat->tex);
    glCreateTextures(GL_TEXTURE_3D, 1, &lat->tex);
    glTextureStorage3D(lat->tex, 1, GL_RGBA32F, nu, nv, nw);
    glTextureParameteri(lat->tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(lat->tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(lat->tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(lat->tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(lat->tex, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    lat->nu = nu;
    lat->nv = nv;
    lat->nw = nw;
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTextureSubImage3D(lat->tex, 0, 0, 0, 0, nu, nv, nw, GL_RGBA, GL_FLOAT, lat->data);
  /* Lattice point i sits at texel centre (i + 0.5) / nu. */
  map[0] = (nu - 1) / ((x1 - x0) * nu);
  map[1] = 0.5 / nu - x0 * map[0];
  map[2] = (nv - 1) / ((y1 - y0) * nv);
  map[3] = 0.5 / nv - y0 * map[2];
  map[4] = 1.0 / (dz * nw);
  map[5] = 0.5 / nw - (ls->zmin - view->zref) * map[4]; /* depths from zref */
  *points = (long)nu * nv * nw;
  return gs__gl_check("uploading the lattice", err);
}

void gs__lattice_bind(const gs__lattice *lat) { glBindTextureUnit(GS_UNIT_XI, lat->tex); }

void gs__lattice_free(gs__lattice *lat) {
  if (lat->tex) glDeleteTextures(1, &lat->tex);
  free(lat->data);
  memset(lat, 0, sizeof *lat);
}
