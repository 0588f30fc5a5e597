/* gl_shafts: the plane-sweep renderer of Dobashi, Yamamoto and Nishita
 * (2000), "Interactive Rendering Method for Displaying Shafts of Light", on
 * OpenGL 4.5 core without a window: through EGL (a GPU where there is one,
 * else Mesa's llvmpipe on the CPU) or, as a fallback, OSMesa (llvmpipe).
 *
 * The image is the radiance of docs/scene-format.md: surfaces shaded as the
 * reference renderer shades them (Lambert and Phong with shadow-map
 * shadows, emission, ambient), attenuated by the medium towards the eye,
 * plus the light the medium scatters once towards the eye, summed over
 * virtual planes parallel to the screen (section 5 of the paper): the
 * scattering term xi on an nu x nv lattice per plane (or per fragment),
 * times the light's pattern (spot profile and light map, or a window's
 * pattern), times its shadow-map visibility, accumulated in 32-bit float.
 * docs/gl_shafts.md describes the method as implemented, with measurements.
 *
 * Limitations: no mirror reflection and no transmission: the `reflect`,
 * `transmit` and `ior` of materials are ignored (semitransparent surfaces
 * are drawn opaque and cast full shadows). Shadows are shadow-map shadows
 * (bilinear comparison: edges are a texel soft).
 *
 * Library calls never exit or abort: they return an sh_status and fill an
 * sh_error (GL errors, shader compile errors and a backend that gives no
 * OpenGL 4.5 core context are SH_ERR_DEVICE).
 *
 * Threads: a renderer owns one GL context. Every gs_renderer_* call makes
 * it current on the calling thread on entry and releases it on exit
 * (restoring the EGL context the thread had current, if any), so a
 * renderer may be used from any thread (calls on one renderer from several
 * threads run one after the other), and the library never leaves its
 * context current on the caller's thread. With
 * libglvnd a thread has one current context across EGL and GLX, so a
 * program that has its own GLX context current (Blender's main thread)
 * drives a renderer from another thread. */
#ifndef GS_RENDER_H
#define GS_RENDER_H

#include "sh_camera.h"
#include "sh_error.h"
#include "sh_image.h"
#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Where the GL context comes from (gs_context.h). AUTO: EGL's device
 * platform (a hardware device before a software one), then EGL's
 * surfaceless platform, then OSMesa; the environment variable
 * SHAFTS_GL_BACKEND ("egl" or "osmesa") narrows AUTO to one backend, which
 * is how the tests run on each. */
typedef enum gs_backend {
  GS_BACKEND_AUTO = 0,
  GS_BACKEND_EGL,
  GS_BACKEND_OSMESA
} gs_backend;

/* How the renderer evaluates the scattering term xi (render.xi, --xi). */
typedef enum gs_xi_mode {
  GS_XI_DEFAULT, /* the renderer's default (GS_DEFAULT_XI) */
  GS_XI_LATTICE, /* on the plane lattice, interpolated (the seed's method) */
  GS_XI_EXACT    /* per fragment */
} gs_xi_mode;

/* Rendering settings. gs_options_defaults fills them from the scene's
 * render object, with the built-in defaults below for keys it lacks. */
