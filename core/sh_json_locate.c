#include "sh_json_locate.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_array.h"
#include "sh_str.h"

/* A cursor over the text. Every read is bounds-checked: past the end, peek
 * returns 0, which no JSON token starts with. */
typedef struct scan {
  const char *s;
  size_t n, i;
} scan;

static int peek(const scan *sc) {
  return sc->i < sc->n ? (unsigned char)sc->s[sc->i] : 0;
}

static void skip_ws(scan *sc) {
  while (sc->i < sc->n) {
    char c = sc->s[sc->i];
    if (c != ' ' && c != '\t' && c != '\r' && c != '\n') break;
    sc->i++;
  }
}

/* At an opening quote: moves past the closing quote (or to the end). */
static void skip_string(scan *sc) {
  sc->i++;
  while (sc->i < sc->n) {
    char c = sc->s[sc->i];
    if (c == '\\')
      sc->i += 2;
    else if (c == '"') {
      sc->i++;
      return;
    } else
      sc->i++;
  }
  if (sc->i > sc->n) sc->i = sc->n;
}

/* Moves past one value of any kind. */
static void skip_value(scan *sc) {
  int c = peek(sc);
  if (c == '"') {
    skip_string(sc);
  } else if (c == '{' || c == '[') {
    int depth = 0;
    while (sc->i < sc->n) {
      c = peek(sc);
      if (c == '"') {
        skip_string(sc);
        continue;
      }
      if (c == '{' || c == '[') depth++;
      if (c == '}' || c == ']') depth--;
      sc->i++;
      if (depth == 0) break;
    }
  } else {
    while (sc->i < sc->n && !strchr(",]} \t\r\n", sc->s[sc->i])) sc->i++;
  }
}

static int hex4(const scan *sc, size_t at, unsigned *out) {
  unsigned v = 0;
  if (at + 4 > sc->n) return 0;
  for (size_t k = at; k < at + 4; k++) {
    char c = sc->s[k];
    v <<= 4;
    if (c >= '0' && c <= '9')
      v |= (unsigned)(c - '0');
    else if (c >= 'a' && c <= 'f')
      v |= (unsigned)(c - 'a' + 10);
    else if (c >= 'A' && c <= 'F')
      v |= (unsigned)(c - 'A' + 10);
    else
      return 0;
  }
  *out = v;
  return 1;
}

static int utf8_encode(unsigned cp, char out[4]) {
  if (cp < 0x80) {
    out[0] = (char)cp;
    return 1;
  }
  if (cp < 0x800) {
    out[0] = (char)(0xC0 | (cp >> 6));
    out[1] = (char)(0x80 | (cp & 0x3F));
    return 2;
  }
  if (cp < 0x10000) {
    out[0] = (char)(0xE0 | (cp >> 12));
    out[1] = (char)(0x80 | ((cp >> 6) & 0x3F));
    out[2] = (char)(0x80 | (cp & 0x3F));
    return 3;
  }
  out[0] = (char)(0xF0 | (cp >> 18));
  out[1] = (char)(0x80 | ((cp >> 12) & 0x3F));
  out[2] = (char)(0x80 | ((cp >> 6) & 0x3F));
  out[3] = (char)(0x80 | (cp & 0x3F));
  return 4;
}

/* Decodes the next character of a string body at sc->i into out (UTF-8) and
 * advances. Returns the number of bytes written, 0 at the closing quote or
 * the end of the text. */
static int next_char(scan *sc, char out[4]) {
  if (sc->i >= sc->n || sc->s[sc->i] == '"') return 0;
  char c = sc->s[sc->i];
  if (c != '\\') {
    out[0] = c;
    sc->i++;
    return 1;
  }
  if (sc->i + 1 >= sc->n) {
    sc->i = sc->n;
    return 0;
  }
  char e = sc->s[sc->i + 1];
  sc->i += 2;
  switch (e) {
  case 'b': out[0] = '\b'; return 1;
  case 'f': out[0] = '\f'; return 1;
  case 'n': out[0] = '\n'; return 1;
  case 'r': out[0] = '\r'; return 1;
  case 't': out[0] = '\t'; return 1;
  case 'u': {
    unsigned cp, lo;
    if (!hex4(sc, sc->i, &cp)) return 0;
    sc->i += 4;
    if (cp >= 0xD800 && cp < 0xDC00 && sc->i + 6 <= sc->n &&
        sc->s[sc->i] == '\\' && sc->s[sc->i + 1] == 'u' &&
        hex4(sc, sc->i + 2, &lo) && lo >= 0xDC00 && lo < 0xE000) {
      sc->i += 6;
      cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
    }
    return utf8_encode(cp, out);
  }
  default: out[0] = e; return 1;
  }
}

/* At an opening quote: compares the decoded string with `key`, then moves
 * past the string. */
static int match_string(scan *sc, const char *key) {
  size_t start = sc->i, k = 0, klen = strlen(key);
  int same = 1;
  char buf[4];
  int m;
  sc->i++;
  while ((m = next_char(sc, buf)) > 0) {
    if (k + (size_t)m > klen || memcmp(key + k, buf, (size_t)m) != 0) {
      same = 0;
      break;
    }
    k += (size_t)m;
  }
  if (same && k != klen) same = 0;
  sc->i = start;
  skip_string(sc);
  return same;
}

