/* Helpers of the tests of the core's own mesh readers (sh_ply_test.c,
 * sh_off_test.c): files written into a test directory and loaded through
 * sh_mesh_load, which must give so many triangles, or fail at once with a
 * located error. */
#ifndef SH_MESH_TEST_UTIL_H
#define SH_MESH_TEST_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sh_mesh.h"
#include "sh_test.h"

/* The test's directory (sh_test_tmpdir) and the last path written. */
static char sh_mesh_test_dir[256];
static char sh_mesh_test_path[512];

/* Writes n bytes to the test directory's file `name`; returns its path
 * (static). */
static SH_TEST__UNUSED const char *write_bytes(const char *name, const void *data, size_t n) {
  snprintf(sh_mesh_test_path, sizeof sh_mesh_test_path, "%s/%s", sh_mesh_test_dir, name);
  FILE *f = fopen(sh_mesh_test_path, "wb");
  if (f) {
    fwrite(data, 1, n, f);
    fclose(f);
  }
  return sh_mesh_test_path;
}

static SH_TEST__UNUSED const char *write_text(const char *name, const char *text) {
  return write_bytes(name, text, strlen(text));
}

/* Loads name (written from text) and expects ntris triangles on nverts
 * vertices, every index in range; the mesh stays in *out if out is not
 * NULL (the caller frees it). */
static SH_TEST__UNUSED void expect_mesh(const char *name, const char *text, int ntris,
                                        int nverts, sh_mesh *out) {
  sh_mesh m;
  sh_error err = SH_ERROR_INIT;
  sh_status s = sh_mesh_load(write_text(name, text), NULL, &m, &err);
  if (s != SH_OK) fprintf(stderr, "%s: %s\n", name, err.message);
  SH_CHECK(s == SH_OK);
  if (s == SH_OK) {
    if (m.ntris != ntris || m.nverts != nverts)
      fprintf(stderr, "%s: %d triangles, %d vertices; want %d, %d\n", name,
              m.ntris, m.nverts, ntris, nverts);
    SH_CHECK(m.ntris == ntris && m.nverts == nverts);
    for (int i = 0; i < 3 * m.ntris; i++) SH_CHECK(m.indices[i] < (unsigned)m.nverts);
  }
  if (out && s == SH_OK)
    *out = m;
  else
    sh_mesh_free(&m);
  sh_error_clear(&err);
}

static SH_TEST__UNUSED void expect_tris(const char *name, const char *text, int ntris,
                                        int nverts) {
  expect_mesh(name, text, ntris, nverts, NULL);
}

/* Loads data and expects SH_ERR_MESH whose message names the file and
 * holds `want`, with the error's line `line` (-1: not checked), in well
 * under a second. */
static SH_TEST__UNUSED void expect_error_at(const char *name, const void *data, size_t n,
                                            int line, const char *want) {
  sh_mesh m;
  sh_error err = SH_ERROR_INIT;
  struct timespec t0, t1;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  sh_status s = sh_mesh_load(write_bytes(name, data, n), NULL, &m, &err);
  clock_gettime(CLOCK_MONOTONIC, &t1);
  double secs = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
  int ok = s == SH_ERR_MESH && strstr(err.message, want) && strstr(err.message, name) &&
           (line < 0 || (err.line == line && strstr(err.file, name)));
  if (!ok)
    fprintf(stderr, "%s: status %d, '%s' (line %d); want SH_ERR_MESH naming the file and "
            "'%s' (line %d)\n", name, s, s ? err.message : "", s ? err.line : 0, want, line);
  SH_CHECK(ok);
  SH_CHECK(m.positions == NULL && m.ntris == 0);
  if (secs > 1.0) fprintf(stderr, "%s: %.2f s\n", name, secs);
  SH_CHECK(secs < 1.0);
  sh_error_clear(&err);
}

static SH_TEST__UNUSED void expect_error(const char *name, const void *data, size_t n,
                                         const char *want) {
  expect_error_at(name, data, n, -1, want);
}

static SH_TEST__UNUSED void expect_text(const char *name, const char *text, const char *want) {
  expect_error(name, text, strlen(text), want);
}

static SH_TEST__UNUSED void expect_text_at(const char *name, const char *text, int line,
                                           const char *want) {
  expect_error_at(name, text, strlen(text), line, want);
}

/* Reads the input fuzz/known/NAME of the source tree ($SHAFTS_SOURCE_DIR)
 * into buf (at most cap bytes); returns its size, 0 if it cannot be read. */
static SH_TEST__UNUSED size_t read_known(const char *name, unsigned char *buf, size_t cap) {
  const char *src = getenv("SHAFTS_SOURCE_DIR");
  char known[1024];
  snprintf(known, sizeof known, "%s/fuzz/known/%s", src ? src : "..", name);
  FILE *f = fopen(known, "rb");
  if (!f) {
    perror(known);
    return 0;
  }
  size_t n = fread(buf, 1, cap, f);
  fclose(f);
  return n;
}

#endif
