// The plane shader of point and spot lights (plane.glsl describes what both
// plane shaders compute).
//
// For point and spot lights the part is parametrised by the angle theta it
// subtends at the light: with h the light's distance from the ray, b the
// ray length (from its point at depth 0) to the foot F of the perpendicular
// from the light, and e the
// unit vector from F towards the light, the point at angle theta is
// F + h tan(theta) dn, its distance to the light r = h / cos(theta), the
// direction to the light wi = cos(theta) e - sin(theta) dn, and
// dt / r^2 = dtheta / h. So 1/r^2 integrates exactly, and the rest of the
// integrand (phase, transmittance, pattern, visibility) is sampled at equal
// steps of theta: one step per u_sub_angle radians (at least one per
// plane), which is one sample in most fragments and many where the ray
// passes near the light. This is the reference's equiangular sampling,
// stratified by the planes.
#include "plane.glsl"

// Per-fragment constants of the angle parametrisation.
vec3 g_foot, g_e, g_dn;
float g_h, g_h0, g_b, g_entry, g_dl;
vec2 g_ndc;
#if LIGHT_TYPE == GS_LIGHT_SPOT
float g_ea, g_da; // e . axis, dn . axis
vec3 g_exa, g_dxa; // e x axis, dn x axis
#if HAS_MAP
float g_er, g_dr, g_eu, g_du; // e and dn . the map's right and up
#endif
#endif
#if SHADOW == GS_SHADOW_2D
vec4 g_qf, g_qd; // the shadow lookup of the foot, and of dn
#endif

// The sine of theta at the true light: k / sqrt(h0^2 + k^2), k the ray
// length from the foot, which is s where h is the light's true distance
// from the ray and differs only within u_light_rmin of the light, where h
// is taken larger (the direction to the light, hence the phase function,
// is the true one there, as in the reference).
float scatter_sin(float k, float s) {
  return g_h0 < g_h ? k * inversesqrt(max(g_h0 * g_h0 + k * k, 1e-30)) : s;
}

// The integrand but for dt / r^2 and the visibility at the angle
// (c, s) = (cos, sin) theta.
vec3 sample_at(float c, float s) {
  float k = g_h * s / c;          // ray length from the foot
  vec3 wi = c * g_e - s * g_dn;   // towards the light
#if XI_EXACT
  vec3 p = g_foot + k * g_dn;
#if LIGHT_INSIDE
  float light_len = g_h / c; // r: the light is inside the medium's region
#else
  float light_len = min(medium_exit(p, wi), g_h / c);
#endif
  // Optical depth towards the light and from the ray's entry into the
  // region to p.
  vec3 tau = optical_depth_span(p, wi, 1.0, 0.0, light_len) +
             optical_depth_span(g_foot, g_dn, 1.0, g_entry - g_b, k);
  vec3 v = sigma_s_at(p) * phase(-scatter_sin(k, s)) * transmittance(tau);
#else
  vec3 v = xi_lattice(g_ndc, (g_b + k) / g_dl);
#endif
#if LIGHT_TYPE == GS_LIGHT_SPOT
  float cl = s * g_da - c * g_ea; // cos of the angle from the spot's axis
  vec3 xa = c * g_exa - s * g_dxa; // wi x axis: its length is the sine
  v *= spot_profile(versine(cl, dot(xa, xa)));
#if HAS_MAP
  vec2 xy = vec2(s * g_dr - c * g_er, s * g_du - c * g_eu) * (u_spot.w / cl);
  v *= (cl > 0.0 && abs(xy.x) <= 1.0 && abs(xy.y) <= 1.0)
           ? texture(u_map, vec2(0.5 * (xy.x + 1.0), 0.5 * (1.0 - xy.y))).rgb
           : vec3(0.0);
#endif
#endif
  return v;
}

