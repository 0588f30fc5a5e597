/* The exporters' table and running an export: build a loaded scene's files
 * for a target, refuse the export if it must be exact and is not, write it
 * whole or not at all.
 *
 * Every target is one row of se_targets (se_targets.c): its name (what
 * `--to` takes), the extension of the file -o names, its build function
 * and its line of help. scene_export's --help, its `--to` and the dispatch
 * below all read that table, so a new exporter is one file with its build
 * function and one row (docs/scene_export.md, "Adding a target").
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


typedef struct se_target {
  const char *name;      /* "pov": what --to takes */
  const char *extension; /* "pov": the extension of the file -o names */
  se_build *build;
  const char *help;      /* what is written and how to render it */
} se_target;

/* The targets, ended by a row of NULLs. */
extern const se_target se_targets[];

/* The target named `name`, or NULL. */
const se_target *se_target_find(const char *name);

/* Builds the export of `scene` for `target` at out_path and writes its
 * files. If `strict` is set and the export needs approximations, nothing
 * is written and SH_ERR_SCENE is returned, with a message counting them.
 * The approximations are left in `notes` (owned by the caller) either
 * way. If `result` is not NULL it receives the export as built, either
 * way too (owned by the caller: se_output_free): the files' paths, the
 * frame the target chose (has_frame 0 for the json target) and the
 * commands that render it (se_output.render). */
sh_status se_export_scene(const sh_scene *scene, const se_target *target,
                          const se_options *opt, const char *out_path,
                          int strict, se_notes *notes, se_output *result,
                          sh_error *err);

/* Loads the scene file at scene_path (sh_scene_load) and exports it without
 * --strict, discarding the notes (the Blender data file keeps them).
 * `target` is a target's name ("pov", "blender", "json"); `quality` 0 is
 * draft, 1 final. The entry point for callers that cannot build C structs
 * (ctypes): the error is read back with sh_error_new's accessors
 * (shafts.h). */
sh_status se_export_file(const char *scene_path, const char *target, int quality,
                         const char *out_path, sh_error *err);

#ifdef __cplusplus
}
#endif
#endif
