/* The embedding API of the scene core: what a program that hosts shafts
 * (the Blender add-on, a Python script through shafts.py, a C application)
 * needs to build a scene from memory and change it between frames, through
 * opaque handles only. docs/api.md describes it with a worked example.
 *
 * Ownership: every call copies what it is given; what a call returns
 * through an `out` pointer the caller frees with the matching _free (NULL
 * is allowed). Errors: every call that can fail returns an sh_status
 * (sh_error.h; SH_OK is 0) and fills the sh_error it is given with a
 * full-sentence message and, for scene text, the file name, line, column
 * and key path. No call prints, exits or aborts. Units and frames are those
 * of the scene format (docs/scene-format.md): scene units, Y up, radiance
 * in W/(sr m^2). */
#ifndef SHAFTS_H
#define SHAFTS_H

#include "sh_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A scene (sh_scene.h has its fields, for C code of this project). */
typedef struct sh_scene sh_scene;

/* The library's version, "MAJOR.MINOR.PATCH" (CMake's project version). */
const char *sh_version(void);

/* ---- Scenes from memory ---- */

/* A triangle mesh the caller holds in memory, named so that a scene's mesh
 * shape can refer to it with {"type": "mesh", "data": "NAME"}.
 * positions: nvertices * 3 floats (x, y, z), object space, scene units,
 * the scene's frame (Y up), every one finite. indices: ntriangles * 3
 * vertex indices in [0, nvertices), counter-clockwise seen from outside.
 * ntriangles >= 1. The parser copies the arrays. */
typedef struct sh_mesh_data {
  const char *name;
  const float *positions;
  int nvertices;
  const int *indices;
  int ntriangles;
} sh_mesh_data;

/* Parses and validates the scene in `text` (scene format v1): `name` is the
 * file name errors give (NULL: "<scene>"), `base_dir` resolves relative
 * file names (NULL or "": as they are written). A mesh shape names either a
 * file ("file") or one of the `nmeshes` in-memory meshes ("data"); an
 * unknown name, non-finite positions or an index out of range are
 * SH_ERR_SCENE errors located at the shape's "data" key, and so is a mesh
 * with no triangles. Names must be distinct (else SH_ERR_ARG). On success
 * *out is a new scene (free with sh_scene_free); on failure it is NULL. */
sh_status sh_scene_parse_ex(const char *text, const char *name,
                            const char *base_dir, const sh_mesh_data *meshes,
                            int nmeshes, sh_scene **out, sh_error *err);

/* As sh_scene_parse_ex, with the meshes as parallel arrays (mesh i is
 * names[i], positions[i], nvertices[i], indices[i], ntriangles[i]), for
 * bindings that should not mirror sh_mesh_data. */
sh_status sh_scene_parse_arrays(const char *text, const char *name,
                                const char *base_dir, int nmeshes,
                                const char *const *names,
                                const float *const *positions,
                                const int *nvertices,
                                const int *const *indices,
                                const int *ntriangles, sh_scene **out,
                                sh_error *err);

/* As sh_scene_parse_ex with no in-memory meshes. */
sh_status sh_scene_parse(const char *text, const char *name,
                         const char *base_dir, sh_scene **out, sh_error *err);

/* Loads the scene file at `path`; relative file names resolve against its
 * directory. */
sh_status sh_scene_load(const char *path, sh_scene **out, sh_error *err);

/* Frees a scene; NULL is allowed. Renderers made from it must be freed
 * first. */
void sh_scene_free(sh_scene *scene);

/* The camera's image size in pixels. */
void sh_scene_image_size(const sh_scene *scene, int *width, int *height);

/* ---- Changing a scene between frames ---- */

/* What sh_scene_update changed, for a renderer's sync call
 * (gs_renderer_sync): bits of `*changed`. */
enum {
  SH_CHANGED_CAMERA = 1,      /* position, look_at, up, fov_y_deg, size */
  SH_CHANGED_LIGHTS = 2,      /* any light's values */
  SH_CHANGED_MEDIUM = 4,      /* coefficients, phase function, bounds */
  SH_CHANGED_SHAPES = 8,      /* shape transforms */
  SH_CHANGED_SIZE = 16,       /* the camera's width or height */
  SH_CHANGED_ENVIRONMENT = 32 /* background or ambient */
};

/* Applies `patch`, a JSON object with any of the members "camera",
 * "lights", "medium", "background", "ambient" and "transforms", to the
 * scene. Each member is written as in a scene file and read by the same
 * parser code, so its errors are located in the patch text (`name` is the
 * file name they give): "camera" is a whole camera object; "lights" the
 * whole array, which must keep the number of lights and the type of each
 * (else SH_ERR_SCENE: the scene must be parsed again); "medium" a medium
 * object or null (no medium); "transforms" an array as long as the scene's
 * shapes, each element a shape's "transform" object or null (unchanged).
 * Relative file names (light maps) resolve against the scene's directory.
 * On error the scene is unchanged. On success `*changed` (if not NULL)
 * gets the SH_CHANGED_* bits of what differs from before. */
sh_status sh_scene_update(sh_scene *scene, const char *patch, const char *name,
                          unsigned *changed, sh_error *err);

/* ---- Errors without the struct ----
 * For bindings that should not mirror sh_error: an error report on the
 * heap and its fields. The strings live as long as the report. */
sh_error *sh_error_new(void);
void sh_error_free(sh_error *err);
sh_status sh_error_status(const sh_error *err);
const char *sh_error_file(const sh_error *err);
int sh_error_line(const sh_error *err);
int sh_error_column(const sh_error *err);
const char *sh_error_key(const sh_error *err); /* the key path */
const char *sh_error_message(const sh_error *err);

#ifdef __cplusplus
}
#endif
#endif
