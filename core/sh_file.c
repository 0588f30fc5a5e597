#include "sh_file.h"
#include "sh_outputs.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

sh_status sh_file_write_atomic(const char *path, const void *data, size_t size,
                               sh_error *err) {
  sh_outputs *set = sh_outputs_new();
  if (!set) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  sh_status st = sh_outputs_write_bytes(set, path, data, size, err);
  if (st == SH_OK) st = sh_outputs_publish(set, err);
  sh_outputs_free(set);
  return st;
}

const char *sh_file_kind(unsigned mode) {
  return S_ISREG(mode)    ? "a regular file"
         : S_ISDIR(mode)  ? "a directory"
         : S_ISCHR(mode)  ? "a character device"
         : S_ISBLK(mode)  ? "a block device"
         : S_ISFIFO(mode) ? "a FIFO"
         : S_ISSOCK(mode) ? "a socket"
                          : "not a file";
}

FILE *sh_file_open_read(const char *path) {
  int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return NULL;
  struct stat sb;
  if (fstat(fd, &sb) == 0 && S_ISREG(sb.st_mode))
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  FILE *f = fdopen(fd, "rb");
  if (!f) {
    int e = errno;
    close(fd);
    errno = e;
  }
  return f;
}

sh_status sh_file_readable(const char *path, long long *size, sh_error *err) {
  struct stat st;
  if (stat(path, &st) != 0 || access(path, R_OK) != 0) {
    int e = errno;
    return sh_error_set(err, SH_ERR_IO, "cannot open '%s': %s", path,
                        strerror(e));
  }
  if (S_ISDIR(st.st_mode))
    return sh_error_set(err, SH_ERR_IO, "cannot open '%s': %s", path,
                        strerror(EISDIR));
  if (!S_ISREG(st.st_mode))
    return sh_error_set(err, SH_ERR_IO,
                        "cannot open '%s': not a regular file (%s)", path,
                        sh_file_kind(st.st_mode));
  if (size) *size = (long long)st.st_size;
  return SH_OK;
}

sh_status sh__file_load_begin(const char *fn, const char *what, void *out,
                              size_t out_size, const char *path,
                              long long *size, sh_error *err) {
  if (!out)
    return sh_error_set(err, SH_ERR_ARG, "%s was given no %s", fn, what);
  memset(out, 0, out_size);
  if (!path || !*path)
    return sh_error_set(err, SH_ERR_ARG, "%s was given no path", fn);
  return sh_file_readable(path, size, err);
}

void sh_file_extension(const char *path, char *buf, size_t size) {
  const char *dot = strrchr(path, '.');
  const char *slash = strrchr(path, '/');
  buf[0] = '\0';
  if (!dot || (slash && dot < slash) || size == 0) return;
  size_t i = 0;
  for (dot++; *dot && i + 1 < size; dot++) buf[i++] = (char)tolower((unsigned char)*dot);
  buf[i] = '\0';
}
