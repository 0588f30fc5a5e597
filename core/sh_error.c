#include "sh_error.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_str.h"
#include "shafts.h"

const char *sh_strerror(sh_status status) {
  switch (status) {
  case SH_OK: return "no error";
  case SH_ERR_IO: return "input/output error";
  case SH_ERR_SYNTAX: return "JSON syntax error";
  case SH_ERR_SCENE: return "invalid scene";
  case SH_ERR_NOMEM: return "out of memory";
  case SH_ERR_IMAGE: return "image error";
  case SH_ERR_MESH: return "mesh error";
  case SH_ERR_DEVICE: return "device error";
  case SH_ERR_ARG: return "invalid argument";
  case SH_ERR_CANCELLED: return "cancelled";
  }
  return "unknown error";
}

void sh_error_init(sh_error *err) {
  const sh_error init = SH_ERROR_INIT;
  *err = init;
}

void sh_error_clear(sh_error *err) {
  if (!err) return;
  free(err->block_);
  sh_error_init(err);
}

void sh_error_move(sh_error *to, sh_error *from) {
  if (to && to != from) {
    free(to->block_);
    *to = *from;
    sh_error_init(from);
  } else if (!to) {
    sh_error_clear(from);
  }
}

/* A string of the report, NULL read as "". */
static const char *sh__error_str(const char *s) { return s ? s : ""; }

/* Points the report's strings into one new block holding copies of file,
 * path and message (which may be its old strings), and frees the old
 * block. 0 when out of memory, the report unchanged. */
static int sh__error_store(sh_error *err, const char *file, const char *path,
                           const char *message) {
  size_t nf = strlen(file) + 1, np = strlen(path) + 1, nm = strlen(message) + 1;
  char *b = malloc(nf + np + nm);
  if (!b) return 0;
  memcpy(b, file, nf);
  memcpy(b + nf, path, np);
  memcpy(b + nf + np, message, nm);
  free(err->block_);
  err->block_ = b;
  err->file = b;
  err->path = b + nf;
  err->message = b + nf + np;
  return 1;
}

sh_status sh_error_vset(sh_error *err, sh_status status, const char *fmt,
                        va_list ap) {
  if (!err) return status;
  /* Formatted before the old block goes: the arguments may point into it. */
  char *message = sh__vprintf_alloc(fmt, ap);
  free(err->block_);
  sh_error_init(err);
  err->status = status;
  if (message) {
    err->block_ = message;
    err->message = message;
  } else {
    err->message = sh_strerror(status);
  }
  return status;
}

sh_status sh_error_set(sh_error *err, sh_status status, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  sh_error_vset(err, status, fmt, ap);
  va_end(ap);
  return status;
}

void sh_error_set_file(sh_error *err, const char *file) {
  if (err)
    sh__error_store(err, sh__error_str(file), sh__error_str(err->path),
                    sh__error_str(err->message));
}

void sh_error_set_key(sh_error *err, const char *fmt, ...) {
  if (!err) return;
  va_list ap;
  va_start(ap, fmt);
  char *key = sh__vprintf_alloc(fmt, ap);
  va_end(ap);
  if (key)
    sh__error_store(err, sh__error_str(err->file), key,
                    sh__error_str(err->message));
  free(key);
}

/* The message, or the status's description when there is none. */
static const char *sh__error_sentence(const sh_error *err) {
  return err->message && err->message[0] ? err->message
                                         : sh_strerror(err->status);
}

unsigned long sh_error_format(const sh_error *err, char *buf,
                              unsigned long size) {
  const char *file = sh__error_str(err->file), *key = sh__error_str(err->path);
  char at[64] = "";
  if (file[0] && err->line > 0)
    snprintf(at, sizeof at, ":%d:%d", err->line, err->column);
  int n = snprintf(buf, size, "%s%s%s%s%s%s", file, at, file[0] ? ": " : "",
                   key, key[0] ? ": " : "", sh__error_sentence(err));
  return n < 0 ? 0 : (unsigned long)n;
}

char *sh_error_text(const sh_error *err) {
  unsigned long n = sh_error_format(err, NULL, 0);
  char *text = malloc(n + 1);
  if (text) sh_error_format(err, text, n + 1);
  return text;
}

/* The accessors of shafts.h, for bindings. */
sh_error *sh_error_new(void) {
  sh_error *err = malloc(sizeof *err);
  if (err) sh_error_init(err);
  return err;
}
void sh_error_free(sh_error *err) {
  sh_error_clear(err);
  free(err);
}
sh_status sh_error_status(const sh_error *err) { return err->status; }
const char *sh_error_file(const sh_error *err) { return sh__error_str(err->file); }
int sh_error_line(const sh_error *err) { return err->line; }
int sh_error_column(const sh_error *err) { return err->column; }
const char *sh_error_key(const sh_error *err) { return sh__error_str(err->path); }
const char *sh_error_message(const sh_error *err) { return sh__error_sentence(err); }
