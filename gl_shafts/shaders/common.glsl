// Declarations and functions shared by every gl_shafts shader. The program
// builder (gs_program.c) puts "#version 450 core" and the variant's
// #defines before this file and the stage's own file after it:
// (the named values, GS_LIGHT_POINT ..., come from gs_shared.h, which the
// builder puts first, and which the C code includes too)
//   LIGHT_TYPE  GS_LIGHT_POINT, GS_LIGHT_SPOT or GS_LIGHT_DIRECTIONAL
//   HAS_MAP     1 if the light has a light map
//   SHADOW      GS_SHADOW_NONE, GS_SHADOW_2D or GS_SHADOW_CUBE
//   CONE_CLIP   1 to clip rays to the spot's cone (outer angle < 90 degrees)
//   PHASE       GS_PHASE_ISOTROPIC, _HENYEY_GREENSTEIN, _NISHITA_HAZY,
//               _NISHITA_MURKY, _RAYLEIGH or _CORNETTE_SHANKS
//   XI_EXACT    1: xi per fragment; 0: interpolated from the lattice
//   JITTER      1: jittered sample depth within each plane's slab
//   GREY_SIGMA  1 if sigma_t is the same in R, G and B
//   SPOT_SMOOTH GS_SPOT_SMOOTH if the spot's inner angle is below its outer
//               one, GS_SPOT_HARD if not, GS_SPOT_BY_VALUE: either, by the
//               values (live programs)
//   SPOT_EXPONENT GS_SPOT_EXPONENT_0, _1, or _ANY for any other exponent
//   LIGHT_INSIDE 1 if a point or spot light is inside the medium's box
//   TAU_SUB     1 if a slab can be optically thick: sample it by optical
//               depth (live programs always do, with a rate of 0 when no
//               slab is thick)
//   MEDIUM      GS_MEDIUM_HOMOGENEOUS, GS_MEDIUM_HEIGHT_FOG or
//               GS_MEDIUM_ATMOSPHERE (medium.glsl, included below, is all
//               that looks at it)
// Live programs (gs_options.live) switch on the scene's structure and on
// the value classes above that are costly to choose per fragment and
// seldom flip (SPOT_EXPONENT, LIGHT_INSIDE, SHADOW 0 for a light without
// shadow casters), so that new values select the same program.
// Conventions: p is a world point (in the anchored space, gs_view.h); z is
// view depth, the distance along the camera's forward axis, counted from the
// depth u_zref (the scene's near end, or the eye when the camera is in the
// scene): the pixel ray is ray_origin + z * d with d the unnormalised
// direction of view_ray (d . forward = 1), and the eye lies at z = -u_zref.
// Counted from the eye, a camera far away kept depths and points only to
// the ulp of its distance (gs_view.h).

#ifndef LIGHT_TYPE
#define LIGHT_TYPE GS_LIGHT_POINT
#endif
#ifndef HAS_MAP
#define HAS_MAP 0
#endif
#ifndef SHADOW
#define SHADOW GS_SHADOW_NONE
#endif
#ifndef CONE_CLIP
#define CONE_CLIP 0
#endif
#ifndef PHASE
#define PHASE GS_PHASE_ISOTROPIC
#endif
#ifndef XI_EXACT
#define XI_EXACT 0
#endif
#ifndef JITTER
#define JITTER 0
#endif
#ifndef GREY_SIGMA
#define GREY_SIGMA 0
#endif
#ifndef TAU_SUB
#define TAU_SUB 0
#endif
#ifndef LIGHT_INSIDE
#define LIGHT_INSIDE 0
#endif
#ifndef SPOT_SMOOTH
#define SPOT_SMOOTH GS_SPOT_SMOOTH
#endif
#ifndef SPOT_EXPONENT
#define SPOT_EXPONENT GS_SPOT_EXPONENT_ANY
#endif

const float PI = 3.14159265358979;
const float BIG = 3.0e38;

