/* The POV-Ray 3.7 exporter.
 *
 * `scene_export SCENE --to pov -o DIR/NAME.pov` writes DIR/NAME.pov,
 * DIR/NAME.ini and, for each light map, DIR/NAME_map<i>.exr (the map as
 * loaded, in linear float); `povray NAME.ini` run in DIR renders DIR/NAME.exr,
 * a linear half-float OpenEXR image of the scene's size and camera.
 *
 * How each feature is mapped (docs/scene_export.md has the table):
 * - Coordinates: POV-Ray is left-handed, so z is negated everywhere; every
 *   length is multiplied by a power of ten that makes the scene a few
 *   hundred units across, so that POV-Ray's fixed tolerances (1e-3 units)
 *   are negligible; coefficients per unit length are divided by it and
 *   intensities multiplied by its square.
 * - Medium: a hollow, invisible box with interior media (method 2, jitter 0,
 *   one sample per interval: a midpoint rule with exact transmittance),
 *   enlarged by a hair so that surfaces lying on the bounds are not
 *   coplanar with it. POV-Ray's phase k is 4 pi times a normalised phase for
 *   types 1 and 5 and has sphere means 1.15331, 1.24680, 1.06583 for types
 *   2, 3, 4; the scattering colour is sigma_s / (4 pi mean) and the
 *   `extinction` keyword 4 pi mean, so in-scattering and extinction are
 *   both exact.
 * - Point and spot lights: 1/r^2 from fade_power 2 with a tiny fade_distance
 *   f and the colour scaled by 1/(2 f^2) (relative error (f/r)^2). POV-Ray
 *   attenuates a shadow ray by interior media only up to the last surface
 *   it crosses, so a light inside the medium gets a tiny invisible, fully
 *   transparent sphere around it: the ray then crosses a surface a radius r
 *   from the light, and the light's colour is multiplied by
 *   exp(-sigma_t r) for the stretch POV-Ray leaves out. Spot profiles are
 *   exact (POV-Ray's spline is the same smoothstep in cos space).
 * - Directional lights: parallel lights placed beyond everything.
 * - Light maps: filter cards (se_geom.h) with the map as an image_map,
 *   `filter all 1`, seen by shadow rays only.
 * - Materials: diffuse / pi as pigment with `diffuse 1` (POV-Ray has no
 *   1/pi), Phong, reflection, transmit through pigment filter and transmit
 *   layers with POV-Ray 3.7's opacity scaling undone, ior.
 * - Shapes: sphere, box and cylinder natively; quads, meshes and
 *   heightfields as mesh2, in object space under a `matrix`. */
#ifndef SE_POV_H
#define SE_POV_H

#include "se_export.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Builds the POV-Ray files for `scene` in `out`; `pov_path` must end in
 * ".pov" and its file name must be plain (se_is_plain_file_name), else
 * SH_ERR_ARG. Approximations are recorded in `notes` and as comments. */
se_build se_pov_build;

#ifdef __cplusplus
}
#endif
#endif
