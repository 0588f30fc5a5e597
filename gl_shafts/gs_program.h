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
} gs__program_entry;

/* The programs built so far; zero-initialise before use. */
typedef struct gs__programs {
  int n, cap;
  gs__program_entry *entry;
} gs__programs;

/* The program of vertex shader vs and fragment shader fs, each compiled as
 * "#version 450 core", `defines`, common.glsl, then the stage's source;
 * built on first use. A compile or link failure is SH_ERR_DEVICE with the
 * shader's name and the GL info log. */
sh_status gs__program_get(gs__programs *cache, const gs__glsl *vs,
                          const gs__glsl *fs, const char *defines,
                          GLuint *out, sh_error *err);

/* Deletes every program; the cache is empty afterwards. */
void gs__programs_free(gs__programs *cache);

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
