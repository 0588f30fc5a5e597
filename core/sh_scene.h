/* The in-memory scene: what a scene file (docs/scene-format.md) describes,
 * validated, with defaults filled in, names resolved to indices, external
 * files (meshes, images) loaded and derived light quantities computed.
 *
 * A scene is produced by sh_scene_load (sh_parse.h) or sh_scene_parse_ex
 * (shafts.h) and freed with sh_scene_free. Renderers and exporters only
 * read it; sh_scene_update (shafts.h) changes its camera, lights, medium
 * and transforms between frames. */
#ifndef SH_SCENE_H
#define SH_SCENE_H

#include "sh_error.h"
#include "sh_image.h"
#include "sh_math.h"
#include "sh_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sh_camera {
  sh_vec3 position, look_at, up; /* up defaults to (0, 1, 0) */
  double fov_y_deg;              /* full vertical field of view, (0, 180) */
  int width, height;             /* pixels, >= 1 */
} sh_camera;

typedef enum sh_phase_type {
  SH_PHASE_ISOTROPIC,
  SH_PHASE_HENYEY_GREENSTEIN,
  SH_PHASE_NISHITA_HAZY,
  SH_PHASE_NISHITA_MURKY,
  SH_PHASE_RAYLEIGH,
  SH_PHASE_CORNETTE_SHANKS /* the contract's "Non-uniform media" */
} sh_phase_type;

typedef struct sh_phase {
  sh_phase_type type;
  double g; /* Henyey-Greenstein and Cornette-Shanks asymmetry, (-1, 1); 0
               for the others */
} sh_phase;

/* The kinds of medium (docs/scene-format.md, "Non-uniform media"). Only
 * sh_medium.h's functions look at the kind: renderers ask the medium for
 * optical depth, coefficients and phase at a point. */
typedef enum sh_medium_type {
  SH_MEDIUM_HOMOGENEOUS, /* the coefficients are the same everywhere */
  SH_MEDIUM_HEIGHT_FOG,  /* every coefficient times exp(-(y - base) / H) */
  SH_MEDIUM_ATMOSPHERE   /* a planet's air: sh_atmosphere */
} sh_medium_type;

/* A planet's air (the contract's "atmosphere", after Nishita et al. 1993
 * and Bruneton 2017), in scene units: a scene in kilometres gives its
 * coefficients per kilometre. h(p) = |p - center| - ground_radius is the
 * height above the ground. At p:
 *   sigma_s = rayleigh_sigma_s exp(-h / rayleigh_H) + mie_sigma_s rho_M,
 *   sigma_a = mie_sigma_a rho_M + ozone_sigma_a rho_O,
 * rho_M = exp(-h / mie_H), rho_O = max(0, 1 - |h - ozone_height| /
 * (ozone_width / 2)); a part that is absent has its coefficients 0. */
typedef struct sh_atmosphere {
  sh_vec3 center;        /* the planet's centre */
  double ground_radius;  /* R_g > 0: the ground, an opaque Lambert sphere */
  double top_radius;     /* R_t > R_g: vacuum above */
  sh_vec3 ground_albedo; /* default 0.1 grey */
  sh_vec3 rayleigh_sigma_s; /* at the ground; phase `rayleigh` */
  double rayleigh_H;        /* > 0 */
  int has_mie;
  sh_vec3 mie_sigma_s, mie_sigma_a; /* at the ground */
  double mie_H;                     /* > 0 */
  sh_phase mie_phase;               /* any phase object */
  int has_ozone;
  sh_vec3 ozone_sigma_a;            /* at the tent's peak */
  double ozone_height, ozone_width; /* the peak's height; width > 0 */
} sh_atmosphere;

typedef struct sh_medium {
  int present;             /* 0: vacuum everywhere, the rest is unused */
  sh_medium_type type;     /* 0 (homogeneous) unless the scene says */
  /* Per unit length, >= 0: everywhere for a homogeneous medium, at
   * base_height for height fog. For an atmosphere, derived: the largest
   * values anywhere (sigma_s at the ground, sigma_a the Mie's at the
   * ground plus the ozone's peak), so that sigma_t is a majorant. */
  sh_vec3 sigma_s, sigma_a;
  sh_vec3 sigma_t;          /* derived: sigma_s + sigma_a */
  double base_height;       /* height fog: the Y of the reference level */
  double scale_height;      /* height fog: H > 0 */
  sh_phase phase;           /* atmosphere: rayleigh (Mie's is its own) */
  sh_vec3 bmin, bmax;       /* the box the medium fills; bmin < bmax; for
                               an atmosphere the box around its top
                               sphere (derived) */
  sh_atmosphere atmo;       /* atmosphere only */
  int line, column; /* of medium.type (else of the medium) in the file; 0
                       if unknown: where tools that refuse a kind point */
  int phase_line, phase_column; /* of medium.phase.type; 0 if unknown */
} sh_medium;

typedef enum sh_light_type {
  SH_LIGHT_POINT,
  SH_LIGHT_SPOT,
  SH_LIGHT_DIRECTIONAL
} sh_light_type;

