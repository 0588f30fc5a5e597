/* The Blender 3.4 exporter (Cycles and EEVEE).
 *
 * `scene_export SCENE --to blender -o DIR/NAME.py` writes DIR/NAME.py, a
 * fixed script (the same bytes for every scene,
 * blender_addon/shafts_blender/convert/blender_build.py, which the add-on's
 * import runs on the same JSON: one converter, se_run.h),
 * DIR/NAME.blender.json, the scene converted to Blender's terms, and
 * DIR/NAME_blender_map<i>.exr for each light map (names no other target
 * writes). The script reads the JSON file
 * next to it with json.load: no scene string is ever part of Python code,
 * and the script never opens a file the JSON names other than the light
 * maps, which it loads as images.
 *
 *   blender -b -P DIR/NAME.py -- --engine cycles|eevee --out IMG.exr
 *           [--samples N] [--seed S]
 *
 * What the JSON holds, already converted by the exporter (so the script
 * stays a thin, fixed loader):
 * - Coordinates: Blender is right-handed with Z up; a scene point (x, y, z)
 *   is (x, -z, y), a rotation, so nothing is mirrored, after the frame's
 *   move and scale (se_scale.h: none for a scene of ordinary size near its
 *   origin), which the JSON's "frame" states.
 * - Camera: its world matrix, the vertical field of view, the image size.
 * - Lights: point and spot lights with power P = 4 pi I watts (I in the
 *   frame's units, times its scale squared; Blender's
 *   convention: a point light of P watts has intensity P / (4 pi) W/sr,
 *   and a spot light the same on its axis); spot_size = 2 outer and
 *   spot_blend = (cos inner - cos outer) / (1 - cos outer), which is the
 *   format's smoothstep exactly, times cos(theta) (Cycles 3.4: our exponent
 *   1); suns with strength = irradiance and angle 0; all with radius 0.
 * - Medium: a box mesh with a volume-only material (Volume Scatter lobes
 *   and Volume Absorption), se_cycles_phase.h.
 * - Shapes: triangle meshes in world coordinates; spheres and cylinders
 *   tessellated (sh_tessellate.h) and smooth-shaded.
 * - Materials: a sum of closures (Diffuse, Glossy for Phong and mirror,
 *   Refraction seen by camera rays and Transparent seen by shadow rays,
 *   Emission) approximating the Whitted model, with the parts that are
 *   approximate listed in the notes.
 * - Light maps: filter cards (se_geom.h) with a Transparent BSDF coloured
 *   by the map, visible to shadow rays only. */
#ifndef SE_BLENDER_H
#define SE_BLENDER_H

#include "se_export.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Builds the Blender files for `scene` in `out`; `py_path` must end in
 * ".py", else SH_ERR_ARG. */
se_build se_blender_build;

/* The fixed script, as written next to every export. */
extern const unsigned char se_blender_script[];
extern const unsigned long se_blender_script_size;

#ifdef __cplusplus
}
#endif
#endif
