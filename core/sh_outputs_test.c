/* Tests of sh_outputs.h: outputs that are inputs or other outputs are
 * refused under every spelling (relative, "..", a symbolic link, a hard
 * link), so is an existing file that is not regular; staged outputs have
 * no name in the directory until published (so a SIGKILL leaves nothing);
 * a run that fails leaves no output and keeps the old file's bytes. */
#include "sh_outputs.h"
#include "sh_parse.h"
#include "sh_test.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmpdir[256];

/* tmpdir + "/" + name, malloc'd. */
static char *in_tmp(const char *name) {
  size_t n = strlen(tmpdir) + strlen(name) + 2;
  char *p = malloc(n);
  snprintf(p, n, "%s/%s", tmpdir, name);
  return p;
}

static int count_entries(const char *dir) {
  DIR *d = opendir(dir);
  if (!d) return -1;
  int n = 0;
  struct dirent *e;
  while ((e = readdir(d)))
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
  closedir(d);
  return n;
}

static void put(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  if (f) {
    fputs(text, f);
    fclose(f);
  }
}

static int holds(const char *path, const char *text) {
  char buf[64] = "";
  FILE *f = fopen(path, "r");
  if (!f) return 0;
  size_t n = fread(buf, 1, sizeof buf - 1, f);
  fclose(f);
  buf[n] = '\0';
  return !strcmp(buf, text);
}

/* An output spelled `out` is refused when `in` is the input. */
static void refused_as_input(const char *in, const char *out,
                             const char *why) {
  sh_error err = SH_ERROR_INIT;
  sh_outputs *set = sh_outputs_new();
  SH_CHECK(sh_outputs_input(set, in, "the scene", &err) == SH_OK);
  sh_status st = sh_outputs_add(set, out, "-o", &err);
  SH_CHECK(st == SH_ERR_ARG);
  if (st != SH_ERR_ARG)
    fprintf(stderr, "  %s: '%s' as output of '%s' was accepted\n", why, out, in);
  else
    SH_CHECK(strstr(err.message, "must not overwrite an input") != NULL);
  sh_outputs_free(set);
  sh_error_clear(&err);
}

static void test_refusals(void) {
  char *scene = in_tmp("s.json"), *sub = in_tmp("sub");
  put(scene, "{}");
  SH_CHECK(mkdir(sub, 0700) == 0);
  char *dotdot = in_tmp("sub/../s.json"), *dots = in_tmp("./sub/.//../s.json");
  char *slink = in_tmp("link.json"), *hard = in_tmp("hard.json");
  SH_CHECK(symlink(scene, slink) == 0);
  SH_CHECK(link(scene, hard) == 0);
  refused_as_input(scene, scene, "the same path");
  refused_as_input(scene, dotdot, "through ..");
  refused_as_input(scene, dots, "through . and //");
  refused_as_input(scene, slink, "a symbolic link");
  refused_as_input(scene, hard, "a hard link");
  refused_as_input(slink, scene, "the input through a link");
  /* A relative spelling from the working directory. */
  char cwd[4096];
  SH_CHECK(getcwd(cwd, sizeof cwd) != NULL);
  SH_CHECK(chdir(tmpdir) == 0);
  refused_as_input(scene, "s.json", "a relative name");
  refused_as_input("s.json", "./sub/../s.json", "relative both");
  SH_CHECK(chdir(cwd) == 0);

  /* Two outputs that are one file, new or existing. */
  sh_error err = SH_ERROR_INIT;
  sh_outputs *set = sh_outputs_new();
  char *a = in_tmp("a.exr"), *a2 = in_tmp("sub/../a.exr");
  SH_CHECK(sh_outputs_add(set, a, "-o", &err) == SH_OK);
  SH_CHECK(sh_outputs_add(set, a2, "--stats", &err) == SH_ERR_ARG);
  SH_CHECK(strstr(err.message, "each output of a run must be a file of its "
                               "own") != NULL);
  SH_CHECK(sh_outputs_add(set, hard, "-o", &err) == SH_OK);
  SH_CHECK(sh_outputs_add(set, scene, "-o", &err) == SH_ERR_ARG);
  /* Not a regular file: a directory, a device. */
  SH_CHECK(sh_outputs_add(set, sub, "-o", &err) == SH_ERR_ARG);
  SH_CHECK(strstr(err.message, "not a regular file") != NULL);
  SH_CHECK(sh_outputs_add(set, "/dev/null", "-o", &err) == SH_ERR_ARG);
  /* A directory that does not exist. */
  char *nowhere = in_tmp("no/such/x.exr");
  SH_CHECK(sh_outputs_add(set, nowhere, "-o", &err) == SH_ERR_IO);
  sh_outputs_free(set);

  unlink(slink);
  unlink(hard);
  unlink(scene);
  rmdir(sub);
  free(scene), free(sub), free(dotdot), free(dots), free(slink), free(hard);
  free(a), free(a2), free(nowhere);
  sh_error_clear(&err);
}

