/* Tests of the OBJ files whose work in assimp grew faster than their size,
 * through sh_mesh_load. A face of more corners than SH_OBJ_MAX_CORNERS,
 * whose triangulation takes time growing as the square of its corners
 * (fuzz/known/obj_polygon: 20001 corners, 5 s in the fuzzing build), is
 * refused at once at its line by sh_obj_check.h, also when it continues
 * over lines or the file is not named *.obj; faces up to the limit still
 * load. A file naming itself as its material library on 4900 lines
 * (fuzz/known/obj_mtllib_repeat), which assimp parsed 4900 times, is
 * refused by sh_mesh.c's budget of reads; one library named once, or
 * twice, still loads. A texture map before a library's first newmtl,
 * which crashed assimp's material reader (fuzz/known/mtl_no_material: a
 * mesh naming itself as its library), is refused at its line, in a
 * library of its own, in the fallback NAME.mtl, after \r line ends and a
 * UTF-8 byte-order mark, and in files whose importer assimp picks by their
 * bytes (a .gltf of OBJ lines, a binary glTF header before OBJ lines); a
 * UTF-16 library is refused; the same statements after newmtl load. */
#include "sh_mesh_test_util.h"

#include "sh_obj_check.h"

/* "v ...\n" for a triangle, then a face of n corners cycling over it,
 * with a line break continued by a backslash after every `wrap` corners
 * (0: none). */
static char *polygon(int n, int wrap) {
  size_t cap = 64 + 5 * (size_t)n;
  char *text = malloc(cap);
  if (!text) return NULL;
  size_t at = (size_t)snprintf(text, cap, "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf");
  for (int i = 0; i < n; i++) {
    at += (size_t)snprintf(text + at, cap - at, " %d", 1 + i % 3);
    if (wrap && i % wrap == wrap - 1) at += (size_t)snprintf(text + at, cap - at, " \\\n");
  }
  snprintf(text + at, cap - at, "\n");
  return text;
}

/* The OBJ `obj`, whose lines `head` come before a triangle, is refused
 * for the library's line `line`; `what` says which case. */
static void expect_library_error_as(const char *obj, const char *library, const char *head,
                                    int line, const char *what) {
  char text[256];
  snprintf(text, sizeof text, "%sv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", head);
  sh_mesh m;
  sh_error err = SH_ERROR_INIT;
  sh_status s = sh_mesh_load(write_text(obj, text), NULL, &m, &err);
  int ok = s == SH_ERR_MESH && strstr(err.message, obj) && strstr(err.message, library) &&
           strstr(err.message, "before the library's first newmtl") && err.line == line &&
           strstr(err.file, library);
  if (!ok)
    fprintf(stderr, "%s (%s): status %d, '%s' (%s line %d); want the library %s's line %d\n",
            obj, what, s, s ? err.message : "", s ? err.file : "", s ? err.line : 0, library,
            line);
  SH_CHECK(ok);
  SH_CHECK(m.positions == NULL && m.ntris == 0);
  sh_error_clear(&err);
}

/* The same for the OBJ named after `library` (.mtl replaced by .obj). */
static void expect_library_error(const char *library, const char *head, int line,
                                 const char *what) {
  char obj[64];
  snprintf(obj, sizeof obj, "%.*s.obj", (int)(strlen(library) - 4), library);
  expect_library_error_as(obj, library, head, line, what);
}

