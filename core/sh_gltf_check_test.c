/* Tests of sh_gltf_check.h through sh_mesh_load: the glTF files on which
 * Debian's assimp 5.2 allocated gigabytes, read through a null pointer or
 * past a buffer (sparse accessors, skins), or copied a shared node
 * exponentially (fuzz/known/gltf_*,
 * the harness's first byte dropped), and their kind, each refused at once
 * at the JSON's line, column and key path; valid files, a sparse accessor
 * among them, still load, also with a buffer file whose bytes look like a
 * material library's statements. */
#include "sh_mesh_test_util.h"

/* A triangle: its buffer (three positions, three 16-bit indices, padding)
 * as a data URI. */
static const char BUFFER[] =
    "\"buffers\":[{\"uri\":\"data:application/octet-stream;base64,"
    "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=\",\"byteLength\":44}],"
    "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},"
    "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6}],";
static const char POSITIONS[] =
    "{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
    "\"max\":[1,1,0],\"min\":[0,0,0]";
static const char REST[] =
    "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}],"
    "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],";

/* A glTF file: the triangle, its position accessor ending with `sparse`
 * (from ",\"sparse\":..." or ""), then `nodes` ("[...]"). */
static const char *gltf(char *buf, size_t size, const char *sparse, const char *nodes) {
  snprintf(buf, size,
           "{\"asset\":{\"version\":\"2.0\"},%s\"accessors\":[%s%s},%s\"nodes\":%s,"
           "\"scenes\":[{\"nodes\":[0]}],\"scene\":0}",
           BUFFER, POSITIONS, sparse, REST, nodes);
  return buf;
}

/* Loads text as `name` and expects SH_ERR_MESH at line 1, `column`, key
 * path `key`, with `want` in the message. */
static void expect_at(const char *name, const char *text, int column, const char *key,
                      const char *want) {
  sh_mesh m;
  sh_error err = SH_ERROR_INIT;
  sh_status s = sh_mesh_load(write_text(name, text), NULL, &m, &err);
  int ok = s == SH_ERR_MESH && strstr(err.file, name) && err.line == 1 &&
           err.column == column && !strcmp(err.path, key) && strstr(err.message, want);
  if (!ok)
    fprintf(stderr, "%s: status %d, %d:%d '%s': %s\n  want 1:%d '%s' with '%s'\n", name, s,
            err.line, err.column, err.path, s ? err.message : "", column, key, want);
  SH_CHECK(ok);
  SH_CHECK(m.positions == NULL);
  sh_error_clear(&err);
}

/* The column of the first `needle` in text, 1-based. */
static int column_of(const char *text, const char *needle) {
  const char *at = strstr(text, needle);
  return at ? (int)(at - text) + 1 : -1;
}

