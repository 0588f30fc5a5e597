/* Internal to sh_mesh.c (not installed, not exported): a check of an OBJ
 * file before assimp reads it, for the one cost assimp does not bound by
 * the file's size.
 *
 * assimp triangulates a polygon (aiProcess_Triangulate) by ear clipping,
 * whose time grows as the square of its corners: a face of 20000 corners
 * took 13 s here (1.4 s for 5000, 3.7 s for 10000; by hand, under load),
 * and 64 kB of "f 1 1 1 ..." hold 32000. A face of more than
 * SH_OBJ_MAX_CORNERS corners is refused, with its line; that bounds the
 * triangulation's work to a constant times the file's size.
 *
 * What counts as a face is what assimp's OBJ parser takes: a line (lines
 * ending in a backslash continue on the next) whose first token is `f`;
 * its corners are its other tokens. */
#ifndef SH_OBJ_CHECK_H
#define SH_OBJ_CHECK_H

#include <stddef.h>

#include "sh_error.h"

#define SH_OBJ_MAX_CORNERS 4096

/* Checks the OBJ file `path`, whose `size` bytes are `data`: SH_OK, or
 * SH_ERR_MESH naming the file and the line of a face of more than
 * SH_OBJ_MAX_CORNERS corners. */
sh_status sh__obj_check(const char *path, const char *data, size_t size,
                        sh_error *err);

#endif
