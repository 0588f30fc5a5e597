/* Shader programs: compiling and linking the embedded GLSL (gs_glsl.h) with
 * a block of #defines that selects a variant, a cache of the variants built
 * so far, and uniform setters. */
#ifndef GS_PROGRAM_H
#define GS_PROGRAM_H

#include "gs_gl.h"
#include "gs_glsl.h"
#include "sh_math.h"

typedef struct gs__program_entry {
  const gs__glsl *vs, *fs;
  char *defines;
  GLuint id;
  unsigned long last_use;
} gs__program_entry;

/* The programs built so far, at most GS__PROGRAMS_MAX (the least recently
 * used goes first); zero-initialise before use. */
#define GS__PROGRAMS_MAX 128
typedef struct gs__programs {
  int n, cap;
  gs__program_entry *entry;
  unsigned long clock;
  long built; /* programs built so far (for statistics) */
} gs__programs;

/* The program of vertex shader vs and fragment shader fs, each compiled as
 * "#version 450 core", gs_shared.h (the numbers C and GLSL share),
 * `defines`, common.glsl, then the stage's source. In common.glsl and in
 * the stage's source a line `#include "NAME"` (one at most in each, at the
 * start of a line) stands for the embedded file NAME (medium.glsl in
 * common.glsl; plane.glsl, shared by the two plane shaders; GLSL has no
 * #include of its own); built on first use. A compile or link failure is
 * SH_ERR_DEVICE with the shader's name and the GL info log. */
sh_status gs__program_get(gs__programs *cache, const gs__glsl *vs,
                          const gs__glsl *fs, const char *defines,
                          GLuint *out, sh_error *err);

/* The source parts a stage is compiled from, in glShaderSource's order
 * (parts and lens: room for GS__SOURCE_PARTS_MAX; lens -1 where a part is
 * NUL-terminated): the version, gs_shared.h, the defines, common.glsl and
 * the stage's file, each with its `#include "NAME"` lines replaced by the
 * embedded file NAME, whose own includes are expanded likewise up to
 * GS__INCLUDE_DEPTH deep (line_after, size bytes, GS__LINE_AFTER_SIZE
 * enough, holds the #line directives that follow them). Returns the
 * number of parts, or 0 with *bad set to the include line if NAME is
 * unknown, nested too deep or the parts do not fit. The program cache on
 * disk keys on the same parts. */
#define GS__SOURCE_PARTS_MAX 40
#define GS__INCLUDE_DEPTH 3
#define GS__LINE_AFTER_SIZE 256
int gs__program_source_parts(const gs__glsl *src, const char *defines, const char **parts,
                             GLint *lens, char *line_after, size_t size, const char **bad);

/* Deletes every program; the cache is empty afterwards. */
void gs__programs_free(gs__programs *cache);

/* The parameters of a draw (camera, medium, light, ...), declared at the
 * top of its program's source in one of two ways, chosen per renderer
 * (gs_options.live); the shaders read the same names either way:
 * - baked: `const vec3 u_org = vec3(...);`, constants holding their values.
 *   llvmpipe folds them into the code, which makes the shaders faster (a
 *   third fewer instructions a frame than with uniforms, measured on the
 *   teapot), at the price of a program per set of values, built when the
 *   values first occur.
 * - live: `uniform vec3 u_org;`, set when the program is bound, so that one
 *   program serves every set of values.
 * Also carries the variant's #define lines. */
typedef struct gs__param_value {
  char name[32];
  int kind; /* 1, 2, 3, 4 floats or 16 (a matrix, row-major) */
  float v[16];
} gs__param_value;

typedef struct gs__params {
  int bake;
  char *text;        /* #defines and declarations */
  size_t len, cap;
  gs__param_value *value; /* uniforms to set (not baked) */
  int n, nvcap;
  int nomem;
  /* The first parameter whose value is not a finite float (empty if none):
   * such a value is never written into a shader nor set as a uniform. */
  char nonfinite[64];
} gs__params;

/* Empties the block (keeping its memory) and sets whether it bakes. */
void gs__params_reset(gs__params *p, int bake);
void gs__params_free(gs__params *p);
/* Appends raw source text (#define lines). */
void gs__params_text(gs__params *p, const char *text);
void gs__param_f(gs__params *p, const char *name, double v);
void gs__param_2f(gs__params *p, const char *name, double x, double y);
void gs__param_v3(gs__params *p, const char *name, sh_vec3 v);
void gs__param_4f(gs__params *p, const char *name, double x, double y,
                  double z, double w);
void gs__param_mat4(gs__params *p, const char *name, const sh_mat4 *m);

/* The program of vs and fs with the block's text before common.glsl, bound
 * (glUseProgram) with the block's uniforms set. */
sh_status gs__program_use(gs__programs *cache, const gs__glsl *vs,
                          const gs__glsl *fs, gs__params *p, GLuint *out,
                          sh_error *err);

/* Uniform setters by name. A name the program does not use (the compiler
 * drops unused uniforms) is ignored. */
void gs__uniform_i(GLuint prog, const char *name, int v);
void gs__uniform_f(GLuint prog, const char *name, double v);
void gs__uniform_2f(GLuint prog, const char *name, double x, double y);
void gs__uniform_v3(GLuint prog, const char *name, sh_vec3 v);
void gs__uniform_4f(GLuint prog, const char *name, double x, double y,
                    double z, double w);
void gs__uniform_mat4(GLuint prog, const char *name, const sh_mat4 *m);

#endif
