/* Internal to sh_mesh.c (not installed, not exported): checks of an OBJ
 * file and of its material libraries before assimp reads them, for what
 * assimp does not bound or does not survive.
 *
 * The faces (sh__obj_check): the one cost assimp does not bound by the
 * file's size.
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

/* The material library (sh__mtl_check): assimp 5.2's reader of MTL files
 * (ObjFileMtlImporter.cpp at v5.2.5, Debian 12's) writes a texture map's
 * name and clamp flag into its current material without asking whether
 * there is one; before the library's first `newmtl` there is none, and the
 * process died of a SIGSEGV (an OBJ naming itself as its library, with a
 * `map_Ke` line: fuzz/known/mtl_no_material; `bump`, `disp`, `norm` and
 * `map_Kd -bm 1` the same), and so does the value of an `a` statement
 * (anisotropy: "a 0.5"; a word after the `a`, as in "aniso 0.5", makes
 * assimp fail the file instead). Every other statement is checked by
 * assimp itself.
 *
 * A statement is what assimp's reader dispatches on: the start of the file
 * and of each line (lines end at \n, \r, \f or a NUL byte; spaces and
 * tabs after a line end are skipped), by its first character: `a`; `m` or
 * `b`, `d`, `n`/`N` followed by a texture keyword (map_..., bump, disp,
 * norm; letters after the first in any case); and `ne` (`newmtl`), after
 * which a material is current to the end. Conservative where cheap: every
 * `map_` statement counts, also those assimp does not know (it skips
 * them), and a material made current by the OBJ's own `usemtl` is not
 * counted on. A UTF-8 byte-order mark is skipped, as assimp drops it; a
 * library starting with a UTF-16 or UTF-32 one is refused (assimp swaps
 * or converts such text with faults: a swap past the buffer's end, a
 * conversion it then throws away, so that what it parses is not what
 * was checked). sh_mesh.c checks, once each before assimp reads it, every
 * file an OBJ load opens besides the mesh (its libraries and the fallback
 * NAME.mtl), and the mesh itself when assimp opens it again while reading
 * it (a mesh naming itself as its library). */

/* Checks the material library `path` of the mesh `mesh`, whose `size`
 * bytes are `data`: SH_OK, or SH_ERR_MESH naming both and the library's
 * line (err->file, err->line) of a statement that needs a current material
 * before the library's first `newmtl`. */
sh_status sh__mtl_check(const char *mesh, const char *path, const char *data,
                        size_t size, sh_error *err);

#endif