int main(void) {
  if (!sh_test_tmpdir(sh_mesh_test_dir, sizeof sh_mesh_test_dir, "sh_obj_check_test"))
    return EXIT_FAILURE;
  unsigned char buf[65536];
  size_t n = read_known("obj_polygon", buf, sizeof buf);
  SH_CHECK(n > 1);
  if (n > 1) expect_error_at("obj_polygon.obj", buf + 1, n - 1, 4, "a face of 20001 corners");

  char *text = polygon(SH_OBJ_MAX_CORNERS + 1, 0);
  SH_CHECK(text != NULL);
  if (text) expect_text_at("long.obj", text, 5, "a face of 4097 corners, more than the 4096");
  free(text);
  text = polygon(SH_OBJ_MAX_CORNERS + 1, 1000);
  if (text) expect_text_at("continued.obj", text, 5, "a face of 4097 corners");
  if (text) expect_text_at("long.mesh_data", text, 5, "a face of 4097 corners");
  free(text);
  /* At the limit: the triangle's corners cycle, so the polygon is
   * degenerate, but assimp takes it (the time is what is bounded). */
  text = polygon(SH_OBJ_MAX_CORNERS, 0);
  if (text) {
    sh_mesh m;
    sh_error err = SH_ERROR_INIT;
    sh_status s = sh_mesh_load(write_text("limit.obj", text), NULL, &m, &err);
    if (s != SH_OK) fprintf(stderr, "limit.obj: %s\n", err.message);
    SH_CHECK(s == SH_OK);
    sh_mesh_free(&m);
    sh_error_clear(&err);
  }
  free(text);
  /* Re-reads: the library named on 4900 lines; a library named twice. */
  n = read_known("obj_mtllib_repeat", buf, sizeof buf);
  SH_CHECK(n > 1);
  if (n > 1) {
    /* The harness names the mesh m.obj. */
    write_bytes("m.obj", buf + 1, n - 1);
    sh_mesh m;
    sh_error err = SH_ERROR_INIT;
    sh_status s = sh_mesh_load(sh_mesh_test_path, NULL, &m, &err);
    SH_CHECK(s == SH_ERR_MESH && strstr(err.message, "more than 16 times over"));
    if (s != SH_ERR_MESH) fprintf(stderr, "obj_mtllib_repeat: status %d\n", s);
    sh_error_clear(&err);
  }
  write_text("lib.mtl", "newmtl grey\nKd 0.5 0.5 0.5\n");
  expect_tris("twice.obj", "mtllib lib.mtl\nmtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
              "usemtl grey\nf 1 2 3\n", 1, 3);
  /* Material statements before any material (sh__mtl_check). */
  n = read_known("mtl_no_material", buf, sizeof buf);
  SH_CHECK(n > 1);
  if (n > 1) expect_error_at("m.obj", buf + 1, n - 1, 1, "a texture map ('map_Ke') before the library's first newmtl");
  static const char *const early[] = {"map_Kd tex.png", "  map_Ke", "bump b.png", "disp d.png",
                                      "norm n.png", "Norm n.png", "map_Kd -bm 1 x.png",
                                      "a 0.5"};
  for (size_t i = 0; i < sizeof early / sizeof *early; i++) {
    char lib[128];
    snprintf(lib, sizeof lib, "# a comment\n%s\nnewmtl grey\n", early[i]);
    write_text("early.mtl", lib);
    expect_library_error("early.mtl", "mtllib early.mtl\n", 2, early[i]);
  }
  write_text("cr.mtl", "# a comment\rmap_Kd tex.png\rnewmtl grey\r");
  expect_library_error("cr.mtl", "mtllib cr.mtl\n", 1, "\\r line ends");
  /* assimp opens NAME.mtl when the library named is missing. */
  write_text("fallback.mtl", "map_Ks s.png\n");
  expect_library_error("fallback.mtl", "mtllib missing.mtl\n", 1, "the fallback library");
  write_text("late.mtl", "# a comment\nnewmtl grey\nKd 0.5 0.5 0.5\nmap_Kd -bm 1 tex.png\n"
                         "bump b.png\ndisp d.png\nnorm n.png\na 0.5\n"
                         "newmtl red\nmap_Ke e.png\n");
  expect_tris("late.obj", "mtllib late.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n", 1, 3);
  /* Files whose importer assimp picks by their bytes (an extension no
   * importer lists, or several: .gltf) are OBJ files if its OBJ importer
   * says so: checked alike. */
  text = polygon(SH_OBJ_MAX_CORNERS + 1, 0);
  if (text) expect_text_at("long.gltf", text, 5, "a face of 4097 corners");
  free(text);
  expect_library_error_as("sniffed.gltf", "early.mtl", "mtllib early.mtl\n", 2, "sniffed");
  expect_library_error_as("sniffed.mesh_data", "early.mtl", "mtllib early.mtl\n", 2, "sniffed");
  /* Byte-order marks: assimp drops a UTF-8 one (the statement after it is
   * checked; a library starting with one loads) and mangles text after a
   * UTF-16 or UTF-32 one (refused). */
  write_text("bom.mtl", "\xEF\xBB\xBFmap_Kd x.png\nnewmtl grey\n");
  expect_library_error("bom.mtl", "mtllib bom.mtl\n", 1, "UTF-8 byte-order mark");
  write_text("bom_ok.mtl", "\xEF\xBB\xBFnewmtl grey\nmap_Kd t.png\n");
  expect_tris("bom_ok.obj", "mtllib bom_ok.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 1, 3);
  static const char utf16[] = "\xFF\xFEn\0e\0w\0m\0t\0l\0 \0a\0\n\0";
  write_bytes("utf16.mtl", utf16, sizeof utf16 - 1);
  {
    sh_mesh m;
    sh_error err = SH_ERROR_INIT;
    sh_status s = sh_mesh_load(
        write_text("utf16.obj", "mtllib utf16.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), NULL,
        &m, &err);
    SH_CHECK(s == SH_ERR_MESH && strstr(err.message, "UTF-16 or UTF-32") &&
             strstr(err.file, "utf16.mtl"));
    if (s != SH_ERR_MESH) fprintf(stderr, "utf16.obj: status %d\n", s);
    sh_error_clear(&err);
  }
  /* A binary glTF header whose JSON chunk is empty, then OBJ lines: the
   * glTF importers refuse it, and assimp's OBJ importer takes it by its
   * bytes (JSON text could hold no mtllib line; binary glTF can). */
  {
    static const char lines[] = "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nmtllib early.mtl\n";
    unsigned char glb[128] = {'g', 'l', 'T', 'F', 2, 0, 0, 0, 0, 0, 0, 0,
                              0, 0, 0, 0, 'J', 'S', 'O', 'N'};
    size_t nglb = 20 + sizeof lines - 1;
    glb[8] = (unsigned char)nglb;
    memcpy(glb + 20, lines, sizeof lines - 1);
    write_bytes("binary.glb", glb, nglb);
    sh_mesh m;
    sh_error err = SH_ERROR_INIT;
    sh_status s = sh_mesh_load(sh_mesh_test_path, NULL, &m, &err);
    SH_CHECK(s == SH_ERR_MESH && strstr(err.file, "early.mtl") && err.line == 2);
    if (s != SH_ERR_MESH || !strstr(err.file, "early.mtl"))
      fprintf(stderr, "binary.glb: status %d, '%s'\n", s, s ? err.message : "");
    if (s == SH_OK) sh_mesh_free(&m);
    sh_error_clear(&err);
  }
  expect_tris("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 \\\n 3 4\n", 2, 4);
  SH_TEST_DONE();
}