int sh__json_locate(const char *text, size_t len, const sh__jseg *path,
                    int depth, int at_key, size_t *offset) {
  scan sc = {text, len, 0};
  skip_ws(&sc);
  for (int d = 0; d < depth; d++) {
    const sh__jseg *seg = &path[d];
    if (seg->key) {
      if (peek(&sc) != '{') return 0;
      sc.i++;
      for (;;) {
        skip_ws(&sc);
        if (peek(&sc) != '"') return 0;
        size_t key_start = sc.i;
        int same = match_string(&sc, seg->key);
        skip_ws(&sc);
        if (peek(&sc) != ':') return 0;
        sc.i++;
        skip_ws(&sc);
        if (same) {
          if (d == depth - 1 && at_key) {
            *offset = key_start;
            return 1;
          }
          break;
        }
        skip_value(&sc);
        skip_ws(&sc);
        if (peek(&sc) != ',') return 0;
        sc.i++;
      }
    } else {
      if (peek(&sc) != '[') return 0;
      sc.i++;
      for (int k = 0;; k++) {
        skip_ws(&sc);
        if (peek(&sc) == ']' || peek(&sc) == 0) return 0;
        if (k == seg->index) break;
        skip_value(&sc);
        skip_ws(&sc);
        if (peek(&sc) != ',') return 0;
        sc.i++;
      }
    }
  }
  if (sc.i >= len && depth > 0) return 0;
  *offset = sc.i;
  return 1;
}

void sh__json_linecol(const char *text, size_t offset, int *line, int *column) {
  int l = 1, c = 1;
  for (size_t j = 0; j < offset && text[j]; j++) {
    if (text[j] == '\n') {
      l++;
      c = 1;
    } else if (((unsigned char)text[j] & 0xC0) != 0x80) {
      c++;
    }
  }
  *line = l;
  *column = c;
}

static int is_identifier(const char *k) {
  if (!*k ||
      !((*k >= 'a' && *k <= 'z') || (*k >= 'A' && *k <= 'Z') || *k == '_'))
    return 0;
  for (; *k; k++)
    if (!((*k >= 'a' && *k <= 'z') || (*k >= 'A' && *k <= 'Z') ||
          (*k >= '0' && *k <= '9') || *k == '_'))
      return 0;
  return 1;
}

/* Appends the step `key` (or, key NULL, the array index) to the heap
 * string *buf. 0 when out of memory, with *buf freed and NULL. */
static int append_step(char **buf, const char *key, int index) {
  char *old = *buf, *s;
  if (!key)
    s = sh__printf_alloc("%s[%d]", old, index);
  else if (!is_identifier(key))
    s = sh__printf_alloc("%s[\"%s\"]", old, key);
  else
    s = sh__printf_alloc(old[0] ? "%s.%s" : "%s%s", old, key);
  free(old);
  *buf = s;
  return s != NULL;
}

char *sh__json_format_path(const sh__jseg *path, int depth) {
  char *buf = sh__printf_alloc("%s", "");
  for (int d = 0; buf && d < depth; d++)
    append_step(&buf, path[d].key, path[d].index);
  return buf;
}

/* A container open at the scanned position, for sh__json_path_at: its key
 * (in an object, once read) is the string at byte `key_at` of the text. */
typedef struct frame {
  char kind; /* '{' or '[' */
  int has_key, index;
  size_t key_at;
} frame;

/* The decoded text of the JSON string whose opening quote is at byte `at`
 * (possibly cut short by the end of the text), on the heap; NULL when out
 * of memory. Decoded, a string is never longer than its JSON text. */
static char *decode_string(const char *text, size_t len, size_t at) {
  scan sc = {text, len, at};
  skip_string(&sc);
  char *out = malloc(sc.i - at + 1);
  if (!out) return NULL;
  size_t k = 0;
  char cb[4];
  int m;
  sc.i = at + 1;
  while ((m = next_char(&sc, cb)) > 0)
    for (int j = 0; j < m; j++) out[k++] = cb[j];
  out[k] = '\0';
  return out;
}

char *sh__json_path_at(const char *text, size_t len, size_t offset) {
  frame *st = NULL;
  int depth = 0, cap = 0, lost = 0; /* lost: frames not recorded (memory) */
  scan sc = {text, len, 0};
  if (offset > len) offset = len;
  while (sc.i < offset) {
    char c = text[sc.i];
    frame *top = depth > 0 && !lost ? &st[depth - 1] : NULL;
    if (c == '"') {
      if (top && top->kind == '{' && !top->has_key) {
        top->key_at = sc.i;
        top->has_key = 1;
      }
      skip_string(&sc);
      continue;
    }
    if (c == '{' || c == '[') {
      frame *grown = lost ? NULL : sh__array_grow(st, depth, &cap, 8, sizeof *st);
      if (grown) {
        st = grown;
        st[depth].kind = c;
        depth++;
      } else {
        lost++;
      }
    } else if (c == '}' || c == ']') {
      if (lost)
        lost--;
      else if (depth > 0)
        depth--;
    } else if (c == ',' && top) {
      if (top->kind == '[')
        top->index++;
      else
        top->has_key = 0;
    }
    sc.i++;
  }
  char *buf = sh__printf_alloc("%s", "");
  for (int d = 0; buf && d < depth; d++) {
    if (st[d].kind == '[') {
      append_step(&buf, NULL, st[d].index);
    } else if (st[d].has_key) {
      char *key = decode_string(text, len, st[d].key_at);
      if (key)
        append_step(&buf, key, 0);
      free(key);
      if (!key) {
        free(buf);
        buf = NULL;
      }
    } else {
      break;
    }
  }
  free(st);
  return buf;
}
