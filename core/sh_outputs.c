/* sh_outputs.h: a run's inputs and outputs compared by resolved path, the
 * outputs staged in unnamed temporary files and published together. */
#define _GNU_SOURCE /* O_TMPFILE */
#include "sh_outputs.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sh_array.h"
#include "sh_image_int.h"
#include "sh_str.h"

typedef struct sh__file {
  char *given;    /* the path as given */
  char *resolved; /* realpath, or realpath(parent) + "/" + name */
  char *what;     /* "the scene", "-o" */
  int output;
  int exists;     /* dev and ino are known */
  dev_t dev;
  ino_t ino;
  /* Staging (outputs): the unnamed temporary's descriptor, or -1; the path
   * the encoder writes to ("/proc/self/fd/N" or the named temporary); its
   * slot in the signal registry when it is named (else -1). */
  int fd;
  char *write_path;
  int slot;
  int staged;
} sh__file;

struct sh_outputs {
  sh__file *files;
  int count, cap;
  int published;
};

/* Named temporaries, for sh_outputs_on_signal: a fixed table of pointers
 * a handler can read without locks. A temporary that finds no free slot is
 * still removed on every path but a signal. */
#define SH__SLOTS 256
static char *_Atomic sh__slots[SH__SLOTS];

static int sh__slot_take(char *path) {
  for (int i = 0; i < SH__SLOTS; i++) {
    char *expected = NULL;
    if (atomic_compare_exchange_strong(&sh__slots[i], &expected, path))
      return i;
  }
  return -1;
}

static void sh__slot_release(int slot) {
  if (slot >= 0) atomic_store(&sh__slots[slot], NULL);
}

void sh_outputs_on_signal(void) {
  for (int i = 0; i < SH__SLOTS; i++) {
    char *p = atomic_load(&sh__slots[i]);
    if (p) unlink(p);
  }
}

sh_outputs *sh_outputs_new(void) { return calloc(1, sizeof(sh_outputs)); }

static char *sh__dup(const char *s) {
  size_t n = strlen(s) + 1;
  char *d = malloc(n);
  if (d) memcpy(d, s, n);
  return d;
}

/* Discards a file's staged temporary, if any. */
static void sh__unstage(sh__file *f) {
  if (f->fd >= 0) close(f->fd);
  else if (f->write_path && f->staged) unlink(f->write_path);
  sh__slot_release(f->slot);
  f->fd = -1;
  f->slot = -1;
  free(f->write_path);
  f->write_path = NULL;
  f->staged = 0;
}

void sh_outputs_free(sh_outputs *set) {
  if (!set) return;
  for (int i = 0; i < set->count; i++) {
    sh__file *f = &set->files[i];
    sh__unstage(f);
    free(f->given);
    free(f->resolved);
    free(f->what);
  }
  free(set->files);
  free(set);
}

/* The directory part of `path` ("." for a bare name, "/" for the root). */
static char *sh__parent(const char *path) {
  const char *slash = strrchr(path, '/');
  if (!slash) return sh__dup(".");
  if (slash == path) return sh__dup("/");
  return sh__printf_alloc("%.*s", (int)(slash - path), path);
}

/* Resolves `path` into f: realpath and identity of an existing file, else
 * the resolved parent joined to the name. 0, or an errno. */
static int sh__resolve(const char *path, sh__file *f) {
  struct stat sb;
  if (stat(path, &sb) == 0) {
    f->exists = 1;
    f->dev = sb.st_dev;
    f->ino = sb.st_ino;
    f->resolved = realpath(path, NULL);
    return f->resolved ? 0 : errno;
  }
  if (errno != ENOENT) return errno;
  char *parent = sh__parent(path);
  if (!parent) return ENOMEM;
  char *real = realpath(parent, NULL);
  int e = errno;
  free(parent);
  if (!real) return e;
  const char *slash = strrchr(path, '/');
  const char *name = slash ? slash + 1 : path;
  f->resolved = sh__printf_alloc("%s%s%s", real,
                                 real[strlen(real) - 1] == '/' ? "" : "/", name);
  free(real);
  return f->resolved ? 0 : ENOMEM;
}

