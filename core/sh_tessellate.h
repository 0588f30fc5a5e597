/* Triangles for the analytic shapes of a scene, for consumers that draw
 * triangles (the GL renderer, exporters to formats without spheres).
 *
 * Accuracy: for a sphere or a cylinder the result is inscribed in the true
 * surface (every vertex lies on it) and every point of the triangles is
 * within max_error of the true surface, and every point of the true surface
 * within max_error of the triangles (a two-sided, Hausdorff bound; the
 * triangles lie inside, never outside, the convex true shape). Boxes, quads,
 * meshes and heightfields are exact. */
#ifndef SH_TESSELLATE_H
#define SH_TESSELLATE_H

#include "sh_error.h"
#include "sh_mesh.h"
#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fills `out` (caller frees with sh_mesh_free) with the shape's triangles in
 * its object space (shape->xform is not applied), counter-clockwise seen
 * from outside:
 * - sphere: a latitude-longitude sphere of 2n segments around and n bands
 *   from pole to pole, n the smallest (at least 2) that meets max_error;
 *   closed, with one vertex at each pole.
 * - cylinder: n segments around, n >= 3 the smallest with
 *   radius (1 - cos(pi / n)) <= max_error; with caps (a fan about the
 *   centre of each end disc) it is closed, without it is an open tube.
 * - box: 8 vertices and 12 triangles, closed.
 * - quad: 4 vertices and 2 triangles, facing u x v.
 * - mesh, heightfield: a copy of shape->mesh.
 * Every closed result shares its vertices, so each edge belongs to exactly
 * two triangles. max_error (scene units, > 0) matters only for spheres and
 * cylinders; a max_error so small that the result would exceed 2^24
 * triangles, a degenerate shape (radius <= 0, a cylinder of zero length) or
 * an unknown type is SH_ERR_ARG. */
sh_status sh_mesh_tessellate(const sh_shape *shape, double max_error,
                             sh_mesh *out, sh_error *err);

/* As sh_mesh_tessellate, with positions p - origin (object space): the
 * float positions then keep their precision for a shape far from the
 * object-space origin (a quad 2e-6 across, 100 units away, collapsed to a
 * line). Meshes and heightfields, stored in float already, gain nothing. */
sh_status sh_mesh_tessellate_about(const sh_shape *shape, double max_error,
                                   sh_vec3 origin, sh_mesh *out,
                                   sh_error *err);

#ifdef __cplusplus
}
#endif
#endif
