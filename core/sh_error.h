/* Error codes and error reports shared by every module of the core library.
 *
 * Library functions never abort or exit: they return an sh_status and, when
 * given an sh_error, fill it with a full-sentence message that names the
 * file, line, column and key path where that is known. A report owns its
 * strings (of any length): initialise it with SH_ERROR_INIT and free them
 * with sh_error_clear. */
#ifndef SH_ERROR_H
#define SH_ERROR_H

#include <stdarg.h>

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

/* A filled-in error report. Its strings are of any length (no path or
 * message is ever cut) and live on the heap, owned by the report:
 *
 *   sh_error err = SH_ERROR_INIT;       (or sh_error_init(&err))
 *   if (sh_scene_load(path, &scene, &err) != SH_OK) ... err.message ...
 *   sh_error_clear(&err);               (frees the strings; err is reusable)
 *
 * A report must be initialised before its first use (a zeroed one, {0},
 * is initialised too) and cleared when done; each call that fills it
 * frees what it held before, so one report serves a whole loop of calls
 * and is cleared once. Calls that succeed leave it as they found it,
 * except those that say they clear it.
 *
 * `file` is the file the error is in, `path` the key path such as
 * "lights[2].intensity", both "" if unknown; `line` and `column` are
 * 1-based, 0 if unknown; `message` is a full sentence. Once a call has
 * filled the report none of them is NULL (a zeroed report that was never
 * filled has NULL strings; the accessors of shafts.h and sh_error_format
 * read NULL as ""). The strings are read-only: change them with the
 * setters below, which copy what they are given. When memory runs out
 * while filling a report, it still gets its status, and its message is
 * the static sh_strerror(status) ("out of memory" for SH_ERR_NOMEM); the
 * location is then left as it was.
 *
 * ABI (libshafts.so.1): five fields then one internal pointer, in this
 * order: int status, const char *file, int line, int column,
 * const char *path, const char *message, void *block_. `block_` is the
 * heap block the strings point into (NULL when they are static); do not
 * touch it, copy a filled report (the copy is not owned: only one of them
 * may be cleared) or free its strings yourself. Bindings that should not
 * mirror the struct use sh_error_new, the accessors and sh_error_free
 * (shafts.h). */
typedef struct sh_error {
  sh_status status;
  const char *file;
  int line, column;
  const char *path;
  const char *message;
  void *block_;
} sh_error;

#define SH_ERROR_INIT {SH_OK, "", 0, 0, "", "", NULL}

/* Initialises a report as SH_ERROR_INIT does. */
void sh_error_init(sh_error *err);

/* Frees the report's strings and initialises it again. NULL is ignored. */
void sh_error_clear(sh_error *err);

/* A short, static description of a status code. */
const char *sh_strerror(sh_status status);

/* Fills `err` (which may be NULL) and returns `status`: the message is the
 * printf format's text, the location is cleared (file and path "", line
 * and column 0). The arguments may be the report's own strings (a message
 * that wraps err->message, say). */
sh_status sh_error_set(sh_error *err, sh_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
sh_status sh_error_vset(sh_error *err, sh_status status, const char *fmt,
                        va_list ap)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 0)))
#endif
    ;

/* The location of a filled report: sets its file (NULL: ""), or its key
 * path from a printf format; the rest is kept. NULL `err` is ignored. */
void sh_error_set_file(sh_error *err, const char *file);
void sh_error_set_key(sh_error *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Moves the report `from` into `to` (freeing what `to` held) and leaves
 * `from` initialised: for a call that reports through a report of its own
 * and hands it on. `to` may be NULL (then `from` is only cleared). */
void sh_error_move(sh_error *to, sh_error *from);

/* Writes "file:line:column: key: message" (parts that are unknown are left
 * out) into buf, which has room for size bytes (NUL-terminated, cut to
 * fit; buf may be NULL when size is 0). Returns the length of the whole
 * text, as snprintf does: a result >= size means it was cut. */
unsigned long sh_error_format(const sh_error *err, char *buf,
                              unsigned long size);

/* The same text on the heap, whole; the caller frees it. NULL when out of
 * memory (sh_error_message still gives the message then). */
char *sh_error_text(const sh_error *err);

#ifdef __cplusplus
}
#endif
#endif
