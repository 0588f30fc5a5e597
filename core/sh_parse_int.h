/* Internal to the scene parser (sh_parse.c, sh_parse_lights.c,
 * sh_parse_shapes.c, sh_parse_files.c): the parser's state and the parts
 * its files share.
 *
 * Every kind of JSON object in a scene is read the same way: check its keys
 * against the table of keys allowed for that kind (a NULL-terminated list
 * beside the kind's reader), read each member with a typed reader of
 * sh_parse_ctx.h, then check the relations between members. To add a key,
 * add it to its kind's table and read it in that kind's function. */
#ifndef SH_PARSE_INT_H
#define SH_PARSE_INT_H

#include <jansson.h>

#include "sh_parse_ctx.h"
#include "sh_scene.h"
#include "shafts.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A list of key tables, for sh__check_keys: SH__KEYS(common, specific). */
#define SH__KEYS(...) ((const char *const *const[]){__VA_ARGS__, NULL})

typedef struct sh__parser {
  sh__pctx c;
  const char *base_dir; /* NULL or "": file names are used as they are */
  int absolute_ok;      /* text from the caller (sh_scene_parse) may name
                           files by absolute paths; a scene file may not */
  sh_scene *scene;      /* being filled; freed by the caller on error */
  const sh_mesh_data *meshes; /* the caller's in-memory meshes ("data") */
  int nmeshes;
} sh__parser;

/* Turns jansson's report of text it could not read (json_loadb) into an
 * sh_error located in `text`. */
sh_status sh__syntax_error(const char *text, size_t len, const char *name,
                           const json_error_t *je, sh_error *err);

/* Joins a file name of the scene (member `key`) to the scene's directory,
 * unless it is absolute, into a new string (*out, caller frees). An
 * absolute name in a scene file is refused (SH_ERR_SCENE). */
sh_status sh__resolve_file(sh__parser *p, const char *key, const char *name,
                           char **out);

/* Checks that the resolved file `path` exists, is not a directory and is
 * not empty, so that a missing file is reported at its key with both the
 * name as written and the resolved path. An empty file is `empty_status`. */
sh_status sh__check_file(sh__parser *p, const char *key, const char *name,
                         const char *path, const char *kind,
                         sh_status empty_status);

/* Reads the image named by the string member `key` of obj into img (caller
 * frees with sh_image_free); *path_out, if path_out is not NULL, gets the
 * resolved path (caller frees). `data` reads the stored values as they are
 * (heightfields) instead of decoding colour to linear radiance. */
sh_status sh__load_image(sh__parser *p, json_t *obj, const char *key,
                         int data, sh_image *img, char **path_out);

/* Reads the optional array member `key` of `root`, whose elements are
 * objects (`what` names one in the error otherwise: "a light"), into a new
 * zeroed array of `size`-byte items, which it returns with its length in
 * *count and the outcome in *st: the array comes back as soon as it is
 * allocated, also when an element then fails, so that the caller can hand
 * a part-read array to the scene that frees it. read_one reads one element
 * with the error path at it. NULL and 0 for an absent or empty array. */
void *sh__parse_objects(sh__parser *p, json_t *root, const char *key,
                        const char *what, size_t size,
                        sh_status (*read_one)(sh__parser *p, json_t *o,
                                              void *item),
                        int *count, sh_status *st);

/* Read one element of the "lights" and of the "shapes" array into item (an
 * sh_light, an sh_shape), as sh__parse_objects calls them. Materials and
 * the camera must have been read already. */
sh_status sh__parse_light(sh__parser *p, json_t *o, void *item);
sh_status sh__parse_shape(sh__parser *p, json_t *o, void *item);

/* Read the "camera" (required) and "medium" (optional) members of `root`
 * into p->scene. A scene patch (sh_scene_update) reads its members with
 * the same functions. */
sh_status sh__parse_camera(sh__parser *p, json_t *root);
sh_status sh__parse_medium(sh__parser *p, json_t *root);

/* Reads the transform object `t` (the current path points at it) into
 * *xform and *inv, checking that it is invertible. */
sh_status sh__parse_transform(sh__parser *p, json_t *t, sh_mat4 *xform,
                              sh_mat4 *inv);

/* Reads member "data" of a mesh shape: the in-memory mesh of that name
 * among p->meshes, checked (finite positions, indices in range) and copied
 * into *mesh. */
sh_status sh__parse_mesh_data(sh__parser *p, json_t *o, sh_mesh *mesh,
                              char **name_out);

#ifdef __cplusplus
}
#endif
#endif
