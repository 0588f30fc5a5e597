/* Tests of sh_off.h through sh_mesh_load (which sends files named *.off,
 * and files whose importer assimp picks by their bytes, whose first bytes are
 * "off", to it): the header's variants (no keyword, COFF, NOFF, STOFF,
 * 4OFF, nOFF, counts on the keyword's line), comments, polygons; and the
 * file on which Debian's assimp 5.2 OFF importer asked for 40 GB
 * (fuzz/known/off_alloc) with its kind, counts the file cannot hold,
 * which must fail at once with an error at the header's line. */
#include "sh_mesh_test_util.h"

static const char TET[] = "4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                          "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

int main(void) {
  if (!sh_test_tmpdir(sh_mesh_test_dir, sizeof sh_mesh_test_dir, "sh_off_test"))
    return EXIT_FAILURE;
  char text[2048];

  /* The header's variants, each a tetrahedron. */
  snprintf(text, sizeof text, "OFF\n%s", TET);
  expect_tris("tet.off", text, 4, 4);
  expect_tris("nokeyword.off", TET, 4, 4);
  snprintf(text, sizeof text, "OFF %s", TET);
  expect_tris("oneline.off", text, 4, 4);
  expect_tris("crlf_comments.off",
              "# a tetrahedron\r\nOFF # the keyword\r\n\r\n4 4 0\r\n0 0 0\r\n# a comment\r\n"
              "1 0 0\r\n0 1 0\r\n0 0 1 # the apex\r\n3 0 2 1\r\n3 0 1 3\r\n\r\n3 0 3 2\r\n"
              "3 1 2 3",
              4, 4);
  /* Colours, normals and texture coordinates after the position, a colour
   * after a face's indices: all skipped. */
  expect_tris("colours.off",
              "COFF\n4 4 6\n0 0 0 255 0 0 255\n1 0 0 0 255 0\n0 1 0 0.5\n0 0 1 1 1 1 1\n"
              "3 0 2 1 255 0 0\n3 0 1 3 0.1 0.2 0.3 1\n3 0 3 2\n3 1 2 3 7\n",
              4, 4);
  expect_tris("normals.off",
              "STCNOFF\n4 4 6\n0 0 0 0 0 1 1 1 1 1 0 0\n1 0 0 0 0 1 1 1 1 1 1 0\n"
              "0 1 0 0 0 1 1 1 1 1 0 1\n0 0 1 0 0 1 1 1 1 1 1 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n"
              "3 1 2 3\n",
              4, 4);
  /* 4OFF: w divides; nOFF 2: z is 0; a quad fans into two triangles, a
   * line and a point are skipped. */
  sh_mesh m;
  memset(&m, 0, sizeof m);
  expect_mesh("homogeneous.off", "4OFF\n3 1 0\n0 0 0 2\n4 0 0 2\n0 6 0 2\n3 0 1 2\n", 1, 3, &m);
  if (m.positions) SH_CHECK(m.positions[3] == 2.0f && m.positions[7] == 3.0f);
  sh_mesh_free(&m);
  expect_mesh("plane.off", "nOFF 2\n4 4 0\n0 0\n1 0\n1 1\n0 1\n4 0 1 2 3\n2 0 1\n1 3\n0\n",
              2, 4, &m);
  if (m.positions) SH_CHECK(m.positions[8] == 0.0f && m.positions[6] == 1.0f);
  sh_mesh_free(&m);
  /* Any file of an extension assimp does not know, starting with "off":
   * this reader too (assimp's OFF importer would get it). */
  snprintf(text, sizeof text, "OFF\n%s", TET);
  expect_tris("tet.mesh_data", text, 4, 4);
  expect_tris("upper.OFF", TET, 4, 4);
  /* assimp picks the importer of a .gltf file by its bytes (two importers
   * list the extension): an OFF header there went to its OFF importer,
   * which asked for 68 GB (fuzz/known/gltf_sniffed_off, found by
   * mesh_fuzz), so such a file is this reader's too. */
  snprintf(text, sizeof text, "OFF\n%s", TET);
  expect_tris("tet.gltf", text, 4, 4);
  expect_text_at("many_vertices.gltf", "OFF\n2000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                 2, "declares 2000000000 vertices");
  {
    unsigned char known[256];
    size_t k = read_known("gltf_sniffed_off", known, sizeof known);
    SH_CHECK(k > 1);
    if (k > 1) expect_error_at("sniffed_off.gltf", known + 1, k - 1, 2, "the face count");
  }

  /* The input mesh_fuzz found (fuzz/known/off_alloc; its first byte picks
   * the format in the harness): a vertex count of 125 digits, which
   * assimp's importer wrapped to 3340530119 and allocated (40 GB). */
  unsigned char buf[4096];
  size_t n = read_known("off_alloc", buf, sizeof buf);
  SH_CHECK(n > 1);
  if (n > 1) expect_error_at("off_alloc.off", buf + 1, n - 1, 2, "the vertex count '4111");
  /* Its kind: counts the file cannot hold, a count that wraps at 2^32
   * among them, and a face's corner count its line cannot hold. */
  expect_text_at("many_vertices.off", "OFF\n2000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                  2, "declares 2000000000 vertices and 1 faces, more lines than the 26 bytes");
  expect_text_at("wrapped.off", "OFF\n4294967299 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 2,
                  "declares 4294967299 vertices");
  expect_text_at("many_faces.off", "OFF\n\n3 400000000\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 3,
                  "declares 3 vertices and 400000000 faces");
  expect_text_at("huge_count.off", "OFF 3 99999999999999999999999 0\n", 1,
                  "the face count '99999999999999999999999' is too large");
  expect_text_at("long_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n400000000 0 1 2\n", 6,
                  "a face counts 400000000 corners, more than its line holds");
  /* Short files and bad values, each at its line. */
  static const struct {
    const char *name, *text, *want;
    int line;
  } BAD[] = {
      {"few_vertices.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n", "the file ends after 2 of its 4 vertices", 4},
      {"few_faces.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "the file ends after 1 of its 2 faces", 6},
      {"index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "a face refers to vertex 3 of 3", 6},
      {"short_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "a face counts 3 corners, more than its line holds", 6},
      {"short_spaced.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1   \n", "the line ends before a face's vertex index", 6},
      {"word.off", "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", "'x' in vertex 1 is not a number", 4},
      {"nan.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "vertex 1 is not a finite number", 4},
      {"huge.off", "OFF\n3 1 0\n0 0 0\n1e39 0 0\n0 1 0\n3 0 1 2\n", "vertex 1 is not a finite number", 4},
      {"w_zero.off", "4OFF\n3 1 0\n0 0 0 1\n1 0 0 0\n0 1 0 1\n3 0 1 2\n", "vertex 1 is not a finite number", 4},
      {"two_coords.off", "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", "vertex 1 has 2 coordinates, not 3", 4},
      {"negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "a face's vertex index '-1' is not a whole number", 6},
      {"binary.off", "OFF BINARY\n3 1 0\n", "binary OFF files are not read", 1},
      {"dimension.off", "nOFF 4\n3 1 0\n", "the dimension is 4", 1},
      {"keyword.off", "\n# ok\nOF\n3 1 0\n", "'OF' is neither an OFF keyword", 3},
      {"no_counts.off", "OFF\n", "the file ends before the vertex count", 1},
      {"one_count.off", "OFF\n3\n0 0 0\n", "the line ends before the face count", 2},
      {"empty.off", "# nothing\n", "the file is empty", 1},
      {"no_tris.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "it has no triangles", -1}};
  for (size_t i = 0; i < sizeof BAD / sizeof BAD[0]; i++)
    expect_text_at(BAD[i].name, BAD[i].text, BAD[i].line, BAD[i].want);
  SH_TEST_DONE();
}