static sh__file *sh__append(sh_outputs *set) {
  sh__file *files = sh__array_grow(set->files, set->count, &set->cap, 8,
                                   sizeof *files);
  if (!files) return NULL;
  set->files = files;
  sh__file *f = &files[set->count];
  f->fd = -1;
  f->slot = -1;
  return f;
}

/* Completes the entry f appended to the set (its resolved path set) with
 * its names, and counts it. */
static sh_status sh__keep(sh_outputs *set, sh__file *f, const char *path,
                          const char *what, sh_error *err) {
  f->given = sh__dup(path);
  f->what = sh__dup(what);
  if (!f->given || !f->what || !f->resolved) {
    free(f->given);
    free(f->what);
    free(f->resolved);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  }
  set->count++;
  return SH_OK;
}

static int sh__same(const sh__file *a, const sh__file *b) {
  if (a->exists && b->exists)
    return a->dev == b->dev && a->ino == b->ino;
  return a->resolved && b->resolved && !strcmp(a->resolved, b->resolved);
}

sh_status sh_outputs_input(sh_outputs *set, const char *path, const char *what,
                           sh_error *err) {
  if (!set || !path || !what)
    return sh_error_set(err, SH_ERR_ARG, "sh_outputs_input: a NULL argument");
  sh__file *f = sh__append(set);
  if (!f) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  if (sh__resolve(path, f) != 0) {
    free(f->resolved);
    f->resolved = sh__dup(path);
    f->exists = 0;
  }
  return sh__keep(set, f, path, what, err);
}

sh_status sh_outputs_scene_inputs(sh_outputs *set, const sh_scene *scene,
                                  sh_error *err) {
  sh_status st = SH_OK;
  if (scene->file) st = sh_outputs_input(set, scene->file, "the scene", err);
  for (int i = 0; st == SH_OK && i < scene->nlights; i++)
    if (scene->lights[i].map_file)
      st = sh_outputs_input(set, scene->lights[i].map_file,
                            "a light map of the scene", err);
  for (int i = 0; st == SH_OK && i < scene->nshapes; i++)
    if (scene->shapes[i].file) {
      st = sh_outputs_input(set, scene->shapes[i].file,
                            "a file of the scene", err);
      for (int k = 0; st == SH_OK && k < scene->shapes[i].nnamed; k++)
        st = sh_outputs_input(set, scene->shapes[i].named[k],
                              "a file a mesh of the scene names", err);
    }
  return st;
}

static sh__file *sh__find_output(sh_outputs *set, const char *path) {
  for (int i = 0; i < set->count; i++)
    if (set->files[i].output && !strcmp(set->files[i].given, path))
      return &set->files[i];
  return NULL;
}

sh_status sh_outputs_add(sh_outputs *set, const char *path, const char *what,
                         sh_error *err) {
  if (!set || !path || !*path || !what)
    return sh_error_set(err, SH_ERR_ARG, "sh_outputs_add: a NULL argument");
  if (set->published)
    return sh_error_set(err, SH_ERR_ARG, "sh_outputs_add: already published");
  sh__file probe;
  memset(&probe, 0, sizeof probe);
  int e = sh__resolve(path, &probe);
  if (e != 0) {
    free(probe.resolved);
    return sh_error_set(err, e == ENOMEM ? SH_ERR_NOMEM : SH_ERR_IO,
                        "cannot write %s '%s': %s", what, path, strerror(e));
  }
  struct stat sb;
  if (probe.exists && stat(path, &sb) == 0 && !S_ISREG(sb.st_mode)) {
    free(probe.resolved);
    return sh_error_set(err, SH_ERR_ARG,
                        "%s '%s' exists and is not a regular file (%s): "
                        "an output replaces the file it names",
                        what, path, S_ISDIR(sb.st_mode) ? "a directory"
                                                        : "a device, FIFO or "
                                                          "socket");
  }
  for (int i = 0; i < set->count; i++) {
    const sh__file *o = &set->files[i];
    if (!sh__same(o, &probe)) continue;
    sh_status st = sh_error_set(
        err, SH_ERR_ARG,
        o->output ? "%s '%s' is the same file as %s '%s' ('%s'): each output "
                    "of a run must be a file of its own"
                  : "%s '%s' is the same file as %s '%s' ('%s'): an output "
                    "must not overwrite an input",
        what, path, o->what, o->given, probe.resolved);
    free(probe.resolved);
    return st;
  }
  sh__file *f = sh__append(set);
  if (!f) {
    free(probe.resolved);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  }
  *f = probe;
  f->fd = -1;
  f->slot = -1;
  f->output = 1;
  return sh__keep(set, f, path, what, err);
}

