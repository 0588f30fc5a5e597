/* What one light reaches, worked out on the CPU once per frame:
 * - its region: the half-spaces that bound where it can shine (a spot's
 *   pyramid circumscribing its cone, a directional light's window prism);
 * - its lit volume: the medium's box inside that region and the view
 *   frustum, a convex polytope, with its view-depth range (where the planes
 *   go) and its screen rectangle (where the lattice goes);
 * - which shapes may cast shadows: those inside the region that no face
 *   plane of their bounding box separates from the light and the lit volume
 *   or another shape (a convex shape does not shadow itself); a light with
 *   no caster needs no shadow map. The map's
 *   projection: a 2D perspective map for spots up to 70 degrees, a cube map
 *   for point lights and wider spots, an orthographic map for directional
 *   lights covering what the camera sees of the lit region (in an
 *   atmosphere, the shapes' bounds: gs__medium_shadow_bounds). */
#ifndef GS_LIGHTVOL_H
#define GS_LIGHTVOL_H

#include "gs_geometry.h"
#include "gs_polytope.h"
#include "gs_view.h"
#include "sh_scene.h"
#include "shaders/gs_shared.h"

/* The shadow map's kind, as the shaders' SHADOW switch numbers it. */
typedef enum gs__shadow_kind {
  GS__SHADOW_NONE = GS_SHADOW_NONE,
  GS__SHADOW_2D = GS_SHADOW_2D,
  GS__SHADOW_CUBE = GS_SHADOW_CUBE
} gs__shadow_kind;

#define GS__MAX_REGION 12

typedef struct gs__light_setup {
  const sh_light *light;
  int nregion;
  gs__halfspace region[GS__MAX_REGION];
  int cone_clip; /* a spot narrower than 90 degrees: clip rays to its cone */

  /* The lit volume (nfaces 0: the light lights no visible medium). */
  gs__poly *vol;
  double zmin, zmax;   /* its view-depth range */
  double rect[4];      /* its screen bounds: ndc x0, y0, x1, y1 */
  /* The screen bounds of the scene's bounds inside the region and the
   * view frustum: the only pixels whose surfaces the light can reach
   * (x0 > x1 if none). */
  double surface_rect[4];

  /* The shadow map, and the shapes drawn into it (casts[i] = 1 if shape i
   * may shadow the lit volume or another shape). */
  gs__shadow_kind shadow;
  unsigned char *casts;
  int nfaces;              /* 1, or 6 for a cube map */
  sh_mat4 face_vp[6];      /* world to clip for each face, reversed depth */
  int light_front[6];      /* 1 if triangles facing the light are front
                              facing (counter-clockwise) in face f */
  sh_mat4 lookup;          /* 2D maps: world to ([0,1]^2, depth) */
  double shadow_near;      /* perspective maps' near distance */
  double shadow_span;      /* the world length the map's side spans: an
                              orthographic map's; per unit of distance from
                              the light for perspective ones (2 tan(outer)
                              for a spot, 2 for a cube map's face) */

  /* A directional light's window: s = win_s . p + win_s[3], t alike. */
  double win_s[4], win_t[4];
} gs__light_setup;

/* Works out light `index` of the scene for the view. A scene without a
 * medium (or with sigma_s = 0) has no lit volume. */
sh_status gs__light_setup_init(gs__light_setup *ls, const sh_scene *scene,
                               int index, const gs__view *view,
                               const gs__geometry *geom, sh_error *err);

void gs__light_setup_free(gs__light_setup *ls);

#endif
