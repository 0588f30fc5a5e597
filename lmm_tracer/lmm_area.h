/* Soft shadows by stochastic area-light sampling, the usual alternative the
 * light meshes method is measured against: every point and spot light
 * becomes a sphere of radius `radius` (its intensity unchanged), and its
 * visibility from a shaded point is the mean of shadow rays to stratified
 * points on the sphere's disc facing the point: `samples` rounded up to a
 * square number of strata. Directional
 * lights keep exact shadows. A shadow hook for the Whitted tracer. */
#ifndef LMM_AREA_H
#define LMM_AREA_H

#include "sh_reference.h"

typedef struct lmm_area lmm_area;

sh_status lmm_area_create(const sh_scene *scene, const sh_rt *rt,
                          double radius, int samples, lmm_area **out,
                          sh_error *err);
void lmm_area_free(lmm_area *area);
const sh_shadow_hook *lmm_area_hook(const lmm_area *area);

#endif