typedef struct sh_light {
  sh_light_type type;
  sh_vec3 position;   /* point, spot */
  sh_vec3 direction;  /* unit; spot: the axis; directional: travel direction */
  sh_vec3 intensity;  /* point, spot: W/sr (on the axis for spots) */
  int soft_shadows;   /* light meshes: 1 (default) soft, 0 hard shadows */
  sh_vec3 irradiance; /* directional: W/m^2 normal to the direction */
  double angular_diameter_deg; /* directional: the sun's disk seen by rays
                                  that leave the scene, in [0, 10]; 0 (the
                                  default): no disk */
  double outer_deg, inner_deg, exponent; /* spot */

  /* Light map (optional). For spots, `map_right` and `map_up` complete
   * `direction` to the light's frame. For directional lights the pattern
   * fills map_origin + s map_u + t map_v. */
  int has_map;
  int map_up_given; /* spot: 1 if the map's up was given, 0 if it comes
                       from the camera's up */
  char *map_file; /* resolved path; owned */
  sh_image map;   /* linear RGB; owned */
  sh_vec3 map_origin, map_u, map_v;
  sh_vec3 map_right, map_up;

  /* Derived by sh_light_prepare (sh_light.h). */
  double cos_outer, cos_inner, tan_outer;
  sh_vec3 map_normal; /* directional: unit normal of the map's plane */
  double disk_cos_half;    /* directional: cos of the disk's half-angle */
  double disk_solid_angle; /* directional: the disk's solid angle (sr), 0
                              without a disk */
} sh_light;

typedef struct sh_material {
  char *name; /* owned */
  sh_vec3 diffuse, specular;
  double shininess; /* default 32 */
  sh_vec3 reflect, transmit;
  double ior; /* default 1 */
  sh_vec3 emission;
  /* Light meshes controls (the project's keys), both default 1. */
  int casts_soft_shadows, receives_soft_shadows;
} sh_material;

typedef enum sh_shape_type {
  SH_SHAPE_MESH,
  SH_SHAPE_SPHERE,
  SH_SHAPE_BOX,
  SH_SHAPE_CYLINDER,
  SH_SHAPE_QUAD,
  SH_SHAPE_HEIGHTFIELD
} sh_shape_type;

typedef struct sh_shape {
  sh_shape_type type;
  int material;        /* index into sh_scene.materials */
  sh_mat4 xform, inv;  /* object to world and back; identity by default */
  sh_vec3 center;      /* sphere */
  double radius;       /* sphere, cylinder */
  sh_vec3 bmin, bmax;  /* box, heightfield */
  sh_vec3 base, top;   /* cylinder */
  int caps;            /* cylinder, default 1 */
  sh_vec3 corner, u, v; /* quad */
  char *file;          /* mesh file or heightfield image, resolved; owned;
                          NULL for a mesh from memory */
  char *data;          /* mesh from memory (shafts.h): its name; owned */
  char **named;        /* the other files the mesh's load read (an OBJ's
                          material library, a glTF's buffers and images),
                          resolved; owned, nnamed of them (sh_outputs.h) */
  int nnamed;
  sh_mesh mesh;        /* mesh, heightfield: object-space triangles; owned */
} sh_shape;

/* A key of the scene's `render` object that a renderer owns (gl_shafts'
 * planes, lattice, light_map_res, shadow_map_res, xi, jitter; the light
 * meshes' mesh_step, kl, scheme). The parser keeps it as given, with where
 * it stands, and the renderer that owns it checks it against its own
 * option table (sh_render_params.h): one limit, one message, located. */
typedef struct sh_render_param {
  char *key;   /* owned */
  char *text;  /* the value as option text: a number, a name, "true" or
                  "false", an array's numbers joined by spaces; owned */
  char *json;  /* the value as compact JSON text; owned */
  int line, column; /* of the value in the scene file; 0 if unknown */
} sh_render_param;

/* The scene's `render` object: the reference's settings, parsed and
 * checked by the core, and the renderers' keys, kept for them. */
typedef struct sh_render_settings {
  int spp;          /* reference: in-scattering samples per pixel, default 16 */
  int max_depth;    /* Whitted recursion limit, default 5 */
  unsigned seed;    /* default 0 */
  double exposure;  /* PNG exposure in stops, default 0 */
  int nparams;
  sh_render_param *params; /* owned; in the file's order */
} sh_render_settings;

typedef struct sh_scene {
  char *file; /* the scene file's path as given; owned */
  char *base_dir; /* what relative file names resolve against; owned;
                     NULL: they are used as written */
  sh_camera camera;
  sh_vec3 background, ambient;
  sh_medium medium;
  int nlights;
  sh_light *lights;
  int nmaterials;
  sh_material *materials;
  int nshapes;
  sh_shape *shapes;
  sh_render_settings render;
} sh_scene;

/* Frees everything the scene owns, then the scene. NULL is allowed. */
void sh_scene_free(sh_scene *scene);

/* The camera's image size in pixels, for callers that see the scene only
 * through this API (language bindings). */
void sh_scene_image_size(const sh_scene *scene, int *width, int *height);

/* True if any material has a non-black transmit colour. */
int sh_scene_has_semitransparent(const sh_scene *scene);

/* The world-space box that holds the shape (its object box, transformed).
 * Returns 0 for a shape with no extent (an empty mesh). */
int sh_shape_bounds(const sh_shape *shape, sh_vec3 *bmin, sh_vec3 *bmax);

/* The world-space box that holds every shape and light position (and the
 * medium's bounds). */
void sh_scene_bounds(const sh_scene *scene, sh_vec3 *bmin, sh_vec3 *bmax);

/* A frame for single-precision work on the box [lo, hi]: *unit the power
 * of two at or above half its diagonal (or, for a box of no size, its
 * largest coordinate; 1 if that is 0 too) and *origin the multiple of
 * *unit nearest its centre, so that the box lies within 2 units of the
 * origin (half the diagonal is at most a unit, the centre within sqrt(3) /
 * 2 of the origin), and moving into the frame, (p - origin) / unit, is
 * exact for coordinates that are multiples of a small power of two of the
 * unit (a floor at y = 0 stays at exactly 0, at any scale). Being
 * quantised, the frame stays when the box moves or grows a little. */
void sh_frame_fit(sh_vec3 lo, sh_vec3 hi, sh_vec3 *origin, double *unit);

#ifdef __cplusplus
}
#endif
#endif
