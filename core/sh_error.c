#include "sh_error.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

sh_status sh_error_set(sh_error *err, sh_status status, const char *fmt, ...) {
  if (err) {
    memset(err, 0, sizeof *err);
    err->status = status;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->message, sizeof err->message, fmt, ap);
    va_end(ap);
  }
  return status;
}

void sh_error_format(const sh_error *err, char *buf, unsigned long size) {
  size_t n = 0;
  buf[0] = '\0';
  if (err->file[0]) {
    if (err->line > 0)
      n += (size_t)snprintf(buf + n, size - n, "%s:%d:%d: ", err->file,
                            err->line, err->column);
    else
      n += (size_t)snprintf(buf + n, size - n, "%s: ", err->file);
  }
  if (n < size && err->path[0])
    n += (size_t)snprintf(buf + n, size - n, "%s: ", err->path);
  if (n < size)
    snprintf(buf + n, size - n, "%s",
             err->message[0] ? err->message : sh_strerror(err->status));
}


/* The accessors of shafts.h, for bindings. */
sh_error *sh_error_new(void) { return calloc(1, sizeof(sh_error)); }
void sh_error_free(sh_error *err) { free(err); }
sh_status sh_error_status(const sh_error *err) { return err->status; }
const char *sh_error_file(const sh_error *err) { return err->file; }
int sh_error_line(const sh_error *err) { return err->line; }
int sh_error_column(const sh_error *err) { return err->column; }
const char *sh_error_key(const sh_error *err) { return err->path; }
const char *sh_error_message(const sh_error *err) {
  return err->message[0] ? err->message : sh_strerror(err->status);
}