static void test_staging(void) {
  sh_error err = SH_ERROR_INIT;
  char *a = in_tmp("a.json"), *b = in_tmp("b.png");
  put(a, "old");
  int before = count_entries(tmpdir);
  sh_image img;
  SH_CHECK(sh_image_alloc(&img, 3, 2, &err) == SH_OK);

  /* Staged outputs have no name: a process killed now leaves nothing. */
  sh_outputs *set = sh_outputs_new();
  SH_CHECK(sh_outputs_write_bytes(set, a, "new", 3, &err) == SH_OK);
  SH_CHECK(sh_outputs_write_image(set, b, &img, 0, NULL, &err) == SH_OK);
  SH_CHECK(count_entries(tmpdir) == before);
  SH_CHECK(holds(a, "old"));
  SH_CHECK(sh_outputs_publish(set, &err) == SH_OK);
  sh_outputs_free(set);
  SH_CHECK(holds(a, "new"));
  SH_CHECK(access(b, R_OK) == 0);
  SH_CHECK(count_entries(tmpdir) == before + 1);
  struct stat sb;
  SH_CHECK(stat(a, &sb) == 0 && (sb.st_mode & 0777) == 0644); /* umask 022 */

  /* A failure after a first output was staged: nothing is published, the
   * old bytes stay, no temporary is left. */
  unlink(b);
  set = sh_outputs_new();
  char *bad = in_tmp("c.nosuchformat");
  SH_CHECK(sh_outputs_write_bytes(set, a, "newer", 5, &err) == SH_OK);
  SH_CHECK(sh_outputs_write_image(set, bad, &img, 0, NULL, &err) != SH_OK);
  sh_outputs_free(set);
  SH_CHECK(holds(a, "new"));
  SH_CHECK(count_entries(tmpdir) == before);

  /* An output never written is an error at publishing, not an empty file. */
  set = sh_outputs_new();
  SH_CHECK(sh_outputs_add(set, b, "-o", &err) == SH_OK);
  SH_CHECK(sh_outputs_publish(set, &err) == SH_ERR_ARG);
  sh_outputs_free(set);
  SH_CHECK(access(b, F_OK) != 0);
  unlink(a);
  sh_image_free(&img);
  free(a), free(b), free(bad);
  sh_error_clear(&err);
}

/* The files a scene's meshes name (a glTF's buffer, an OBJ's material
 * library) are inputs too: -o naming one is refused (before, only the
 * scene, its meshes, heightfields and light maps were). */
static void test_mesh_files(void) {
  char *bin = in_tmp("m.bin"), *gltf = in_tmp("m.gltf"), *obj = in_tmp("t.obj");
  char *mtl = in_tmp("t.mtl"), *scene = in_tmp("meshes.json");
  float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  FILE *f = fopen(bin, "wb");
  if (f) {
    fwrite(tri, sizeof tri, 1, f);
    fclose(f);
  }
  put(gltf, "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0, \"scenes\": [{\"nodes\": [0]}],"
            " \"nodes\": [{\"mesh\": 0}], \"meshes\": [{\"primitives\": [{\"attributes\":"
            " {\"POSITION\": 0}}]}], \"buffers\": [{\"byteLength\": 36, \"uri\": \"m.bin\"}],"
            " \"bufferViews\": [{\"buffer\": 0, \"byteLength\": 36}], \"accessors\":"
            " [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\","
            " \"min\": [0, 0, 0], \"max\": [1, 1, 0]}]}");
  put(mtl, "newmtl grey\nKd 0.5 0.5 0.5\n");
  put(obj, "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl grey\nf 1 2 3\n");
  put(scene, "{\"format\": \"shafts-scene\", \"version\": 1, \"camera\": {\"position\":"
             " [0, 1, 5], \"look_at\": [0, 0, 0], \"fov_y_deg\": 45, \"width\": 8,"
             " \"height\": 6}, \"lights\": [], \"materials\": {\"m\": {\"diffuse\":"
             " [0.5, 0.5, 0.5]}}, \"shapes\": [{\"type\": \"mesh\", \"material\": \"m\","
             " \"file\": \"m.gltf\"}, {\"type\": \"mesh\", \"material\": \"m\","
             " \"file\": \"t.obj\"}]}");
  sh_scene *s = NULL;
  sh_error err = SH_ERROR_INIT;
  sh_status st = sh_scene_load(scene, &s, &err);
  if (st != SH_OK) fprintf(stderr, "  meshes.json: %s\n", err.message);
  SH_CHECK(st == SH_OK);
  if (s) {
    const char *outs[2] = {bin, mtl};
    for (int i = 0; i < 2; i++) {
      sh_outputs *set = sh_outputs_new();
      SH_CHECK(sh_outputs_scene_inputs(set, s, &err) == SH_OK);
      st = sh_outputs_add(set, outs[i], "-o", &err);
      if (st != SH_ERR_ARG)
        fprintf(stderr, "  -o %s, a file a mesh names, was accepted\n", outs[i]);
      SH_CHECK(st == SH_ERR_ARG && strstr(err.message, "must not overwrite an input") &&
               strstr(err.message, "a file a mesh of the scene names"));
      sh_outputs_free(set);
    }
    sh_scene_free(s);
  }
  unlink(bin), unlink(gltf), unlink(obj), unlink(mtl), unlink(scene);
  free(bin), free(gltf), free(obj), free(mtl), free(scene);
  sh_error_clear(&err);
}

int main(void) {
  if (!sh_test_tmpdir(tmpdir, sizeof tmpdir, "sh_outputs_test")) return 1;
  umask(022);
  test_refusals();
  test_mesh_files();
  test_staging();
  rmdir(tmpdir);
  printf("%d checks, %d failed\n", sh_test_checks, sh_test_failures);
  return sh_test_failures ? 1 : 0;
}
