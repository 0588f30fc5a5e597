#include "sh_cli.h"

#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_file.h"
#include "sh_json_out.h"

int sh_cli_int(const char *tool, const char *option, const char *text,
               long lo, long hi, long *out) {
  char *end = NULL;
  errno = 0;
  long v = text ? strtol(text, &end, 10) : 0;
  if (!text || end == text || *end || errno || v < lo || v > hi) {
    fprintf(stderr, "%s: %s expects an integer in [%ld, %ld], got '%s'\n",
            tool, option, lo, hi, text ? text : "(nothing)");
    return 0;
  }
  *out = v;
  return 1;
}

int sh_cli_double(const char *tool, const char *option, const char *text,
                  double *out) {
  char *end = NULL;
  double v = text ? strtod(text, &end) : 0;
  if (!text || end == text || *end || !isfinite(v)) {
    fprintf(stderr, "%s: %s expects a finite number, got '%s'\n", tool,
            option, text ? text : "(nothing)");
    return 0;
  }
  *out = v;
  return 1;
}

int sh_cli_operand(const char *tool, const char *arg, const char **slots[],
                   int n) {
  if (arg[0] == '-' && arg[1] != '\0') {
    fprintf(stderr, "%s: unknown option '%s' (see --help)\n", tool, arg);
    return 0;
  }
  for (int k = 0; k < n; k++)
    if (!*slots[k]) {
      *slots[k] = arg;
      return 1;
    }
  fprintf(stderr, "%s: unexpected argument '%s' (see --help)\n", tool, arg);
  return 0;
}

int sh_cli_check_render_outputs(const char *tool, const char *scene,
                                const char *const *outputs, int noutputs) {
  if (!scene || noutputs <= 0) {
    fprintf(stderr, "%s: need a scene file and -o OUTPUT (see --help)\n", tool);
    return 0;
  }
  for (int k = 0; k < noutputs; k++) {
    char ext[16];
    sh_file_extension(outputs[k], ext, sizeof ext);
    if (strcmp(ext, "exr") && strcmp(ext, "png")) {
      fprintf(stderr, "%s: output '%s' must end in .exr or .png\n", tool, outputs[k]);
      return 0;
    }
  }
  return 1;
}

int sh_cli_report(const char *tool, const sh_error *err) {
  char buf[2048];
  sh_error_format(err, buf, sizeof buf);
  fprintf(stderr, "%s: error: %s\n", tool, buf);
  return sh_exit_code(err->status);
}

struct sh_stats {
  json_t *obj;
};

sh_stats *sh_stats_new(void) {
  sh_stats *s = malloc(sizeof *s);
  if (!s) return NULL;
  s->obj = json_object();
  if (!s->obj) {
    free(s);
    return NULL;
  }
  return s;
}

sh_stats *sh_stats_from_json(const char *text) {
  json_t *o = text ? json_loads(text, 0, NULL) : NULL;
  sh_stats *s = o && json_is_object(o) ? malloc(sizeof *s) : NULL;
  if (!s) {
    json_decref(o);
    return NULL;
  }
  s->obj = o;
  return s;
}

void sh_stats_num(sh_stats *s, const char *key, double value) {
  if (s) sh__json_num(s->obj, key, value);
}

void sh_stats_str(sh_stats *s, const char *key, const char *value) {
  if (s) json_object_set_new(s->obj, key, json_string(value));
}

sh_status sh_stats_write(const sh_stats *s, const char *path, sh_error *err) {
  if (!s) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  char *text = sh__json_dumps(json_incref(s->obj));
  if (!text) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  size_t n = 0;
  while (text[n]) n++;
  text[n] = '\n'; /* replaces the terminator; the size below includes it */
  sh_status st = sh_file_write_atomic(path, text, n + 1, err);
  free(text);
  return st;
}

void sh_stats_free(sh_stats *s) {
  if (!s) return;
  json_decref(s->obj);
  free(s);
}

int sh_exit_code(sh_status status) {
  switch (status) {
  case SH_OK: return 0;
  case SH_ERR_SYNTAX:
  case SH_ERR_SCENE:
  case SH_ERR_IMAGE:
  case SH_ERR_MESH:
  case SH_ERR_ARG: return 2;
  default: return 1;
  }
}
