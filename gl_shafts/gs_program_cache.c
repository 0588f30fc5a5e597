/* The program cache on disk (gs_program_cache.h). */
#define _GNU_SOURCE /* O_PATH, O_TMPFILE */
#include "gs_program_cache.h"
#include "gs_program.h"

#include "shafts.h"
#include "sh_str.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define GS__CACHE_MAGIC "SHPROGB1"
#define GS__CACHE_LIMIT ((off_t)64 << 20)
#define GS__CACHE_KEEP ((off_t)48 << 20)

static atomic_long gs__hits, gs__misses, gs__stores;

gs__program_cache_counts gs__program_cache_counts_get(void) {
  gs__program_cache_counts c = {atomic_load(&gs__hits),
                                atomic_load(&gs__misses),
                                atomic_load(&gs__stores)};
  return c;
}

char *gs__program_cache_dir(void) {
  const char *env = getenv("SHAFTS_PROGRAM_CACHE");
  const char *xdg = getenv("XDG_CACHE_HOME");
  const char *home = getenv("HOME");
  if (env)
    return env[0] && strcmp(env, "off") && strcmp(env, "0")
               ? sh__printf_alloc("%s", env)
               : NULL;
  if (xdg && xdg[0] == '/')
    return sh__printf_alloc("%s/shafts/programs", xdg);
  if (home && home[0] == '/')
    return sh__printf_alloc("%s/.cache/shafts/programs", home);
  return NULL;
}

int gs__program_cache_open_dir(const char *dir, int create) {
  size_t n = strlen(dir) + 1;
  char *copy = malloc(n);
  if (!copy)
    return -1;
  memcpy(copy, dir, n);
  /* O_PATH: a directory only searched (mode --x) is walked through too. */
  const int flags = O_PATH | O_DIRECTORY | O_CLOEXEC;
  int fd = open(copy[0] == '/' ? "/" : ".", flags);
  for (char *s = copy; fd >= 0 && *s;) {
    char *end = strchr(s, '/');
    if (end)
      *end = '\0';
    if (*s) {
      int next = openat(fd, s, flags);
      if (next < 0 && errno == ENOENT && create &&
          (mkdirat(fd, s, 0700) == 0 || errno == EEXIST))
        next = openat(fd, s, flags);
      close(fd);
      fd = next;
    }
    s = end ? end + 1 : s + strlen(s);
  }
  free(copy);
  return fd;
}

void gs__program_cache_driver(char *buf, size_t size) {
  static const GLenum names[4] = {GL_VENDOR, GL_RENDERER, GL_VERSION,
                                  GL_SHADING_LANGUAGE_VERSION};
  size_t used = 0;
  buf[0] = '\0';
  for (int i = 0; i < 4 && used < size; i++) {
    const char *s = (const char *)glGetString(names[i]);
    int n = snprintf(buf + used, size - used, "%s\n", s ? s : "?");
    used += n > 0 ? (size_t)n : 0;
  }
  if (used < size)
    snprintf(buf + used, size - used, "shafts %s\n", sh_version());
}

/* Appends one stage's source parts to the key (key NULL: counts only);
 * returns the bytes, or 0 if a part cannot be made (an unknown include,
 * which compiling will report). */
static size_t gs__key_stage(char *key, const gs__glsl *src, const char *defines) {
  const char *parts[GS__SOURCE_PARTS_MAX], *bad = NULL;
  GLint lens[GS__SOURCE_PARTS_MAX];
  char line_after[GS__LINE_AFTER_SIZE];
  int n = gs__program_source_parts(src, defines, parts, lens, line_after,
                                   sizeof line_after, &bad);
  if (n <= 0)
    return 0;
  size_t at = 0;
  for (int i = 0; i < n; i++) {
    size_t l = lens[i] < 0 ? strlen(parts[i]) : (size_t)lens[i];
    if (key)
      memcpy(key + at, parts[i], l);
    at += l;
  }
  if (key)
    key[at] = '\0'; /* the stages' boundary */
  return at + 1;
}

