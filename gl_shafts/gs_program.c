#include "gs_program.h"
#include "gs_program_cache.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_array.h"

/* Where the parts of a stage go: parts and lens with room for max, and
 * the #line directives that follow included files, written into lines
 * (size bytes, used so far). */
typedef struct source_out {
  const char **parts;
  GLint *lens;
  int n, max;
  char *lines;
  size_t size, used;
} source_out;

/* Adds the parts of text to o: text with each `#include "NAME"` line (at
 * the start of a line) replaced by the embedded file NAME, itself expanded
 * so (up to GS__INCLUDE_DEPTH deep), and followed by a #line that restores
 * text's own numbering. Returns 0 with *bad at the include line if NAME is
 * unknown, nested too deep or the parts do not fit, else 1. */
static int add_with_include(const char *t, source_out *o, int depth, const char **bad) {
#define ADD(s, l) (o->parts[o->n] = (s), o->lens[o->n++] = (GLint)(l))
  const char *from = t, *inc = NULL;
  int line = 1;
  for (;;) {
    inc = strstr(from, "#include \"");
    while (inc && inc != t && inc[-1] != '\n') inc = strstr(inc + 1, "#include \"");
    if (!inc) {
      if (o->n >= o->max) break;
      ADD(from, -1);
      return 1;
    }
    const char *name = inc + strlen("#include \""), *quote = strchr(name, '"');
    const char *eol = strchr(inc, '\n');
    const gs__glsl *file = NULL;
    for (int i = 0; quote && gs__glsl_all[i] && !file; i++)
      if (strlen(gs__glsl_all[i]->name) == (size_t)(quote - name) &&
          !strncmp(gs__glsl_all[i]->name, name, (size_t)(quote - name)))
        file = gs__glsl_all[i];
    for (const char *c = from; c < inc; c++) line += *c == '\n';
    char *after = o->lines + o->used;
    int len = snprintf(after, o->size - o->used, "\n#line %d\n", line + 1);
    if (!file || depth >= GS__INCLUDE_DEPTH || o->n + 3 > o->max || len < 0 ||
        (size_t)len >= o->size - o->used)
      break;
    o->used += (size_t)len + 1;
    ADD(from, inc - from);
    if (!add_with_include(file->text, o, depth + 1, bad)) return 0;
    if (o->n + 2 > o->max) break;
    ADD(after, -1);
    if (!eol) return 1;
    from = eol + 1;
    line++;
  }
#undef ADD
  *bad = inc ? inc : from;
  return 0;
}

int gs__program_source_parts(const gs__glsl *src, const char *defines, const char **parts,
                             GLint *lens, char *line_after, size_t size, const char **bad) {
  source_out o = {parts, lens, 0, GS__SOURCE_PARTS_MAX, line_after, size, 0};
  parts[o.n] = "#version 450 core\n", lens[o.n++] = -1;
  parts[o.n] = gs__glsl_gs_shared_h.text, lens[o.n++] = -1;
  parts[o.n] = defines, lens[o.n++] = -1;
  parts[o.n] = "\n#line 1\n", lens[o.n++] = -1;
  if (!add_with_include(gs__glsl_common_glsl.text, &o, 0, bad)) return 0;
  parts[o.n] = "\n#line 1\n", lens[o.n++] = -1;
  if (o.n >= o.max || !add_with_include(src->text, &o, 0, bad)) return 0;
  return o.n;
}

/* Whether a shader's compile (status GL_COMPILE_STATUS) or a program's link
 * (GL_LINK_STATUS) failed; if so, log holds the driver's reason. */
static int failed(GLuint object, GLenum status, char *log, GLsizei size) {
  GLint ok = 0;
  if (status == GL_LINK_STATUS)
    glGetProgramiv(object, status, &ok);
  else
    glGetShaderiv(object, status, &ok);
  if (ok) return 0;
  if (status == GL_LINK_STATUS)
    glGetProgramInfoLog(object, size, NULL, log);
  else
    glGetShaderInfoLog(object, size, NULL, log);
  return 1;
}

