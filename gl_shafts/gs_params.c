#include "gs_params.h"

#include <stdio.h>

#include "gs_medium.h"
#include "sh_medium.h"

/* The variant's switches. Live programs (not baked) choose the spot
 * profile's edge (hard or smooth) per fragment, so that retuning a cone
 * selects the same program. Two switches that values decide stay, in live
 * programs too, as choosing them per fragment costs much (llvmpipe runs
 * both sides of a branch): the cosine exponent's class (0, 1, other: a pow
 * per sample) and a light inside the medium's box (no clipping of the
 * light's ray: together 12% of a live teapot frame's instructions), as
 * does SHADOW 0 for a light without casters (gs_lightvol.h; a shadow
 * lookup per sample doubled the stage's frame); they seldom flip, and both
 * variants stay cached once they have. */
static void defines(gs__params *p, const sh_scene *scene,
                    const gs__light_setup *ls, int live, const char *extra) {
  const sh_light *l = ls ? ls->light : NULL;
  int type = !l || l->type == SH_LIGHT_POINT ? GS_LIGHT_POINT
             : l->type == SH_LIGHT_SPOT        ? GS_LIGHT_SPOT
                                               : GS_LIGHT_DIRECTIONAL;
  const sh_medium *m = &scene->medium;
  int phase = GS_PHASE_ISOTROPIC;
  if (m->present) switch (m->phase.type) {
    case SH_PHASE_ISOTROPIC: phase = GS_PHASE_ISOTROPIC; break;
    case SH_PHASE_HENYEY_GREENSTEIN: phase = GS_PHASE_HENYEY_GREENSTEIN; break;
    case SH_PHASE_NISHITA_HAZY: phase = GS_PHASE_NISHITA_HAZY; break;
    case SH_PHASE_NISHITA_MURKY: phase = GS_PHASE_NISHITA_MURKY; break;
    case SH_PHASE_RAYLEIGH: phase = GS_PHASE_RAYLEIGH; break;
    case SH_PHASE_CORNETTE_SHANKS: phase = GS_PHASE_CORNETTE_SHANKS; break;
    }
  const sh_vec3 t = m->sigma_t;
  int grey = !m->present || (t.x == t.y && t.y == t.z);
  /* The spot profile's shape: smoothstep or hard edge; exponent 0, 1 or
   * other (pow). */
  int spot = l && l->type == SH_LIGHT_SPOT;
  int smooth = spot && live                       ? GS_SPOT_BY_VALUE
               : spot && l->cos_inner > l->cos_outer ? GS_SPOT_SMOOTH
                                                     : GS_SPOT_HARD;
  int expo = !spot || l->exponent == 0 ? GS_SPOT_EXPONENT_0
             : l->exponent == 1        ? GS_SPOT_EXPONENT_1
                                       : GS_SPOT_EXPONENT_ANY;
  int inside = l && l->type != SH_LIGHT_DIRECTIONAL && m->present &&
               l->position.x >= m->bmin.x && l->position.x <= m->bmax.x &&
               l->position.y >= m->bmin.y && l->position.y <= m->bmax.y &&
               l->position.z >= m->bmin.z && l->position.z <= m->bmax.z;
  char buf[512];
  snprintf(buf, sizeof buf,
           "#define LIGHT_TYPE %d\n#define HAS_MAP %d\n#define SHADOW %d\n"
           "#define CONE_CLIP %d\n#define PHASE %d\n#define GREY_SIGMA %d\n"
           "#define SPOT_SMOOTH %d\n#define SPOT_EXPONENT %d\n"
           "#define LIGHT_INSIDE %d\n#define MEDIUM %d\n",
           type, l ? l->has_map : 0, ls ? (int)ls->shadow : GS_SHADOW_NONE,
           ls ? ls->cone_clip : 0, phase, grey, smooth, expo, inside,
           gs__medium_kind(m));
  gs__params_text(p, buf);
  if (extra) gs__params_text(p, extra);
}

gs__params *gs__params_begin(const gs__frame *fr, const gs__light_setup *ls,
                             const char *extra) {
  gs__params *p = fr->params;
  const gs__view *view = fr->view;
  const sh_scene *scene = fr->scene;
  gs__params_reset(p, fr->bake);
  defines(p, scene, ls, !fr->bake, extra);
  const sh_camera_frame *f = &view->frame;
  /* Positions in the anchored space (gs_view.h). */
  /* The rays as GL sees them, relative to the depth zref (gs_view.h). */
  gs__param_v3(p, "u_org", view->org);
  gs__param_f(p, "u_zref", view->zref);
  gs__param_2f(p, "u_depth_ab", view->depth_a, view->depth_b);
  gs__param_v3(p, "u_fwd", f->forward);
  gs__param_v3(p, "u_rx", sh_scale(f->right, view->sx));
  gs__param_v3(p, "u_uy", sh_scale(f->up, view->sy));
  gs__param_v3(p, "u_rc", sh_add(sh_scale(f->right, view->cx),
                                 sh_scale(f->up, view->cy)));
  gs__param_2f(p, "u_ndc_scale", 2.0 / view->width, 2.0 / view->height);
  /* GL's pixel (0, 0) is pixel (x0, image height - y1) of the whole image
   * counted from the bottom: per-pixel patterns follow the whole image. */
  gs__param_2f(p, "u_frag0", view->win.x0,
               scene->camera.height - view->win.y1);
  const sh_medium *m = &scene->medium;
  gs__medium_params(p, view, m);
  /* Without a light, zeros: common.glsl's functions name these. */
  static const sh_light none;
  static const gs__light_setup no_setup = {.light = &none};
  if (!ls) ls = &no_setup;
  const sh_light *l = ls->light;
  gs__param_v3(p, "u_lpos", gs__anchored(view, l->position));
  gs__param_f(p, "u_light_rmin", sh_medium_light_min_distance(m));
  gs__param_v3(p, "u_ldir", l->direction);
  gs__param_v3(p, "u_lpower",
               l->type == SH_LIGHT_DIRECTIONAL ? l->irradiance : l->intensity);
  /* The cone's angles as versines, 1 - cos = 2 sin^2(angle / 2), which
   * keep their precision in float for narrow cones (common.glsl's
   * spot_profile). */
  double so = sin(0.5 * l->outer_deg * SH_PI / 180.0);
  double si = sin(0.5 * l->inner_deg * SH_PI / 180.0);
  gs__param_4f(p, "u_spot", 2.0 * so * so, 2.0 * si * si, l->exponent,
               l->tan_outer > 0 ? 1.0 / l->tan_outer : 0.0);
  gs__param_v3(p, "u_map_right", l->map_right);
  gs__param_v3(p, "u_map_up", l->map_up);
  const double *ws = ls->win_s, *wt = ls->win_t;
  sh_vec3 a = view->anchor;
  gs__param_4f(p, "u_win_s", ws[0], ws[1], ws[2],
               ws[3] + ws[0] * a.x + ws[1] * a.y + ws[2] * a.z);
  gs__param_4f(p, "u_win_t", wt[0], wt[1], wt[2],
               wt[3] + wt[0] * a.x + wt[1] * a.y + wt[2] * a.z);
  sh_mat4 lookup = gs__anchored_mat(view, &ls->lookup);
  gs__param_mat4(p, "u_shadow_mat", &lookup);
  gs__param_f(p, "u_shadow_near", ls->shadow_near);
  return p;
}