char *gs__program_cache_key(const char *driver, const gs__glsl *vs,
                            const gs__glsl *fs, const char *defines,
                            size_t *len) {
  size_t nd = strlen(driver) + 1;
  size_t nv = gs__key_stage(NULL, vs, defines);
  size_t nf = gs__key_stage(NULL, fs, defines);
  if (!nv || !nf)
    return NULL;
  char *key = malloc(nd + nv + nf);
  if (!key)
    return NULL;
  memcpy(key, driver, nd);
  gs__key_stage(key + nd, vs, defines);
  gs__key_stage(key + nd + nv, fs, defines);
  *len = nd + nv + nf;
  return key;
}

void gs__program_cache_name(const char *key, size_t len,
                            char name[GS__CACHE_NAME_SIZE]) {
  uint64_t h = 1469598103934665603ULL;
  for (size_t i = 0; i < len; i++) {
    h ^= (unsigned char)key[i];
    h *= 1099511628211ULL;
  }
  snprintf(name, GS__CACHE_NAME_SIZE, "%016llx.bin", (unsigned long long)h);
}

/* Whether the current context can hand out program binaries. */
static int gs__binaries_supported(void) {
  GLint formats = 0;
  glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &formats);
  return formats > 0;
}

typedef struct gs__cache_header {
  char magic[8];
  uint32_t format, key_len, binary_len;
} gs__cache_header;

/* Reads (or, if writing, writes) exactly n bytes, retrying short and
 * interrupted calls; 1 on success. */
static int gs__transfer(int fd, void *buf, size_t n, int writing) {
  char *p = buf;
  while (n) {
    ssize_t r = writing ? write(fd, p, n) : read(fd, p, n);
    if (r < 0 && errno == EINTR)
      continue;
    if (r <= 0)
      return 0;
    p += r;
    n -= (size_t)r;
  }
  return 1;
}

GLuint gs__program_cache_load_key(const char *dir, const char *key,
                                  size_t len) {
  char name[GS__CACHE_NAME_SIZE];
  gs__program_cache_name(key, len, name);
  int dirfd = gs__program_cache_open_dir(dir, 0);
  int fd = dirfd < 0 ? -1 : openat(dirfd, name, O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    if (dirfd >= 0)
      close(dirfd);
    return 0;
  }
  gs__cache_header h;
  char *buf = NULL;
  GLuint prog = 0;
  int stale = 0;
  struct stat st;
  if (fstat(fd, &st) != 0 || !gs__transfer(fd, &h, sizeof h, 0) ||
      memcmp(h.magic, GS__CACHE_MAGIC, 8) || h.key_len != len ||
      (off_t)(sizeof h + (size_t)h.key_len + h.binary_len) != st.st_size ||
      h.binary_len == 0 || h.binary_len > (1u << 30)) {
    stale = 1; /* foreign, short or from another layout */
    goto done;
  }
  buf = malloc((size_t)h.key_len + h.binary_len);
  if (!buf || !gs__transfer(fd, buf, (size_t)h.key_len + h.binary_len, 0))
    goto done;
  if (memcmp(buf, key, len))
    goto done; /* another key with the same hash: leave its file alone */
  prog = glCreateProgram();
  if (!prog)
    goto done;
  glProgramBinary(prog, h.format, buf + h.key_len, (GLsizei)h.binary_len);
  GLint linked = 0;
  glGetProgramiv(prog, GL_LINK_STATUS, &linked);
  if (!linked) {
    /* Refused (another driver build, a format it no longer takes): drain
     * the error glProgramBinary may have raised, and drop the file. */
    while (glGetError() != GL_NO_ERROR) {
    }
    glDeleteProgram(prog);
    prog = 0;
    stale = 1;
    goto done;
  }
  futimens(fd, NULL); /* recently used: the eviction keeps it */
done:
  free(buf);
  close(fd);
  if (stale)
    unlinkat(dirfd, name, 0);
  close(dirfd);
  return prog;
}

