/* Internal to sh_mesh.c (not installed, not exported): a reader of OFF
 * files (Geomview's Object File Format, text only), used instead of
 * assimp's.
 *
 * Why not assimp: Debian's assimp 5.2 OFF importer allocates the vertices
 * and faces its header declares before it reads a line (a 170-byte file
 * whose vertex count overflows to 3.3e9 asked for 40 GB,
 * fuzz/known/off_alloc, found by fuzz/mesh_fuzz), and what it then reads
 * is silently bent (tried by hand): a file with fewer vertex lines than
 * declared has its face lines read as vertices and the rest put at the
 * origin, an index out of range becomes the last vertex, a face of more
 * than 9 corners is dropped, a count beyond 2^32 wraps (4294967299 is 3). A
 * pre-check of the header before assimp would have to copy assimp's own
 * tokenising to see the counts it sees and would leave the rest bent; the
 * format is small enough to read whole. This reader checks each count
 * against the bytes left before it allocates or loops, so its work and
 * memory are bounded by the file's size (12 bytes of positions per byte of
 * file at most), and a bad file is an error at its line.
 *
 * What it reads (sh_mesh_reader.h's conventions):
 *   [ST][C][N][4][n]OFF      the optional header keyword (OFF BINARY is
 *                            refused); the prefixes say what follows each
 *                            vertex's position (texture coordinates,
 *                            colour, normal: skipped), 4 a homogeneous w
 *                            that divides the position, n a dimension
 *   [NDIM]                   after nOFF: 1 to 3 coordinates a vertex (the
 *                            missing ones are 0)
 *   NV NF [NE]               the counts; the vertices start on the next line
 *   x y z [...]              NV vertex lines, the rest of each line skipped
 *   n i1 ... in [...]        NF face lines, indices counted from 0; a
 *                            polygon of n > 3 corners becomes n - 2
 *                            triangles fanned from i1, faces of fewer than
 *                            3 corners are skipped (points and lines), the
 *                            rest of the line (a colour) is skipped
 * Blank lines and '#' comments (to the line's end) are skipped anywhere;
 * what follows the last face is not read. */
#ifndef SH_OFF_H
#define SH_OFF_H

#include <stddef.h>

#include "sh_error.h"
#include "sh_mesh.h"

/* Whether a file starting with these bytes may be an OFF file without
 * ending in ".off": its first three bytes are "off" in any case, which is
 * all assimp asks before it hands a file to its OFF importer when it
 * picks the importer by the file's bytes (no importer, or several, list
 * the file's extension: sh_mesh.c's assimp_sniffs). */
int sh__off_magic(const unsigned char *head, size_t n);

/* Reads the OFF file `path`, whose `size` bytes are `data` (with a NUL
 * after them), into `mesh` (zeroed first; the caller frees it with
 * sh_mesh_free), in the C numeric locale, which the caller sets.
 * SH_ERR_MESH at the line for a malformed or truncated file, a count the
 * file's size cannot hold, an index out of range, a vertex that is not a
 * finite float, or no triangles; SH_ERR_NOMEM. */
sh_status sh__off_read(const char *path, const char *data, size_t size,
                       sh_mesh *mesh, sh_error *err);

#endif
