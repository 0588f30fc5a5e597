// The plane shader of directional lights (plane.glsl has what both plane
// shaders compute): a part is sampled once at its middle (or a jittered
// depth), or, with a window, at equal steps of length, one per
// u_sub_texels texels of the window's pattern that it crosses, and in a
// dense medium one per optical depth u_sub_tau / 2, and where the medium's
// density varies as many as its variation asks; its visibility at one
// point per VIS_TEXELS shadow-map texels it crosses (u_shadow_res, the
// map's size).
#include "plane.glsl"

// The integrand but for dt at view depth z, without the visibility:
// xi * pattern.
vec3 sample_dir(vec3 o, float z, vec3 d, float dl, vec2 ndc, float entry) {
  vec3 p = o + z * d;
#if XI_EXACT
  vec3 wi = -u_ldir;
  // Optical depth towards the light (the sun: to the region's boundary) and
  // from the ray's entry into the region to p.
  vec3 tau = optical_depth_span(p, wi, 1.0, 0.0, medium_exit(p, wi)) +
             optical_depth_span(o, d, dl, entry, z);
  vec3 v = sigma_s_at(p) * phase(dot(wi, d) / dl) * transmittance(tau);
#else
  vec3 v = xi_lattice(ndc, z);
#endif
  return v * light_pattern(p);
}

// A directional light's visibility at view depth z of the ray o + z d.
float vis_dir(vec3 o, float z, vec3 d) { return shadow_volume(shadow_at(o + z * d, VOLUME_MARGIN)); }

// A step's visibility samples inside (vis_step): one per VIS_TEXELS
// texels of the shadow map it crosses, at most VIS_MAX_SAMPLES.
// side_lit_bench.sh's comb at 8 planes: one per texel (at most 32) 2.0%
// from the reference, one per 4 (16) 2.2%, one per 8 (8) 2.9%, none 17.5%.
#define VIS_TEXELS 4.0
#define VIS_MAX_SAMPLES 16

// The shadow map's texels the pixel's ray d crosses per unit of view
// depth: the map is orthographic, so its coordinates are affine along the
// ray (0 without a map).
float vis_rate(vec3 d) {
#if SHADOW != GS_SHADOW_NONE
  return length((mat3(u_shadow_mat) * d).xy) * u_shadow_res;
#else
  return 0.0;
#endif
}

// Its visibility over the step [a, b] of a part, whose start sees v0 (set
// to what b sees, for the next step). A step that crosses more than
// VIS_TEXELS texels of the shadow map (rate texels per unit of view depth,
// vis_rate) takes the mean of one visibility sample per VIS_TEXELS texels
// at their middles (at most VIS_MAX_SAMPLES), so that a shadow lying
// wholly inside it, as thin shafts crossing the view at a wide angle make
// one (lit, shadow, lit), is seen. Otherwise, where the ends differ, the step holds a shadow's edge,
// found by bisection (as for point lights), and the visibility is the
// fraction on each side; elsewhere the ends' mean. Both are loops of 0
// turns where they are not needed, not ifs: llvmpipe runs both sides of a
// branch in every lane, but leaves a loop once no lane is in it.
float vis_step(vec3 o, float a, float b, vec3 d, float rate, inout float v0) {
#if SHADOW != GS_SHADOW_NONE
  float va = v0, v1 = vis_dir(o, b, d);
  v0 = v1;
  int n = int(min(ceil((b - a) * rate / VIS_TEXELS), float(VIS_MAX_SAMPLES)));
  n = n > 1 ? n : 0;
  float sum = 0.0, w = (b - a) / float(max(n, 1));
  for (int j = 0; j < n; j++) sum += vis_dir(o, a + (float(j) + 0.5) * w, d);
  float l = a, r = b;
  int edge_steps = n == 0 && abs(v1 - va) > 0.5 ? EDGE_STEPS : 0;
  for (int j = 0; j < edge_steps; j++) {
    float m = 0.5 * (l + r);
    if ((vis_dir(o, m, d) > 0.5) == (va > 0.5)) l = m; else r = m;
  }
  return n > 0 ? sum / float(n) : mix(v1, va, clamp((0.5 * (l + r) - a) / (b - a), 0.0, 1.0));
#else
  return 1.0;
#endif
}

void main() {
  vec4 iv = texelFetch(u_interval, ivec2(gl_FragCoord.xy), 0);
  float lo = max(v_slab.x, iv.x), hi = min(v_slab.y, iv.y);
  if (!(hi > lo)) discard;
  vec2 ndc = gl_FragCoord.xy * u_ndc_scale - 1.0;
  vec3 d = ndc_ray(ndc), o = ndc_origin(ndc);
  float dl = length(d);
  float u = jitter_offset();
#if HAS_MAP || TAU_SUB || MEDIUM_VARIES
  // A window's pattern: one sample per u_sub_texels texels of the light map
  // that the part of the ray crosses (at least one per plane); in a dense
  // medium, one per optical depth u_sub_tau / 2; where the medium varies,
  // as many as its variation asks (medium.glsl).
  float k = 0.0;
#if HAS_MAP
  vec2 rate = vec2(dot(u_win_s.xyz, d), dot(u_win_t.xyz, d)) * u_map_size;
  k = length(rate) * u_inv_sub_texels;
#endif
#if TAU_SUB
  k = max(k, dl * u_tau_rate);
#endif
#if MEDIUM_VARIES
  k = max(k, dl * medium_variation_rate(d / dl));
#endif
  int n = int(clamp(ceil((hi - lo) * k), 1.0, 64.0));
  vec3 sum = vec3(0.0);
  float w = (hi - lo) / float(n), v0 = vis_dir(o, lo, d), vrate = vis_rate(d);
  for (int i = 0; i < n; i++) {
    float a = lo + float(i) * w, z = a + u * w;
    sum += sample_dir(o, z, d, dl, ndc, iv.z) * vis_step(o, a, a + w, d, vrate, v0);
  }
  sum *= 1.0 / float(n);
#else
  float z = mix(lo, hi, u), v0 = vis_dir(o, lo, d);
  vec3 sum = sample_dir(o, z, d, dl, ndc, iv.z) * vis_step(o, lo, hi, d, vis_rate(d), v0);
#endif
  o_color = vec4(u_lpower * sum * ((hi - lo) * dl), 0.0);
}
