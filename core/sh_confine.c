#include "sh_confine.h"

#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

/* Whether the resolved `real` is `real_root` or lies below it at a path
 * boundary ("/a/b" holds "/a/b/c", not "/a/bc"); the root "/" holds
 * everything. */
static int below(const char *real, const char *real_root) {
  size_t n = strlen(real_root);
  return strncmp(real, real_root, n) == 0 &&
         (real[n] == '\0' || real[n] == '/' || (n > 0 && real_root[n - 1] == '/'));
}

static int confined(const char *path, const char *root, char **resolved,
                    char *(*resolve)(const char *)) {
  if (resolved) *resolved = NULL;
  char *real_root = realpath(root && *root ? root : ".", NULL);
  if (!real_root) return -1;
  char *real = resolve(path);
  if (!real) {
    int e = errno;
    free(real_root);
    errno = e;
    return -1;
  }
  int inside = below(real, real_root);
  free(real_root);
  if (resolved)
    *resolved = real;
  else
    free(real);
  return inside;
}

static char *resolve_existing(const char *path) { return realpath(path, NULL); }

/* `path` resolved as far as it exists: its deepest existing ancestor with
 * realpath (links followed), then the rest of its components with "." and
 * ".." taken by name (a ".." past a missing directory climbs all the
 * same). NULL only when out of memory (errno ENOMEM). */
static char *resolve_placed(const char *path) {
  char *real = realpath(path, NULL);
  if (real) return real;
  size_t len = strlen(path);
  char *head = malloc(len + 2);
  if (!head) return NULL;
  memcpy(head, path, len + 1);
  /* Strip components from the end until what is left resolves; "." (or
   * "/" for an absolute name) always does. */
  size_t cut = len;
  for (;;) {
    while (cut > 0 && head[cut - 1] == '/') cut--;
    while (cut > 0 && head[cut - 1] != '/') cut--;
    while (cut > 1 && head[cut - 1] == '/') cut--;
    if (cut == 0) {
      strcpy(head, path[0] == '/' ? "/" : ".");
    } else {
      head[cut] = '\0';
    }
    real = realpath(head, NULL);
    if (real || cut == 0) break;
  }
  free(head);
  if (!real) return NULL;
  const char *rest = path + cut;
  size_t n = strlen(real);
  char *out = malloc(n + strlen(rest) + 2);
  if (!out) {
    free(real);
    errno = ENOMEM;
    return NULL;
  }
  memcpy(out, real, n + 1);
  free(real);
  while (*rest) {
    while (*rest == '/') rest++;
    size_t k = strcspn(rest, "/");
    if (k == 0) break;
    if (k == 2 && rest[0] == '.' && rest[1] == '.') {
      char *slash = strrchr(out, '/');
      if (slash) {
        n = slash == out ? 1 : (size_t)(slash - out);
        out[n] = '\0';
      }
    } else if (!(k == 1 && rest[0] == '.')) {
      if (!(n == 1 && out[0] == '/')) out[n++] = '/';
      memcpy(out + n, rest, k);
      n += k;
      out[n] = '\0';
    }
    rest += k;
  }
  return out;
}

int sh__confined(const char *path, const char *root, char **resolved) {
  return confined(path, root, resolved, resolve_existing);
}

int sh__confined_name(const char *path, const char *root, char **resolved) {
  return confined(path, root, resolved, resolve_placed);
}
