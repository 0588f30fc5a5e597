/* The normalised scene writer: `scene_export SCENE --to json -o OUT.json`.
 *
 * It writes the loaded scene back in scene format v1 with everything the
 * loader derived made explicit: every default filled in, spot axes as unit
 * `direction`s (never `look_at`), a spot light map's `up` as the frame the
 * loader built, shape transforms as `matrix`, and file names relative to
 * the output's directory: files outside its tree are copied beside it as
 * NAME.map<i>.EXT, NAME.mesh<i>.EXT, NAME.height<i>.EXT (a scene names only
 * files in its own tree). Numbers are printed with 17
 * significant digits, so loading the result gives the same scene; the
 * test se_json_test checks every field. */
#ifndef SE_JSON_H
#define SE_JSON_H

#include <jansson.h>

#include "se_export.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Builds the normalised scene file in `out` (the exporters' build
 * signature, se_run.h; `opt` and `notes` are unused: the file is exact). */
se_build se_json_build;

/* The scene's medium as the format's medium object (every key explicit, in
 * the scene's units and frame), or NULL when out of memory; the Blender
 * writer stores it for the add-on's medium properties (se_blender.h). */
json_t *se_json_medium(const sh_medium *m);

#ifdef __cplusplus
}
#endif
#endif
