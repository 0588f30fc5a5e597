// One virtual plane's in-scattering for one light, added to the image:
//   power * xi * pattern * visibility * dt
// integrated over the part of the plane's slab [z_front, z_back] that the
// pixel's ray spends in the lit medium (the interval texture). A view depth
// step dz is a ray length dt = dz |d|, |d| = 1 / cos(angle to the view
// axis). The lattice (or xi_r2_exact) gives xi * r^2; 1 / r^2 is integrated
// exactly.
flat in vec2 v_slab;
flat in float v_plane;
layout(binding = 3) uniform sampler2D u_interval;
layout(binding = 4) uniform sampler3D u_xi;
uniform vec4 u_xi_xy; // lattice texture coordinates: ndc.x * x + y, ndc.y * z + w
uniform vec2 u_xi_z;  // and z * x + y
uniform float u_inv_sub_angle; // 1 / the largest angle one sample stands for
layout(location = 0) out vec4 o_color;

// xi of eq. 6 at p without its 1 / r^2 (sigma_s p(alpha) Tr_light Tr_eye),
// cam_len being the length of the ray inside the medium before p.
vec3 xi_r2_exact(vec3 p, vec3 dn, float cam_len) {
#if LIGHT_TYPE == 2
  vec3 wi = -u_ldir;
  float light_len = box_exit(p, wi);
#else
  vec3 tol = u_lpos - p;
  float r = max(length(tol), 1e-30);
  vec3 wi = tol / r;
  float light_len = min(box_exit(p, wi), r);
#endif
  return u_sigma_s * phase(dot(wi, dn)) * exp(-u_sigma_t * (light_len + cam_len));
}

// The integrand but for dt / r^2 at view depth z of the pixel's ray:
// xi r^2 * pattern * visibility.
vec3 integrand(float z, vec3 d, float dl, vec3 dn, float entry, vec2 ndc) {
  vec3 p = u_eye + z * d;
#if XI_EXACT
  vec3 xi = xi_r2_exact(p, dn, (z - entry) * dl);
#else
  vec3 xi = texture(u_xi, vec3(ndc.x * u_xi_xy.x + u_xi_xy.y,
                               ndc.y * u_xi_xy.z + u_xi_xy.w,
                               z * u_xi_z.x + u_xi_z.y)).rgb;
#endif
  return xi * light_pattern(p) * shadow_at(p);
}

void main() {
  vec4 iv = texelFetch(u_interval, ivec2(gl_FragCoord.xy), 0);
  float lo = max(v_slab.x, iv.x), hi = min(v_slab.y, iv.y);
  if (!(hi > lo)) discard;
  vec2 ndc = gl_FragCoord.xy * u_ndc_scale - 1.0;
  vec3 d = u_fwd + ndc.x * u_rx + ndc.y * u_uy;
  float dl = length(d);
  vec3 dn = d / dl;
#if JITTER
  // Interleaved gradient noise, rotated by the golden ratio from plane to
  // plane: a stratified, per-pixel offset.
  float u = fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
  u = fract(u + 0.618034 * v_plane);
#else
  float u = 0.5;
#endif
#if LIGHT_TYPE == 2
  // Directional light: dt = dz |d|, sampled at the fraction u of the part.
  vec3 sum = integrand(mix(lo, hi, u), d, dl, dn, iv.z, ndc) * ((hi - lo) * dl);
#else
  // Point and spot lights: the 1 / r^2 of xi integrates exactly over the
  // part, as the angle it subtends at the light: with h the light's distance
  // from the ray and b the ray length to its foot, the integral of dt / r^2
  // from t0 to t1 is (atan((t1 - b) / h) - atan((t0 - b) / h)) / h. The
  // rest of the integrand is sampled at equal steps of that angle (as the
  // reference's equiangular sampling does), one step per u_sub_angle
  // radians: one sample in most of the slab's parts, more where the ray
  // passes near the light, whose pattern then sweeps by within a slab.
  vec3 q = u_eye - u_lpos;
  float b = -dot(q, dn);
  float h = max(length(q + b * dn), 1e-6 * (abs(b) + 1.0));
  float ta = (lo * dl - b) / h, tb = (hi * dl - b) / h;
  float dtheta = atan(tb - ta, 1.0 + ta * tb);
  int n = int(clamp(ceil(dtheta * u_inv_sub_angle), 1.0, 64.0));
  float step = dtheta / float(n);
  vec3 sum = vec3(0.0);
  for (int i = 0; i < n; i++) {
    float tu = tan((float(i) + u) * step);
    float z = clamp((b + h * (ta + tu) / (1.0 - ta * tu)) / dl, lo, hi);
    sum += integrand(z, d, dl, dn, iv.z, ndc);
  }
  sum *= step / h;
#endif
  o_color = vec4(u_lpower * sum, 0.0);
}
