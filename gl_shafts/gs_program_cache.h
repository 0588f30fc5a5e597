/* A cache on disk of linked shader programs, through ARB_get_program_binary
 * (core in GL 4.1): the driver's binary of each program gs_program.c links
 * is kept in a file, and a later process (or renderer) that needs the same
 * program from the same driver loads it with glProgramBinary instead of
 * compiling and linking the GLSL.
 *
 * Key: the exact text each stage is compiled from (the #version line, the
 * variant's #defines and baked parameters, common.glsl, the stage's source
 * with its include; gs__program_source_parts of gs_program.h gives it, and
 * gs_program.c compiles from the same call), and the driver: GL_VENDOR, GL_RENDERER, GL_VERSION,
 * GL_SHADING_LANGUAGE_VERSION and this library's version (sh_version). A
 * file's name is a 64-bit FNV-1a hash of the key, and the file holds the
 * whole key, compared byte for byte on load, so a hash collision is a miss,
 * never a wrong program. A binary the driver refuses (glProgramBinary
 * leaves the program unlinked, as after a driver update that kept its
 * strings) is removed and the program compiled as if it were not there.
 *
 * Where: $SHAFTS_PROGRAM_CACHE if set ("off" or "" turns the cache off),
 * else $XDG_CACHE_HOME/shafts/programs, else ~/.cache/shafts/programs, a
 * directory of any length (reached through directory descriptors, openat,
 * so even one longer than PATH_MAX works).
 * Bounded: past 64 MiB the files least recently used (by modification
 * time, which a hit refreshes) go until it is under 48 MiB.
 *
 * Failures never fail a render: a directory that cannot be made or
 * written, a short or foreign file, a driver with no binary formats
 * (GL_NUM_PROGRAM_BINARY_FORMATS is 0) all fall back to compiling, and
 * nothing is printed. Writes are atomic (an unnamed temporary, O_TMPFILE,
 * given its name only when complete, so even a killed process leaves no
 * partial entry), so processes and threads may share the directory.
 *
 * On Mesa the binary holds the linked program in Mesa's intermediate form,
 * not llvmpipe's machine code: the JIT compilation at the first draw is
 * spared by Mesa's own shader cache (MESA_SHADER_CACHE_DIR, on by default),
 * which this cache complements (docs/gl_shafts.md, "Start-up of the command
 * line", has both measured). */
#ifndef GS_PROGRAM_CACHE_H
#define GS_PROGRAM_CACHE_H

#include "gs_gl.h"
#include "gs_glsl.h"

#include <stddef.h>

/* Before glLinkProgram: asks the driver to keep the program's binary
 * retrievable (GL_PROGRAM_BINARY_RETRIEVABLE_HINT). */
void gs__program_cache_prepare(GLuint prog);

/* The program of vs and fs with `defines`, linked from the cache with the
 * context current on this thread, or 0 if it is not there (or the cache is
 * off). Leaves no GL error behind. */
GLuint gs__program_cache_load(const gs__glsl *vs, const gs__glsl *fs,
                              const char *defines);

/* Stores the binary of prog, just linked from vs, fs and `defines`. */
void gs__program_cache_store(GLuint prog, const gs__glsl *vs,
                             const gs__glsl *fs, const char *defines);

/* The layer below, for the tests: the cache directory now (malloc'ed, of
 * any length; NULL when the cache is off or out of memory), the driver
 * description of the current context, the key of a program (malloc'ed,
 * *len bytes; NULL out of memory or for an unknown include), and loading
 * and storing by key in a given directory. store returns 1 if a file was
 * written. */
char *gs__program_cache_dir(void);
void gs__program_cache_driver(char *buf, size_t size);
char *gs__program_cache_key(const char *driver, const gs__glsl *vs,
                            const gs__glsl *fs, const char *defines,
                            size_t *len);
/* The name of a key's file in the directory: its FNV-1a 64 hash in hex and
 * ".bin", 20 characters and a NUL. */
#define GS__CACHE_NAME_SIZE 21
void gs__program_cache_name(const char *key, size_t len,
                            char name[GS__CACHE_NAME_SIZE]);
/* Opens the directory `dir` (O_PATH), walking it one component at a time
 * with openat so that its length is not bounded by PATH_MAX (only each
 * component by NAME_MAX), making the missing ones (0700) if `create`.
 * Returns the descriptor, or -1 with errno. */
int gs__program_cache_open_dir(const char *dir, int create);
GLuint gs__program_cache_load_key(const char *dir, const char *key,
                                  size_t len);
int gs__program_cache_store_key(const char *dir, const char *key, size_t len,
                                GLuint prog);

/* Counts since the process started: programs loaded from the cache,
 * looked for and not found (or refused), and stored. */
typedef struct gs__program_cache_counts {
  long hits, misses, stores;
} gs__program_cache_counts;
gs__program_cache_counts gs__program_cache_counts_get(void);

#endif
