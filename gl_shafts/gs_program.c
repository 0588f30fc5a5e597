#include "gs_program.h"

#include <stdlib.h>
#include <string.h>

static sh_status compile(GLenum type, const gs__glsl *src, const char *defines,
                         GLuint *out, sh_error *err) {
  const char *parts[] = {"#version 450 core\n", defines, "\n#line 1\n",
                         gs__glsl_common_glsl.text, "\n#line 1\n", src->text};
  GLuint sh = glCreateShader(type);
  if (!sh) return gs__gl_check("creating a shader", err);
  glShaderSource(sh, (GLsizei)(sizeof parts / sizeof parts[0]), parts, NULL);
  glCompileShader(sh);
  GLint ok = 0;
  glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[700];
    glGetShaderInfoLog(sh, sizeof log, NULL, log);
    glDeleteShader(sh);
    return sh_error_set(err, SH_ERR_DEVICE,
                        "the shader %s (with common.glsl and \"%s\") does not "
                        "compile: %s",
                        src->name, defines, log);
  }
  *out = sh;
  return SH_OK;
}

static sh_status build(const gs__glsl *vs, const gs__glsl *fs,
                       const char *defines, GLuint *out, sh_error *err) {
  GLuint v = 0, f = 0;
  sh_status st = compile(GL_VERTEX_SHADER, vs, defines, &v, err);
  if (st == SH_OK) st = compile(GL_FRAGMENT_SHADER, fs, defines, &f, err);
  if (st != SH_OK) {
    if (v) glDeleteShader(v);
    return st;
  }
  GLuint prog = glCreateProgram();
  glAttachShader(prog, v);
  glAttachShader(prog, f);
  glLinkProgram(prog);
  glDeleteShader(v);
  glDeleteShader(f);
  GLint ok = 0;
  glGetProgramiv(prog, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[700];
    glGetProgramInfoLog(prog, sizeof log, NULL, log);
    glDeleteProgram(prog);
    return sh_error_set(err, SH_ERR_DEVICE,
                        "the shaders %s and %s (with \"%s\") do not link: %s",
                        vs->name, fs->name, defines, log);
  }
  *out = prog;
  return gs__gl_check("building a shader program", err);
}

sh_status gs__program_get(gs__programs *c, const gs__glsl *vs,
                          const gs__glsl *fs, const char *defines,
                          GLuint *out, sh_error *err) {
  for (int i = 0; i < c->n; i++)
    if (c->entry[i].vs == vs && c->entry[i].fs == fs &&
        !strcmp(c->entry[i].defines, defines)) {
      *out = c->entry[i].id;
      return SH_OK;
    }
  if (c->n == c->cap) {
    int cap = c->cap ? 2 * c->cap : 16;
    gs__program_entry *e = realloc(c->entry, (size_t)cap * sizeof *e);
    if (!e) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
    c->entry = e;
    c->cap = cap;
  }
  size_t len = strlen(defines) + 1;
  char *copy = malloc(len);
  if (!copy) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  memcpy(copy, defines, len);
  GLuint id = 0;
  sh_status st = build(vs, fs, defines, &id, err);
  if (st != SH_OK) {
    free(copy);
    return st;
  }
  c->entry[c->n].vs = vs;
  c->entry[c->n].fs = fs;
  c->entry[c->n].defines = copy;
  c->entry[c->n].id = id;
  c->n++;
  *out = id;
  return SH_OK;
}

void gs__programs_free(gs__programs *c) {
  for (int i = 0; i < c->n; i++) {
    glDeleteProgram(c->entry[i].id);
    free(c->entry[i].defines);
  }
  free(c->entry);
  memset(c, 0, sizeof *c);
}

void gs__uniform_i(GLuint prog, const char *name, int v) {
  GLint loc = glGetUniformLocation(prog, name);
  if (loc >= 0) glProgramUniform1i(prog, loc, v);
}

void gs__uniform_f(GLuint prog, const char *name, double v) {
  GLint loc = glGetUniformLocation(prog, name);
  if (loc >= 0) glProgramUniform1f(prog, loc, (float)v);
}

void gs__uniform_2f(GLuint prog, const char *name, double x, double y) {
  GLint loc = glGetUniformLocation(prog, name);
  if (loc >= 0) glProgramUniform2f(prog, loc, (float)x, (float)y);
}

void gs__uniform_v3(GLuint prog, const char *name, sh_vec3 v) {
  GLint loc = glGetUniformLocation(prog, name);
  if (loc >= 0) glProgramUniform3f(prog, loc, (float)v.x, (float)v.y, (float)v.z);
}

void gs__uniform_4f(GLuint prog, const char *name, double x, double y,
                    double z, double w) {
  GLint loc = glGetUniformLocation(prog, name);
  if (loc >= 0)
    glProgramUniform4f(prog, loc, (float)x, (float)y, (float)z, (float)w);
}

void gs__uniform_mat4(GLuint prog, const char *name, const sh_mat4 *m) {
  GLint loc = glGetUniformLocation(prog, name);
  if (loc < 0) return;
  float f[16];
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 4; c++) f[4 * r + c] = (float)m->m[r][c];
  glProgramUniformMatrix4fv(prog, loc, 1, GL_TRUE, f); /* row-major */
}
