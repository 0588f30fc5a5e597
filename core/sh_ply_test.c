/* Tests of sh_ply.h through sh_mesh_load (which sends every file that
 * starts as a PLY file to it): ASCII, binary little- and big-endian,
 * polygons, triangle strips, skipped elements and properties; and the
 * files on which Debian's assimp 5.2 PLY reader loops forever or reads
 * gigabytes (fuzz/known/ply_hang and its kinds: no end_header, counts the
 * file cannot hold), which must fail at once with a located error. CTest
 * gives this test 60 s (core/CMakeLists.txt); each of those files took
 * assimp forever, or over 10 s and 2 GB. */
#include "sh_mesh_test_util.h"

static const char *const HEAD =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\n";

int main(void) {
  if (!sh_test_tmpdir(sh_mesh_test_dir, sizeof sh_mesh_test_dir, "sh_ply_test")) return EXIT_FAILURE;
  char text[2048];

  /* ASCII: a quad (two triangles), comments, an element and properties to
   * skip (a list among them), CRLF line ends, upper-case magic. */
  expect_tris("quad.ply",
              "PLY\r\nformat ascii 1.0\r\ncomment a quad\r\nobj_info none\r\n"
              "element vertex 4\r\nproperty float x\r\nproperty uchar red\r\n"
              "property float y\r\nproperty double z\r\n"
              "element face 1\r\nproperty list uchar int vertex_indices\r\n"
              "property list uint8 float texcoord\r\n"
              "element camera 1\r\nproperty float view_px\r\nend_header\r\n"
              "0 9 0 0\r\n1 9 0 0\r\n1 9 1 0\r\n0 9 1 0\r\n4 0 1 2 3 2 0.5 0.5\r\n7.5\r\n",
              2, 4);
  /* A pentagon fans into three triangles; a line and a point are skipped;
   * vertex_index (singular) names the list too. */
  snprintf(text, sizeof text,
           "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
           "property float z\nelement face 3\nproperty list uchar uint vertex_index\n"
           "end_header\n0 0 0\n1 0 0\n1 1 0\n0.5 2 0\n0 1 0\n5 0 1 2 3 4\n2 0 1\n1 3\n");
  expect_tris("pentagon.ply", text, 3, 5);
  /* Triangle strips with a restart: 0 1 2 3 | 1 2 3 -> 2 + 1 triangles. */
  snprintf(text, sizeof text,
           "%selement tristrips 1\nproperty list int int vertex_indices\nend_header\n"
           "0 0 0\n1 0 0\n0 1 0\n1 1 0\n8 0 1 2 3 -1 1 2 3\n", HEAD);
  expect_tris("strips.ply", text, 3, 4);

  /* Binary, both byte orders: the add-on's layout (shafts_blender's
   * convert/files.py), one triangle. */
  for (int be = 0; be < 2; be++) {
    const char *hdr = be ? "ply\nformat binary_big_endian 1.0\n"
                         : "ply\nformat binary_little_endian 1.0\n";
    char head[512];
    int hn = snprintf(head, sizeof head,
                      "%selement vertex 3\nproperty float x\nproperty float y\n"
                      "property float z\nelement face 1\n"
                      "property list uchar int vertex_indices\nend_header\n", hdr);
    unsigned char buf[1024];
    memcpy(buf, head, (size_t)hn);
    size_t n = (size_t)hn;
    float v[9] = {0, 0, 0, 2, 0, 0, 0, 3, 0};
    for (int i = 0; i < 9; i++) {
      unsigned char b[4];
      memcpy(b, &v[i], 4);
      for (int k = 0; k < 4; k++) buf[n + (size_t)k] = b[be ? 3 - k : k];
      n += 4;
    }
    buf[n++] = 3;
    for (int i = 0; i < 3; i++) {
      int x = i;
      unsigned char b[4];
      memcpy(b, &x, 4);
      for (int k = 0; k < 4; k++) buf[n + (size_t)k] = b[be ? 3 - k : k];
      n += 4;
    }
    sh_mesh m;
    sh_error err = SH_ERROR_INIT;
    const char *p = write_bytes(be ? "tri_be.ply" : "tri_le.ply", buf, n);
    sh_status s = sh_mesh_load(p, NULL, &m, &err);
    SH_CHECK(s == SH_OK);
    if (s == SH_OK) {
      SH_CHECK(m.ntris == 1 && m.nverts == 3);
      SH_CHECK(m.positions[3] == 2.0f && m.positions[7] == 3.0f);
      SH_CHECK(m.indices[0] == 0 && m.indices[1] == 1 && m.indices[2] == 2);
    }
    sh_mesh_free(&m);
    /* An index out of range, in binary data: at the byte after the list. */
    unsigned char bad[1024];
    memcpy(bad, buf, n);
    bad[be ? n - 1 : n - 4] = 9;
    char want[64];
    snprintf(want, sizeof want, "byte %zu: a face refers to vertex 9 of 3", n);
    expect_error(be ? "index_be.ply" : "index_le.ply", bad, n, want);
    /* Cut inside the data: an error at a byte offset. */
    expect_error(be ? "cut_be.ply" : "cut_le.ply", buf, n - 3, "byte");
    /* The header with no end_header, in binary. */
    expect_error(be ? "open_be.ply" : "open_le.ply", buf,
                 strlen(hdr) + strlen("element vertex 3\nproperty float x\n"), "end_header");
    sh_error_clear(&err);
  }

  /* The input mesh_fuzz found (fuzz/known/ply_hang; its first byte picks
   * the format in the harness): a header with no end_header line, on
   * which assimp never returned. */
  unsigned char buf[4096];
  size_t n = read_known("ply_hang", buf, sizeof buf);
  SH_CHECK(n > 1);
  if (n > 1) expect_error("ply_hang.ply", buf + 1, n - 1, "line 7: unknown header keyword 'e'");
  /* Its kind: headers that end without end_header. */
  expect_error("no_end.ply", HEAD, strlen(HEAD), "no 'end_header' line");
  expect_text("magic_only.ply", "ply\n", "no 'end_header' line");
  expect_text("format_only.ply", "ply\nformat ascii 1.0\n", "no 'end_header' line");
  /* Counts the file cannot hold (assimp: 2 GB in 10 s, 4 GB in 20 s). */
  snprintf(text, sizeof text,
           "ply\nformat ascii 1.0\nelement vertex 2000000000\nproperty float x\n"
           "property float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n");
  expect_error("many_vertices.ply", text, strlen(text), "line 3: element 'vertex' declares 2000000000");
  snprintf(text, sizeof text,
           "%selement face 1\nproperty list uint int vertex_indices\nend_header\n"
           "0 0 0\n1 0 0\n0 1 0\n1 1 0\n400000000 0 1 2\n", HEAD);
  expect_error("long_list.ply", text, strlen(text), "line 14: a list of element 'face' counts 400000000");
  snprintf(text, sizeof text,
           "ply\nformat binary_little_endian 1.0\nelement vertex 4294967295\n"
           "property double x\nproperty double y\nproperty double z\nend_header\n");
  expect_error("many_binary.ply", text, strlen(text), "declares 4294967295");
  snprintf(text, sizeof text,
           "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\n");
  expect_error("count_overflow.ply", text, strlen(text), "too large");
  /* Bad values, located: four vertices and one face, one value changed. */
  static const struct {
    const char *name, *vertices, *face, *want;
  } BAD[] = {
      {"index.ply", "0 0 0\n1 0 0\n", "3 0 1 4", "line 14: a face refers to vertex 4 of 4"},
      {"nan.ply", "0 0 0\n1 nan 0\n", "3 0 1 2", "line 11: vertex 1 is not a finite number"},
      {"huge.ply", "0 0 0\n1 1e39 0\n", "3 0 1 2", "vertex 1 is not a finite number"},
      {"word.ply", "0 0 0\n1 x 0\n", "3 0 1 2",
       "line 11: 'x' in element 'vertex' instance 1 is not a number"},
      {"range.ply", "0 0 0\n1 0 0\n", "300 0 1 2", "out of its type's range"}};
  for (size_t i = 0; i < sizeof BAD / sizeof BAD[0]; i++) {
    snprintf(text, sizeof text,
             "%selement face 1\nproperty list uchar int vertex_indices\nend_header\n"
             "%s0 1 0\n1 1 0\n%s\n", HEAD, BAD[i].vertices, BAD[i].face);
    expect_text(BAD[i].name, text, BAD[i].want);
  }
  expect_text("keyword.ply", "ply\nformat ascii 1.0\nelemnt vertex 3\nend_header\n",
               "line 3: unknown header keyword 'elemnt'");
  expect_text("format.ply", "ply\nformat binary 1.0\nend_header\n", "unknown format 'binary'");
  expect_text("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\nend_header\n", "line 4: unknown type 'real'");
  expect_text("noxyz.ply",
              "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n", "lacks property x, y or z");
  snprintf(text, sizeof text, "%send_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n", HEAD);
  expect_error("nofaces.ply", text, strlen(text), "no triangles");
  SH_TEST_DONE();
}
