/* The coordinate and unit mapping of every target, in one place.
 *
 * The scene is right-handed with Y up, in scene units. A target's frame
 * names, for each of its axes, the scene axis it is and its sign, and how
 * many of its length units make one scene unit:
 * - POV-Ray: left-handed, Y up: (x, y, z) -> (x, y, -z), a mirror that
 *   POV-Ray's own left-handedness undoes; the centre of the scene's
 *   bounds (lights, medium, shapes; not the camera) at the origin and
 *   lengths times a power of ten that puts their bounding sphere near 300
 *   units (se_scale.h), so POV-Ray's fixed epsilons stay negligible;
 *   coefficients per unit length (sigma_s, sigma_a) divided by it.
 * - Blender: right-handed, Z up: (x, y, z) -> (x, -z, y), a rotation about
 *   X, so nothing is mirrored; one scene unit is one metre, unless the
 *   scene lies beyond what Cycles' single precision holds: then its
 *   content or camera is moved to the origin and lengths are multiplied
 *   by a power of ten (se_scale.h).
 * - the normalised scene (--to json): the identity.
 * Exporters map points, directions, lengths, coefficients and matrices
 * through their frame only.
 *
 * What a uniform scale s does to the other quantities, so that the image
 * is the same as the unscaled scene's in exact arithmetic (every pixel's
 * radiance is unchanged when every length is multiplied by s):
 * - radiance (emission, background, ambient, the sun's disk) and the
 *   irradiance of a parallel light (W/m^2, the same at any distance):
 *   unchanged;
 * - coefficients per unit length (sigma_s, sigma_a): divided by s, so
 *   optical depths sigma l stay;
 * - the radiant intensity of a point or spot light (W/sr), whose
 *   irradiance is I / d^2: multiplied by s^2 (se_frame_intensity), as is
 *   the power of an area light of given radiance (P = pi L A); the
 *   format has none, and emissive surfaces are radiance.
 * - angles (field of view, cones), albedos and phase functions:
 *   unchanged. */
#ifndef SE_FRAME_H
#define SE_FRAME_H

#include "sh_math.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct se_frame {
  int axis[3];     /* target axis i is scene axis axis[i] ... */
  double sign[3];  /* ... times sign[i] */
  double scale;    /* target length units per scene unit */
  sh_vec3 origin;  /* the scene point at the target's origin */
} se_frame;

/* POV-Ray's frame, with the scene's point `origin` at POV-Ray's origin
 * (a scene far from its origin keeps its digits in the printed numbers
 * and against POV-Ray's absolute tolerances). */
se_frame se_frame_pov(double scale, sh_vec3 origin);
/* Blender's frame, likewise with `origin` at Blender's origin. */
se_frame se_frame_blender(double scale, sh_vec3 origin);

/* A point: moved by -origin, axes mapped, scaled. */
sh_vec3 se_frame_point(const se_frame *f, sh_vec3 p);
/* A direction (or a vector that is not a length): axes mapped only. */
sh_vec3 se_frame_dir(const se_frame *f, sh_vec3 d);
/* A length, and a coefficient per unit length (sigma). */
double se_frame_length(const se_frame *f, double length);
sh_vec3 se_frame_per_length(const se_frame *f, sh_vec3 coefficient);
/* A radiant intensity (W/sr) or a power: times scale^2. */
sh_vec3 se_frame_intensity(const se_frame *f, sh_vec3 intensity);
/* Entry (row, col) of object-to-world matrix m in the target: its row
 * `row` of the mapped, scaled transform (col 3 is the translation). */
double se_frame_matrix(const se_frame *f, const sh_mat4 *m, int row, int col);

#ifdef __cplusplus
}
#endif
#endif
