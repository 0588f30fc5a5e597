#include "gs_medium.h"

#include "shaders/gs_shared.h"

#include <math.h>

#include "gs_atmo.h"
#include "gs_atmo_render.h"
#include "sh_medium.h"

int gs__medium_is_atmosphere(const sh_medium *m) {
  return m->present && m->type == SH_MEDIUM_ATMOSPHERE;
}

sh_status gs__medium_check(const sh_scene *scene, sh_error *err) {
  /* An atmosphere: gs_atmo_render, gs_atmo_light and the surface pass
   * draw every light and shape in it. */
  if (gs__medium_is_atmosphere(&scene->medium)) return SH_OK;
  return sh_medium_require_kinds(scene, "gl_shafts",
                                 SH_MEDIUM_KIND(SH_MEDIUM_HOMOGENEOUS) |
                                     SH_MEDIUM_KIND(SH_MEDIUM_HEIGHT_FOG),
                                 err);
}

int gs__medium_kind(const sh_medium *m) {
  if (gs__medium_is_atmosphere(m)) return GS_MEDIUM_ATMOSPHERE;
  return m->present && m->type == SH_MEDIUM_HEIGHT_FOG ? GS_MEDIUM_HEIGHT_FOG
                                                       : GS_MEDIUM_HOMOGENEOUS;
}

int gs__medium_shadow_bounds(const sh_scene *scene, sh_vec3 *lo, sh_vec3 *hi) {
  if (!gs__medium_is_atmosphere(&scene->medium)) {
    sh_scene_bounds(scene, lo, hi);
    return 0;
  }
  *lo = sh_v3s(INFINITY);
  *hi = sh_v3s(-INFINITY);
  for (int i = 0; i < scene->nshapes; i++) {
    sh_vec3 slo, shi;
    if (!sh_shape_bounds(&scene->shapes[i], &slo, &shi)) continue;
    *lo = sh_vmin(*lo, slo);
    *hi = sh_vmax(*hi, shi);
  }
  if (lo->x > hi->x) *lo = *hi = sh_v3s(0.0);
  return 1;
}

void gs__medium_params(gs__params *p, const gs__view *view, const sh_medium *m) {
  int on = m->present;
  gs__param_v3(p, "u_sigma_s", on ? m->sigma_s : sh_v3s(0));
  gs__param_v3(p, "u_sigma_t", on ? m->sigma_t : sh_v3s(0));
  gs__param_v3(p, "u_bmin", on ? gs__anchored(view, m->bmin) : sh_v3s(0));
  gs__param_v3(p, "u_bmax", on ? gs__anchored(view, m->bmax) : sh_v3s(0));
  gs__param_f(p, "u_g", on ? m->phase.g : 0.0);
  /* Height fog's base height in the anchored space, and 1 / H. */
  int fog = gs__medium_kind(m) == GS_MEDIUM_HEIGHT_FOG;
  gs__param_2f(p, "u_fog", fog ? m->base_height - view->anchor.y : 0.0,
               fog ? 1.0 / m->scale_height : 0.0);
  /* An atmosphere's sphere and table (atmo_table.glsl). */
  if (!gs__medium_is_atmosphere(m)) return;
  const sh_atmosphere *a = &m->atmo;
  double rg = a->ground_radius, rt = a->top_radius;
  gs__param_v3(p, "u_atmo_c", gs__anchored(view, a->center));
  gs__param_f(p, "u_rg", rg);
  gs__param_f(p, "u_rt", rt);
  gs__param_f(p, "u_hh", sqrt((rt - rg) * (rt + rg)));
  gs__param_2f(p, "u_table_size", GS__ATMO_TABLE_MU, GS__ATMO_TABLE_R);
}

double gs__medium_sigma_t_max(const sh_medium *m, const gs__poly *vol) {
  sh_vec3 lo = sh_v3s(INFINITY), hi = sh_v3s(-INFINITY);
  for (int f = 0; f < vol->nfaces; f++)
    for (int i = 0; i < vol->face[f].n; i++) {
      lo = sh_vmin(lo, vol->face[f].v[i]);
      hi = sh_vmax(hi, vol->face[f].v[i]);
    }
  if (!vol->nfaces) return 0.0;
  return sh_max3(sh_medium_majorant_box(m, lo, hi));
}
