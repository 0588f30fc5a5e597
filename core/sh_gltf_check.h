/* Internal to sh_mesh.c (not installed, not exported): a check of a glTF
 * file's JSON (a .gltf file, or the JSON chunk of a .glb) before assimp
 * reads it, for what Debian's assimp 5.2 glTF importer does not check.
 *
 * Found by hand (fuzz/known/gltf_*, core/sh_gltf_check_test.c) while
 * checking the formats mesh_fuzz feeds for counts larger than the file:
 *   - a sparse accessor's array is allocated at the accessor's count before
 *     anything is checked (a 700-byte file asked for 12 GB), read with the
 *     sparse count from its index and value views without a bound (a heap
 *     over-read), and without its `indices` or `values` objects, or their
 *     `bufferView`, assimp reads through a null pointer;
 *   - a skin's inverse bind matrices are read, one a joint, through a
 *     null pointer when the skin has none (glTF allows that: identities)
 *     and past the accessor when it holds fewer than the joints (found by
 *     hand: SEGV in the fuzzing build, fuzz/known/gltf_skin_*);
 *   - a node that is the child of two nodes is copied for each (glTF 2.0
 *     says the hierarchy is a set of disjoint trees): a chain of 24 nodes
 *     each naming the next twice, 1.3 kB, took over 2 GB.
 * assimp checks the rest of what a file declares against its data (buffer
 * lengths against their data, views against buffers, accessors against
 * views), so the check is of these alone, not a glTF reader.
 *
 * The JSON must be what jansson accepts, without duplicate keys (so that
 * what assimp's rapidjson reads is what was checked). */
#ifndef SH_GLTF_CHECK_H
#define SH_GLTF_CHECK_H

#include <stddef.h>

#include "sh_error.h"

/* Whether assimp's glTF importers could read the file `path` by its name:
 * its extension is gltf or glb (any case) or it has none. (sh_mesh.c
 * checks, besides, every file whose importer assimp picks by its bytes.) */
int sh__gltf_candidate(const char *path);

/* Whether the `size` bytes `data` are JSON text to sh__gltf_check (its
 * first non-blank byte is '{'). Such a file that passed the check is valid
 * JSON, none of whose lines can begin with an OBJ statement (JSON's strings
 * hold no line ends, and nothing follows the value), so assimp's OBJ
 * importer, if it took the file after the glTF importers refused it,
 * would open no material library. (Not so a binary glTF: its binary chunk
 * may hold anything.) */
int sh__gltf_json_text(const char *data, size_t size);

/* Checks the glTF file `path`, whose `size` bytes are `data`: SH_OK, or
 * SH_ERR_MESH naming the file, with the line, column and key path of the
 * offending value in the JSON (the JSON chunk's, for a .glb). A file that
 * is not glTF (not a JSON object, nor a binary glTF container with all
 * of its JSON) is SH_OK: assimp refuses it. JSON that jansson does not
 * accept, or with a key twice in an object, is an error at its line and
 * column. */
sh_status sh__gltf_check(const char *path, const char *data, size_t size,
                         sh_error *err);

#endif
