#include "se_text.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int plain_char(int c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
         (c >= '0' && c <= '9') || c == '_' || c == '.' || c == '+' ||
         c == '-';
}

void se_comment_text(const char *in, char *out, size_t size) {
  size_t n = 0, len = strlen(in);
  for (size_t i = 0; i < len && n + 1 < size; i++) {
    int c = (unsigned char)in[i];
    int block = c == '*' && ((i > 0 && in[i - 1] == '/') || in[i + 1] == '/');
    out[n++] = (char)(c >= 0x20 && c < 0x7f && !block ? c : '_');
  }
  out[n] = '\0';
  if (len > n && size >= 4) memcpy(out + size - 4, "...", 4);
}

void se_plain_name(const char *in, char *out, size_t size) {
  size_t n = 0;
  for (; in[n] && n + 1 < size; n++) {
    int c = (unsigned char)in[n];
    out[n] = (char)(plain_char(c) && !(n == 0 && (c == '.' || c == '-')) ? c : '_');
  }
  if (n == 0 && size > 1) out[n++] = '_';
  out[n] = '\0';
}

int se_is_plain_file_name(const char *name) {
  if (!name[0] || name[0] == '-' || name[0] == '.') return 0;
  for (const char *p = name; *p; p++)
    if (!plain_char((unsigned char)*p)) return 0;
  return 1;
}

void se_shell_word(se_buf *b, const char *word) {
  int plain = word[0] && word[0] != '-';
  for (const char *p = word; *p && plain; p++)
    plain = plain_char((unsigned char)*p) || *p == '/';
  if (plain) {
    se_buf_puts(b, word);
    return;
  }
  se_buf_puts(b, "'");
  for (const char *p = word; *p; p++) {
    if (*p == '\'') se_buf_puts(b, "'\\''");
    else se_buf_append(b, p, 1);
  }
  se_buf_puts(b, "'");
}

const char *se_base_name(const char *path) {
  const char *slash = strrchr(path, '/');
  return slash ? slash + 1 : path;
}

char *se_replace_extension(const char *path, const char *suffix) {
  const char *base = se_base_name(path);
  const char *dot = strrchr(base, '.');
  size_t keep = dot && dot != base ? (size_t)(dot - path) : strlen(path);
  size_t n = keep + strlen(suffix) + 1;
  char *s = malloc(n);
  if (!s) return NULL;
  memcpy(s, path, keep);
  strcpy(s + keep, suffix);
  return s;
}

char *se_printf_alloc(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  char *s = n >= 0 ? malloc((size_t)n + 1) : NULL;
  if (!s) return NULL;
  va_start(ap, fmt);
  vsnprintf(s, (size_t)n + 1, fmt, ap);
  va_end(ap);
  return s;
}
