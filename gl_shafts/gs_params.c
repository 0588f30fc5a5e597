#include "gs_params.h"

#include <stdio.h>

#include "gs_program.h"

void gs__defines(char *buf, size_t size, const sh_scene *scene,
                 const gs__light_setup *ls, const char *extra) {
  const sh_light *l = ls ? ls->light : NULL;
  int type = !l ? 0 : l->type == SH_LIGHT_POINT ? 0 : l->type == SH_LIGHT_SPOT ? 1 : 2;
  int phase = 0;
  if (scene->medium.present) switch (scene->medium.phase.type) {
    case SH_PHASE_ISOTROPIC: phase = 0; break;
    case SH_PHASE_HENYEY_GREENSTEIN: phase = 1; break;
    case SH_PHASE_NISHITA_HAZY: phase = 2; break;
    case SH_PHASE_NISHITA_MURKY: phase = 3; break;
    case SH_PHASE_RAYLEIGH: phase = 4; break;
    }
  const sh_vec3 t = scene->medium.sigma_t;  /* 0 without a medium */
  int grey = !scene->medium.present || (t.x == t.y && t.y == t.z);
  /* The spot profile's shape: smoothstep or hard edge; exponent 0, 1 or
   * other (pow). */
  int smooth = l && l->type == SH_LIGHT_SPOT && l->cos_inner > l->cos_outer;
  int expo = !l || l->type != SH_LIGHT_SPOT || l->exponent == 0 ? 0
             : l->exponent == 1 ? 1 : 2;
  const sh_medium *m = &scene->medium;
  int inside = l && l->type != SH_LIGHT_DIRECTIONAL && m->present &&
               l->position.x >= m->bmin.x && l->position.x <= m->bmax.x &&
               l->position.y >= m->bmin.y && l->position.y <= m->bmax.y &&
               l->position.z >= m->bmin.z && l->position.z <= m->bmax.z;
  snprintf(buf, size,
           "#define LIGHT_TYPE %d\n#define HAS_MAP %d\n#define SHADOW %d\n"
           "#define CONE_CLIP %d\n#define PHASE %d\n#define GREY_SIGMA %d\n"
           "#define SPOT_SMOOTH %d\n#define SPOT_EXPONENT %d\n"
           "#define LIGHT_INSIDE %d\n%s",
           type, l ? l->has_map : 0, ls ? (int)ls->shadow : 0,
           ls ? ls->cone_clip : 0, phase, grey, smooth, expo, inside,
           extra ? extra : "");
}

void gs__set_view_uniforms(GLuint prog, const gs__view *view,
                           const sh_scene *scene) {
  const sh_camera_frame *f = &view->frame;
  gs__uniform_v3(prog, "u_eye", f->origin);
  gs__uniform_v3(prog, "u_fwd", f->forward);
  gs__uniform_v3(prog, "u_rx", sh_scale(f->right, f->tan_half_x));
  gs__uniform_v3(prog, "u_uy", sh_scale(f->up, f->tan_half_y));
  gs__uniform_2f(prog, "u_ndc_scale", 2.0 / view->width, 2.0 / view->height);
  const sh_medium *m = &scene->medium;
  int on = m->present;
  gs__uniform_v3(prog, "u_sigma_s", on ? m->sigma_s : sh_v3s(0));
  gs__uniform_v3(prog, "u_sigma_t", on ? m->sigma_t : sh_v3s(0));
  gs__uniform_v3(prog, "u_bmin", on ? m->bmin : sh_v3s(0));
  gs__uniform_v3(prog, "u_bmax", on ? m->bmax : sh_v3s(0));
  gs__uniform_f(prog, "u_g", on ? m->phase.g : 0.0);
}

void gs__set_light_uniforms(GLuint prog, const gs__light_setup *ls) {
  const sh_light *l = ls->light;
  gs__uniform_v3(prog, "u_lpos", l->position);
  gs__uniform_v3(prog, "u_ldir", l->direction);
  gs__uniform_v3(prog, "u_lpower",
                 l->type == SH_LIGHT_DIRECTIONAL ? l->irradiance : l->intensity);
  if (l->type == SH_LIGHT_SPOT)
    gs__uniform_4f(prog, "u_spot", l->cos_outer, l->cos_inner, l->exponent,
                   l->tan_outer > 0 ? 1.0 / l->tan_outer : 0.0);
  gs__uniform_v3(prog, "u_map_right", l->map_right);
  gs__uniform_v3(prog, "u_map_up", l->map_up);
  gs__uniform_4f(prog, "u_win_s", ls->win_s[0], ls->win_s[1], ls->win_s[2], ls->win_s[3]);
  gs__uniform_4f(prog, "u_win_t", ls->win_t[0], ls->win_t[1], ls->win_t[2], ls->win_t[3]);
  gs__uniform_mat4(prog, "u_shadow_mat", &ls->lookup);
  gs__uniform_f(prog, "u_shadow_near", ls->shadow_near);
}
