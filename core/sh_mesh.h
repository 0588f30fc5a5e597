/* Triangle meshes: loading mesh files through assimp and building heightfield
 * grids. Tessellating analytic shapes for consumers that draw triangles is
 * in sh_tessellate.h (it needs sh_shape, which sh_scene.h defines). */
#ifndef SH_MESH_H
#define SH_MESH_H

#include "sh_error.h"
#include "sh_image.h"
#include "sh_math.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An indexed triangle mesh with float positions. Counter-clockwise triangles
 * (seen from outside) face outwards. */
typedef struct sh_mesh {
  int nverts, ntris;
  float *positions;   /* 3 * nverts floats; owned */
  unsigned *indices;  /* 3 * ntris indices; owned */
} sh_mesh;

/* Frees the arrays and zeroes the struct; safe on a zeroed struct. */
void sh_mesh_free(sh_mesh *mesh);

/* Loads every mesh of a file that assimp reads (OBJ, glTF, STL, ...), node
 * transforms applied, triangulated, into one mesh (caller frees with
 * sh_mesh_free). A PLY file (one whose first non-blank bytes are "ply") is
 * read by sh_ply.h's reader instead, never by assimp's (which loops
 * forever on some files), and an OFF file (named *.off, or whose first
 * bytes are "off" if assimp would pick its importer by the file's bytes:
 * when no importer, or several, list its extension) by sh_off.h's
 * (assimp's allocates what its header declares); a glTF file (or any file
 * assimp would pick an importer for by its bytes) is checked by
 * sh_gltf_check.h before assimp reads it, an OBJ file's (the same)
 * polygons and its material libraries (a texture map before any newmtl,
 * which crashed assimp) by sh_obj_check.h. assimp may read the files of a load 16 times
 * over their size (plus 1 MiB) at most: a file named again and again (one
 * material library on many lines) is refused. Every file the load opens (the mesh, an OBJ's material
 * library, a glTF's buffers) must resolve inside the directory `root` (NULL:
 * the mesh's own directory); a file outside it is refused (sh_confine.h).
 * A missing file is SH_ERR_IO; an unreadable one, one with no triangles,
 * one naming a file outside `root`, or one with a vertex that is not a
 * finite float, SH_ERR_MESH (the message names the vertex). */
sh_status sh_mesh_load(const char *path, const char *root, sh_mesh *mesh,
                       sh_error *err);

/* sh_mesh_load, also giving the other files the load opened (an OBJ's
 * material library, a glTF's buffers and images), resolved, in *named
 * (malloc'ed, *nnamed of them; the caller frees each and the array, also
 * on error). Internal to the core (the scene parser keeps them for
 * sh_outputs.h's check that no output overwrites an input). */
sh_status sh__mesh_load_named(const char *path, const char *root, sh_mesh *mesh,
                              char ***named, int *nnamed, sh_error *err);

/* Builds the heightfield of a grey image (its mean of R, G, B, clamped to
 * [0, 1], as height) spanning the box [bmin, bmax]: vertex (i, j) of the image's pixel
 * (column i, row j) sits at x = bmin.x + i/(w-1) * dx, z = bmin.z + j/(h-1)
 * * dz, y = bmin.y + grey * dy. Two triangles per grid cell, facing +Y.
 * The image needs at least 2x2 pixels and the box min < max in x and z,
 * min <= max in y; otherwise SH_ERR_ARG. */
sh_status sh_mesh_heightfield(const sh_image *img, sh_vec3 bmin, sh_vec3 bmax,
                              sh_mesh *mesh, sh_error *err);

#ifdef __cplusplus
}
#endif
#endif
