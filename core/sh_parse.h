/* The scene-file parser: JSON text (scene format v1, docs/scene-format.md)
 * to an sh_scene. It is separate from every consumer: renderers and
 * exporters alike call sh_scene_load and read the result.
 *
 * Every error names the file, line and column, the key path (such as
 * "lights[2].intensity"), and what was expected; a misspelled key gets a
 * "did you mean" suggestion. Unknown keys are errors. */
#ifndef SH_PARSE_H
#define SH_PARSE_H

#include "sh_error.h"
#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The largest scene file sh_scene_load reads: 64 MiB (a scene holds its
 * meshes in files; 64 MiB of JSON is millions of numbers). */
#define SH_SCENE_MAX_BYTES (64 << 20)

/* Loads and validates the scene file at `path`; files it names (meshes,
 * images) are resolved relative to its directory. On success *out holds a
 * new scene (caller frees with sh_scene_free); on failure *out is NULL and
 * `err` says why (SH_ERR_IO, SH_ERR_SYNTAX, SH_ERR_SCENE, SH_ERR_IMAGE,
 * SH_ERR_MESH or SH_ERR_NOMEM). A path that is not a regular file (a
 * directory, /dev/zero, a FIFO) is SH_ERR_IO; a file larger than
 * SH_SCENE_MAX_BYTES is SH_ERR_SCENE. */
sh_status sh_scene_load(const char *path, sh_scene **out, sh_error *err);

/* As sh_scene_load, from text in memory; `name` is used in messages and
 * `base_dir` resolves relative file names, which must stay in its tree.
 * Unlike a scene file (whose absolute file names are refused), text a
 * program passes in may name files by absolute paths: the program chose
 * them (the Blender add-on names the user's images where they are). */
sh_status sh_scene_parse(const char *text, const char *name,
                         const char *base_dir, sh_scene **out, sh_error *err);

#ifdef __cplusplus
}
#endif
#endif