static sh_status compile(GLenum type, const gs__glsl *src, const char *defines,
                         GLuint *out, sh_error *err) {
  const char *parts[GS__SOURCE_PARTS_MAX], *bad = NULL;
  GLint lens[GS__SOURCE_PARTS_MAX];
  char line_after[GS__LINE_AFTER_SIZE];
  int nparts = gs__program_source_parts(src, defines, parts, lens, line_after,
                                        sizeof line_after, &bad);
  if (!nparts) {
    const char *eol = strchr(bad, '\n');
    return sh_error_set(err, SH_ERR_DEVICE, "the shader %s includes an unknown file: %.*s",
                        src->name, (int)(eol ? eol - bad : (long)strlen(bad)), bad);
  }
  GLuint sh = glCreateShader(type);
  if (!sh) return gs__gl_check("creating a shader", err);
  glShaderSource(sh, (GLsizei)nparts, parts, lens);
  glCompileShader(sh);
  char log[700];
  if (failed(sh, GL_COMPILE_STATUS, log, sizeof log)) {
    glDeleteShader(sh);
    /* The driver's reason first: the defines can be long, and a message
     * has a bounded length. */
    return sh_error_set(err, SH_ERR_DEVICE,
                        "the shader %s does not compile: %s (with "
                        "common.glsl and \"%.300s\")",
                        src->name, log, defines);
  }
  *out = sh;
  return SH_OK;
}

static sh_status build(const gs__glsl *vs, const gs__glsl *fs,
                       const char *defines, GLuint *out, sh_error *err) {
  /* A binary of the same sources from the same driver, kept on disk by an
   * earlier run (gs_program_cache.h). */
  if ((*out = gs__program_cache_load(vs, fs, defines)))
    return SH_OK;
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
  gs__program_cache_prepare(prog);
  glLinkProgram(prog);
  glDeleteShader(v);
  glDeleteShader(f);
  char log[700];
  if (failed(prog, GL_LINK_STATUS, log, sizeof log)) {
    glDeleteProgram(prog);
    return sh_error_set(err, SH_ERR_DEVICE,
                        "the shaders %s and %s (with \"%s\") do not link: %s",
                        vs->name, fs->name, defines, log);
  }
  *out = prog;
  st = gs__gl_check("building a shader program", err);
  if (st == SH_OK)
    gs__program_cache_store(prog, vs, fs, defines);
  return st;
}

