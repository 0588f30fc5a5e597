// A pixel of the atmosphere under one sun, at full resolution:
// - what its ray ends on: the ground, an opaque Lambert sphere lit through
//   the air (albedo / pi * E * cos * the sun's transmittance), seen through
//   the air; or the background (FIRST 1: the first sun's pass, drawn
//   without blending) and the sun's disk (u_disk_chord2, u_disk_radiance)
//   through the air where the ray leaves;
// - with LATTICE 1, the scattered light of the sampling layers drawn on the
//   lattice (u_lattice, one texel per u_lat_step x u_lat_step pixels),
//   interpolated bilinearly when the four lattice neighbours' rays end on
//   the same class as the pixel's own (atmo.glsl's ray_class: the horizon
//   and the limb are jumps that interpolation must not cross). The 2002
//   slides likewise evaluate the sun's light at lattice points and
//   interpolate it.
//   The pixels it cannot serve are marked at depth 1 (0 for the others).
// With FIXUP 1 (a second pass, added, depth test EQUAL at depth 1): the
// marked pixels alone, their rays integrated over the same layers
// (atmo.glsl's layers_radiance) as the lattice's points are. It is a
// pass of its own because llvmpipe runs both sides of a branch for every
// pixel of a SIMD vector, but skips the shader for a vector whose
// fragments all fail the depth test (the Earth from space at 640x480: the
// integration as a branch of the compose pass cost 0.48 s a frame, against
// 0.06 s for the pass without it; as a pass whose fragments discarded the
// pixels the lattice serves, the test before the discard cost as much as
// the compose pass).
layout(location = 0) out vec4 o_color;
layout(binding = GS_UNIT_ATMO_LATTICE) uniform sampler2D u_lattice;
uniform float u_lat_step;
#ifndef FIRST
#define FIRST 1
#endif
#ifndef LATTICE
#define LATTICE 1
#endif
#ifndef FIXUP
#define FIXUP 0
#endif

#include "atmo.glsl"

// The ray's end: the ground's or the background's radiance through the air.
vec3 ray_end(Setup s) {
  vec3 tau_eye = vec3(0.0); // to the ground, or along the whole ray
  float tg = -1.0;
#if EYE_OUTSIDE
  // One lookup: from the ground point back to the top, or twice from the
  // ray's lowest point (the whole chord), or nothing where the ray misses.
  float b2g = (s.b - u_rg) * (s.b + u_rg); // b^2 - R_g^2
  float sg = sqrt(max(-b2g, 0.0));
  bool ground = s.ry.mu < 0.0 && s.ground;
  if (ground) tg = s.tp - sg;
  tau_eye = (ground ? 1.0 : s.ry.mu < 0.0 && s.b < u_rt ? 2.0 : 0.0) *
            tau_top(ground ? u_rg : s.b, ground ? 0.0 : b2g, ground ? sg / u_rg : 0.0);
#else
  // The eye's depth along the ray, or along its reverse when it meets
  // the ground; the ground's own lookups in a loop of 0 or 1 trips (see
  // atmo.glsl's inscatter_open: a branch would cost every pixel of a SIMD
  // vector both sides).
  tau_eye = tau_top(u_re, u_ce, s.ground ? -s.ry.mu : s.ry.mu);
  if (s.ground) tg = s.tend;
#endif
  vec3 e = s.ry.d - u_lsun;
  vec3 L = (FIRST == 1 ? u_background : vec3(0.0)) +
           (dot(e, e) <= u_disk_chord2 ? u_disk_radiance : vec3(0.0));
  for (int i = 0; i < (tg > 0.0 ? 1 : 0); i++) {
#if !EYE_OUTSIDE
    float mu_g = (u_re * s.ry.mu + tg) / u_rg;
    tau_eye = tau_top(u_rg, 0.0, -mu_g) - tau_eye;
#endif
    float mu_sg = (u_re * s.ry.mu_s + tg * s.ry.nu) / u_rg;
    L = u_albedo / PI * u_esun * max(mu_sg, 0.0) * sun_tr(u_rg, 0.0, mu_sg) *
        sun_vis_at(s.ry, tg);
  }
  return exp(-max(tau_eye, vec3(0.0))) * L;
}

// Whether the pixel's four lattice neighbours see the class its own ray
// does (their classes are the lattice's alpha), and their bilinear sum.
bool lattice_serves(Setup s, out vec3 sum) {
  ivec2 size = textureSize(u_lattice, 0);
  vec2 x = gl_FragCoord.xy / u_lat_step - 0.5;
  ivec2 i0 = ivec2(floor(x));
  vec2 f = x - vec2(i0);
  float own = float(ray_class(s.ry));
  bool same = true;
  sum = vec3(0.0);
  for (int k = 0; k < 4; k++) {
    ivec2 o = ivec2(k & 1, k >> 1);
    vec4 v = texelFetch(u_lattice, clamp(i0 + o, ivec2(0), size - 1), 0);
    same = same && v.a == own;
    float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
    sum += w * v.rgb;
  }
  return same;
}

void main() {
  Setup s = setup_ray(frag_pos());
#if FIXUP
  o_color = vec4(layers_radiance(s) * u_esun, 0.0);
#else
  vec3 L = ray_end(s);
#if LATTICE
  vec3 sum;
  bool served = lattice_serves(s, sum);
  if (served) L += sum;
  gl_FragDepth = served ? 0.0 : 1.0;
#endif
  o_color = vec4(L, 0.0);
#endif
}
