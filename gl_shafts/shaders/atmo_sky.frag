// The sky from inside the atmosphere (Dobashi, Yamamoto and Nishita 2002,
// slides 35-44): one sampling plane, the slab of view depths u_slab
// (uniform, so that every plane shares the program), added to the image.
// Each fragment integrates the single scattering of its pixel's ray over
// the slab's part in the air and out of the planet's shadow, the optical
// depths to the sun and to the eye read from the table. Eye at the origin
// (atmo.glsl).
layout(location = 0) out vec4 o_color;
uniform vec2 u_slab;

#define EYE_TAU(p) (g_down ? tau_top(p.r, p.rho2, -p.mu_p) - g_tau_e \
                           : g_tau_e - tau_top(p.r, p.rho2, p.mu_p))
bool g_down;
vec3 g_tau_e;

#include "atmo.glsl"

void main() {
  vec3 v = view_ray(gl_FragCoord.xy);
  float vl = length(v);
  Ray ry = make_ray(v / vl);
  float tg = ground_t(ry);
  float tend = tg > 0.0 ? tg : top_exit_t(ry);
  float ta = u_slab.x * vl, tb = min(u_slab.y * vl, tend);
  if (!(tb > ta)) discard;
  // The eye's optical depth to a point: the difference of the depths to
  // the top from the eye and from the point, along the ray, or, when the
  // ray meets the ground, along its reverse (which reaches the top).
  g_down = tg > 0.0;
  g_tau_e = tau_top(u_re, u_ce, g_down ? -ry.mu : ry.mu);
  vec3 L = inscatter_lit(ry, ta, tb, shadow_span(ry));
  o_color = vec4(L * u_esun, 0.0);
}
