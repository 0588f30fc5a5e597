/* The scene parser's external files: names resolved against the scene's
 * directory, checked, and images read. */
#include "sh_parse_int.h"
#include "sh_file.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "sh_confine.h"

sh_status sh__resolve_file(sh__parser *p, const char *key, const char *name,
                           char **out) {
  const char *base = p->base_dir;
  size_t bl = base ? strlen(base) : 0;
  if (!name[0])
    return sh__fail_at(&p->c, key, SH_ERR_SCENE,
                       "expected a file name, found an empty string");
  /* A scene file names only files in its own directory tree: an absolute
   * name could be any file of the system (issue 11, files that escape).
   * Text a program passes in (sh_scene_parse) may: the program chose. */
  if (name[0] == '/' && !p->absolute_ok)
    return sh__fail_at(&p->c, key, SH_ERR_SCENE,
                       "the file name '%s' is absolute: a scene names its "
                       "files relative to its own directory, inside its tree",
                       name);
  char *path = malloc(bl + strlen(name) + 2);
  if (!path) return sh__fail_at(&p->c, key, SH_ERR_NOMEM, "out of memory");
  if (bl == 0 || name[0] == '/')
    strcpy(path, name);
  else
    sprintf(path, "%s%s%s", base, base[bl - 1] == '/' ? "" : "/", name);
  *out = path;
  return SH_OK;
}

sh_status sh__check_file(sh__parser *p, const char *key, const char *name,
                         const char *path, const char *kind,
                         sh_status empty_status) {
  /* Relative names must stay in the scene's tree: checked first, so that
   * a name outside it is refused as such whether or not the file exists
   * (a missing "../x.obj" was reported as missing). */
  char *real = NULL;
  int inside = name[0] == '/' ? 1 : sh__confined_name(path, p->base_dir, &real);
  if (inside == 0) {
    sh_status st = sh__fail_at(
        &p->c, key, SH_ERR_SCENE,
        "the %s '%s' resolves to '%s', outside the scene's directory '%s': "
        "a scene uses only files in its own directory tree",
        kind, name, real, p->base_dir && *p->base_dir ? p->base_dir : ".");
    free(real);
    return st;
  }
  free(real);
  struct stat sb;
  if (stat(path, &sb) != 0)
    return sh__fail_at(&p->c, key, SH_ERR_IO,
                       "cannot open the %s '%s' (resolved to '%s'): %s", kind,
                       name, path, strerror(errno));
  if (!S_ISREG(sb.st_mode))
    return sh__fail_at(&p->c, key, SH_ERR_IO,
                       "the %s '%s' (resolved to '%s') is %s, not a regular "
                       "file",
                       kind, name, path, sh_file_kind(sb.st_mode));
  if (sb.st_size == 0)
    return sh__fail_at(&p->c, key, empty_status,
                       "the %s '%s' (resolved to '%s') is an empty file", kind,
                       name, path);
  return SH_OK;
}

sh_status sh__load_image(sh__parser *p, json_t *obj, const char *key,
                         int data, sh_image *img, char **path_out) {
  const char *name;
  char *path = NULL;
  sh_status st;
  sh_error e = SH_ERROR_INIT;
  if ((st = sh__string(&p->c, obj, key, 1, &name))) return st;
  if ((st = sh__resolve_file(p, key, name, &path))) return st;
  if ((st = sh__check_file(p, key, name, path, "image", SH_ERR_IMAGE)))
    goto out;
  if ((st = data ? sh_image_read_data(path, img, &e)
                  : sh_image_read(path, img, &e))) {
    const char *fmt = "cannot read the image '%s': ";
    size_t n = strlen(fmt) + strlen(path);
    char *prefix = malloc(n);
    if (prefix) snprintf(prefix, n, fmt, path);
    sh__fail_from(&p->c, key, &e, prefix ? prefix : "cannot read an image: ");
    free(prefix);
    goto out;
  }
  if (img->width < 1 || img->height < 1 || !img->rgb) {
    st = sh__fail_at(&p->c, key, SH_ERR_IMAGE, "the image '%s' has no pixels",
                     path);
    goto out;
  }
  /* Texels scale light (maps) or give heights: each must be a finite,
   * non-negative number, or the radiance would be NaN, infinite or
   * negative. The first bad texel is named (column, row from the top). */
  for (long i = 0; i < (long)img->width * img->height * 3; i++) {
    float v = img->rgb[i];
    if (isfinite(v) && v >= 0.0f) continue;
    long px = i / 3;
    st = sh__fail_at(&p->c, key, SH_ERR_IMAGE,
                     "the image '%s' has the value %g at texel (%ld, %ld), "
                     "channel %c: expected a finite number >= 0",
                     path, (double)v, px % img->width, px / img->width,
                     "RGB"[i % 3]);
    sh_image_free(img);
    goto out;
  }
out:
  sh_error_clear(&e);
  if (st == SH_OK && path_out)
    *path_out = path;
  else
    free(path);
  return st;
}
