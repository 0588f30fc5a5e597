/* Error reports (sh_error.h): strings of any length owned by the report,
 * set, located, moved and cleared; a scene path of 5000 characters and a
 * mesh named by one reach the report whole (issue 11, kind 5: the report
 * held file[512], path[256] and message[1024] and cut what was longer). */
#define _GNU_SOURCE /* O_PATH */
#include "sh_error.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sh_str.h"
#include "sh_test.h"
#include "shafts.h"

/* A string of n characters: 'a'..'z' over and over. */
static char *letters(size_t n) {
  char *s = malloc(n + 1);
  if (!s) return NULL;
  for (size_t i = 0; i < n; i++) s[i] = (char)('a' + i % 26);
  s[n] = '\0';
  return s;
}

static void test_report(void) {
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(err.status == SH_OK && !strcmp(err.message, "") && !err.block_);
  char *file = letters(5000), *key = letters(3000), *msg = letters(7000);
  SH_CHECK(file && key && msg);
  if (!file || !key || !msg) return;
  SH_CHECK(sh_error_set(&err, SH_ERR_SCENE, "bad: %s", msg) == SH_ERR_SCENE);
  sh_error_set_file(&err, file);
  sh_error_set_key(&err, "lights[%d].%s", 2, key);
  err.line = 3;
  err.column = 4;
  SH_CHECK(err.status == SH_ERR_SCENE && !strcmp(err.file, file));
  SH_CHECK(strlen(err.path) == 10 + 3000 && !strncmp(err.path, "lights[2].abc", 13));
  SH_CHECK(strlen(err.message) == 5 + 7000 && !strcmp(err.message + 5, msg));
  /* The formatted text, whole on the heap; cut to a buffer, with the
   * length it would need, as snprintf. */
  char *text = sh_error_text(&err);
  size_t want = 5000 + 6 + 3010 + 2 + 7005; /* file:3:4: key: message */
  SH_CHECK(text && strlen(text) == want && !strncmp(text + 5000, ":3:4: lights[2]", 15));
  char small[16];
  SH_CHECK(sh_error_format(&err, small, sizeof small) == want &&
           strlen(small) == sizeof small - 1);
  free(text);
  /* Setting again frees what it held, and may wrap its own message. */
  sh_error_set(&err, SH_ERR_IO, "again: %s", err.message);
  SH_CHECK(err.status == SH_ERR_IO && strlen(err.message) == 7 + 5 + 7000);
  SH_CHECK(!strcmp(err.file, "") && !strcmp(err.path, "") && err.line == 0);
  /* Moved: the target owns the strings, the source is initialised. */
  sh_error to = SH_ERROR_INIT;
  sh_error_set(&to, SH_ERR_ARG, "to be replaced");
  sh_error_move(&to, &err);
  SH_CHECK(to.status == SH_ERR_IO && strlen(to.message) == 7012);
  SH_CHECK(err.status == SH_OK && !err.block_ && !strcmp(err.message, ""));
  sh_error_move(NULL, &to); /* only cleared */
  SH_CHECK(to.status == SH_OK && !to.block_);
  /* NULL reports are ignored; a zeroed one reads as empty. */
  SH_CHECK(sh_error_set(NULL, SH_ERR_IO, "x") == SH_ERR_IO);
  sh_error_set_file(NULL, "x");
  sh_error_set_key(NULL, "x");
  sh_error_clear(NULL);
  sh_error zero = {0};
  SH_CHECK(!strcmp(sh_error_file(&zero), "") && !strcmp(sh_error_key(&zero), ""));
  SH_CHECK(!strcmp(sh_error_message(&zero), "no error"));
  SH_CHECK(sh_error_format(&zero, small, sizeof small) == 8 && !strcmp(small, "no error"));
  sh_error_set(&zero, SH_ERR_MESH, "%s", "");
  SH_CHECK(!strcmp(sh_error_message(&zero), "mesh error"));
  sh_error_clear(&zero);
  /* The heap report of the bindings. */
  sh_error *h = sh_error_new();
  SH_CHECK(h && !strcmp(sh_error_message(h), "no error"));
  if (h) {
    sh_error_set(h, SH_ERR_IMAGE, "%s", msg);
    sh_error_set_file(h, file);
    SH_CHECK(!strcmp(sh_error_file(h), file) && !strcmp(sh_error_message(h), msg));
  }
  sh_error_free(h);
  sh_error_free(NULL);
  free(file);
  free(key);
  free(msg);
  sh_error_clear(&err);
  sh_error_clear(&to);
}