int main(void) {
  if (!sh_test_tmpdir(sh_mesh_test_dir, sizeof sh_mesh_test_dir, "sh_gltf_check_test"))
    return EXIT_FAILURE;
  char text[4096];

  /* Valid files: the triangle; with a sparse accessor moving vertex 1 to
   * itself (indices from view 1, values from view 0); a node with a
   * child; glTF 1.0's nodes by name are read as assimp reads them. */
  expect_tris("tri.gltf", gltf(text, sizeof text, "", "[{\"mesh\":0}]"), 1, 3);
  expect_tris("sparse.gltf",
              gltf(text, sizeof text,
                   ",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":1,\"componentType\":"
                   "5123},\"values\":{\"bufferView\":0}}",
                   "[{\"mesh\":0}]"),
              1, 3);
  expect_tris("tree.gltf", gltf(text, sizeof text, "", "[{\"children\":[1]},{\"mesh\":0}]"), 1,
              3);

  /* The inputs found by hand (fuzz/known). */
  static const struct {
    const char *known, *name, *key, *at, *want;
  } KNOWN[] = {
      {"gltf_sparse_alloc", "sparse_alloc.gltf", "accessors[0]", "{\"componentType\": 5126",
       "a sparse accessor of 1000000000 elements of 12 bytes, more than the 44 bytes"},
      {"gltf_sparse_null", "sparse_null.gltf", "accessors[0].sparse", "{\"count\": 1",
       "a sparse accessor needs 'indices'"},
      {"gltf_sparse_overread", "sparse_overread.gltf", "accessors[0].sparse.count",
       "100000000", "a sparse accessor's count is a whole number from 1 to the accessor's count (3)"},
      {"gltf_shared_nodes", "shared_nodes.gltf", "nodes[0].children[1]", "1]}",
       "node 1 is a child of two nodes, or twice of one"},
      {"gltf_skin_null", "skin_null.gltf", "skins[0]", "{\"joints\"",
       "a skin (of node 1) needs its inverseBindMatrices"},
      {"gltf_skin_overread", "skin_overread.gltf", "skins[0].inverseBindMatrices",
       "2}]}", "accessor 2 holds 1 inverse bind matrices, fewer than the skin's 900"}};
  for (size_t i = 0; i < sizeof KNOWN / sizeof KNOWN[0]; i++) {
    unsigned char buf[4096];
    size_t n = read_known(KNOWN[i].known, buf, sizeof buf - 1);
    SH_CHECK(n > 1);
    if (n <= 1) continue;
    buf[n] = '\0';
    const char *json = (const char *)buf + 1;
    int column = column_of(json, KNOWN[i].at);
    if (!strcmp(KNOWN[i].known, "gltf_shared_nodes")) /* the second 1 of [1,1] */
      column = column_of(json, "[1,1]") + 3;
    expect_at(KNOWN[i].name, json, column, KNOWN[i].key, KNOWN[i].want);
  }

  /* Their kind: every part of a sparse accessor assimp uses unchecked. */
  static const struct {
    const char *name, *sparse, *key, *at, *want;
  } SPARSE[] = {
      {"no_values.gltf", "{\"count\":1,\"indices\":{\"bufferView\":1,\"componentType\":5123}}",
       "accessors[0].sparse", "{\"count\"", "needs 'values'"},
      {"no_view.gltf", "{\"count\":1,\"indices\":{\"componentType\":5123},\"values\":{\"bufferView\":0}}",
       "accessors[0].sparse.indices", "{\"componentType\"", "sparse indices need a bufferView"},
      {"bad_view.gltf", "{\"count\":1,\"indices\":{\"bufferView\":1,\"componentType\":5123},\"values\":{\"bufferView\":7}}",
       "accessors[0].sparse.values.bufferView", "7}", "sparse values need a bufferView (one of the 2)"},
      {"float_indices.gltf", "{\"count\":1,\"indices\":{\"bufferView\":1,\"componentType\":5126},\"values\":{\"bufferView\":0}}",
       "accessors[0].sparse.indices.componentType", "5126}", "5121, 5123 or 5125"},
      {"long_indices.gltf", "{\"count\":3,\"indices\":{\"bufferView\":1,\"byteOffset\":2,\"componentType\":5123},\"values\":{\"bufferView\":0}}",
       "accessors[0].sparse.indices", "{\"bufferView\":1,\"byteOffset\"",
       "3 sparse indices of 2 bytes from byte 2, more than bufferView 1's 6 bytes"},
      {"zero_count.gltf", "{\"count\":0,\"indices\":{\"bufferView\":1,\"componentType\":5123},\"values\":{\"bufferView\":0}}",
       "accessors[0].sparse.count", "0,\"indices\"", "from 1 to the accessor's count"},
      {"not_object.gltf", "7", "accessors[0].sparse", "7}", "'sparse' is an object"}};
  for (size_t i = 0; i < sizeof SPARSE / sizeof SPARSE[0]; i++) {
    char sparse[512];
    snprintf(sparse, sizeof sparse, ",\"sparse\":%s", SPARSE[i].sparse);
    gltf(text, sizeof text, sparse, "[{\"mesh\":0}]");
    int column = column_of(strstr(text, "\"sparse\""), SPARSE[i].at);
    column += (int)(strstr(text, "\"sparse\"") - text);
    expect_at(SPARSE[i].name, text, column, SPARSE[i].key, SPARSE[i].want);
  }
  /* A node twice in one list, and a node under two parents. */
  gltf(text, sizeof text, "", "[{\"mesh\":0,\"children\":[1,1]},{}]");
  expect_at("twice.gltf", text, column_of(text, "[1,1]") + 3, "nodes[0].children[1]",
            "node 1 is a child of two nodes");
  gltf(text, sizeof text, "", "[{\"mesh\":0,\"children\":[2]},{\"children\":[2]},{}]");
  expect_at("two_parents.gltf", text,
            (int)(strstr(strstr(text, "[2]}") + 1, "[2]}") - text) + 2, "nodes[1].children[0]",
            "node 2 is a child of two nodes");
  /* glTF 1.0 names its nodes: a chain of 25 nodes each naming the next
   * twice took assimp 11.6 GB and more than a minute (by hand). */
  {
    size_t at = (size_t)snprintf(text, sizeof text,
                                 "{\"asset\":{\"version\":\"1.0\"},\"scene\":\"s\","
                                 "\"scenes\":{\"s\":{\"nodes\":[\"n0\"]}},\"nodes\":{");
    for (int i = 0; i < 24; i++)
      at += (size_t)snprintf(text + at, sizeof text - at,
                             "\"n%d\":{\"children\":[\"n%d\",\"n%d\"]},", i, i + 1, i + 1);
    snprintf(text + at, sizeof text - at, "\"n24\":{}}}");
    expect_at("named.gltf", text, column_of(text, "\"n1\"]"), "nodes.n0.children[1]",
              "node n1 is a child of two nodes");
  }
  /* JSON that could read otherwise in assimp's parser: a key twice, a
   * syntax error; both at their place. */
  expect_at("duplicate.gltf", "{\"nodes\":[],\"nodes\":[{\"children\":[0,0]}]}", 19, "",
            "duplicate object key");
  {
    sh_mesh m;
    sh_error err = SH_ERROR_INIT;
    sh_status s = sh_mesh_load(write_text("syntax.gltf", "{\n  \"nodes\": [,]\n}"), NULL, &m, &err);
    SH_CHECK(s == SH_ERR_MESH && err.line == 2 && strstr(err.message, "line 2"));
    if (s != SH_ERR_MESH || err.line != 2) fprintf(stderr, "syntax.gltf: %s\n", err.message);
    sh_error_clear(&err);
  }
  /* A glTF whose buffer is a file of its own holding lines an MTL check
   * refuses, and whose JSON holds a token of assimp's OBJ importer ("I/O
   * v3": "o "), as Blender's exporter writes: its buffer is no material
   * library, so it loads (named .gltf, which two importers list, so that
   * assimp picks the importer by the bytes). */
  {
    unsigned char bin[64];
    const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const unsigned short idx[4] = {0, 1, 2, 0};
    static const char lines[] = "\nmap_Kd x.png\na 0.5\n";
    memcpy(bin, pos, sizeof pos);
    memcpy(bin + 36, idx, sizeof idx);
    memcpy(bin + 44, lines, sizeof lines - 1);
    size_t nbin = 44 + sizeof lines - 1;
    write_bytes("tri.bin", bin, nbin);
    char json[2048];
    snprintf(json, sizeof json,
             "{\"asset\":{\"generator\":\"Khronos glTF Blender I/O v3.4.50\",\"version\":\"2.0\"},"
             "\"buffers\":[{\"uri\":\"tri.bin\",\"byteLength\":%zu}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},"
             "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6}],\"accessors\":[%s},%s"
             "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}",
             nbin, POSITIONS, REST);
    expect_tris("external.gltf", json, 1, 3);
  }
  /* A binary glTF under another name: assimp's glTF importers read binary
   * glTF by the name alone (a .glb renamed .gltf failed with "aiScene::
   * mNumMeshes is 0"), so it is refused, saying so. */
  {
    static const unsigned char glb[20] = {'g', 'l', 'T', 'F', 2, 0, 0, 0, 20, 0, 0, 0,
                                          0, 0, 0, 0, 'J', 'S', 'O', 'N'};
    expect_error("glb_named.gltf", glb, sizeof glb, "a binary glTF (GLB), which assimp reads only from a file named *.glb");
    expect_error("glb_named.bin", glb, sizeof glb, "rename it");
  }
  SH_TEST_DONE();
}
