/* Running an export: build a loaded scene's files for a target, refuse the
 * export if it must be exact and is not, write it whole or not at all.
 *
 * The command line (main.c) and the Blender add-on's import (through
 * libshafts.so and ctypes: blender_addon/shafts_blender/convert/importer.py)
 * both go through se_export_scene, so `scene_export --to blender` and
 * File > Import > Shafts scene build the same Blender data with the same
 * code (se_blender.c), read by the same script (blender_build.py). */
#ifndef SE_RUN_H
#define SE_RUN_H

#include "se_export.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum se_target { SE_TARGET_POV, SE_TARGET_BLENDER, SE_TARGET_JSON } se_target;

/* Builds the export of `scene` for `target` at out_path (se_pov.h,
 * se_blender.h, se_json.h) and writes its files. If `strict` is set and the
 * export needs approximations, nothing is written and SH_ERR_SCENE is
 * returned, with a message counting them. The approximations are left in
 * `notes` (owned by the caller) either way. */
sh_status se_export_scene(const sh_scene *scene, se_target target, const se_options *opt,
                          const char *out_path, int strict, se_notes *notes,
                          sh_error *err);

/* Loads the scene file at scene_path (sh_scene_load) and exports it without
 * --strict, discarding the notes (the Blender data file keeps them).
 * `target` is "pov", "blender" or "json"; `quality` 0 is draft, 1 final.
 * The entry point for callers that cannot build C structs (ctypes): the
 * error is read back with sh_error_format. */
sh_status se_export_file(const char *scene_path, const char *target, int quality,
                         const char *out_path, sh_error *err);

#ifdef __cplusplus
}
#endif
#endif
