/* libFuzzer harness of the scene parser: the input is scene text, parsed
 * (sh_scene_parse) against fuzz/assets, so that names of meshes, light
 * maps and heightfields the corpus holds lead into the file checks, the
 * confinement and the loaders too. Any result is fine; a crash, a leak or
 * undefined behaviour is a fault. Seeds: fuzz/corpus/scene, dictionary:
 * fuzz/scene.dict (docs/fuzzing.md). */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sh_parse.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char *text = malloc(size + 1);
  if (!text) return 0;
  memcpy(text, data, size);
  text[size] = '\0';
  sh_scene *scene = NULL;
  sh_error err = SH_ERROR_INIT;
  if (sh_scene_parse(text, "fuzz.json", SHAFTS_FUZZ_ASSETS, &scene, &err) ==
      SH_OK)
    sh_scene_free(scene);
  sh_error_clear(&err);
  free(text);
  return 0;
}
