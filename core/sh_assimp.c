/* assimp's C API through dlopen (sh_assimp.h). */
#include "sh_assimp.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

#ifndef SH_ASSIMP_SONAME
#define SH_ASSIMP_SONAME "libassimp.so.5"
#endif

static pthread_once_t sh__assimp_once = PTHREAD_ONCE_INIT;
static sh__assimp sh__assimp_fns;
static int sh__assimp_ok;
static char sh__assimp_why[512];

static void sh__assimp_load(void) {
  void *h = dlopen(SH_ASSIMP_SONAME, RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    const char *e = dlerror();
    snprintf(sh__assimp_why, sizeof sh__assimp_why, "%s",
             e ? e : "dlopen failed");
    return;
  }
  /* POSIX dlsym returns data pointers; converting them to function
   * pointers is what dlsym is for. */
  *(void **)&sh__assimp_fns.import_file_ex = dlsym(h, "aiImportFileEx");
  *(void **)&sh__assimp_fns.get_error_string = dlsym(h, "aiGetErrorString");
  *(void **)&sh__assimp_fns.release_import = dlsym(h, "aiReleaseImport");
  size_t (*format_count)(void);
  const struct aiImporterDesc *(*format_description)(size_t index);
  *(void **)&format_count = dlsym(h, "aiGetImportFormatCount");
  *(void **)&format_description = dlsym(h, "aiGetImportFormatDescription");
  if (!sh__assimp_fns.import_file_ex || !sh__assimp_fns.get_error_string ||
      !sh__assimp_fns.release_import || !format_count || !format_description) {
    snprintf(sh__assimp_why, sizeof sh__assimp_why,
             "it lacks aiImportFileEx, aiGetErrorString, aiReleaseImport, "
             "aiGetImportFormatCount or aiGetImportFormatDescription");
    return;
  }
  size_t n = format_count();
  const char **ext = calloc(n ? n : 1, sizeof *ext);
  if (!ext) {
    snprintf(sh__assimp_why, sizeof sh__assimp_why, "out of memory");
    return;
  }
  for (size_t i = 0; i < n; i++) {
    const struct aiImporterDesc *d = format_description(i);
    ext[i] = d && d->mFileExtensions ? d->mFileExtensions : "";
  }
  sh__assimp_fns.nformats = n;
  sh__assimp_fns.format_extensions = ext;
  sh__assimp_ok = 1;
}

const sh__assimp *sh__assimp_get(const char *path, sh_error *err) {
  pthread_once(&sh__assimp_once, sh__assimp_load);
  if (sh__assimp_ok)
    return &sh__assimp_fns;
  sh_error_set(err, SH_ERR_MESH,
               "cannot load mesh '%s': assimp (" SH_ASSIMP_SONAME
               ") could not be loaded: %s",
               path, sh__assimp_why);
  return NULL;
}
