/* The frame (se_frame.h) each renderer's export gets: a uniform length
 * scale and an origin, chosen from what the image needs so that the image
 * does not depend on where the scene sits or how large it is
 * (docs/scene_export.md, "Precision"; issue 11, kind 3), or forced
 * (scene_export --scale VALUE | none, se_options).
 *
 * Both rules start from the content sphere (se_content_sphere: shapes,
 * lights and the medium's box, not the camera) of centre c and radius r,
 * and scale every quantity as se_frame.h says, so that the export is the
 * same scene in exact arithmetic.
 * - POV-Ray (double precision, absolute tolerances of 1e-3 units): c at
 *   the origin, lengths times the power of ten that makes r about 300 units
 *   (for an atmosphere: the air's thickness about 100), however far the
 *   camera (measured: 0.13% from the reference with the camera 5e9 units
 *   away).
 * - Blender (Cycles and EEVEE compute in single precision, and hold about
 *   1e-6 to 1e5 units in radius and 1e5 radii from the origin, measured):
 *   lengths times 10^-floor(log10 r) when r lies outside [1e-2, 1e2] (so
 *   that r is 1 to 10 units: a scene 1 to 10 in radius scaled by a power
 *   of ten exports as the plain scene does), else 1 (for an atmosphere:
 *   the power of ten that makes the air 10 to 100 units thick, since
 *   Blender's clip start is at least 1e-6 units); the camera at the
 *   origin if it lies inside the content sphere, else c, when that point is
 *   more than 100 r from the origin, else no move; and for a camera more
 *   than 1e3 r from c looking along a scene axis with its up along
 *   another, in a medium box or none, Blender's axes turned to the
 *   camera's (its rotation then the identity, which single precision holds
 *   exactly). A scene of ordinary size near its origin is exported as it
 *   is (the add-on imports it in its own units), and any other the same as
 *   it scaled, moved and turned there.
 * What the frame cannot fix is a note (the export is approximate;
 * --strict refuses it): for Blender a camera more than 3e4 r from c that
 * is not turned (single precision cannot hold its rotation at that ratio
 * of the camera's distance to the scene's size); and, with a forced scale
 * or none, a frame outside the target's range (for POV-Ray a scene less
 * than 3 units in radius). */
#ifndef SE_SCALE_H
#define SE_SCALE_H

#include "se_export.h"

#ifdef __cplusplus
extern "C" {
#endif

se_frame se_scale_pov(const sh_scene *scene, const se_options *opt, se_notes *notes);
se_frame se_scale_blender(const sh_scene *scene, const se_options *opt, se_notes *notes);

/* The frame in words, for --verbose and the files' headers: "lengths
 * multiplied by S, the scene point (x, y, z) at the origin", or "the
 * scene's own units and position". malloc'd; NULL if out of memory. */
char *se_scale_describe(const se_frame *frame);

#ifdef __cplusplus
}
#endif
#endif
