#include "sh_confine.h"

#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

int sh__confined(const char *path, const char *root, char **resolved) {
  if (resolved) *resolved = NULL;
  char *real_root = realpath(root && *root ? root : ".", NULL);
  if (!real_root) return -1;
  char *real = realpath(path, NULL);
  if (!real) {
    int e = errno;
    free(real_root);
    errno = e;
    return -1;
  }
  size_t n = strlen(real_root);
  /* The root itself, or below it at a path boundary ("/a/b" holds "/a/b/c",
   * not "/a/bc"); the root "/" holds everything. */
  int inside = strncmp(real, real_root, n) == 0 &&
               (real[n] == '\0' || real[n] == '/' ||
                (n > 0 && real_root[n - 1] == '/'));
  free(real_root);
  if (resolved)
    *resolved = real;
  else
    free(real);
  return inside;
}
