#include "sh_array.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

void *sh__array_grow(void *items, int count, int *cap, int first,
                     size_t size) {
  if (count == *cap) {
    if (*cap > INT_MAX / 2) return NULL;
    int bigger = *cap ? 2 * *cap : first;
    void *moved = realloc(items, size * (size_t)bigger);
    if (!moved) return NULL;
    items = moved;
    *cap = bigger;
  }
  memset((char *)items + size * (size_t)count, 0, size);
  return items;
}
