/* Internal to the core's own mesh readers (sh_ply.h, sh_off.h; not
 * installed, not exported): the state and the steps they share.
 *
 * A reader parses a whole file held in memory (followed by a NUL, so that
 * strtod stops), in the C numeric locale (sh_mesh.c sets it around the
 * call). It checks every count the file declares (vertices, faces, a
 * list's entries) against the bytes that remain before it allocates or
 * loops, so that its work and memory are bounded by the file's size, and it
 * builds the triangles as it reads. Errors are SH_ERR_MESH, "cannot load
 * mesh 'PATH': line N: WHAT" (text) or "...: byte N: WHAT" (binary data),
 * with the error's file and line set; SH_ERR_NOMEM. */
#ifndef SH_MESH_READER_H
#define SH_MESH_READER_H

#include <stddef.h>

#include "sh_error.h"
#include "sh_mesh.h"

typedef struct sh__mesh_reader {
  const char *path;           /* for messages */
  const char *data, *p, *end; /* the file, the cursor, the file's end */
  long line;                  /* of the cursor, in text */
  sh_error *err;
  size_t nverts;              /* as the file declares */
  float *pos;                 /* 3 * nverts, zeroed (sh__mesh_reader_vertices) */
  unsigned *tris;             /* 3 * ntris, room for cap */
  size_t ntris, cap;
  long long *list;            /* one polygon's or list's indices */
  size_t list_cap;
} sh__mesh_reader;

/* Starts reading the `size` bytes at `data` (line 1, no vertices). */
void sh__mesh_reader_init(sh__mesh_reader *r, const char *path,
                          const char *data, size_t size, sh_error *err);

/* Sets the error: at `line` if it is > 0, else at the cursor's byte
 * offset. Returns SH_ERR_MESH. */
sh_status sh__mesh_reader_fail(sh__mesh_reader *r, long line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* The blanks between tokens: space, tab, CR, LF, VT, FF. */
int sh__mesh_is_space(char c);

/* Parses the n bytes at s as a whole number of decimal digits: 1 and *out,
 * 0 if they are not digits (or n is 0), -1 if the number exceeds SIZE_MAX. */
int sh__mesh_whole(const char *s, size_t n, size_t *out);

/* Allocates the n vertices the file declares (zeroed), after the caller
 * has checked n against the bytes left; more than INT_MAX / 3 is an error
 * at `line`. */
sh_status sh__mesh_reader_vertices(sh__mesh_reader *r, size_t n, long line);

/* Sets coordinate `axis` (0, 1, 2) of vertex k (counted from 0); a value
 * that is not a finite float is an error at `line`. */
sh_status sh__mesh_reader_coord(sh__mesh_reader *r, size_t k, int axis, double v,
                                long line);

/* Makes room for a list of n indices in r->list (n checked against the
 * bytes left by the caller). */
sh_status sh__mesh_reader_list(sh__mesh_reader *r, size_t n);

/* Checks the n indices of r->list (counted from 0) against the vertex
 * count; -1 is let through if `restart` is set (triangle strips). The
 * error names `what` ("face") and `line`. */
sh_status sh__mesh_reader_check(sh__mesh_reader *r, size_t n, int restart,
                                const char *what, long line);

/* Adds the triangle (a, b, c) unless two corners are the same vertex. */
sh_status sh__mesh_reader_triangle(sh__mesh_reader *r, long long a, long long b,
                                   long long c, long line);

/* The polygon of the n checked indices of r->list, fanned from its first
 * corner into n - 2 triangles (none for n < 3: points and lines). */
sh_status sh__mesh_reader_fan(sh__mesh_reader *r, size_t n, long line);

/* Ends the read whose status is st: on SH_OK with triangles, hands the
 * vertices and triangles to `mesh`; otherwise frees them (no triangles is
 * an error). Frees the list either way; returns the final status. */
sh_status sh__mesh_reader_finish(sh__mesh_reader *r, sh_status st, sh_mesh *mesh);

#endif