typedef struct gs_options {
  int planes;               /* virtual planes per light, 1..100000; 0: by
                               the light's kind (GS_DEFAULT_PLANES_*) */
  int lattice_u, lattice_v; /* lattice points per plane, each 2..4096 */
  int light_map_res;        /* 0: light maps at their own size; else
                               resampled to R x R, 1..16384 */
  int shadow_map_res;       /* shadow-map size in texels, 1..16384; 0: by
                               the light's kind (GS_DEFAULT_SHADOW_*) */
  gs_xi_mode xi;            /* GS_XI_LATTICE (the seed's) or GS_XI_EXACT */
  int jitter;               /* 1: per-pixel jitter of the sample depths */
  double sub_angle_deg;     /* point and spot lights: a plane's fragment
                               takes one sample per this angle (degrees)
                               its part of the ray subtends at the light,
                               so rays passing near a light are sampled
                               finely (at most 1024 samples a fragment
                               of a point or spot light, 64 of a
                               directional light); (0, 30] */
  double sub_texels;        /* lights with a map (a spot's gobo, a
                               directional light's window): a plane's
                               fragment takes one sample per this many
                               texels of the map its part of the ray
                               crosses (capped as for sub_angle_deg) */
  sh_crop crop;             /* the pixels to draw (sh_camera.h): an
                               off-axis part of the camera's frustum at the
                               whole image's resolution; all zero: the whole
                               image (gs_options_defaults) */
  gs_backend backend;       /* GS_BACKEND_AUTO unless asked */
  int live;                 /* 0 (default): every value of the scene (camera,
                               lights, medium) is baked into the shader
                               programs as a constant, the fastest frames on
                               llvmpipe but a program build (0.1-0.25 s a
                               light) for every new set of values; 1: the
                               values are uniforms, and only the scene's
                               structure (light kind, light map, shadow-map
                               kind, spot narrower than 90 degrees, phase
                               function type, grey extinction, the xi mode,
                               jitter) and three seldom-flipping value
                               classes (a spot's cosine exponent 0, 1 or
                               other; a light inside the medium's box or
                               not; a light with shadow casters or none)
                               select programs, so a renderer kept warm
                               across scene changes (gs_renderer_sync)
                               compiles nothing; frames cost more
                               (docs/gl_shafts.md, "Live mode") */
} gs_options;

/* The built-in defaults, chosen by measurement (docs/gl_shafts.md). Point
 * and spot lights need one plane, their angular sub-samples doing the
 * rest (more planes only add fragments, each with its own set-up);
 * directional lights are sampled by the planes. Orthographic shadow
 * maps cover more than a spot's cone, so they get more texels. */
#define GS_DEFAULT_PLANES_LOCAL 1
/* The most lights gs_renderer_create accepts (SH_ERR_SCENE at the key
 * "lights" beyond): each light has its own surface pass and plane sweep
 * and the cost grows faster than the count (docs/gl_shafts.md, "Limits"). */
#define GS_MAX_LIGHTS 256
#define GS_DEFAULT_PLANES_DIRECTIONAL 8
#define GS_DEFAULT_LATTICE 20
#define GS_DEFAULT_SHADOW_LOCAL 1024
#define GS_DEFAULT_SHADOW_DIRECTIONAL 2048
#define GS_DEFAULT_XI GS_XI_EXACT
#define GS_DEFAULT_JITTER 0
#define GS_DEFAULT_SUB_ANGLE_DEG 4.0
#define GS_DEFAULT_SUB_TEXELS 2.0

/* The defaults, overridden by the scene's render keys that are given and
 * valid (gs_options_from_scene, gs_named.h, reports a bad one with its
 * place; gs_render and gs_renderer_create refuse a scene with one). */
gs_options gs_options_defaults(const sh_scene *scene);

/* The planes and shadow-map size a light of this kind gets with these
 * options (resolving 0, "by the light's kind"). */
int gs_light_planes(const gs_options *opt, sh_light_type type);
int gs_light_shadow_map_res(const gs_options *opt, sh_light_type type);

/* SH_ERR_ARG with a message naming the option (as the error's key) if a
 * value is out of range. The limits and choices are one table
 * (gs_named.c) that gs_options_set (gs_named.h) reads too. */
sh_status gs_options_check(const gs_options *opt, sh_error *err);

