/* Internal to sh_mesh.c (not installed, not exported): a reader of PLY
 * files (Turk's polygon file format: a text header, then ASCII, binary
 * little-endian or binary big-endian data), used instead of assimp's.
 *
 * Why not assimp: Debian's assimp 5.2 PLY reader loops forever on a header
 * with no `end_header` line (fuzz/known/ply_hang, found by fuzz/mesh_fuzz;
 * ASCII and binary alike: it asks for the next line at the end of the file
 * without end), and reads past the data for as many instances or list
 * entries as the file declares, allocating as it goes (an element of 2e9
 * vertices in a 200-byte file took 2 GB in 10 s; a face list of 4e8 entries
 * 4 GB in 20 s). A library must not hang on a file, and a pre-check of the
 * header cannot see a list's count in the data; this reader checks every
 * count against the bytes that remain before it allocates or loops, so its
 * work and memory are bounded by the file's size.
 *
 * What it reads: the element `vertex` (properties x, y, z of any scalar
 * type), `face` (the list `vertex_indices` or `vertex_index`; a polygon of
 * n > 3 corners becomes n - 2 triangles fanned from its first corner, faces
 * of fewer than 3 corners are skipped, as points and lines are) and
 * `tristrips` (the list `vertex_indices`, -1 restarting the strip, every
 * second triangle's winding turned back). Every other element and property
 * is read and skipped. Errors name the file and the header line, the data
 * line (ASCII) or the byte offset (binary). */
#ifndef SH_PLY_H
#define SH_PLY_H

#include <stddef.h>

#include "sh_error.h"
#include "sh_mesh.h"

/* Whether a file starting with these bytes goes to the PLY reader: its
 * first non-blank bytes are "ply" in any case, which is all assimp's PLY
 * importer asks before it parses the header. */
int sh__ply_magic(const unsigned char *head, size_t n);

/* Reads the PLY file `path`, whose `size` bytes are `data` (with a NUL
 * after them), into `mesh` (zeroed first; the caller frees it with
 * sh_mesh_free), in the C numeric locale, which the caller sets
 * (sh_mesh_reader.h). SH_ERR_MESH with the place for a malformed or truncated
 * file, a count the file's size cannot hold, an index out of range, a
 * vertex that is not a finite float, or no triangles; SH_ERR_NOMEM. */
sh_status sh__ply_read(const char *path, const char *data, size_t size,
                       sh_mesh *mesh, sh_error *err);

#endif
