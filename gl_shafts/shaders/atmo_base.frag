// What a pixel's ray ends on, under one sun: the ground, an opaque Lambert
// sphere lit through the air (albedo / pi * E * cos * the sun's
// transmittance), seen through the air; or, with FIRST 1 (the first sun's
// pass, drawn without blending), the background through the air where the
// ray leaves. Eye at the origin (atmo.glsl); EYE_OUTSIDE for the planet
// from space.
layout(location = 0) out vec4 o_color;
#ifndef FIRST
#define FIRST 1
#endif
#define EYE_TAU(p) vec3(0.0)

#include "atmo.glsl"

void main() {
  vec3 v = view_ray(gl_FragCoord.xy);
  Ray ry = make_ray(normalize(v));
  float tg = -1.0;
  vec3 tau_eye = vec3(0.0); // to the ground, or along the whole ray
  float rg2 = u_rg * u_rg;
#if EYE_OUTSIDE
  // The impact parameter b (the ray's least distance from the centre) from
  // a cross product, which keeps its precision at the disc's centre.
  float b = u_re * length(cross(u_up, ry.d));
  float b2g = (b - u_rg) * (b + u_rg); // b^2 - R_g^2
  if (ry.mu < 0.0 && b < u_rg) {
    float sg = sqrt(-b2g);
    tg = -u_re * ry.mu - sg;
    tau_eye = tau_top(u_rg, 0.0, sg / u_rg);
  } else if (ry.mu < 0.0 && b < u_rt) {
    tau_eye = 2.0 * tau_top(b, b2g, 0.0);
  }
#else
  tg = ground_t(ry);
  if (tg > 0.0) {
    float mu_g = (u_re * ry.mu + tg) / u_rg;
    tau_eye = tau_top(u_rg, 0.0, -mu_g) - tau_top(u_re, u_ce, -ry.mu);
  } else {
    tau_eye = tau_top(u_re, u_ce, ry.mu);
  }
#endif
  vec3 L = vec3(0.0);
  vec3 tr = exp(-max(tau_eye, vec3(0.0)));
  if (tg > 0.0) {
    float mu_sg = (u_re * ry.mu_s + tg * ry.nu) / u_rg;
    L = tr * u_albedo / PI * u_esun * max(mu_sg, 0.0) * sun_tr(u_rg, 0.0, mu_sg);
  } else if (FIRST == 1) {
    L = tr * u_background;
  }
  o_color = vec4(L, 0.0);
}
