/* Geometry the exporters share: the scene's bounding sphere, and the
 * "filter cards" that realise light maps in renderers without them.
 *
 * A light map becomes a card: a flat, image-textured, transparent surface
 * that only shadow rays see, whose transmittance at each point is the
 * map's linear value (a gobo in front of a spot, a stained-glass window in
 * front of the sun). The cards here reproduce the scene format's mapping
 * exactly:
 * - a spot's map covers [-tan(outer), tan(outer)]^2 of the plane at unit
 *   distance along the axis; a square of half-width d tan(outer) at
 *   distance d is its central projection, the same for every d. A small d
 *   puts the card between the light and everything it lights.
 * - a directional light's map is projected along the light's direction, so
 *   the window may slide along the direction without changing what it
 *   casts. The card is the window moved upstream, beyond every object, and
 *   an opaque wall around it blocks the light outside the window, as the
 *   format says. */
#ifndef SE_GEOM_H
#define SE_GEOM_H

#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A sphere holding the scene's content: every shape, light position and
 * the medium's bounds (sh_scene_bounds), not the camera, which may be far
 * away: the exporters' tolerances, cards and scales follow the content's
 * size (relative to a sphere that held a camera 5000 units away, they
 * swamped a scene 3.5 across). A content of no size gets the camera's
 * distance, or 1. */
void se_content_sphere(const sh_scene *scene, sh_vec3 *center, double *radius);

/* 1 if p lies inside the box [bmin, bmax] (boundary included). */
int se_in_box(sh_vec3 p, sh_vec3 bmin, sh_vec3 bmax);

/* A card: the parallelogram origin + x ex + y ey, x and y in [0, 1], with
 * the image's bottom-left corner at x = y = 0, its right along ex and its
 * top along ey (the convention of POV-Ray's image_map and of texture
 * coordinates). */
typedef struct se_card {
  sh_vec3 origin, ex, ey;
  sh_vec3 normal; /* unit, ex x ey */
} se_card;

/* The card of a spot light's map at distance `dist` along its axis. */
se_card se_spot_card(const sh_light *light, double dist);

/* The card of a directional light's map, moved upstream out of the sphere
 * (center, radius), and the wall around it: the rectangle [wall_lo.x,
 * wall_hi.x] x [wall_lo.y, wall_hi.y] in the card's (x, y) coordinates,
 * which holds the unit square with a margin and the shadow of the whole
 * sphere. `light_distance` is how far from `center`, against the light's
 * direction, a parallel light must stand to be beyond the card. */
typedef struct se_window {
  se_card card;
  double wall_lo_x, wall_lo_y, wall_hi_x, wall_hi_y;
  double light_distance;
} se_window;

se_window se_window_card(const sh_light *light, sh_vec3 center, double radius);

/* The point of a card at (x, y). */
sh_vec3 se_card_point(const se_card *card, double x, double y);

#ifdef __cplusplus
}
#endif
#endif
