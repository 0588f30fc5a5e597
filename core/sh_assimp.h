/* Internal to sh_mesh.c (not installed, not exported): assimp's C API,
 * loaded with dlopen the first time a mesh file is loaded rather than
 * linked, so that programs that load no mesh file (every --help, scenes of
 * analytic shapes) do not pay its start-up: libassimp and its 8 libraries
 * cost 2.5-3 ms of CPU before main on this machine, 90% of gl_shafts'
 * start-up once OpenImageIO was gone (gl_shafts/cli_bench.sh).
 *
 * The library is opened by its SONAME (SH_ASSIMP_SONAME, read from the
 * assimp found at configure time), once per process, and never closed. */
#ifndef SH_ASSIMP_H
#define SH_ASSIMP_H

#include "sh_error.h"

#include <assimp/cfileio.h>
#include <assimp/cimport.h>

/* What sh_mesh.c uses: three functions, with assimp's signatures, and the
 * importers' extensions. */
typedef struct sh__assimp {
  const struct aiScene *(*import_file_ex)(const char *file, unsigned flags,
                                          struct aiFileIO *fs);
  const char *(*get_error_string)(void);
  void (*release_import)(const struct aiScene *scene);
  /* Each importer's extensions (its aiImporterDesc's mFileExtensions:
   * "gltf glb", separated by spaces), `nformats` of them, read once when
   * the library is loaded (aiGetImportFormatDescription constructs an
   * Importer, every importer with it, on each call). Owned by this module
   * and assimp, for the life of the process. */
  size_t nformats;
  const char **format_extensions;
} sh__assimp;

/* Loads assimp on first use (thread-safe) and returns its functions, or
 * NULL and SH_ERR_MESH naming the library and why, for the mesh `path`. */
const sh__assimp *sh__assimp_get(const char *path, sh_error *err);

#endif