sh_status gs__program_get(gs__programs *c, const gs__glsl *vs,
                          const gs__glsl *fs, const char *defines,
                          GLuint *out, sh_error *err) {
  c->clock++;
  for (int i = 0; i < c->n; i++)
    if (c->entry[i].vs == vs && c->entry[i].fs == fs &&
        !strcmp(c->entry[i].defines, defines)) {
      c->entry[i].last_use = c->clock;
      *out = c->entry[i].id;
      return SH_OK;
    }
  if (c->n == GS__PROGRAMS_MAX) {
    /* Full: drop the least recently used (baked programs pile up when the
     * camera moves). */
    int lru = 0;
    for (int i = 1; i < c->n; i++)
      if (c->entry[i].last_use < c->entry[lru].last_use) lru = i;
    glDeleteProgram(c->entry[lru].id);
    free(c->entry[lru].defines);
    c->entry[lru] = c->entry[--c->n];
  }
  gs__program_entry *e = sh__array_grow(c->entry, c->n, &c->cap, 16,
                                        sizeof *e);
  if (!e) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  c->entry = e;
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
  c->entry[c->n].last_use = c->clock;
  c->n++;
  c->built++;
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

void gs__params_reset(gs__params *p, int bake) {
  p->bake = bake;
  p->len = 0;
  p->n = 0;
  p->nomem = 0;
  p->nonfinite[0] = '\0';
  if (p->text) p->text[0] = '\0';
}

void gs__params_free(gs__params *p) {
  free(p->text);
  free(p->value);
  memset(p, 0, sizeof *p);
}

void gs__params_text(gs__params *p, const char *text) {
  size_t n = strlen(text);
  if (p->len + n + 1 > p->cap) {
    size_t cap = p->cap ? 2 * p->cap : 4096;
    while (cap < p->len + n + 1) cap *= 2;
    char *t = realloc(p->text, cap);
    if (!t) {
      p->nomem = 1;
      return;
    }
    p->text = t;
    p->cap = cap;
  }
  memcpy(p->text + p->len, text, n + 1);
  p->len += n;
}

/* A float as a GLSL literal that reads back as the same float. */
static void literal(char *buf, size_t size, float v) {
  snprintf(buf, size, "%.9g", (double)v);
  if (!strpbrk(buf, ".eEn")) strncat(buf, ".0", size - strlen(buf) - 1);
}

static const char *const TYPES[17] = {NULL, "float", "vec2", "vec3", "vec4",
                                      NULL, NULL, NULL, NULL, NULL, NULL,
                                      NULL, NULL, NULL, NULL, NULL, "mat4"};

static void param(gs__params *p, const char *name, int kind, const float *v) {
  char line[1024];
  for (int i = 0; i < kind; i++)
    if (!isfinite(v[i])) {
      if (!p->nonfinite[0])
        snprintf(p->nonfinite, sizeof p->nonfinite, "%s", name);
      return;
    }
  if (p->bake) {
    /* GLSL matrices are built column by column. */
    int n = snprintf(line, sizeof line, "const %s %s = %s(", TYPES[kind], name, TYPES[kind]);
    for (int i = 0; i < kind; i++) {
      char lit[32];
      literal(lit, sizeof lit, kind == 16 ? v[4 * (i % 4) + i / 4] : v[i]);
      n += snprintf(line + n, sizeof line - (size_t)n, "%s%s", i ? ", " : "", lit);
    }
    snprintf(line + n, sizeof line - (size_t)n, ");\n");
    gs__params_text(p, line);
    return;
  }
  snprintf(line, sizeof line, "uniform %s %s;\n", TYPES[kind], name);
  gs__params_text(p, line);
  gs__param_value *nv = sh__array_grow(p->value, p->n, &p->nvcap, 32,
                                       sizeof *nv);
  if (!nv) {
    p->nomem = 1;
    return;
  }
  p->value = nv;
  gs__param_value *pv = &p->value[p->n++];
  snprintf(pv->name, sizeof pv->name, "%s", name);
  pv->kind = kind;
  memcpy(pv->v, v, (size_t)kind * sizeof *v);
}

void gs__param_f(gs__params *p, const char *name, double v) {
  float f[1] = {(float)v};
  param(p, name, 1, f);
}

void gs__param_2f(gs__params *p, const char *name, double x, double y) {
  float f[2] = {(float)x, (float)y};
  param(p, name, 2, f);
}

void gs__param_v3(gs__params *p, const char *name, sh_vec3 v) {
  float f[3] = {(float)v.x, (float)v.y, (float)v.z};
  param(p, name, 3, f);
}

void gs__param_4f(gs__params *p, const char *name, double x, double y,
                  double z, double w) {
  float f[4] = {(float)x, (float)y, (float)z, (float)w};
  param(p, name, 4, f);
}

void gs__param_mat4(gs__params *p, const char *name, const sh_mat4 *m) {
  float f[16];
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 4; c++) f[4 * r + c] = (float)m->m[r][c];
  param(p, name, 16, f);
}

sh_status gs__program_use(gs__programs *c, const gs__glsl *vs,
                          const gs__glsl *fs, gs__params *p, GLuint *out,
                          sh_error *err) {
  if (p->nomem) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  if (p->nonfinite[0])
    return sh_error_set(err, SH_ERR_SCENE,
                        "the scene gives the shader parameter %s a value that "
                        "is not a finite single-precision number (beyond "
                        "3.4e38 or not a number): scale the scene's "
                        "quantities down",
                        p->nonfinite);
  sh_status st = gs__program_get(c, vs, fs, p->text ? p->text : "", out, err);
  if (st != SH_OK) return st;
  glUseProgram(*out);
  for (int i = 0; i < p->n; i++) {
    const gs__param_value *v = &p->value[i];
    GLint loc = glGetUniformLocation(*out, v->name);
    if (loc < 0) continue;
    switch (v->kind) {
    case 1: glProgramUniform1f(*out, loc, v->v[0]); break;
    case 2: glProgramUniform2f(*out, loc, v->v[0], v->v[1]); break;
    case 3: glProgramUniform3f(*out, loc, v->v[0], v->v[1], v->v[2]); break;
    case 4: glProgramUniform4f(*out, loc, v->v[0], v->v[1], v->v[2], v->v[3]); break;
    default: glProgramUniformMatrix4fv(*out, loc, 1, GL_TRUE, v->v); break;
    }
  }
  return SH_OK;
}
