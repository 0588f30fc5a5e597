/* The program cache on disk (gs_program_cache.h): a render whose programs
 * come from the cache gives the same image, bit for bit, as one that
 * compiled them and as one with the cache off; a program is found again
 * only for the same sources and the same driver (a changed define or
 * driver string is a miss); a binary the driver refuses and a foreign file
 * are misses that remove the file; a cache that cannot be written never
 * fails a render. The cache lives in a temporary directory of its own
 * (SHAFTS_PROGRAM_CACHE). */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "gs_context.h"
#include "gs_program_cache.h"
#include "sh_str.h"
#include "test_util.h"

static const char *SCENE =
    "{\"format\": \"shafts-scene\", \"version\": 1,"
    " \"camera\": {\"position\": [2.5, 2, 3], \"look_at\": [0, 0.6, 0],"
    "  \"fov_y_deg\": 45, \"width\": 48, \"height\": 36},"
    " \"medium\": {\"sigma_s\": [0.2, 0.2, 0.2], \"sigma_a\": [0.01, 0.01, 0.01],"
    "  \"phase\": {\"type\": \"henyey_greenstein\", \"g\": 0.3},"
    "  \"bounds\": {\"min\": [-3, 0, -3], \"max\": [3, 4, 3]}},"
    " \"lights\": [{\"type\": \"spot\", \"position\": [-0.5, 3.2, 0.2],"
    "  \"look_at\": [0, 0, 0], \"intensity\": [40, 40, 40],"
    "  \"outer_angle_deg\": 28, \"inner_angle_deg\": 20}],"
    " \"materials\": {\"grey\": {\"diffuse\": [0.6, 0.6, 0.6]}},"
    " \"shapes\": [{\"type\": \"box\", \"min\": [-3, -0.1, -3], \"max\": [3, 0, 3],"
    "  \"material\": \"grey\"},"
    "  {\"type\": \"sphere\", \"center\": [0, 0.6, 0], \"radius\": 0.5,"
    "   \"material\": \"grey\"}]}";

static int same_image(const sh_image *a, const sh_image *b) {
  return a->rgb && b->rgb && a->width == b->width && a->height == b->height &&
         !memcmp(a->rgb, b->rgb, sizeof(float) * 3 * a->width * a->height);
}

/* Renders with the cache at `where` ("off" for none). */
static sh_status render(const sh_scene *scene, const char *where, sh_image *out) {
  setenv("SHAFTS_PROGRAM_CACHE", where, 1);
  return tu_gl(scene, NULL, out);
}

static void test_renders(const sh_scene *scene, const char *dir) {
  sh_image fresh = {0}, stored = {0}, cached = {0};
  tu_check(render(scene, "off", &fresh) == SH_OK, "a render with the cache off");
  gs__program_cache_counts c0 = gs__program_cache_counts_get();
  tu_check(c0.hits == 0 && c0.misses == 0 && c0.stores == 0,
           "the cache off is not even looked at");
  tu_check(render(scene, dir, &stored) == SH_OK, "a render filling the cache");
  gs__program_cache_counts c1 = gs__program_cache_counts_get();
  printf("filling: %ld misses, %ld stored\n", c1.misses, c1.stores);
  tu_check(c1.misses > 0 && c1.stores == c1.misses && c1.hits == 0,
           "every program was looked for, compiled and stored");
  tu_check(render(scene, dir, &cached) == SH_OK, "a render from the cache");
  gs__program_cache_counts c2 = gs__program_cache_counts_get();
  printf("from the cache: %ld hits\n", c2.hits);
  tu_check(c2.hits == c1.stores && c2.misses == c1.misses && c2.stores == c1.stores,
           "the second render loads every program and compiles none");
  tu_check(same_image(&stored, &fresh), "compiled with the cache on = cache off, bit for bit");
  tu_check(same_image(&cached, &fresh), "loaded from the cache = compiled, bit for bit");

  /* Another intensity: baked into the programs as a constant, so their
   * sources change and the cache must miss on them. */
  char *json = strdup(SCENE), *at = strstr(json, "[40, 40, 40]");
  memcpy(at, "[50, 50, 50]", 12);
  sh_scene *brighter = tu_scene(json);
  free(json);
  sh_image img = {0};
  tu_check(brighter && render(brighter, dir, &img) == SH_OK, "a render with another intensity");
  gs__program_cache_counts c3 = gs__program_cache_counts_get();
  printf("another intensity: %ld misses, %ld hits\n", c3.misses - c2.misses, c3.hits - c2.hits);
  tu_check(c3.misses > c2.misses, "changed sources are compiled, not taken from the cache");
  tu_check(img.rgb && !same_image(&img, &cached), "and the image changes");
  sh_image_free(&img);
  sh_scene_free(brighter);
  sh_image_free(&fresh);
  sh_image_free(&stored);
  sh_image_free(&cached);
}

/* The size of a file, -1 if it does not exist. */
static long file_size(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return -1;
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fclose(f);
  return n;
}

/* Reads the key held by one cache file of dir (the first found): the
 * header is 8 magic bytes and three 32-bit counts (format, key and binary
 * lengths). Returns it malloc'ed, or NULL. */
