/* Error codes and error reports shared by every module of the core library.
 *
 * Library functions never abort or exit: they return an sh_status and, when
 * given an sh_error, fill it with a full-sentence message that names the
 * file, line, column and key path where that is known. */
#ifndef SH_ERROR_H
#define SH_ERROR_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sh_status {
  SH_OK = 0,
  SH_ERR_IO = 1,       /* a file could not be read or written */
  SH_ERR_SYNTAX = 2,   /* the scene file is not valid JSON */
  SH_ERR_SCENE = 3,    /* valid JSON that breaks the scene format */
  SH_ERR_NOMEM = 4,    /* an allocation failed */
  SH_ERR_IMAGE = 5,    /* an image could not be decoded or encoded */
  SH_ERR_MESH = 6,     /* a mesh file could not be loaded */
  SH_ERR_DEVICE = 7,   /* Embree or GL reported an error */
  SH_ERR_ARG = 8,      /* a bad argument to a library call */
  SH_ERR_CANCELLED = 9 /* the caller asked the work to stop */
} sh_status;

#define SH_ERROR_MSG_MAX 1024

/* A filled-in error report. `line` and `column` are 1-based, 0 if unknown;
 * `path` is the key path such as "lights[2].intensity", empty if unknown. */
typedef struct sh_error {
  sh_status status;
  char file[512];
  int line, column;
  char path[256];
  char message[SH_ERROR_MSG_MAX];
} sh_error;

/* A short, static description of a status code. */
const char *sh_strerror(sh_status status);

/* Fills `err` (which may be NULL) and returns `status`. The message is a
 * printf format. */
sh_status sh_error_set(sh_error *err, sh_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Writes "file:line:column: key: message" (parts that are unknown are left
 * out) into buf, which has room for size bytes. */
void sh_error_format(const sh_error *err, char *buf, unsigned long size);

#ifdef __cplusplus
}
#endif
#endif