// The parameters come first, as constants or uniforms (gs_params.c):
// camera: u_org and u_zref (below), u_depth_ab (the depth buffer holds
//   (u_depth_ab.y - u_depth_ab.x z) / (u_zref + z), gs_view.h), u_fwd, u_rx and u_uy (right and up times the drawn
//   window's half size on the plane one unit ahead: tan(half fov) for the
//   whole image), u_rc (the window's centre on that plane, 0 for the whole
//   image), u_ndc_scale (2 / width, 2 / height of the window), u_frag0 (the
//   window's corner in the whole image's pixels, from the bottom left);
// medium (0 without one; gs_medium.c): u_sigma_s, u_sigma_t (at the base
//   height for height fog), the box u_bmin, u_bmax, the Henyey-Greenstein
//   u_g, and height fog's u_fog (medium.glsl);
// light: u_lpos, u_ldir (unit axis or travel direction), u_lpower
//   (intensity or irradiance), u_spot (1 - cos outer, 1 - cos inner,
//   exponent, 1 / tan outer), the spot light map's frame u_map_right, u_map_up, a
//   window's coordinates s = dot(u_win_s.xyz, p) + u_win_s.w and u_win_t,
//   the 2D shadow map's lookup u_shadow_mat (world to [0,1]^2 x reversed
//   depth) and the cube map's near distance u_shadow_near; u_light_rmin, the
//   nearest a ray is taken to pass to a point or spot light (sh_medium.h).
layout(binding = GS_UNIT_MAP) uniform sampler2D u_map;

layout(binding = GS_UNIT_SHADOW_2D) uniform sampler2DShadow u_shadow2d;
layout(binding = GS_UNIT_SHADOW_CUBE) uniform samplerCubeShadow u_shadowcube;
layout(binding = GS_UNIT_SHADOW_DEPTH_2D) uniform sampler2D u_shadow2d_depth;
layout(binding = GS_UNIT_SHADOW_DEPTH_CUBE) uniform samplerCube u_shadowcube_depth;

// The unnormalised direction (d . u_fwd = 1) of the ray through a point of
// the drawn window's NDC, and through a fragment's centre.
vec3 ndc_ray(vec2 ndc) {
  return u_fwd + u_rc + ndc.x * u_rx + ndc.y * u_uy;
}

vec3 view_ray(vec2 frag) {
  return ndc_ray(frag * u_ndc_scale - 1.0);
}

// The point at z = 0 of the ray through a point of the window's NDC, and
// through a fragment's centre: u_org (the view axis at u_zref) plus u_zref
// (d - u_fwd), both small where the scene is.
vec3 ndc_origin(vec2 ndc) {
  return u_org + u_zref * (u_rc + ndc.x * u_rx + ndc.y * u_uy);
}

vec3 view_origin(vec2 frag) {
  return ndc_origin(frag * u_ndc_scale - 1.0);
}

// The depth buffer's value at view depth z (from u_zref), as gs_view.c's
// projection gives it.
float depth_at(float z) {
  return (u_depth_ab.y - u_depth_ab.x * z) / (u_zref + z);
}

// 1 / d with zero components replaced by a huge number of the right sign,
// so that box slabs never see 0 * infinity.
vec3 safe_inv(vec3 d) {
  vec3 a = 1.0 / max(abs(d), vec3(1e-30));
  return mix(a, -a, lessThan(d, vec3(0.0)));
}

// The part [t0, t1] of o + t d, t in [lo, hi], inside the medium's box
// (empty when t0 >= t1).
vec2 box_clip(vec3 o, vec3 d, float lo, float hi) {
  vec3 inv = safe_inv(d);
  vec3 ta = (u_bmin - o) * inv, tb = (u_bmax - o) * inv;
  vec3 t0 = min(ta, tb), t1 = max(ta, tb);
  return vec2(max(lo, max(t0.x, max(t0.y, t0.z))),
              min(hi, min(t1.x, min(t1.y, t1.z))));
}

// Distance from p, inside the box, to the box's boundary along unit w.
float box_exit(vec3 p, vec3 w) {
  vec3 t = (mix(u_bmin, u_bmax, step(0.0, w)) - p) * safe_inv(w);
  return max(min(t.x, min(t.y, t.z)), 0.0);
}

// The medium: its region, optical depth, transmittance and coefficients at
// a point, chosen by MEDIUM (the only code that looks at the medium's kind).
#include "medium.glsl"

// The optical depth of the pixel ray o + z d between the eye (z = -u_zref)
// and z.
vec3 optical_depth_eye(vec3 o, vec3 d, float z) {
  vec2 t = medium_clip(o, d, -u_zref, z);
  return t.y > t.x ? optical_depth_span(o, d, length(d), t.x, t.y) : vec3(0.0);
}

// Cornette and Shanks' phase function of asymmetry g at cos(alpha)
// (sh_phase_eval).
float phase_cornette_shanks(float g, float c) {
  float den = 1.0 + g * g - 2.0 * g * c;
  return 3.0 * (1.0 - g * g) * (1.0 + c * c) / (8.0 * PI * (2.0 + g * g) * den * sqrt(den));
}