static char *key_of_a_file(const char *dir, size_t *len) {
  DIR *d = opendir(dir);
  if (!d) return NULL;
  char *path = NULL;
  for (struct dirent *de; !path && (de = readdir(d));)
    if (strlen(de->d_name) + 1 == GS__CACHE_NAME_SIZE && strstr(de->d_name, ".bin"))
      path = sh__printf_alloc("%s/%s", dir, de->d_name);
  closedir(d);
  FILE *f = path ? fopen(path, "rb") : NULL;
  free(path);
  if (!f) return NULL;
  unsigned char h[20];
  char *key = NULL;
  if (fread(h, 1, 20, f) == 20) {
    unsigned n;
    memcpy(&n, h + 12, 4);
    key = malloc(n ? n : 1);
    if (key && fread(key, 1, n, f) != n) {
      free(key);
      key = NULL;
    }
    *len = n;
  }
  fclose(f);
  return key;
}

/* Keys, with a context current: only the same sources and driver hit. The
 * key of a program the renders stored is the driver's description, a NUL,
 * then each stage's sources, each followed by a NUL. */
static void test_keys(const char *dir) {
  gs__context *ctx = NULL;
  sh_error err = SH_ERROR_INIT;
  if (gs__context_create(GS_BACKEND_AUTO, &ctx, &err) != SH_OK) {
    tu_check(0, "a GL context for the key tests");
    return;
  }
  size_t n = 0;
  char *same = key_of_a_file(dir, &n);
  tu_check(same != NULL, "a stored program's key");
  if (!same) {
    gs__context_release(ctx);
    gs__context_free(ctx);
    return;
  }
  char driver[1024];
  gs__program_cache_driver(driver, sizeof driver);
  printf("driver: %s", driver);
  tu_check(!strcmp(same, driver), "the key starts with the current driver's description");
  /* The same sources, another driver string. */
  const char *other = "Another Vendor\nAnother GPU\n4.6.0 99.9\n4.60\nshafts 0.1.0\n";
  size_t skip = strlen(same) + 1, n_drv = strlen(other) + 1 + (n - skip);
  char *drv = malloc(n_drv);
  memcpy(drv, other, strlen(other) + 1);
  memcpy(drv + strlen(other) + 1, same + skip, n - skip);
  /* The same driver, one character of the sources changed. */
  char *src = malloc(n);
  memcpy(src, same, n);
  src[skip + (n - skip) / 2] ^= 1;

  GLuint p = gs__program_cache_load_key(dir, same, n);
  tu_check(p != 0, "the same sources and driver: found");
  tu_check(gs__program_cache_load_key(dir, src, n) == 0, "a changed source: not found");
  tu_check(gs__program_cache_load_key(dir, drv, n_drv) == 0, "another driver: not found");
  tu_check(p && gs__program_cache_store_key(dir, drv, n_drv, p) == 1,
           "stored under another driver string");
  GLuint q = gs__program_cache_load_key(dir, drv, n_drv);
  tu_check(q != 0, "found under that driver string");
  if (q) glDeleteProgram(q);
  q = gs__program_cache_load_key(dir, same, n);
  tu_check(q != 0, "and still under the real one (two files)");
  if (q) glDeleteProgram(q);
  if (p) glDeleteProgram(p);

  /* A binary the driver refuses: the bytes after the file's key
   * overwritten (the header is 20 bytes). */
  char name[GS__CACHE_NAME_SIZE];
  gs__program_cache_name(drv, n_drv, name);
  char *path = sh__printf_alloc("%s/%s", dir, name);
  tu_check(file_size(path) > 0, "the file of the key is there");
  FILE *f = fopen(path, "r+b");
  if (f) {
    long size = file_size(path);
    fseek(f, 20 + (long)n_drv, SEEK_SET);
    for (long i = 20 + (long)n_drv; i < size && i < 20 + (long)n_drv + 64; i++) fputc(0xA5, f);
    fclose(f);
  }
  p = gs__program_cache_load_key(dir, drv, n_drv);
  GLenum gl_err = glGetError();
  printf("corrupted binary: program %u, GL error 0x%x\n", p, gl_err);
  tu_check(p == 0 && gl_err == GL_NO_ERROR,
           "a corrupted binary is refused, with no GL error left");
  if (p) glDeleteProgram(p);
  tu_check(file_size(path) < 0, "and its file removed");
  /* A foreign file under a key's name. */
  f = fopen(path, "wb");
  if (f) {
    fputs("not a program", f);
    fclose(f);
  }
  tu_check(gs__program_cache_load_key(dir, drv, n_drv) == 0 && file_size(path) < 0,
           "a foreign file is a miss, removed");
  free(path);
  free(same);
  free(src);
  free(drv);
  gs__context_release(ctx);
  gs__context_free(ctx);
  sh_error_clear(&err);
}

/* Whether SHAFTS_PROGRAM_CACHE (or, unset, XDG_CACHE_HOME or HOME) gives
 * the directory `want` (NULL: the cache off). */
