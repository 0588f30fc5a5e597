#include "se_jsontext.h"

#include <stdio.h>
#include <stdlib.h>

void se_json_number(se_buf *b, double v) {
  char s[40];
  for (int prec = 1; prec <= 17; prec++) {
    snprintf(s, sizeof s, "%.*g", prec, v);
    if (strtod(s, NULL) == v) break;
  }
  se_buf_puts(b, s);
  /* Keep a real a real: "1" would read back as an integer, which the scene
   * format accepts but other readers may not mean. */
  int plain = 1;
  for (const char *p = s; *p; p++)
    if (*p == '.' || *p == 'e' || *p == 'n' || *p == 'i') plain = 0;
  if (plain) se_buf_puts(b, ".0");
}

static void newline(se_buf *b, int indent, int level) {
  if (indent <= 0) return;
  se_buf_puts(b, "\n");
  for (int i = 0; i < indent * level; i++) se_buf_puts(b, " ");
}

static int all_scalars(const json_t *a) {
  size_t i;
  json_t *v;
  json_array_foreach(a, i, v) if (json_is_object(v) || json_is_array(v)) return 0;
  return 1;
}

static void print(se_buf *b, const json_t *v, int indent, int level) {
  if (json_is_object(v)) {
    const char *key;
    json_t *m;
    int first = 1;
    se_buf_puts(b, "{");
    json_object_foreach((json_t *)v, key, m) {
      if (!first) se_buf_puts(b, indent > 0 ? "," : ", ");
      first = 0;
      newline(b, indent, level + 1);
      json_t *k = json_string(key);
      char *ks = k ? json_dumps(k, JSON_ENCODE_ANY) : NULL;
      if (ks) se_buf_puts(b, ks);
      else b->failed = 1;
      free(ks);
      json_decref(k);
      se_buf_puts(b, ": ");
      print(b, m, indent, level + 1);
    }
    if (!first) newline(b, indent, level);
    se_buf_puts(b, "}");
  } else if (json_is_array(v)) {
    size_t i;
    json_t *e;
    int inline_ = indent <= 0 || all_scalars(v);
    se_buf_puts(b, "[");
    json_array_foreach(v, i, e) {
      if (i) se_buf_puts(b, inline_ ? ", " : ",");
      if (!inline_) newline(b, indent, level + 1);
      print(b, e, indent, level + 1);
    }
    if (!inline_ && json_array_size(v)) newline(b, indent, level);
    se_buf_puts(b, "]");
  } else if (json_is_real(v)) {
    se_json_number(b, json_real_value(v));
  } else {
    char *s = json_dumps(v, JSON_ENCODE_ANY);
    if (s) se_buf_puts(b, s);
    else b->failed = 1;
    free(s);
  }
}

void se_json_text(se_buf *b, const json_t *value, int indent) {
  print(b, value, indent, 0);
}