// The normalised phase function at cos(alpha) (sh_phase_eval).
float phase(float c) {
#if PHASE == GS_PHASE_CORNETTE_SHANKS
  return phase_cornette_shanks(u_g, c);
#elif PHASE == GS_PHASE_HENYEY_GREENSTEIN
  float den = 1.0 + u_g * u_g - 2.0 * u_g * c;
  return (1.0 - u_g * u_g) / (4.0 * PI * den * sqrt(den));
#elif PHASE == GS_PHASE_NISHITA_HAZY
  float x = 0.5 * (1.0 + c), x2 = x * x, x4 = x2 * x2;
  return (1.0 + 9.0 * x4 * x4) / (8.0 * PI);
#elif PHASE == GS_PHASE_NISHITA_MURKY
  float y = 0.5 * (1.0 + c);
  y *= y; y *= y; y *= y; y *= y; y *= y;
  return 33.0 * (1.0 + 50.0 * y) / (332.0 * PI);
#elif PHASE == GS_PHASE_RAYLEIGH
  return 3.0 * (1.0 + c * c) / (16.0 * PI);
#else
  return 1.0 / (4.0 * PI);
#endif
}

// 1 - cos(theta) of a unit direction at the angle theta from a unit axis,
// from c = cos(theta) and s2 = sin^2(theta) (|w x axis|^2): near the axis
// as s2 / (1 + c), which keeps its relative precision, where 1 - c would
// lose it (float resolves 1 - c only to 6e-8, a 0.02-degree angle).
float versine(float c, float s2) { return c > 0.0 ? s2 / (1.0 + c) : 1.0 - c; }

// The spot profile (sh_spot_profile) at the angle theta from the axis,
// given as its versine v = 1 - cos(theta): a narrow cone's edge (1 -
// cos(0.3 degrees) = 1.4e-5) is compared where float resolves it. u_spot.x
// and .y are the outer and inner angles' versines.
float spot_profile(float v) {
#if SPOT_SMOOTH == GS_SPOT_BY_VALUE
  // A hard edge is u in {0, 1}, where the smoothstep is exact.
  float u = u_spot.x > u_spot.y ? clamp((u_spot.x - v) / (u_spot.x - u_spot.y), 0.0, 1.0)
                                : (v <= u_spot.x ? 1.0 : 0.0);
  float f = u * u * (3.0 - 2.0 * u);
#elif SPOT_SMOOTH == GS_SPOT_SMOOTH
  float u = clamp((u_spot.x - v) / (u_spot.x - u_spot.y), 0.0, 1.0);
  float f = u * u * (3.0 - 2.0 * u);
#else
  float f = v <= u_spot.x ? 1.0 : 0.0;
#endif
#if SPOT_EXPONENT == GS_SPOT_EXPONENT_1
  f *= max(1.0 - v, 0.0);
#elif SPOT_EXPONENT == GS_SPOT_EXPONENT_ANY
  f *= pow(max(1.0 - v, 0.0), u_spot.z);
#endif
  return f;
}

// The light's angular pattern at p: spot profile times light map, or the
// directional window's pattern (0 outside it); 1 for plain lights.
vec3 light_pattern(vec3 p) {
#if LIGHT_TYPE == GS_LIGHT_SPOT
  vec3 d = p - u_lpos;
  float z = dot(d, u_ldir), dd = max(dot(d, d), 1e-30);
  vec3 x = cross(d, u_ldir);
  vec3 f = vec3(spot_profile(versine(z * inversesqrt(dd), dot(x, x) / dd)));
#if HAS_MAP
  vec2 xy = vec2(dot(d, u_map_right), dot(d, u_map_up)) * (u_spot.w / z);
  if (!(z > 0.0) || abs(xy.x) > 1.0 || abs(xy.y) > 1.0) return vec3(0.0);
  f *= texture(u_map, vec2(0.5 * (xy.x + 1.0), 0.5 * (1.0 - xy.y))).rgb;
#endif
  return f;
#elif LIGHT_TYPE == GS_LIGHT_DIRECTIONAL && HAS_MAP
  vec2 st = vec2(dot(u_win_s.xyz, p) + u_win_s.w, dot(u_win_t.xyz, p) + u_win_t.w);
  if (st.x < 0.0 || st.x > 1.0 || st.y < 0.0 || st.y > 1.0) return vec3(0.0);
  return texture(u_map, st).rgb;
#else
  return vec3(1.0);
#endif
}

// What the light delivers at p before visibility: the irradiance normal to
// wi (the unit direction towards the light), with the light's pattern,
// 1 / r^2 and the medium's transmittance (sh_light_incident times Tr).
vec3 light_incident(vec3 p, out vec3 wi) {
#if LIGHT_TYPE == GS_LIGHT_DIRECTIONAL
  wi = -u_ldir;
  return u_lpower * light_pattern(p) * transmittance(optical_depth_ray(p, wi));
#else
  vec3 tol = u_lpos - p;
  float r2 = max(dot(tol, tol), 1e-30);
  wi = tol * inversesqrt(r2);
  return u_lpower * light_pattern(p) * transmittance(optical_depth(p, u_lpos)) / r2;
#endif
}

