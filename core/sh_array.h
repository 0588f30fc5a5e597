/* Arrays that grow by doubling, for the modules that append items one at a
 * time (a set of output files, a program cache, an exporter's notes). */
#ifndef SH_ARRAY_H
#define SH_ARRAY_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Makes room for item `count` in `items`, an array of *cap items of `size`
 * bytes (NULL with *cap 0 at first): when it is full, reallocates it to
 * twice its capacity (`first` items the first time) and updates *cap.
 * Returns the array, perhaps moved, with the new item zeroed, or NULL when
 * out of memory, leaving the array and *cap as they were. */
void *sh__array_grow(void *items, int count, int *cap, int first,
                     size_t size);

#ifdef __cplusplus
}
#endif
#endif
