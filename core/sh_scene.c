#include "sh_scene.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

void sh_scene_free(sh_scene *scene) {
  if (!scene) return;
  for (int i = 0; i < scene->nlights; i++) {
    free(scene->lights[i].map_file);
    sh_image_free(&scene->lights[i].map);
  }
  free(scene->lights);
  for (int i = 0; i < scene->nmaterials; i++) free(scene->materials[i].name);
  free(scene->materials);
  for (int i = 0; i < scene->nshapes; i++) {
    free(scene->shapes[i].file);
    free(scene->shapes[i].data);
    for (int k = 0; k < scene->shapes[i].nnamed; k++) free(scene->shapes[i].named[k]);
    free(scene->shapes[i].named);
    sh_mesh_free(&scene->shapes[i].mesh);
  }
  free(scene->shapes);
  for (int i = 0; i < scene->render.nparams; i++) {
    free(scene->render.params[i].key);
    free(scene->render.params[i].text);
    free(scene->render.params[i].json);
  }
  free(scene->render.params);
  free(scene->file);
  free(scene->base_dir);
  free(scene);
}

void sh_scene_image_size(const sh_scene *scene, int *width, int *height) {
  *width = scene->camera.width;
  *height = scene->camera.height;
}

int sh_scene_has_semitransparent(const sh_scene *scene) {
  for (int i = 0; i < scene->nmaterials; i++)
    if (!sh_is_black(scene->materials[i].transmit)) return 1;
  return 0;
}

/* The object-space box of a shape; returns 0 if it has none (an empty
 * mesh). */
static int shape_object_bounds(const sh_shape *s, sh_vec3 *lo, sh_vec3 *hi) {
  switch (s->type) {
  case SH_SHAPE_SPHERE:
    *lo = sh_sub(s->center, sh_v3s(s->radius));
    *hi = sh_add(s->center, sh_v3s(s->radius));
    return 1;
  case SH_SHAPE_BOX:
    *lo = s->bmin;
    *hi = s->bmax;
    return 1;
  case SH_SHAPE_CYLINDER: {
    /* A disc of radius r normal to unit a reaches r sqrt(1 - a_i^2) along
     * axis i from its centre. */
    sh_vec3 a = sh_normalize(sh_sub(s->top, s->base));
    sh_vec3 e = sh_v3(s->radius * sqrt(fmax(0.0, 1.0 - a.x * a.x)),
                      s->radius * sqrt(fmax(0.0, 1.0 - a.y * a.y)),
                      s->radius * sqrt(fmax(0.0, 1.0 - a.z * a.z)));
    *lo = sh_sub(sh_vmin(s->base, s->top), e);
    *hi = sh_add(sh_vmax(s->base, s->top), e);
    return 1;
  }
  case SH_SHAPE_QUAD: {
    sh_vec3 p[3] = {sh_add(s->corner, s->u), sh_add(s->corner, s->v),
                    sh_add(sh_add(s->corner, s->u), s->v)};
    *lo = *hi = s->corner;
    for (int i = 0; i < 3; i++) {
      *lo = sh_vmin(*lo, p[i]);
      *hi = sh_vmax(*hi, p[i]);
    }
    return 1;
  }
  case SH_SHAPE_MESH:
  case SH_SHAPE_HEIGHTFIELD:
    if (s->mesh.nverts > 0 && s->mesh.positions) {
      const float *p = s->mesh.positions;
      *lo = *hi = sh_v3(p[0], p[1], p[2]);
      for (int i = 1; i < s->mesh.nverts; i++) {
        sh_vec3 q = sh_v3(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
        *lo = sh_vmin(*lo, q);
        *hi = sh_vmax(*hi, q);
      }
      return 1;
    }
    if (s->type == SH_SHAPE_HEIGHTFIELD) {
      *lo = s->bmin;
      *hi = s->bmax;
      return 1;
    }
    return 0;
  }
  return 0;
}

int sh_shape_bounds(const sh_shape *s, sh_vec3 *lo, sh_vec3 *hi) {
  sh_vec3 olo, ohi;
  if (!shape_object_bounds(s, &olo, &ohi)) return 0;
  /* The world box of the transformed object box: its 8 corners. */
  *lo = sh_v3s(DBL_MAX);
  *hi = sh_v3s(-DBL_MAX);
  for (int k = 0; k < 8; k++) {
    sh_vec3 p = sh_v3(k & 1 ? ohi.x : olo.x, k & 2 ? ohi.y : olo.y,
                      k & 4 ? ohi.z : olo.z);
    p = sh_xform_point(&s->xform, p);
    *lo = sh_vmin(*lo, p);
    *hi = sh_vmax(*hi, p);
  }
  return 1;
}

void sh_scene_bounds(const sh_scene *scene, sh_vec3 *bmin, sh_vec3 *bmax) {
  sh_vec3 lo = sh_v3s(DBL_MAX), hi = sh_v3s(-DBL_MAX);
  if (scene->medium.present) {
    lo = sh_vmin(lo, scene->medium.bmin);
    hi = sh_vmax(hi, scene->medium.bmax);
  }
  for (int i = 0; i < scene->nlights; i++) {
    const sh_light *l = &scene->lights[i];
    if (l->type == SH_LIGHT_POINT || l->type == SH_LIGHT_SPOT) {
      lo = sh_vmin(lo, l->position);
      hi = sh_vmax(hi, l->position);
    }
  }
  for (int i = 0; i < scene->nshapes; i++) {
    sh_vec3 slo, shi;
    if (!sh_shape_bounds(&scene->shapes[i], &slo, &shi)) continue;
    lo = sh_vmin(lo, slo);
    hi = sh_vmax(hi, shi);
  }
  if (lo.x > hi.x) lo = hi = sh_v3s(0.0);
  *bmin = lo;
  *bmax = hi;
}

void sh_frame_fit(sh_vec3 lo, sh_vec3 hi, sh_vec3 *origin, double *unit) {
  *origin = sh_v3s(0.0);
  *unit = 1.0;
  if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) return;
  sh_vec3 c = sh_scale(sh_add(lo, hi), 0.5);
  double r = 0.5 * sh_length(sh_sub(hi, lo));
  if (!(r > 0)) r = sh_max3(sh_vmax(sh_neg(c), c));
  if (!(r > 0) || !isfinite(r)) return;
  *unit = exp2(ceil(log2(r)));
  *origin = sh_v3(*unit * round(c.x / *unit), *unit * round(c.y / *unit),
                  *unit * round(c.z / *unit));
}