// The 2D shadow map's texture coordinates and depth from the lookup
// q = u_shadow_mat * (p, 1). A directional light's map is orthographic
// (q.w = 1), a spot's perspective with q.z = u_shadow_near (gs_lightvol.c):
// written so, live programs skip the products by 0 and 1 that baked ones
// fold away (the same values, bit for bit).
vec3 shadow_coord(vec4 q) {
#if LIGHT_TYPE == GS_LIGHT_DIRECTIONAL
  return q.xyz;
#else
  return vec3(q.xy, u_shadow_near) / q.w;
#endif
}

// A point of the medium is lit only if all four texels of its filtered
// shadow lookup say so, and it is nearer the light than what they hold by
// 1e-4 of its depth (reversed depth, which for perspective maps is 1 /
// distance): behind a zero-thickness caster, stored with no bias, at least
// one of the four does not (gs_shadow.c; a plane's depth is affine in the
// map), and a ray's end on a caster's face that squarely faces the light
// (the same depth in all four) counts as in its shadow. A lookup that mixed
// them let light through closed walls, and a light inside a closed box
// showed a halo on the box. Shadows in the medium so grow by less than a
// texel at their edges.
const float VOLUME_MARGIN = 1.0 - 1e-4;
float shadow_volume(float filtered) { return step(0.9999, filtered); }

// The light's visibility at p from its shadow map (1: lit); `margin`
// scales the point's reversed depth (1: none).
float shadow_at(vec3 p, float margin) {
#if SHADOW == GS_SHADOW_2D
  vec3 c = shadow_coord(u_shadow_mat * vec4(p, 1.0));
  return texture(u_shadow2d, vec3(c.xy, c.z * margin));
#elif SHADOW == GS_SHADOW_CUBE
  vec3 d = p - u_lpos;
  vec3 a = abs(d);
  return texture(u_shadowcube, vec4(d, margin * u_shadow_near / max(a.x, max(a.y, a.z))));
#else
  return 1.0;
#endif
}

// The sun's disks (docs/scene-format.md, "The sun's disk"): SUN_DISKS(d),
// the radiance the unit direction d sees from them, sums sun_disk over the
// (u_sun_dirN, u_sun_radianceN) pairs that gs__sun_disks (gs_surface.h)
// declares; a program without them sees none. u_sun_dirN holds the
// direction the light comes from and the squared chord |d - s|^2 at the
// disk's edge.
vec3 sun_disk(vec3 d, vec4 dir_chord2, vec3 radiance) {
  vec3 e = d - dir_chord2.xyz;
  return dot(e, e) <= dir_chord2.w ? radiance : vec3(0.0);
}
#ifndef SUN_DISKS
#define SUN_DISKS(d) vec3(0.0)
#endif

// Whether p lies behind the surface that the four texels of its lookup
// hold, all four of them a caster: the stored depths interpolated with the
// filter's own weights (affine in the map for a plane, so exact for one
// caster's plane) against p's, by 1e-6 of it (VOLUME_MARGIN's 1e-4 missed
// a floor point 1e-4 behind a wall the light faces, 2e-5 of its depth). A
// filtered comparison of a point just behind a caster that the light
// grazes meets texels a texel away where the caster's steep depth lies
// beyond the point, and calls it partly lit (surface.frag); the
// interpolated depth does not.
const float BEHIND_MARGIN = 1.0 - 1e-6;
bool shadow_behind(vec3 p) {
#if SHADOW == GS_SHADOW_2D
  vec3 c = shadow_coord(u_shadow_mat * vec4(p, 1.0));
  vec4 texels = textureGather(u_shadow2d_depth, c.xy);
  float held = texture(u_shadow2d_depth, c.xy).r;
  return all(greaterThan(texels, vec4(0.0))) && c.z < held * BEHIND_MARGIN;
#elif SHADOW == GS_SHADOW_CUBE
  vec3 d = p - u_lpos;
  vec3 a = abs(d);
  vec4 texels = textureGather(u_shadowcube_depth, d);
  float held = texture(u_shadowcube_depth, d).r;
  return all(greaterThan(texels, vec4(0.0))) &&
         u_shadow_near / max(a.x, max(a.y, a.z)) < held * BEHIND_MARGIN;
#else
  return false;
#endif
}
