#include "gs_sweep.h"

#include "shaders/gs_shared.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gs_params.h"
#include "gs_medium.h"
#include "sh_medium.h"

/* The phase function's forward peak: the angle (radians) at which it has
 * fallen halfway from its peak to its least value. */
static double phase_half_angle(const sh_phase *ph) {
  double top = sh_phase_eval(ph, 1.0), bottom = top;
  for (int i = 1; i <= 180; i++)
    bottom = fmin(bottom, sh_phase_eval(ph, cos(i * SH_PI / 180.0)));
  for (int i = 1; i <= 1800; i++) {
    double a = i * SH_PI / 1800.0;
    if (sh_phase_eval(ph, cos(a)) <= 0.5 * (top + bottom)) return a;
  }
  return SH_PI;
}

sh_status gs__sweep_init(gs__sweep *sw, sh_error *err) {
  memset(sw, 0, sizeof *sw);
  glCreateVertexArrays(1, &sw->vao);
  glCreateBuffers(1, &sw->vbo);
  glVertexArrayVertexBuffer(sw->vao, 0, sw->vbo, 0, 5 * sizeof(float));
  glEnableVertexArrayAttrib(sw->vao, 0);
  glVertexArrayAttribFormat(sw->vao, 0, 4, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(sw->vao, 0, 0);
  glEnableVertexArrayAttrib(sw->vao, 1);
  glVertexArrayAttribFormat(sw->vao, 1, 1, GL_FLOAT, GL_FALSE, 4 * sizeof(float));
  glVertexArrayAttribBinding(sw->vao, 1, 0);
  glCreateQueries(GL_SAMPLES_PASSED, 1, &sw->query);
  return gs__gl_check("creating the sweep's buffers", err);
}

static int reserve_slabs(gs__sweep *sw, size_t n) {
  if (n <= sw->scap) return 1;
  GLint *f = realloc(sw->first, n * sizeof *f);
  if (!f) return 0;
  sw->first = f;
  GLsizei *c = realloc(sw->count, n * sizeof *c);
  if (!c) return 0;
  sw->count = c;
  sw->scap = n;
  return 1;
}

static int reserve_verts(gs__sweep *sw, size_t n) {
  if (n <= sw->vcap) return 1;
  if (n < 2 * sw->vcap) n = 2 * sw->vcap;
  float *v = realloc(sw->verts, n * 5 * sizeof *v);
  if (!v) return 0;
  sw->verts = v;
  sw->vcap = n;
  return 1;
}

/* The screen polygons of the slabs: the convex hull of the projection of
 * the lit volume's part between the slab's planes, grown by half a pixel on
 * every side (the hull of the projected points moved to the corners of a
 * pixel's square around them). The rasteriser covers a pixel whose centre
 * is inside; a part narrower than a pixel (a narrow spot near its apex)
 * may hold a pixel's ray while its thin polygon, rounded to the
 * rasteriser's grid, misses that pixel's centre: grown so, every pixel
 * whose ray can meet the part is drawn, and the interval texture decides
 * what it adds. Returns the number of slabs with a polygon; adds their
 * areas in pixels to *pixels. */
static int build_slabs(gs__sweep *sw, const gs__sweep_job *job, double *pixels) {
  enum { MAXPTS = 4 * GS__POLY_MAX_FACES * GS__POLY_MAX_FACE_VERTS, GROWN = 4 * MAXPTS };
  const gs__light_setup *ls = job->light;
  const gs__view *view = job->frame->view;
  sh_vec3 *pts = malloc(MAXPTS * sizeof *pts);
  double(*xy)[2] = malloc(GROWN * sizeof *xy);
  double(*hull)[2] = malloc(2 * GROWN * sizeof *hull);
  int nslabs = 0;
  size_t nv = 0;
  if (!pts || !xy || !hull) goto done;
  sh_vec3 fwd = view->frame.forward;
  double base = sh_dot(fwd, view->frame.origin);
  double dz = (ls->zmax - ls->zmin) / job->planes;
  /* Half a pixel, in normalised device coordinates. */
  double hx = 1.0 / view->width, hy = 1.0 / view->height;
  for (int k = 0; k < job->planes; k++) {
    double za = ls->zmin + k * dz, zb = k + 1 == job->planes ? ls->zmax : za + dz;
    int n = gs__poly_slab_points(ls->vol, fwd, base + za, base + zb, pts, MAXPTS);
    for (int i = 0; i < n; i++) {
      double x, y;
      gs__view_ndc(view, pts[i], &x, &y);
      for (int c = 0; c < 4; c++) {
        xy[4 * i + c][0] = x + (c & 1 ? hx : -hx);
        xy[4 * i + c][1] = y + (c & 2 ? hy : -hy);
      }
    }
    int h = gs__hull2d(xy, 4 * n, hull);
    if (h < 3) continue;
    if (!reserve_verts(sw, nv + (size_t)h)) {
      nslabs = -1;
      goto done;
    }
    sw->first[nslabs] = (GLint)nv;
    sw->count[nslabs] = h;
    double area = 0;
    for (int i = 0; i < h; i++) {
      float *o = sw->verts + 5 * nv++;
      o[0] = (float)hull[i][0];
      o[1] = (float)hull[i][1];
      /* Depths as GL sees them, from zref (gs_view.h). */
      o[2] = (float)(za - view->zref);
      o[3] = (float)(zb - view->zref);
      o[4] = (float)k;
      int j = (i + 1) % h;
      area += hull[i][0] * hull[j][1] - hull[j][0] * hull[i][1];
    }
    *pixels += 0.5 * area * 0.25 * view->width * view->height;
    nslabs++;
  }
done:
  free(pts);
  free(xy);
  free(hull);
  if (nslabs > 0)
    glNamedBufferData(sw->vbo, (GLsizeiptr)(nv * 5 * sizeof(float)), sw->verts,
                      GL_STREAM_DRAW);
  return nslabs;
}

static sh_status interval_pass(const gs__sweep_job *job, const gs__target *t,
                               sh_error *err) {
  const gs__light_setup *ls = job->light;
  gs__params *p = gs__params_begin(job->frame, ls, "");
  gs__param_f(p, "u_depth", 0.0);
  GLuint prog;
  sh_status st = gs__program_use(job->frame->progs, &gs__glsl_screen_vert,
                                 &gs__glsl_interval_frag, p, &prog, err);
  if (st != SH_OK) return st;
  glBindFramebuffer(GL_FRAMEBUFFER, t->interval_fbo);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glBindTextureUnit(GS_UNIT_LINDEPTH, t->lindepth);
  /* The light's screen rectangle, a pixel wider on every side; the planes
   * never leave it, so the rest of the texture may hold other lights'. */
  double px = 2.0 / t->width, py = 2.0 / t->height;
  float x0 = (float)fmax(ls->rect[0] - px, -1), y0 = (float)fmax(ls->rect[1] - py, -1);
  float x1 = (float)fmin(ls->rect[2] + px, 1), y1 = (float)fmin(ls->rect[3] + py, 1);
  const float rect[8] = {x0, y0, x1, y0, x1, y1, x0, y1};
  gs__target_draw_polygon(t, rect, 4);
  return gs__gl_check("computing the lit intervals", err);
}

sh_status gs__sweep_light(gs__sweep *sw, const gs__sweep_job *job,
                          const gs__target *t, gs__sweep_counts *counts,
                          sh_error *err) {
  const gs__light_setup *ls = job->light;
  if (!ls->vol->nfaces) return SH_OK;
  if (!reserve_slabs(sw, (size_t)job->planes))
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory for the planes");
  double pixels = 0;
  int nslabs = build_slabs(sw, job, &pixels);
  if (nslabs < 0) return sh_error_set(err, SH_ERR_NOMEM, "out of memory for the planes");
  if (nslabs == 0) return SH_OK;
  sh_status st = interval_pass(job, t, err);
  if (st != SH_OK) return st;

  /* Optically thick slabs (optical depth change above GS__SUB_TAU along a
   * ray's part, whose length is at most the slab's depth times the longest
   * |d|, at the largest sigma_t in the lit volume) are sampled by optical
   * depth too. */
  const sh_medium *med = &job->frame->scene->medium;
  double smax = gs__medium_sigma_t_max(med, ls->vol);
  const sh_camera_frame *cf = &job->frame->view->frame;
  double dlmax = sqrt(1.0 + cf->tan_half_x * cf->tan_half_x + cf->tan_half_y * cf->tan_half_y);
  double slab = (ls->zmax - ls->zmin) / job->planes * dlmax;
  int tau_sub = 2.0 * smax * slab > GS__SUB_TAU;
  /* Live programs always have the optical-depth sampling, turned off by a
   * rate of 0: the camera and the lights decide the slabs' depth. */
  int live = !job->frame->bake;
  char extra[160];
  snprintf(extra, sizeof extra, "#define XI_EXACT %d\n#define JITTER %d\n#define TAU_SUB %d\n",
           job->lattice == NULL, job->jitter, tau_sub || live);
  gs__params *p = gs__params_begin(job->frame, ls, extra);
  /* A spot's smooth edge is sampled at least once per its width, a
   * forward-peaked phase function (Nishita's murky) four times per the
   * peak's half width. A cone narrower than the sub-angle takes four
   * samples per edge width: a ray crosses such a cone in a few steps, too
   * few for the midpoint rule on its profile (a 0.3-degree spot with a
   * 0.2-degree edge was 5.7% too bright), and a crossing's angle is short,
   * so the samples stay few. */
  double sub = job->sub_angle;
  const sh_light *l = ls->light;
  if (l->type == SH_LIGHT_SPOT && l->inner_deg < l->outer_deg) {
    double edge = (l->outer_deg - l->inner_deg) * SH_PI / 180.0;
    sub = fmin(sub, l->outer_deg * SH_PI / 180.0 < sub ? 0.25 * edge : edge);
  }
  sub = fmin(sub, 0.25 * phase_half_angle(&med->phase));
  gs__param_f(p, "u_inv_sub_angle", 1.0 / sub);
  gs__param_f(p, "u_inv_sub_texels", 1.0 / job->sub_texels);
  gs__param_2f(p, "u_map_size", job->map_width, job->map_height);
  gs__param_f(p, "u_shadow_res",
              ls->shadow != GS__SHADOW_NONE && job->shadow ? job->shadow->res : 0);
  gs__param_f(p, "u_tau_rate", tau_sub || !live ? 2.0 * smax / GS__SUB_TAU : 0.0);
  const double *m = job->lattice_map;
  gs__param_4f(p, "u_xi_xy", m[0], m[1], m[2], m[3]);
  gs__param_2f(p, "u_xi_z", m[4], m[5]);
  GLuint prog;
  const gs__glsl *fs = l->type == SH_LIGHT_DIRECTIONAL ? &gs__glsl_plane_dir_frag
                                                       : &gs__glsl_plane_local_frag;
  st = gs__program_use(job->frame->progs, &gs__glsl_plane_vert, fs, p, &prog, err);
  if (st != SH_OK) return st;
  if (job->lattice) gs__lattice_bind(job->lattice);
  if (ls->shadow != GS__SHADOW_NONE) gs__shadow_bind(job->shadow);
  if (job->map) glBindTextureUnit(GS_UNIT_MAP, job->map);
  glBindTextureUnit(GS_UNIT_INTERVAL, t->interval);

  glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
  gs__target_draw_buffers(t, 1);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glBeginQuery(GL_SAMPLES_PASSED, sw->query);
  glBindVertexArray(sw->vao);
  glMultiDrawArrays(GL_TRIANGLE_FAN, sw->first, sw->count, nslabs);
  glEndQuery(GL_SAMPLES_PASSED);
  GLuint64 passed = 0;
  glGetQueryObjectui64v(sw->query, GL_QUERY_RESULT, &passed);
  counts->planes += nslabs;
  counts->fragments_rasterized += pixels;
  counts->fragments += (double)passed;
  return gs__gl_check("drawing the planes", err);
}

void gs__sweep_free(gs__sweep *sw) {
  if (sw->vbo) glDeleteBuffers(1, &sw->vbo);
  if (sw->vao) glDeleteVertexArrays(1, &sw->vao);
  if (sw->query) glDeleteQueries(1, &sw->query);
  free(sw->verts);
  free(sw->first);
  free(sw->count);
  memset(sw, 0, sizeof *sw);
}
