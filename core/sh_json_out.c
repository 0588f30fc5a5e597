#include "sh_json_out.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void sh__json_num(json_t *o, const char *key, double v) {
  if (v == floor(v) && fabs(v) < 9007199254740992.0)
    json_object_set_new(o, key, json_integer((json_int_t)v));
  else
    json_object_set_new(o, key, json_real(v));
}

char *sh__json_dumps(json_t *o) {
  if (!o) return NULL;
  char *text = json_dumps(o, JSON_INDENT(2) | JSON_REAL_PRECISION(10));
  json_decref(o);
  return text;
}

size_t sh__json_dump_to(json_t *o, char *buf, size_t size) {
  char *text = sh__json_dumps(o);
  if (!text) return 0;
  size_t n = strlen(text);
  if (buf && size > 0) {
    size_t k = n < size - 1 ? n : size - 1;
    memcpy(buf, text, k);
    buf[k] = '\0';
  }
  free(text);
  return n;
}
