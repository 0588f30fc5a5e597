/* The check of a glTF file's JSON before assimp reads it (sh_gltf_check.h).
 * The format: the glTF 2.0 specification (Khronos), sections "Nodes and
 * Hierarchy", "Sparse Accessors" and "Binary glTF Layout"; glTF 1.0's
 * nodes are named in an object rather than an array. */
#include "sh_gltf_check.h"

#include <jansson.h>
#include <limits.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "sh_file.h"
#include "sh_json_locate.h"
#include "sh_str.h"

int sh__gltf_candidate(const char *path) {
  char ext[8];
  sh_file_extension(path, ext, sizeof ext);
  return !ext[0] || !strcmp(ext, "gltf") || !strcmp(ext, "glb");
}

typedef struct check {
  const char *path, *text; /* the file, its JSON */
  size_t len;
  const char *where;       /* "" or " (in its JSON chunk)" */
  sh_error *err;
} check;

/* The error at the value of the key path seg[0..depth). */
static sh_status fail(const check *c, const sh__jseg *seg, int depth, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static sh_status fail(const check *c, const sh__jseg *seg, int depth, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  char *what = sh__vprintf_alloc(fmt, ap);
  va_end(ap);
  char *at = sh__json_format_path(seg, depth);
  sh_error_set(c->err, SH_ERR_MESH, "cannot load mesh '%s'%s: %s: %s", c->path, c->where,
               at ? at : "", what ? what : "out of memory");
  sh_error_set_file(c->err, c->path);
  if (at) sh_error_set_key(c->err, "%s", at);
  free(what);
  free(at);
  if (c->err) {
    size_t off;
    if (sh__json_locate(c->text, c->len, seg, depth, 0, &off))
      sh__json_linecol(c->text, off, &c->err->line, &c->err->column);
  }
  return SH_ERR_MESH;
}

/* An integer member >= 0, or -1 if it is missing or not one. */
static long long whole(const json_t *obj, const char *key) {
  const json_t *v = json_object_get(obj, key);
  return json_is_integer(v) && json_integer_value(v) >= 0 ? json_integer_value(v) : -1;
}

/* Every node the child of one node at most: otherwise assimp copies a
 * shared subtree for every parent that names it. */
static sh_status check_nodes(const check *c, const json_t *root) {
  const json_t *nodes = json_object_get(root, "nodes");
  size_t n = json_is_array(nodes) ? json_array_size(nodes)
             : json_is_object(nodes) ? json_object_size(nodes) : 0;
  if (n == 0) return SH_OK;
  unsigned char *parents = calloc(n, 1);
  const char **keys = json_is_object(nodes) ? calloc(n, sizeof *keys) : NULL;
  json_t *index = keys ? json_object() : NULL; /* glTF 1.0: name -> its place */
  sh_status st = SH_OK;
  if (!parents || (json_is_object(nodes) && (!keys || !index)))
    st = sh_error_set(c->err, SH_ERR_NOMEM, "out of memory");
  if (st == SH_OK && keys) {
    size_t i = 0;
    const char *k;
    json_t *v;
    json_object_foreach((json_t *)nodes, k, v) {
      keys[i] = k;
      if (json_object_set_new(index, k, json_integer((json_int_t)i++)))
        st = sh_error_set(c->err, SH_ERR_NOMEM, "out of memory");
    }
  }
  for (size_t i = 0; i < n && st == SH_OK; i++) {
    const json_t *node = keys ? json_object_get(nodes, keys[i]) : json_array_get(nodes, i);
    const json_t *children = json_object_get(node, "children");
    for (size_t k = 0; k < json_array_size(children) && st == SH_OK; k++) {
      const json_t *ch = json_array_get(children, k);
      if (keys && json_is_string(ch)) ch = json_object_get(index, json_string_value(ch));
      else if (keys) ch = NULL;
      if (!json_is_integer(ch) || json_integer_value(ch) < 0 ||
          (unsigned long long)json_integer_value(ch) >= n)
        continue; /* not a node: assimp refuses it */
      size_t child = (size_t)json_integer_value(ch);
      if (parents[child]++) {
        sh__jseg seg[4] = {{"nodes", 0}, {keys ? keys[i] : NULL, (int)i}, {"children", 0},
                           {NULL, (int)k}};
        char name[64];
        snprintf(name, sizeof name, "%zu", child);
        st = fail(c, seg, 4,
                  "node %s is a child of two nodes, or twice of one (a glTF node "
                  "hierarchy is a set of disjoint trees; assimp copies a shared node for "
                  "each parent)", keys ? keys[child] : name);
      }
    }
  }
  json_decref(index);
  free(parents);
  free(keys);
  return st;
}

/* Bytes of a component type and components of an accessor type; 0 for
 * one the specification does not name. */
static size_t component_size(long long t) {
  return t == 5120 || t == 5121 ? 1 : t == 5122 || t == 5123 ? 2 : t == 5125 || t == 5126 ? 4 : 0;
}
static size_t components(const json_t *type) {
  static const struct { const char *name; size_t n; } T[] = {
      {"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT2", 4}, {"MAT3", 9}, {"MAT4", 16}};
  for (size_t i = 0; i < sizeof T / sizeof T[0]; i++)
    if (json_is_string(type) && !strcmp(json_string_value(type), T[i].name)) return T[i].n;
  return 0;
}

/* A sparse accessor's parts, all of which assimp uses unchecked: its
 * count, its indices' and values' views holding count entries, and its
 * own count, for which it allocates an array, within the buffers' bytes. */
static sh_status check_sparse(const check *c, const json_t *root, size_t i,
                              const json_t *acc, unsigned long long buffer_bytes) {
  const json_t *sparse = json_object_get(acc, "sparse"), *views = json_object_get(root, "bufferViews");
  sh__jseg seg[5] = {{"accessors", 0}, {NULL, (int)i}, {"sparse", 0}, {NULL, 0}, {NULL, 0}};
  long long count = whole(acc, "count"), n = whole(sparse, "count");
  size_t elem = component_size(whole(acc, "componentType")) * components(json_object_get(acc, "type"));
  if (!json_is_object(sparse)) return fail(c, seg, 3, "a sparse accessor's 'sparse' is an object");
  if (elem == 0) elem = 64; /* assimp refuses it, or takes the largest */
  if (count < 0 || (unsigned long long)count > buffer_bytes / elem)
    return fail(c, seg, 2,
                "a sparse accessor of %lld elements of %zu bytes, more than the %llu bytes "
                "of the file's buffers", count, elem, buffer_bytes);
  seg[3].key = "count";
  if (n < 1 || n > count)
    return fail(c, seg, 4, "a sparse accessor's count is a whole number from 1 to the "
                "accessor's count (%lld)", count);
  static const char *const PART[2] = {"indices", "values"};
  for (int p = 0; p < 2; p++) {
    const json_t *part = json_object_get(sparse, PART[p]);
    seg[3].key = PART[p];
    if (!json_is_object(part)) return fail(c, seg, 3, "a sparse accessor needs '%s'", PART[p]);
    long long view = whole(part, "bufferView"), off = whole(part, "byteOffset");
    size_t size = p ? elem : component_size(whole(part, "componentType"));
    seg[4].key = "bufferView";
    if (view < 0 || (unsigned long long)view >= json_array_size(views))
      return fail(c, seg, json_object_get(part, "bufferView") ? 5 : 4,
                  "sparse %s need a bufferView (one of the %zu)", PART[p],
                  json_array_size(views));
    seg[4].key = "componentType";
    long long type = whole(part, "componentType");
    if (!p && type != 5121 && type != 5123 && type != 5125)
      return fail(c, seg, json_object_get(part, "componentType") ? 5 : 4,
                  "sparse indices are of componentType 5121, 5123 or 5125");
    long long len = whole(json_array_get(views, (size_t)view), "byteLength");
    if (off < 0) off = 0;
    if (len < off || (unsigned long long)n > (unsigned long long)(len - off) / size)
      return fail(c, seg, 4, "%lld sparse %s of %zu bytes from byte %lld, more than "
                  "bufferView %lld's %lld bytes", n, PART[p], size, off, view, len);
  }
  return SH_OK;
}

static sh_status check_accessors(const check *c, const json_t *root) {
  const json_t *accessors = json_object_get(root, "accessors");
  const json_t *buffers = json_object_get(root, "buffers");
  unsigned long long bytes = 0;
  for (size_t b = 0; b < json_array_size(buffers); b++) {
    long long len = whole(json_array_get(buffers, b), "byteLength");
    if (len > 0 && bytes < ULLONG_MAX / 2) bytes += (unsigned long long)len;
  }
  for (size_t i = 0; i < json_array_size(accessors); i++) {
    const json_t *acc = json_array_get(accessors, i);
    if (!json_object_get(acc, "sparse")) continue;
    sh_status st = check_sparse(c, root, i, acc, bytes);
    if (st != SH_OK) return st;
  }
  return SH_OK;
}

/* The skin of each node that has one: assimp reads one inverse bind
 * matrix per joint from the accessor `inverseBindMatrices`, through a null
 * pointer when it is missing (which glTF allows, meaning identities) and
 * past the accessor's data when it holds fewer matrices than joints. */
static sh_status check_skins(const check *c, const json_t *root) {
  const json_t *nodes = json_object_get(root, "nodes"), *skins = json_object_get(root, "skins");
  const json_t *accessors = json_object_get(root, "accessors");
  for (size_t i = 0; i < json_array_size(nodes); i++) {
    long long k = whole(json_array_get(nodes, i), "skin");
    if (k < 0 || (unsigned long long)k >= json_array_size(skins)) continue; /* assimp refuses */
    const json_t *skin = json_array_get(skins, (size_t)k);
    size_t joints = json_array_size(json_object_get(skin, "joints"));
    long long ibm = whole(skin, "inverseBindMatrices");
    sh__jseg seg[3] = {{"skins", 0}, {NULL, (int)k}, {"inverseBindMatrices", 0}};
    if (ibm < 0)
      return fail(c, seg, json_object_get(skin, "inverseBindMatrices") ? 3 : 2,
                  "a skin (of node %zu) needs its inverseBindMatrices: assimp 5.2 reads "
                  "them without checking that they are there", i);
    long long count = whole(json_array_get(accessors, (size_t)ibm), "count");
    if ((unsigned long long)ibm < json_array_size(accessors) && (count < 0 || (size_t)count < joints))
      return fail(c, seg, 3, "accessor %lld holds %lld inverse bind matrices, fewer than the "
                  "skin's %zu joints", ibm, count, joints);
  }
  return SH_OK;
}

static uint32_t le32(const unsigned char *p) {
  return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

int sh__gltf_json_text(const char *data, size_t size) {
  size_t lead = 0;
  while (lead < size && data[lead] && strchr(" \t\r\n", data[lead])) lead++;
  return lead < size && data[lead] == '{';
}

sh_status sh__gltf_check(const char *path, const char *data, size_t size, sh_error *err) {
  check c = {path, data, size, "", err};
  const unsigned char *u = (const unsigned char *)data;
  if (size >= 4 && !memcmp(data, "glTF", 4)) {
    char ext[8];
    sh_file_extension(path, ext, sizeof ext);
    if (strcmp(ext, "glb")) {
      /* assimp's glTF importers read binary glTF by the name alone. */
      sh_error_set(err, SH_ERR_MESH,
                   "cannot load mesh '%s': it is a binary glTF (GLB), which assimp reads "
                   "only from a file named *.glb: rename it", path);
      sh_error_set_file(err, path);
      return SH_ERR_MESH;
    }
    /* Binary glTF: a 12-byte header (magic, version, length), then the
     * JSON's length and format (version 1) or type (2), then the JSON.
     * assimp checks the lengths against the file itself (tried by hand:
     * each a length of 2^32 - 16 in a 588-byte file), and refuses a file
     * whose JSON is not all there. */
    if (size < 20 || le32(u + 12) > size - 20) return SH_OK;
    c.text = data + 20;
    c.len = le32(u + 12);
    c.where = " (in its JSON chunk)";
  }
  size_t lead = 0;
  while (lead < c.len && strchr(" \t\r\n", c.text[lead]) && c.text[lead]) lead++;
  if (lead == c.len || c.text[lead] != '{') return SH_OK; /* not glTF: assimp refuses it */
  json_error_t je;
  json_t *root = json_loadb(c.text, c.len, JSON_REJECT_DUPLICATES, &je);
  if (!root) {
    sh_error_set(err, SH_ERR_MESH, "cannot load mesh '%s'%s: line %d, column %d: %s", path,
                 c.where, je.line, je.column, je.text);
    sh_error_set_file(err, path);
    if (err) {
      err->line = je.line;
      err->column = je.column;
    }
    return SH_ERR_MESH;
  }
  sh_status st = check_nodes(&c, root);
  if (st == SH_OK) st = check_accessors(&c, root);
  if (st == SH_OK) st = check_skins(&c, root);
  json_decref(root);
  return st;
}