/* Where the time of a frame went, and how much was drawn. */
typedef struct gs_stats {
  double seconds;          /* the frame: everything below together */
  double shadow_seconds;   /* working out the lights' volumes, shadow maps */
  double surface_seconds;  /* surfaces and background */
  double lattice_seconds;  /* evaluating and uploading xi on the lattices;
                              an atmosphere: its layers drawn on the
                              lattice of pixels */
  double plane_seconds;    /* the sweep: intervals and planes; an
                              atmosphere: its full-resolution passes
                              (compose, fix-up) */
  double readback_seconds; /* reading the image back from GL */
  double setup_seconds;    /* gs_render only: creating the context,
                              uploading the scene, compiling shaders
                              (not in `seconds`) */
  int lights_swept;        /* lights whose lit volume the camera sees */
  int shadow_maps;         /* shadow maps rendered in this draw (a map
                              whose key did not change is kept) */
  long planes;             /* planes drawn, over all lights (an
                              atmosphere's sampling planes, the eye in
                              the air) */
  long spheres;            /* an atmosphere's sampling spheres (the eye
                              above its top), over all suns */
  long lattice_points;     /* xi evaluations on the CPU */
  double fragments;        /* plane fragments that added light */
  double fragments_rasterized; /* pixels the planes' polygons cover */
  long triangles;          /* surface triangles */
  int width, height;
  char renderer[128];      /* GL_RENDERER */
  char backend[16];        /* "egl" or "osmesa": the backend used */
  char vendor[128];        /* GL_VENDOR */
  int programs_compiled;   /* shader programs built since the previous
                              draw (by this draw or a sync before it) */
  int programs_cached;     /* shader programs the renderer holds */
} gs_stats;

typedef struct gs_renderer gs_renderer;

/* Creates a renderer for a scene, which must outlive it: a GL context, the
 * scene's triangles and light maps uploaded. The options are copied; NULL
 * means gs_options_defaults(scene). */
sh_status gs_renderer_create(const sh_scene *scene, const gs_options *opt,
                             gs_renderer **out, sh_error *err);

/* Renders one frame into rgb: width * height * 3 floats (the camera's
 * size, or the crop's), linear radiance, row-major from the top-left pixel (as
 * sh_image). `stats` may be NULL. */
sh_status gs_renderer_draw(gs_renderer *r, float *rgb, gs_stats *stats,
                           sh_error *err);

/* Takes in changes that the caller made to the renderer's scene
 * (sh_scene_update of core/shafts.h) before the next draw. `changed` holds
 * the SH_CHANGED_* bits it returned (camera 1, lights 2, medium 4, shape
 * transforms 8, image size 16, background or ambient 32; ~0u: anything):
 * a new size resizes the render targets, the camera and the shape
 * transforms update the triangles of the shapes they concern (moved
 * shapes, and curved ones whose tessellation follows the view), a light
 * map that changed is uploaded again. The lights' volumes are worked out
 * again at the next draw after any change but the background's or the
 * ambient's; a light's shadow map is drawn again only if its projection,
 * its casters or their triangles changed (a shape moved, a curved shape's
 * tessellation followed the camera; a directional light's map follows the
 * view), else it is kept from the last draw. No program is built here; with
 * gs_options.live, the next draw builds none either unless a structural
 * switch changed (a light map added or removed, the phase function's
 * type, a spot's shadow-map kind, the medium's grey coefficients turning
 * coloured, a spot's exponent leaving its class 0, 1 or other, a light
 * entering or leaving the medium's box, a light gaining its first shadow
 * caster or losing its last; each builds once, after which both variants
 * are cached; stats.programs_compiled counts them). The scene must keep its
 * number of lights and shapes (SH_ERR_ARG otherwise: make a new renderer);
 * more than GS_MAX_LIGHTS lights is SH_ERR_SCENE at the key "lights", as
 * in gs_renderer_create.
 * On error the renderer must be freed. */
sh_status gs_renderer_sync(gs_renderer *r, unsigned changed, sh_error *err);

/* Frees the renderer and its context; NULL is allowed. Call it on no
 * thread other than one that could draw (the context must not be current
 * elsewhere). */
void gs_renderer_free(gs_renderer *r);

/* Renders `scene` into `out`, which the call allocates at the camera's size
 * (caller frees with sh_image_free): create, draw, free. */
sh_status gs_render(const sh_scene *scene, const gs_options *opt,
                    sh_image *out, gs_stats *stats, sh_error *err);

#ifdef __cplusplus
}
#endif
#endif