/* Makes `levels` nested directories of `width` characters under dir,
 * through directory descriptors (the whole path is longer than open(2)
 * takes), with a file `name` holding `text` in the deepest. Returns the
 * relative path "d.../d.../name", or NULL. */
static char *deep_file(const char *dir, int levels, size_t width,
                       const char *name, const char *text) {
  char *part = letters(width), *rel = sh__printf_alloc("%s", "");
  int fd = open(dir, O_PATH | O_DIRECTORY);
  for (int i = 0; part && rel && fd >= 0 && i < levels; i++) {
    part[0] = (char)('0' + i % 10);
    int made = mkdirat(fd, part, 0700) == 0 || errno == EEXIST;
    int next = made ? openat(fd, part, O_PATH | O_DIRECTORY) : -1;
    close(fd);
    fd = next;
    char *longer = sh__printf_alloc("%s%s/", rel, part);
    free(rel);
    rel = longer;
  }
  int out = fd >= 0 ? openat(fd, name, O_WRONLY | O_CREAT | O_TRUNC, 0600) : -1;
  int ok = out >= 0 && write(out, text, strlen(text)) == (ssize_t)strlen(text);
  if (out >= 0) close(out);
  if (fd >= 0) close(fd);
  char *path = ok && rel ? sh__printf_alloc("%s%s", rel, name) : NULL;
  free(part);
  free(rel);
  return path;
}

/* A scene file at the end of a path of 5000 characters: open(2) refuses
 * the path (ENAMETOOLONG), and the report names it whole; a scene that
 * names a mesh by a relative path of 5000 characters gets a message and a
 * formatted text holding that path whole. */
static void test_long_paths(const char *tmp) {
  size_t width = 199;
  int levels = (int)((5000 - strlen(tmp)) / (width + 1)) + 1;
  char *rel = deep_file(tmp, levels, width, "scene.json", "{\"format\": ");
  char *path = rel ? sh__printf_alloc("%s/%s", tmp, rel) : NULL;
  SH_CHECK(path && strlen(path) >= 5000);
  if (!path) return;
  printf("a scene path of %zu characters\n", strlen(path));
  sh_error err = SH_ERROR_INIT;
  sh_scene *s = NULL;
  SH_CHECK(sh_scene_load(path, &s, &err) == SH_ERR_IO && s == NULL);
  SH_CHECK(!strcmp(err.file, path));
  char *text = sh_error_text(&err);
  SH_CHECK(text && !strncmp(text, path, strlen(path)) &&
           strstr(text, "File name too long"));
  free(text);

  char *mesh = deep_file(tmp, levels, width, "m.obj", "v 0 0 0\n");
  char *scene = mesh ? sh__printf_alloc(
      "{\"format\": \"shafts-scene\", \"version\": 1,\n"
      " \"camera\": {\"position\": [0, 0, 5], \"look_at\": [0, 0, 0],"
      " \"fov_y_deg\": 40, \"width\": 8, \"height\": 6},\n"
      " \"materials\": {\"m\": {}},\n"
      " \"shapes\": [{\"type\": \"mesh\", \"material\": \"m\", \"file\": \"%s\"}]}",
      mesh) : NULL;
  SH_CHECK(scene != NULL);
  if (scene) {
    SH_CHECK(sh_scene_parse(scene, "long.json", tmp, &s, &err) == SH_ERR_IO);
    SH_CHECK(strstr(err.message, mesh) != NULL && !strcmp(err.path, "shapes[0].file") &&
             err.line == 4 && !strcmp(err.file, "long.json"));
    if (!strstr(err.message, mesh)) fprintf(stderr, "  got: %.200s...\n", err.message);
  }
  sh_error_clear(&err);
  free(scene);
  free(mesh);
  free(path);
  free(rel);
}

int main(void) {
  const char *base = getenv("TMPDIR");
  char *dir = sh__printf_alloc("%s/sh_error_test.XXXXXX", base && *base ? base : "/tmp");
  if (!dir || !mkdtemp(dir)) {
    perror("mkdtemp");
    return EXIT_FAILURE;
  }
  test_report();
  test_long_paths(dir);
  char *rm = sh__printf_alloc("rm -rf '%s'", dir);
  if (!rm || system(rm) != 0) fprintf(stderr, "could not remove %s\n", dir);
  free(rm);
  free(dir);
  SH_TEST_DONE();
}