/* Writes n bytes as the file `name` of the directory dirfd atomically: in
 * an unnamed temporary (O_TMPFILE) given a hidden name once complete and
 * renamed over `name`, so a killed process leaves no partial entry; where
 * the file system has no O_TMPFILE, in the hidden named temporary
 * ".NAME.<pid>.<n>" from the start (which a process killed meanwhile
 * leaves, and the eviction removes an hour later). 1 on success. */
static int gs__cache_write(int dirfd, const char *name, const void *data,
                           size_t n) {
  static atomic_uint serial;
  char *tmp = sh__printf_alloc(".%s.%ld.%u", name, (long)getpid(),
                               atomic_fetch_add(&serial, 1));
  if (!tmp)
    return 0;
  int named = 0;
  int fd = openat(dirfd, ".", O_TMPFILE | O_WRONLY | O_CLOEXEC, 0644);
  if (fd < 0) {
    fd = openat(dirfd, tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    named = fd >= 0;
  }
  int ok = fd >= 0 && gs__transfer(fd, (void *)data, n, 1);
  if (ok && !named) {
    char *proc = sh__printf_alloc("/proc/self/fd/%d", fd);
    ok = proc && linkat(AT_FDCWD, proc, dirfd, tmp, AT_SYMLINK_FOLLOW) == 0;
    named = ok;
    free(proc);
  }
  if (fd >= 0)
    close(fd);
  ok = ok && renameat(dirfd, tmp, dirfd, name) == 0;
  if (!ok && named)
    unlinkat(dirfd, tmp, 0);
  free(tmp);
  return ok;
}

typedef struct gs__cache_entry {
  char name[GS__CACHE_NAME_SIZE];
  off_t size;
  struct timespec mtime;
} gs__cache_entry;

static int gs__older_first(const void *a, const void *b) {
  const struct timespec *x = &((const gs__cache_entry *)a)->mtime;
  const struct timespec *y = &((const gs__cache_entry *)b)->mtime;
  if (x->tv_sec != y->tv_sec)
    return x->tv_sec < y->tv_sec ? -1 : 1;
  return x->tv_nsec < y->tv_nsec ? -1 : x->tv_nsec > y->tv_nsec;
}

/* Past GS__CACHE_LIMIT bytes of programs, removes the least recently used
 * until under GS__CACHE_KEEP; removes the hidden temporaries of
 * gs__cache_write older than an hour. */
static void gs__cache_evict(int dirfd) {
  int fd = openat(dirfd, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  DIR *d = fd < 0 ? NULL : fdopendir(fd);
  if (!d) {
    if (fd >= 0)
      close(fd);
    return;
  }
  struct timespec now;
  clock_gettime(CLOCK_REALTIME, &now);
  gs__cache_entry *e = NULL;
  size_t n = 0, cap = 0;
  off_t total = 0;
  struct dirent *de;
  while ((de = readdir(d))) {
    size_t l = strlen(de->d_name);
    struct stat st;
    if (de->d_name[0] == '.' && l > GS__CACHE_NAME_SIZE &&
        !strncmp(de->d_name + 17, ".bin.", 5) &&
        fstatat(dirfd, de->d_name, &st, AT_SYMLINK_NOFOLLOW) == 0 &&
        S_ISREG(st.st_mode) && st.st_mtim.tv_sec + 3600 < now.tv_sec) {
      unlinkat(dirfd, de->d_name, 0);
      continue;
    }
    if (l + 1 != GS__CACHE_NAME_SIZE || strcmp(de->d_name + 16, ".bin"))
      continue;
    if (fstatat(dirfd, de->d_name, &st, AT_SYMLINK_NOFOLLOW) != 0)
      continue;
    if (n == cap) {
      size_t c = cap ? 2 * cap : 64;
      gs__cache_entry *ne = realloc(e, c * sizeof *e);
      if (!ne)
        break;
      e = ne;
      cap = c;
    }
    memcpy(e[n].name, de->d_name, GS__CACHE_NAME_SIZE);
    e[n].size = st.st_size;
    e[n].mtime = st.st_mtim;
    total += st.st_size;
    n++;
  }
  closedir(d);
  if (total > GS__CACHE_LIMIT) {
    qsort(e, n, sizeof *e, gs__older_first);
    for (size_t i = 0; i < n && total > GS__CACHE_KEEP; i++) {
      if (unlinkat(dirfd, e[i].name, 0) == 0)
        total -= e[i].size;
    }
  }
  free(e);
}

int gs__program_cache_store_key(const char *dir, const char *key, size_t len,
                                GLuint prog) {
  GLint size = 0;
  glGetProgramiv(prog, GL_PROGRAM_BINARY_LENGTH, &size);
  if (size <= 0 || len > UINT32_MAX)
    return 0;
  char *bin = malloc((size_t)size);
  if (!bin)
    return 0;
  GLsizei got = 0;
  GLenum format = 0;
  glGetProgramBinary(prog, size, &got, &format, bin);
  int dirfd = -1;
  int ok = got > 0 && glGetError() == GL_NO_ERROR &&
           (dirfd = gs__program_cache_open_dir(dir, 1)) >= 0;
  char *file = NULL;
  if (ok) {
    char name[GS__CACHE_NAME_SIZE];
    gs__program_cache_name(key, len, name);
    gs__cache_header h;
    memcpy(h.magic, GS__CACHE_MAGIC, 8);
    h.format = format;
    h.key_len = (uint32_t)len;
    h.binary_len = (uint32_t)got;
    size_t n = sizeof h + len + (size_t)got;
    file = malloc(n);
    ok = file != NULL;
    if (ok) {
      memcpy(file, &h, sizeof h);
      memcpy(file + sizeof h, key, len);
      memcpy(file + sizeof h + len, bin, (size_t)got);
      ok = gs__cache_write(dirfd, name, file, n);
    }
  }
  free(file);
  free(bin);
  if (ok)
    gs__cache_evict(dirfd);
  if (dirfd >= 0)
    close(dirfd);
  return ok;
}

void gs__program_cache_prepare(GLuint prog) {
  glProgramParameteri(prog, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
}

/* The directory (malloc'ed) and the key of a program, or 0 if the cache
 * is off or cannot serve this context. */
static int gs__cache_begin(const gs__glsl *vs, const gs__glsl *fs,
                           const char *defines, char **dir, char **key,
                           size_t *len) {
  *key = NULL;
  *dir = gs__program_cache_dir();
  if (!*dir || !gs__binaries_supported())
    return 0;
  char driver[1024];
  gs__program_cache_driver(driver, sizeof driver);
  *key = gs__program_cache_key(driver, vs, fs, defines, len);
  return *key != NULL;
}

GLuint gs__program_cache_load(const gs__glsl *vs, const gs__glsl *fs,
                              const char *defines) {
  char *dir = NULL, *key = NULL;
  size_t len = 0;
  GLuint prog = 0;
  if (gs__cache_begin(vs, fs, defines, &dir, &key, &len)) {
    prog = gs__program_cache_load_key(dir, key, len);
    atomic_fetch_add(prog ? &gs__hits : &gs__misses, 1);
  }
  free(key);
  free(dir);
  return prog;
}

void gs__program_cache_store(GLuint prog, const gs__glsl *vs,
                             const gs__glsl *fs, const char *defines) {
  char *dir = NULL, *key = NULL;
  size_t len = 0;
  if (gs__cache_begin(vs, fs, defines, &dir, &key, &len) &&
      gs__program_cache_store_key(dir, key, len, prog))
    atomic_fetch_add(&gs__stores, 1);
  free(key);
  free(dir);
}
