// A point or spot light in an atmosphere (gs_atmo_light.h), added to the
// image at full resolution: the single scattering of the light along the
// pixel's ray in the air, up to what the ray ends on, and the ground's
// Lambert term when the ray ends on it (the shapes' own are the surface
// pass's). The light's 1 / r^2 is integrated exactly in the angle domain,
// as the sweep's slabs take it: with h the light's distance from the ray
// and theta the angle of a point seen from the light across the ray, dt /
// r^2 = dtheta / h. The rest of the integrand (the air's sigma_s and
// phase mixture at the point, the light's pattern, its transmittance to
// the point through the air, medium.glsl's atmosphere, and its shadow map,
// and the eye's transmittance, atmo.glsl's EYE_TAU) is sampled in
// u_intervals equal steps of theta with 3-point Gauss-Legendre each.
// Parameters: those of the sky's passes (atmo.glsl, gs_atmo_shapes.h),
// the light's (common.glsl), u_intervals.
layout(location = 0) out vec4 o_color;
uniform int u_intervals;

#include "atmo.glsl"

// What the light delivers at p per unit intensity and solid angle, before
// the 1 / r^2: its pattern, the air's transmittance (0 through the ground)
// and its shadow map; wi the unit direction towards it.
vec3 light_at(vec3 p, out vec3 wi) {
  vec3 tol = u_lpos - p;
  wi = normalize(tol);
  vec3 e = u_lpower * light_pattern(p) * transmittance(optical_depth(p, u_lpos));
  return e * shadow_volume(shadow_at(p, VOLUME_MARGIN));
}

void main() {
  Setup s = setup_ray(frag_pos());
  setup_tau(s);
  Ray ry = s.ry;
  // Where the ray meets the ground (BIG if it does not; from space the
  // near side of the ground's sphere), and what it ends on.
  float tg = s.ground ? s.tend : BIG;
#if EYE_OUTSIDE
  tg = s.ground ? s.tp - sqrt(max((u_rg - s.b) * (u_rg + s.b), 0.0)) : BIG;
#endif
  float tend = min(min(s.tend, tg), g_tsurf);
  vec2 span = medium_clip(u_eye, ry.d, 0.0, tend);
  vec3 L = vec3(0.0);
  vec3 v = u_lpos - u_eye;
  float tc = dot(v, ry.d);
  float h = max(length(v - tc * ry.d), u_light_rmin);
  if (span.y > span.x) {
    float ta = atan((span.x - tc) / h), tb = atan((span.y - tc) / h);
    float half_len = 0.5 * (tb - ta) / float(u_intervals);
    for (int k = 0; k < u_intervals; k++) {
      float mid = ta + (2.0 * float(k) + 1.0) * half_len;
      for (int i = -1; i <= 1; i++) {
        float t = tc + h * tan(mid + float(i) * GL3_X * half_len);
        vec3 wi;
        vec3 e = light_at(u_eye + t * ry.d, wi);
        if (max(e.r, max(e.g, e.b)) <= 0.0) continue;
        Pt p = point_at(ry, t);
        float nu = dot(ry.d, wi);
        vec3 f = scatter_at(p.h, rayleigh_phase(nu), mie_phase(nu)) * e *
                 exp(-max(EYE_TAU(p), vec3(0.0)));
        L += f * (i == 0 ? GL3_W1 : GL3_W0);
      }
    }
    L *= half_len / h;
  }
  // The ground where the ray ends on it: Lambert, lit through the air.
  if (tg < g_tsurf) {
    vec3 q = u_eye + tg * ry.d, wi;
    vec3 e = light_at(q, wi);
    vec3 n = normalize(q - u_atmo_c);
    vec3 tol = u_lpos - q;
    float cosl = dot(n, wi);
    if (cosl > 0.0) {
      Pt p = point_at(ry, tg);
      L += u_albedo / PI * e * (cosl / max(dot(tol, tol), 1e-30)) *
           exp(-max(EYE_TAU(p), vec3(0.0)));
    }
  }
  o_color = vec4(L, 0.0);
}
