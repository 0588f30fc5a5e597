/* Lights: the spot profile, light maps, and the unshadowed irradiance a light
 * delivers at a point (before visibility and the medium's transmittance). */
#ifndef SH_LIGHT_H
#define SH_LIGHT_H

#include "sh_error.h"
#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The largest angular diameter of a directional light's disk, degrees (the
 * contract's "The sun's disk"; the Sun's is about 0.53). */
#define SH_SUN_DISK_MAX_DEG 10.0

/* Computes a light's derived fields (cosines, the light-map frame, the
 * disk's cone and solid angle) once its
 * parsed fields are set. `camera_up` orients a spot's light map when the
 * scene gives no "up". Returns SH_ERR_SCENE with a message if the frame is
 * degenerate (an up vector parallel to the axis, a flat window). */
sh_status sh_light_prepare(sh_light *light, sh_vec3 camera_up, int has_up,
                           sh_error *err);

/* The spot profile of scene-format.md at cos(theta) from the axis:
 * cos^exponent * smoothstep((cos - cos outer) / (cos inner - cos outer)),
 * with a hard edge when inner equals outer. */
double sh_spot_profile(const sh_light *light, double cos_theta);

/* What a light sends towards point p, unshadowed and in vacuum.
 * Writes the unit direction from p towards the light to *wi and the distance
 * to the light to *dist (INFINITY for directional lights), and returns the
 * irradiance normal to *wi: intensity * profile * map / r^2 for point and spot
 * lights, irradiance * pattern for directional ones. */
sh_vec3 sh_light_incident(const sh_light *light, sh_vec3 p, sh_vec3 *wi,
                          double *dist);

/* The light map's value (linear RGB) in the direction from the light to p
 * (spot), or at p's projection onto the window (directional): 1 if the light
 * has no map, 0 outside a directional light's window. */
sh_vec3 sh_light_map_value(const sh_light *light, sh_vec3 p);

/* The sun's disk (docs/scene-format.md, "The sun's disk"): the radiance a
 * ray in the unit direction d that leaves the scene sees from a
 * directional light with angular_diameter_deg > 0, before the medium's
 * transmittance: irradiance / Omega inside the cone of half-angle
 * theta = angular_diameter_deg / 2 around the direction the light comes
 * from (the edge included), 0 outside it and for every other light.
 * Omega = 2 pi (1 - cos theta), computed as 4 pi sin^2(theta / 2) to keep
 * its digits for small disks. The light map plays no part: the disk is
 * uniform. Shading still treats the light as one direction. */
sh_vec3 sh_light_disk_radiance(const sh_light *light, sh_vec3 d);

/* The radiance a ray in the unit direction d sees when it leaves the
 * scene, before the medium's transmittance: the scene's background plus
 * every light's disk (sh_light_disk_radiance). */
sh_vec3 sh_scene_background_radiance(const sh_scene *scene, sh_vec3 d);

#ifdef __cplusplus
}
#endif
#endif
