// Per pixel and light: the view-depth interval [z0, z1] (counted from
// u_zref, as every depth in GL) of the pixel's ray that the light can reach
// in the medium (inside its region, the spot's cone or the window's prism,
// and in front of the surface), and the depth where the ray enters the
// medium's region (where its optical depth from the eye begins).
layout(binding = GS_UNIT_LINDEPTH) uniform sampler2D u_lindepth;
layout(location = 0) out vec4 o_interval;

// Keeps the z of [iv.x, iv.y] where 0 <= a + b z <= 1.
vec2 clip_unit(vec2 iv, float a, float b) {
  if (abs(b) < 1e-30) return (a < 0.0 || a > 1.0) ? vec2(BIG, -BIG) : iv;
  float z0 = -a / b, z1 = (1.0 - a) / b;
  return vec2(max(iv.x, min(z0, z1)), min(iv.y, max(z0, z1)));
}

// The z of o + z d inside the spot's front cone (a convex set), as in
// sh_light_clip: the roots of tan^2(outer) (v.a)^2 - |v_perp|^2 = 0 with
// v = o + z d - L split into its parts along the axis a and across it.
// Written so, with z counted from the foot of the light's perpendicular
// on the line, no term cancels for a narrow cone (cos^2 - c^2 |v|^2 with
// cos(outer) near 1 did: a 0.3-degree cone's chords came out empty or
// twice too long). The discriminant B^2 - AC is k2 |da vp - va dp|^2 -
// |vp x dp|^2 (Lagrange's identity), free of that cancellation too.
vec2 cone_clip(vec3 o, vec3 d) {
  vec3 w = o - u_lpos;
  float zf = -dot(w, d) / dot(d, d);
  vec3 v = w + zf * d;
  float k2 = 1.0 / (u_spot.w * u_spot.w); // tan^2(outer)
  float va = dot(v, u_ldir), da = dot(d, u_ldir);
  vec3 vp = v - va * u_ldir, dp = d - da * u_ldir;
  float A = k2 * da * da - dot(dp, dp);
  float B = k2 * va * da - dot(vp, dp);
  float C = k2 * va * va - dot(vp, vp);
  vec3 x = cross(vp, dp), y = da * vp - va * dp;
  float disc = k2 * dot(y, y) - dot(x, x);
  if (disc < 0.0) {
    // No crossing: the line is never inside (A < 0), or inside the double
    // cone throughout, which only a line through the apex can be.
    if (A < 0.0) return vec2(BIG, -BIG);
    float za = zf - va / da;
    return da > 0.0 ? vec2(za, BIG) : vec2(-BIG, za);
  }
  float q = -(B + (B >= 0.0 ? sqrt(disc) : -sqrt(disc)));
  float r0 = q / A, r1 = C / q;
  float lo = min(r0, r1), hi = max(r0, r1);
  if (A < 0.0) {
    // Inside between the roots, on one nappe: keep it if it is the front one.
    return va + (0.5 * (lo + hi)) * da >= 0.0 ? vec2(lo, hi) + zf : vec2(BIG, -BIG);
  }
  // Inside outside the roots; the front nappe is the end the ray runs to
  // along the axis.
  return da > 0.0 ? vec2(hi + zf, BIG) : vec2(-BIG, lo + zf);
}

void main() {
  vec3 d = view_ray(gl_FragCoord.xy), o = view_origin(gl_FragCoord.xy);
  float zs = texelFetch(u_lindepth, ivec2(gl_FragCoord.xy), 0).r;
  vec2 region = medium_clip(o, d, -u_zref, zs);
  vec2 iv = region;
#if LIGHT_TYPE == GS_LIGHT_SPOT && CONE_CLIP
  vec2 c = cone_clip(o, d);
  iv = vec2(max(iv.x, c.x), min(iv.y, c.y));
#endif
#if LIGHT_TYPE == GS_LIGHT_DIRECTIONAL && HAS_MAP
  iv = clip_unit(iv, dot(u_win_s.xyz, o) + u_win_s.w, dot(u_win_s.xyz, d));
  iv = clip_unit(iv, dot(u_win_t.xyz, o) + u_win_t.w, dot(u_win_t.xyz, d));
#endif
  o_interval = vec4(iv, region.x, 0.0);
}