static int dir_is(const char *want) {
  char *got = gs__program_cache_dir();
  int ok = want ? got && !strcmp(got, want) : got == NULL;
  free(got);
  return ok;
}

static void test_unwritable(const sh_scene *scene, const char *dir) {
  char *file = sh__printf_alloc("%s/a_file", dir);
  char *below = sh__printf_alloc("%s/programs", file);
  FILE *f = fopen(file, "wb");
  if (f) fclose(f);
  sh_image img = {0};
  gs__program_cache_counts c0 = gs__program_cache_counts_get();
  tu_check(render(scene, below, &img) == SH_OK,
           "a cache directory that cannot be made does not fail the render");
  gs__program_cache_counts c1 = gs__program_cache_counts_get();
  tu_check(c1.stores == c0.stores, "and nothing is stored");
  sh_image_free(&img);
  remove(file);
  free(file);
  free(below);
  setenv("SHAFTS_PROGRAM_CACHE", "off", 1);
  tu_check(dir_is(NULL), "SHAFTS_PROGRAM_CACHE=off turns it off");
  setenv("SHAFTS_PROGRAM_CACHE", "", 1);
  tu_check(dir_is(NULL), "SHAFTS_PROGRAM_CACHE= turns it off");
  unsetenv("SHAFTS_PROGRAM_CACHE");
  setenv("XDG_CACHE_HOME", "/somewhere", 1);
  tu_check(dir_is("/somewhere/shafts/programs"), "XDG_CACHE_HOME/shafts/programs");
  unsetenv("XDG_CACHE_HOME");
  setenv("HOME", "/home/someone", 1);
  tu_check(dir_is("/home/someone/.cache/shafts/programs"), "else ~/.cache/shafts/programs");
}

/* A cache directory longer than PATH_MAX (4096): 30 nested directories of
 * 200 characters under the temporary directory, which open(2) refuses as
 * one path (ENAMETOOLONG). The cache makes it, stores every program there
 * and loads them again, bit for bit (issue 11: no path is cut or turns a
 * feature off by its length). */
static void test_long_dir(const sh_scene *scene, const char *dir) {
  char part[201];
  memset(part, 'd', 200);
  part[200] = '\0';
  char *lng = sh__printf_alloc("%s", dir);
  for (int i = 0; lng && i < 30; i++) {
    char *next = sh__printf_alloc("%s/%02d%s", lng, i, part + 2);
    free(lng);
    lng = next;
  }
  if (!lng) {
    tu_check(0, "memory for a long directory");
    return;
  }
  printf("a cache directory of %zu characters\n", strlen(lng));
  tu_check(strlen(lng) > 6000, "the directory is longer than PATH_MAX");
  setenv("SHAFTS_PROGRAM_CACHE", lng, 1);
  tu_check(dir_is(lng), "and kept whole");
  sh_image fresh = {0}, stored = {0}, cached = {0};
  tu_check(render(scene, "off", &fresh) == SH_OK, "a render with the cache off");
  gs__program_cache_counts c0 = gs__program_cache_counts_get();
  tu_check(render(scene, lng, &stored) == SH_OK, "a render filling the long directory");
  gs__program_cache_counts c1 = gs__program_cache_counts_get();
  tu_check(render(scene, lng, &cached) == SH_OK, "a render from the long directory");
  gs__program_cache_counts c2 = gs__program_cache_counts_get();
  printf("long directory: %ld stored, then %ld hits\n", c1.stores - c0.stores,
         c2.hits - c1.hits);
  tu_check(c1.stores > c0.stores && c1.stores - c0.stores == c1.misses - c0.misses,
           "every program is stored in the long directory");
  tu_check(c2.hits - c1.hits == c1.stores - c0.stores && c2.misses == c1.misses,
           "and every one loaded from it");
  tu_check(same_image(&stored, &fresh) && same_image(&cached, &fresh),
           "the same image, bit for bit");
  int fd = gs__program_cache_open_dir(lng, 0);
  tu_check(fd >= 0, "the long directory exists");
  if (fd >= 0) close(fd);
  sh_image_free(&fresh);
  sh_image_free(&stored);
  sh_image_free(&cached);
  free(lng);
}

/* Removes the cache directory's files and the directory. */
static void clean(const char *dir) {
  char *cmd = sh__printf_alloc("rm -rf '%s'", dir);
  if (!cmd || system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
  free(cmd);
}

int main(void) {
  const char *base = getenv("TMPDIR");
  char *dir = sh__printf_alloc("%s/program_cache_test.XXXXXX", base && *base ? base : "/tmp");
  if (!dir || !mkdtemp(dir)) {
    perror("mkdtemp");
    return 1;
  }
  sh_scene *scene = tu_scene(SCENE);
  if (!scene) return 1;
  test_renders(scene, dir);
  test_keys(dir);
  test_long_dir(scene, dir);
  test_unwritable(scene, dir);
  sh_scene_free(scene);
  clean(dir);
  free(dir);
  printf("%s\n", tu_failures ? "FAILED" : "all passed");
  return tu_failures ? 1 : 0;
}
