// Per pixel and light: the view-depth interval [z0, z1] of the pixel's ray
// that the light can reach in the medium (inside the box, the spot's cone or
// the window's prism, and in front of the surface), and the depth where the
// ray enters the box (for the transmittance towards the eye).
layout(binding = GS_UNIT_LINDEPTH) uniform sampler2D u_lindepth;
layout(location = 0) out vec4 o_interval;

// Keeps the z of [iv.x, iv.y] where 0 <= a + b z <= 1.
vec2 clip_unit(vec2 iv, float a, float b) {
  if (abs(b) < 1e-30) return (a < 0.0 || a > 1.0) ? vec2(BIG, -BIG) : iv;
  float z0 = -a / b, z1 = (1.0 - a) / b;
  return vec2(max(iv.x, min(z0, z1)), min(iv.y, max(z0, z1)));
}

// The z of o + z d inside the spot's front cone (a convex set), as in
// sh_light_clip: roots of (v.a)^2 - cos^2 |v|^2 = 0 with v = o + z d - L.
vec2 cone_clip(vec3 o, vec3 d) {
  vec3 v = o - u_lpos;
  float c2 = u_spot.x * u_spot.x;
  float va = dot(v, u_ldir), da = dot(d, u_ldir);
  float A = da * da - c2 * dot(d, d);
  float B = va * da - c2 * dot(v, d);
  float C = va * va - c2 * dot(v, v);
  float disc = B * B - A * C;
  if (disc < 0.0) {
    // No crossing: the line is never inside (A < 0), or inside the double
    // cone throughout, which only a line through the apex can be.
    if (A < 0.0) return vec2(BIG, -BIG);
    float za = -va / da;
    return da > 0.0 ? vec2(za, BIG) : vec2(-BIG, za);
  }
  float q = -(B + (B >= 0.0 ? sqrt(disc) : -sqrt(disc)));
  float r0 = q / A, r1 = C / q;
  float lo = min(r0, r1), hi = max(r0, r1);
  if (A < 0.0) {
    // Inside between the roots, on one nappe: keep it if it is the front one.
    return dot(v + (0.5 * (lo + hi)) * d, u_ldir) >= 0.0 ? vec2(lo, hi)
                                                         : vec2(BIG, -BIG);
  }
  // Inside outside the roots; the front nappe is the end the ray runs to
  // along the axis.
  return da > 0.0 ? vec2(hi, BIG) : vec2(-BIG, lo);
}

void main() {
  vec3 d = view_ray(gl_FragCoord.xy);
  float zs = texelFetch(u_lindepth, ivec2(gl_FragCoord.xy), 0).r;
  vec2 box = box_clip(u_eye, d, 0.0, zs);
  vec2 iv = box;
#if LIGHT_TYPE == GS_LIGHT_SPOT && CONE_CLIP
  vec2 c = cone_clip(u_eye, d);
  iv = vec2(max(iv.x, c.x), min(iv.y, c.y));
#endif
#if LIGHT_TYPE == GS_LIGHT_DIRECTIONAL && HAS_MAP
  iv = clip_unit(iv, dot(u_win_s.xyz, u_eye) + u_win_s.w, dot(u_win_s.xyz, d));
  iv = clip_unit(iv, dot(u_win_t.xyz, u_eye) + u_win_t.w, dot(u_win_t.xyz, d));
#endif
  o_interval = vec4(iv, box.x, 0.0);
}
