// The atmosphere from above its top (Dobashi, Yamamoto and Nishita 2002,
// slides 32-34: the planet from space): one sampling sphere, standing for
// the shell of radii u_shell (R_a, R_b) about the planet's centre, added to
// the image. A fragment integrates the single scattering of its pixel's
// ray over the ray's parts inside the shell (in front of the ground, out
// of the planet's shadow), split at the ray's lowest point; the optical
// depths to the sun and to the eye come from the table. Eye at the origin
// (atmo.glsl), EYE_OUTSIDE 1.
layout(location = 0) out vec4 o_color;
uniform vec2 u_shell;

// The eye's optical depth to a point: before the ray's lowest point, the
// depth from the point back to the top (the ray came in that way); after
// it, the whole chord's less the rest to the top.
#define EYE_TAU(p) (p.mu_p <= 0.0 ? tau_top(p.r, p.rho2, -p.mu_p) \
                                  : g_tau_chord - tau_top(p.r, p.rho2, p.mu_p))
vec3 g_tau_chord;

#include "atmo.glsl"

void main() {
  vec3 v = view_ray(gl_FragCoord.xy);
  Ray ry = make_ray(normalize(v));
  float b = u_re * length(cross(u_up, ry.d));
  float ra = u_shell.x, rb = u_shell.y;
  if (ry.mu >= 0.0 || b >= rb) discard;
  float tp = -u_re * ry.mu; // the lowest point
  float sb = sqrt((rb - b) * (rb + b));
  float sa = b < ra ? sqrt((ra - b) * (ra + b)) : 0.0;
  bool ground = b < u_rg;
  g_tau_chord = ground ? vec3(0.0) : 2.0 * tau_top(b, (b - u_rg) * (b + u_rg), 0.0);
  vec2 sh = shadow_span(ry);
  // In front of the lowest point: [tp - sb, tp - sa]; behind it, unless
  // the ground stops the ray: [tp + sa, tp + sb].
  vec3 L = inscatter_lit(ry, tp - sb, tp - sa, sh);
  if (!ground) L += inscatter_lit(ry, tp + sa, tp + sb, sh);
  o_color = vec4(L * u_esun, 0.0);
}
