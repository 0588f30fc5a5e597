/* The Blender target's atmosphere (docs/scene_export.md, "Non-uniform
 * media"): the planet's ground as a Lambert mesh and the air as a volume
 * material on a closed mesh around the top sphere, for Cycles. EEVEE is
 * refused by the script (its froxel grid cannot hold a planet's air).
 *
 * Cycles 3.4 scatters at a point with the sum of its Volume Scatter
 * closures' weights times the plain sum of their phase functions
 * (se_cycles_phase.h), so a mixture whose weights change from point to
 * point (Rayleigh and Mie, by their sigma_s there) cannot be built from
 * closures that are all present. The material instead keeps ONE scattering
 * lobe at each shading point, chosen by a hash of the position (White
 * Noise Texture) with probability q_X = l_X rho_X / L for part X (l_X the
 * luminance of its sigma_s at the ground, rho_X its density profile, L the
 * sum over the parts), and gives it the weight sigma_X / q_X = (sigma_X0 /
 * l_X) L: the expected in-scattering is the exact mixture sum_X sigma_X
 * p_X. The extinction must not be random, so each choice carries a Volume
 * Absorption of the rest, sum_Y rho_Y (sigma_Y0 - (sigma_X0 / l_X) l_Y),
 * which is negative in some channels (Cycles sums extinction weights
 * without clamping): the extinction is sigma_t exactly at every point.
 * Within a part, lobes of a fitted Henyey-Greenstein mixture
 * (se_phase_to_hg_lobes) are chosen the same way.
 *
 * Densities come from a node graph of the distance r to the centre: exp(-h
 * / H) (at most 1) and the ozone's tent, h = r - R_g, all times (r < R_t).
 * Cycles ray-marches the volume in steps of 0.1 of its mesh's mean extent
 * times the material's step rate: the data's rate makes a step a given
 * fraction of the smallest scale height, and volume_max_steps lets a ray
 * cross the shell's longest chord in such steps.
 *
 * Lengths and coefficients go through the export's frame (se_frame.h,
 * se_scale.h: the air 10 to 100 units thick, kilometres for the Earth, so
 * that Blender's smallest clip start, 1e-6 units, stays below the camera's
 * height). */
#ifndef SE_BLENDER_ATMO_H
#define SE_BLENDER_ATMO_H

#include <jansson.h>

#include "se_export.h"
#include "se_frame.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The step along a ray, as a fraction of the smallest scale height. */
#define SE_ATMO_STEP_FRACTION 2.0

/* Adds the ground's material to `materials` and its mesh to `meshes`, and
 * returns the data's medium object (its "atmosphere" holds the container
 * mesh and the node graph's terms), or NULL if out of memory. Notes what
 * Cycles approximates (the phases) to `notes`. */
json_t *se_blender_atmosphere(const sh_scene *scene, const se_frame *frame,
                              json_t *materials, json_t *meshes, se_notes *notes);

/* The camera's clip start for a scene with an atmosphere: a thousandth of
 * the camera's height above the ground (or of its distance to the top
 * sphere's surface, if that is nearer), in scene units. */
double se_blender_atmo_clip_start(const sh_scene *scene);

#ifdef __cplusplus
}
#endif
#endif