/* Opens the temporary an output is written to: unnamed (O_TMPFILE) in the
 * destination's directory where the file system and /proc allow, else a
 * hidden named file beside the destination, registered for signals. */
static sh_status sh__stage(sh__file *f, sh_error *err) {
  static atomic_uint counter;
  sh__unstage(f);
  char *dir = sh__parent(f->resolved);
  if (!dir) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  int fd = open(dir, O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  if (fd >= 0) {
    char *proc = sh__printf_alloc("/proc/self/fd/%d", fd);
    if (proc && access(proc, W_OK) == 0) {
      free(dir);
      f->fd = fd;
      f->write_path = proc;
      f->staged = 1;
      return SH_OK;
    }
    free(proc);
    close(fd);
  }
  const char *name = strrchr(f->resolved, '/') + 1;
  const char *dot = strrchr(name, '.');
  int stem = dot && dot != name ? (int)(dot - name) : (int)strlen(name);
  int last = 0;
  for (int attempt = 0; attempt < 100; attempt++) {
    char *tmp = sh__printf_alloc("%s%s.%.*s.%ld.%u%s", dir,
                                 dir[strlen(dir) - 1] == '/' ? "" : "/", stem,
                                 name, (long)getpid(),
                                 atomic_fetch_add(&counter, 1u),
                                 dot && dot != name ? dot : "");
    if (!tmp) {
      free(dir);
      return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
    }
    f->slot = sh__slot_take(tmp); /* before the file exists */
    int nfd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (nfd >= 0) {
      close(nfd);
      free(dir);
      f->write_path = tmp;
      f->staged = 1;
      return SH_OK;
    }
    last = errno;
    sh__slot_release(f->slot);
    f->slot = -1;
    free(tmp);
    if (last != EEXIST) break;
  }
  free(dir);
  return sh_error_set(err, SH_ERR_IO, "cannot write %s '%s': %s", f->what,
                      f->given, strerror(last));
}

static sh_status sh__output_for(sh_outputs *set, const char *path,
                                sh__file **out, sh_error *err) {
  if (!set || !path)
    return sh_error_set(err, SH_ERR_ARG, "sh_outputs: a NULL argument");
  if (set->published)
    return sh_error_set(err, SH_ERR_ARG, "sh_outputs: already published");
  sh__file *f = sh__find_output(set, path);
  if (!f) {
    sh_status st = sh_outputs_add(set, path, "the output", err);
    if (st != SH_OK) return st;
    f = &set->files[set->count - 1];
  }
  *out = f;
  return sh__stage(f, err);
}

sh_status sh_outputs_write_bytes(sh_outputs *set, const char *path,
                                 const void *data, size_t size, sh_error *err) {
  sh__file *f;
  sh_status st = sh__output_for(set, path, &f, err);
  if (st != SH_OK) return st;
  int fd = open(f->write_path, O_WRONLY | O_TRUNC | O_CLOEXEC);
  const char *p = data;
  size_t left = size;
  while (fd >= 0 && left > 0) {
    ssize_t n = write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    p += n;
    left -= (size_t)n;
  }
  int e = fd < 0 ? errno : left > 0 ? (errno ? errno : EIO) : 0;
  if (fd >= 0 && close(fd) != 0 && !e) e = errno;
  if (e) {
    sh__unstage(f);
    return sh_error_set(err, SH_ERR_IO, "cannot write %s '%s': %s", f->what,
                        path, strerror(e));
  }
  return SH_OK;
}

sh_status sh_outputs_write_image(sh_outputs *set, const char *path,
                                 const sh_image *img, double exposure,
                                 const char *const *attrs, sh_error *err) {
  sh_status st = sh__image_check(path, img, exposure, err);
  if (st != SH_OK) return st;
  sh__file *f;
  if ((st = sh__output_for(set, path, &f, err)) != SH_OK) return st;
  st = sh__image_encode(f->write_path, path, img, exposure, attrs, err);
  if (st != SH_OK) sh__unstage(f);
  return st;
}

/* Names staged file f: its unnamed temporary is linked to a hidden name
 * first (a name cannot be linked over), which the rename then replaces the
 * destination with. */
static int sh__link_named(sh__file *f) {
  static atomic_uint counter;
  for (int attempt = 0; attempt < 100; attempt++) {
    char *tmp = sh__printf_alloc("%s.%ld.%u.publish", f->resolved,
                                 (long)getpid(), atomic_fetch_add(&counter, 1u));
    if (!tmp) return ENOMEM;
    if (linkat(AT_FDCWD, f->write_path, AT_FDCWD, tmp, AT_SYMLINK_FOLLOW) == 0) {
      close(f->fd);
      f->fd = -1;
      free(f->write_path);
      f->write_path = tmp;
      f->slot = sh__slot_take(tmp);
      return 0;
    }
    int e = errno;
    free(tmp);
    if (e != EEXIST) return e;
  }
  return EEXIST;
}

sh_status sh_outputs_publish(sh_outputs *set, sh_error *err) {
  if (!set) return sh_error_set(err, SH_ERR_ARG, "sh_outputs_publish: NULL");
  if (set->published)
    return sh_error_set(err, SH_ERR_ARG, "sh_outputs_publish: already published");
  for (int i = 0; i < set->count; i++)
    if (set->files[i].output && !set->files[i].staged)
      return sh_error_set(err, SH_ERR_ARG,
                          "sh_outputs_publish: %s '%s' was never written",
                          set->files[i].what, set->files[i].given);
  /* INT and TERM wait until every output has its name. */
  sigset_t hold, old;
  sigemptyset(&hold);
  sigaddset(&hold, SIGINT);
  sigaddset(&hold, SIGTERM);
  sigaddset(&hold, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &hold, &old);
  sh_status st = SH_OK;
  for (int i = 0; st == SH_OK && i < set->count; i++) {
    sh__file *f = &set->files[i];
    if (!f->output || f->fd < 0) continue;
    int e = sh__link_named(f);
    if (e)
      st = sh_error_set(err, SH_ERR_IO, "cannot write %s '%s': %s", f->what,
                        f->given, strerror(e));
  }
  for (int i = 0; st == SH_OK && i < set->count; i++) {
    sh__file *f = &set->files[i];
    if (!f->output) continue;
    if (rename(f->write_path, f->resolved) != 0) {
      st = sh_error_set(err, SH_ERR_IO, "cannot write %s '%s': %s", f->what,
                        f->given, strerror(errno));
      break;
    }
    sh__slot_release(f->slot);
    f->slot = -1;
    f->staged = 0; /* published: nothing to discard */
  }
  if (st != SH_OK)
    for (int i = 0; i < set->count; i++)
      if (set->files[i].output) sh__unstage(&set->files[i]);
  set->published = 1;
  pthread_sigmask(SIG_SETMASK, &old, NULL);
  return st;
}