// The light's visibility at the angle (c, s).
float vis_at(float c, float s) {
#if SHADOW == GS_SHADOW_2D
  vec4 q = g_qf + (g_h * s / c) * g_qd;
  vec3 sc = shadow_coord(q);
  return shadow_volume(texture(u_shadow2d, vec3(sc.xy, sc.z * VOLUME_MARGIN)));
#elif SHADOW == GS_SHADOW_CUBE
  vec3 wi = c * g_e - s * g_dn;
  vec3 a = abs(wi);
  return shadow_volume(
      texture(u_shadowcube, vec4(-wi, VOLUME_MARGIN * u_shadow_near * c /
                                           (g_h * max(a.x, max(a.y, a.z))))));
#else
  return 1.0;
#endif
}

void main() {
  vec4 iv = texelFetch(u_interval, ivec2(gl_FragCoord.xy), 0);
  // The first plane's part also takes the ray's stretch in front of the
  // camera's near plane, where the lit volume (and so the slabs) begins:
  // next to a light that stretch holds much of the light (the camera at a
  // light lost 6% of it).
  float lo = v_plane == 0.0 ? iv.x : max(v_slab.x, iv.x), hi = min(v_slab.y, iv.y);
  if (!(hi > lo)) discard;
  g_ndc = gl_FragCoord.xy * u_ndc_scale - 1.0;
  vec3 d = ndc_ray(g_ndc), o = ndc_origin(g_ndc);
  g_dl = length(d);
  g_dn = d / g_dl;
  // Ray lengths are counted from o, the ray's point at depth 0 (near the
  // scene): from the eye, b and the parts' ends were all about the camera's
  // distance and their differences cancelled.
  vec3 q = o - u_lpos;
  g_b = -dot(q, g_dn);
  g_foot = o + g_b * g_dn;
  vec3 ev = u_lpos - g_foot;
  // At least the light's minimal distance (sh_medium.h): a ray through the
  // light integrates 1 / ((t - b)^2 + u_light_rmin^2), as in every
  // renderer; below that, a floor relative to the ray's lengths (an
  // absolute one swamps a scene a billionth of a unit across).
  g_h0 = length(ev);
  g_h = max(g_h0, max(u_light_rmin, 1e-6 * (abs(g_b) + abs(hi) * g_dl)));
  g_e = g_h0 > 0.0 ? ev / g_h0 : vec3(0.0);
  g_entry = iv.z * g_dl;
#if LIGHT_TYPE == GS_LIGHT_SPOT
  g_ea = dot(g_e, u_ldir);
  g_da = dot(g_dn, u_ldir);
  g_exa = cross(g_e, u_ldir);
  g_dxa = cross(g_dn, u_ldir);
#if HAS_MAP
  g_er = dot(g_e, u_map_right);
  g_dr = dot(g_dn, u_map_right);
  g_eu = dot(g_e, u_map_up);
  g_du = dot(g_dn, u_map_up);
#endif
#endif
#if SHADOW == GS_SHADOW_2D
  g_qf = u_shadow_mat * vec4(g_foot, 1.0);
  g_qd = u_shadow_mat * vec4(g_dn, 0.0);
#endif
  // The part's ends as angles: tan(theta) = (t - b) / h, as (cos, sin).
  float ta = (lo * g_dl - g_b) / g_h, tb = (hi * g_dl - g_b) / g_h;
  float ca = inversesqrt(1.0 + ta * ta), sa = ta * ca;
  float cb = inversesqrt(1.0 + tb * tb), sb = tb * cb;
  float dtheta = atan(ca * sb - sa * cb, ca * cb + sa * sb);
  // n samples at the middles (or jittered points) of n equal steps. The
  // steps are small (at most u_sub_angle, below 30 degrees), so their
  // half-angle tangents come from a series, and the angles by rotation:
  // no trigonometric function but the atan above. llvmpipe runs every
  // branch and every loop to its longest lane, so the code has none but
  // this loop.
  float k = dtheta * u_inv_sub_angle;
#if LIGHT_TYPE == GS_LIGHT_SPOT && HAS_MAP
  // A gobo: also one sample per u_sub_texels texels of the map that the
  // part's projection from the light crosses (a straight segment: the
  // projection of a line), which near the apex are many per degree.
  vec2 ga = vec2(sa * g_dr - ca * g_er, sa * g_du - ca * g_eu) / (sa * g_da - ca * g_ea);
  vec2 gb = vec2(sb * g_dr - cb * g_er, sb * g_du - cb * g_eu) / (sb * g_da - cb * g_ea);
  k = max(k, length((gb - ga) * (0.5 * u_spot.w) * u_map_size) * u_inv_sub_texels);
#endif
#if TAU_SUB || MEDIUM_VARIES
  // In a dense medium also one sample per optical depth u_sub_tau / 2 (the
  // transmittances towards the eye and the light change at most at 2
  // sigma_t), and where the medium varies as many as its variation asks
  // (medium.glsl): the largest length step, at the end further from the
  // foot, is h (1 + tan^2) times the angle step.
#if TAU_SUB
  float rate = u_tau_rate;
#else
  float rate = 0.0;
#endif
#if MEDIUM_VARIES
  rate = max(rate, medium_variation_rate(g_dn));
#endif
  k = max(k, rate * g_h * (1.0 + max(ta * ta, tb * tb)) * dtheta);
#endif
  int n = int(clamp(ceil(k), 1.0, 1024.0));
  float step = dtheta / float(n);
  float x = 0.5 * step, x2 = x * x;
  float tau = x * (1.0 + x2 * (1.0 / 3.0 + x2 * (2.0 / 15.0 + x2 * (17.0 / 315.0))));
  float inv = 1.0 / (1.0 + tau * tau);
  float cs = (1.0 - tau * tau) * inv, ss = 2.0 * tau * inv; // the step
#if JITTER
  x = jitter_offset() * step;
  x2 = x * x;
  tau = 0.5 * x * (1.0 + x2 * (1.0 / 12.0 + x2 * (1.0 / 120.0)));
  inv = 1.0 / (1.0 + tau * tau);
  float c0 = (1.0 - tau * tau) * inv, s0 = 2.0 * tau * inv; // the offset
#else
  float c0 = sqrt(0.5 * (1.0 + cs)), s0 = tau * c0; // half a step
#endif
  float c = ca * c0 - sa * s0, s = sa * c0 + ca * s0;
  vec3 sum = vec3(0.0);
#if SHADOW != GS_SHADOW_NONE
  float bc = ca, bs = sa;  // the start of the current step
  float v0 = vis_at(bc, bs);
#endif
  for (int i = 0; i < n; i++) {
#if SHADOW != GS_SHADOW_NONE
    // Visibility: where it changes between a step's ends, the step holds a
    // shadow's edge: bisection finds it, and the step's visibility is the
    // fraction on each side; elsewhere it is sampled with the rest. The
    // normalised sum of two unit vectors halves their angle exactly, so the
    // edge's place as a fraction of the step is followed alongside ([fl, fr]),
    // and a step without an edge takes the middle, the ends' mean. The
    // bisection is a loop of 0 turns where the ends agree rather than an
    // if: llvmpipe runs both sides of a branch in every lane, but leaves a
    // loop once no lane is in it.
    float ec = bc * cs - bs * ss, es = bs * cs + bc * ss;
    float v1 = vis_at(ec, es);
    float lc = bc, lsn = bs, rc = ec, rsn = es, fl = 0.0, fr = 1.0;
    int edge_steps = abs(v1 - v0) > 0.5 ? EDGE_STEPS : 0;
    for (int j = 0; j < edge_steps; j++) {
      float mc = lc + rc, ms = lsn + rsn, mi = inversesqrt(mc * mc + ms * ms);
      mc *= mi;
      ms *= mi;
      float fm = 0.5 * (fl + fr);
      if ((vis_at(mc, ms) > 0.5) == (v0 > 0.5)) {
        lc = mc;
        lsn = ms;
        fl = fm;
      } else {
        rc = mc;
        rsn = ms;
        fr = fm;
      }
    }
    float vis = mix(v1, v0, 0.5 * (fl + fr));
    sum += sample_at(c, s) * vis;
    v0 = v1;
    bc = ec;
    bs = es;
#else
    sum += sample_at(c, s);
#endif
    float c2 = c * cs - s * ss;
    s = s * cs + c * ss;
    c = c2;
  }
  sum *= 1.0 / float(n);
  o_color = vec4(u_lpower * sum * (dtheta / g_h), 0.0);
}
