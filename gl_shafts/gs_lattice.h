/* The seed's lattice (Dobashi et al. 2000, section 5.1): the scattering term
 *   xi(p) = sigma_s p(alpha) Tr(p, light) Tr(eye, p) / r^2
 * (eq. 6 without dt, with the scene's normalised phase function; no 1/r^2
 * for directional lights) evaluated on the CPU at nu x nv lattice points on
 * each plane and stored in a 3D float texture whose layers are the planes.
 * The texture holds xi r^2, the smooth part: the sweep integrates the 1/r^2
 * exactly over each plane's slab (plane_local.frag), which interpolation
 * across the lattice could not do near the light.
 * The lattice spans the light's screen rectangle; its layers sit at the
 * planes' slab boundaries (planes + 1 layers), or, with fewer planes than
 * lattice points a side, max(nu, nv) + 1 layers evenly over the same depths,
 * so that the texture's trilinear filtering interpolates xi across each
 * plane, as the seed's Gouraud shading does, and between planes, for the
 * sample depths the sweep takes inside each slab. */
#ifndef GS_LATTICE_H
#define GS_LATTICE_H

#include "gs_gl.h"
#include "gs_lightvol.h"
#include "gs_view.h"
#include "sh_scene.h"

typedef struct gs__lattice {
  GLuint tex;
  int nu, nv, nw; /* the texture's size */
  float *data;
  size_t cap;     /* floats in data */
} gs__lattice;

/* xi at world point p for the light, seen from the eye (RGB), times r^2
 * for point and spot lights (r the distance to the light). */
sh_vec3 gs__xi_r2(const sh_scene *scene, const sh_light *light, sh_vec3 eye,
                  sh_vec3 p);

/* Evaluates xi on the light's lattice (nu x nv points over ls->rect, at
 * max(planes, nu, nv) + 1 depths evenly from zmin to zmax) and uploads it.
 * Returns the number of points in *points.
 * Writes the texture-coordinate map the plane shader needs:
 * s = ndc.x * map[0] + map[1], t = ndc.y * map[2] + map[3],
 * r = z * map[4] + map[5]. */
sh_status gs__lattice_eval(gs__lattice *lat, const sh_scene *scene,
                           const gs__view *view, const gs__light_setup *ls,
                           int nu, int nv, int planes, double map[6],
                           long *points, sh_error *err);

/* Binds the lattice texture to texture unit 4. */
void gs__lattice_bind(const gs__lattice *lat);

void gs__lattice_free(gs__lattice *lat);

#endif
