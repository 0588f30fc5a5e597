// Shapes in an atmosphere (gs_atmo_shapes.h), the sky's side: atmo.glsl
// includes this file after inscatter_open. A pixel's ray ends on the
// surface the surface pass drew there (SURFACES 1: the view depth it wrote,
// u_lindepth, GS_UNIT_LINDEPTH), and the shapes shadow the sun in the air
// and on the ground (SHADOW GS_SHADOW_2D: the sun's orthographic shadow
// map, gs_lightvol.h, over the shapes' bounds).
//
// Volumetric shadows: the part of the ray whose points project into the
// map and lie no nearer the sun than its near end (where any caster can
// be) is sampled with the map, the rest of each layer's stretch is
// integrated by inscatter_open as before. The samples are one per texel
// of the map the part crosses (the map's coordinates are affine along the
// ray), at least CASTER_MIN_SAMPLES and at most CASTER_MAX_SAMPLES, at
// their centres (the midpoint rule): a lit-shadow-lit sequence within one
// layer is followed at the map's own resolution where the part crosses
// fewer than CASTER_MAX_SAMPLES texels, and at that many steps otherwise.
// Parameters (gs_atmo_shapes.c): u_eye (the eye in the anchored space),
// u_shadow_res (the map's texels a side).

#ifndef SURFACES
#define SURFACES 0
#endif

const int CASTER_MIN_SAMPLES = 4;
const int CASTER_MAX_SAMPLES = 16;

// Where the pixel's ray ends on a surface (distance along the unit ray),
// BIG where it does not (setup_ray sets it).
float g_tsurf = BIG;

#if SURFACES
layout(binding = GS_UNIT_LINDEPTH) uniform sampler2D u_lindepth;
#endif

// The distance along the unit ray of the pixel at frag (its direction's
// length per unit view depth vl) to the surface drawn there.
float surface_t(vec2 frag, float vl) {
#if SURFACES
  float z = texelFetch(u_lindepth, ivec2(frag), 0).r;
  return z < 1e37 ? (z + u_zref) * vl : BIG;
#else
  return BIG;
#endif
}

#if SHADOW == GS_SHADOW_2D
// The sun's visibility at distance t along the ray from the map: a point
// beyond the map's far end (its depth below 0) is behind every caster,
// lit only where no caster is stored; the margin and the rule are the
// sweep's (common.glsl's shadow_volume).
float sun_vis_at(Ray ry, float t) {
  vec4 c = u_shadow_mat * vec4(u_eye + t * ry.d, 1.0);
  float z = max(c.z, 1e-30) * VOLUME_MARGIN;
  return shadow_volume(texture(u_shadow2d, vec3(c.xy, z)));
}

// The part of [ta, tb] inside the map's prism: x and y in [0, 1], the
// depth at most 1 (no nearer the sun than the map's near end).
vec2 caster_span(Ray ry, float ta, float tb) {
  vec3 c0 = (u_shadow_mat * vec4(u_eye, 1.0)).xyz, c1 = mat3(u_shadow_mat) * ry.d;
  vec3 inv = safe_inv(c1);
  vec3 lo = (vec3(0.0, 0.0, -BIG) - c0) * inv, hi = (vec3(1.0) - c0) * inv;
  vec3 t0 = min(lo, hi), t1 = max(lo, hi);
  return vec2(max(ta, max(t0.x, max(t0.y, t0.z))), min(tb, min(t1.x, min(t1.y, t1.z))));
}

// The scattered radiance per unit irradiance of [ta, tb] inside the prism,
// by the midpoint rule over the map's texels, out of the planet's shadow
// sh.
vec3 inscatter_shadowed(Ray ry, float ta, float tb, vec2 sh) {
  vec2 c1 = (mat3(u_shadow_mat) * ry.d).xy;
  float texels = length(c1) * (tb - ta) * u_shadow_res;
  int n = int(clamp(ceil(texels), float(CASTER_MIN_SAMPLES), float(CASTER_MAX_SAMPLES)));
  float dt = (tb - ta) / float(n);
  vec3 sum = vec3(0.0);
  for (int i = 0; i < n; i++) {
    float t = ta + (float(i) + 0.5) * dt;
    if (t > sh.x && t < sh.y) continue;
    float v = sun_vis_at(ry, t);
    if (v > 0.0) sum += inscatter_at(ry, t) * v;
  }
  return sum * dt;
}
#else
float sun_vis_at(Ray ry, float t) { return 1.0; }
#endif

// The scattered radiance per unit irradiance of the ray's stretch [ta, tb]
// up to the surface, out of the planet's and the shapes' shadows.
vec3 inscatter_lit(Ray ry, float ta, float tb, vec2 sh) {
  tb = min(tb, g_tsurf);
#if SHADOW == GS_SHADOW_2D
  vec2 p = caster_span(ry, ta, tb);
  if (p.y > p.x)
    return inscatter_open(ry, ta, p.x, sh) + inscatter_shadowed(ry, p.x, p.y, sh) +
           inscatter_open(ry, p.y, tb, sh);
#endif
  return inscatter_open(ry, ta, tb, sh);
}
