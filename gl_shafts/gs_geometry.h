/* The scene's surfaces as GL triangles: every shape tessellated
 * (sh_tessellate.h), moved to world space, with the normals the reference
 * renderer shades with: the exact normals of cylinder walls (interpolated
 * across the tessellation), the flat geometric normal of each triangle for
 * meshes, boxes, quads and heightfields. Spheres are drawn exactly: their
 * triangles only cover them, and the surface shader finds the true surface
 * point, normal and depth on each pixel's ray (the reference intersects
 * spheres exactly too); their shadows come from the inscribed tessellation. */
#ifndef GS_GEOMETRY_H
#define GS_GEOMETRY_H

#include "gs_gl.h"
#include "gs_view.h"
#include "sh_scene.h"

typedef struct gs__shape_draw {
  int first, count;    /* vertex range in the buffer */
  int material;        /* index into the scene's materials */
  sh_vec3 bmin, bmax;  /* world bounds */
  int convex;          /* a closed convex shape or a flat one: cannot shadow itself */
  int closed;          /* a closed surface, outward counter-clockwise */
  int mirrored;        /* its transform mirrors: triangles are clockwise */
  int exact_sphere;    /* a sphere: the surface shader intersects the true
                          sphere; its triangles are inscribed, and scaled
                          by `inflate` about `center` (world) they
                          circumscribe it */
  double inflate;
  sh_vec3 center;
  double error;        /* the tessellation error it was built with */
  sh_mat4 xform;       /* the transform it was built with */
} gs__shape_draw;

typedef struct gs__geometry {
  GLuint vao, vbo;     /* position (location 0) and normal (1), 3 floats each */
  int nverts, nshapes;
  gs__shape_draw *shape;
  long triangles;
  sh_vec3 anchor;      /* the view's anchor the triangles are relative to */
} gs__geometry;

/* Tessellates and uploads the scene's shapes, relative to the view's
 * anchor (gs_view.h). Spheres and cylinders get a
 * tessellation error of a quarter pixel at their distance from the camera
 * (never below 1e-4 of their radius). */
sh_status gs__geometry_build(const sh_scene *scene, const gs__view *view,
                             gs__geometry *g, sh_error *err);

/* Brings the triangles up to date with the scene's shape transforms and
 * the view (which sets curved shapes' tessellation): a shape that moved, or
 * whose tessellation error changed, is tessellated again and uploaded in
 * place; if its vertex count or the view's anchor changed, the whole
 * buffer is built again
 * (*rebuilt = 1: the vertex array object is new). *changed = 1 if any
 * shape's triangles changed (what shadow maps are keyed by). The scene must
 * have the same shapes as when built (SH_ERR_ARG otherwise). */
sh_status gs__geometry_update(const sh_scene *scene, const gs__view *view,
                              gs__geometry *g, int *rebuilt, int *changed,
                              sh_error *err);

void gs__geometry_free(gs__geometry *g);

#endif
