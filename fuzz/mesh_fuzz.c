/* libFuzzer harness of the mesh-loading path (sh_mesh_load: the confined
 * assimp file system, the import, the finiteness checks, and the core's
 * own readers of PLY and OFF files, sh_ply.h and sh_off.h): the first byte
 * picks the format (OBJ, PLY, glTF, STL, OFF), the rest is the file,
 * written into a directory of the process's own and loaded from there.
 * Seeds: fuzz/corpus/mesh (docs/fuzzing.md). */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sh_mesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char dir[64];
static char path[96];

static void remove_dir(void) {
  unlink(path);
  rmdir(dir);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static const char *const ext[] = {"obj", "ply", "gltf", "stl", "off"};
  if (size < 1) return 0;
  if (!dir[0]) {
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/shafts_mesh_fuzz.XXXXXX",
             tmp && *tmp && strlen(tmp) < 30 ? tmp : "/tmp");
    if (!mkdtemp(dir)) abort();
    atexit(remove_dir);
  }
  unlink(path);
  snprintf(path, sizeof path, "%s/m.%s", dir, ext[data[0] % 5]);
  FILE *f = fopen(path, "wb");
  if (!f) abort();
  fwrite(data + 1, 1, size - 1, f);
  fclose(f);
  sh_mesh mesh;
  sh_error err = SH_ERROR_INIT;
  if (sh_mesh_load(path, dir, &mesh, &err) == SH_OK) sh_mesh_free(&mesh);
  sh_error_clear(&err);
  return 0;
}
