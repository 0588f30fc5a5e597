// The atmosphere (gs_atmo.h): its coefficients by height, the phase
// mixture, the optical-depth table (gs_atmo_table.h) and the geometry of a
// pixel's ray about the planet, shared by atmo_layer.frag and
// atmo_compose.frag; the optical-depth table's lookup is medium.glsl's
// (atmo_table.glsl).
//
// Coordinates are the eye's: the eye is the origin, the planet's centre
// lies at -u_re * u_up (u_up the unit vertical at the eye, u_re the eye's
// distance from the centre). Every radius and height along a ray comes from
// the quantities the C side computes in double precision, so nothing
// cancels in float: u_ce = r_e^2 - R_g^2 (= h_e (2 R_g + h_e)), and a point
// at distance t along the unit ray d (mu = d . u_up) has
//   rho^2(t) = r(t)^2 - R_g^2 = u_ce + t (2 r_e mu + t),
// its height h = rho^2 / (r + R_g). With the eye 1 m above a 6360 km
// planet, r_e in float is known to 0.5 m, rho^2 and h to a few
// micrometres.
//
// Parameters (gs_atmo_render.c): u_up, u_re, u_ce, u_rg, u_rt, u_hh
// (sqrt(R_t^2 - R_g^2)), u_ray_s, u_ray_h, u_mie_s, u_mie_t (Mie's sigma_s
// + sigma_a), u_mie_h, u_mie_g, u_oz_a, u_oz_c, u_oz_w, u_albedo, u_lsun
// (unit, towards the sun), u_esun (irradiance), u_table_size (n_mu, n_r),
// u_background, u_lat_scale (a uniform). MIE_PHASE selects Mie's phase function (ATMO_MIE_*),
// EYE_OUTSIDE 1 an eye above the top (the planet from space).

#define ATMO_MIE_ISOTROPIC 0
#define ATMO_MIE_HG 1
#define ATMO_MIE_CS 2
#define ATMO_MIE_HAZY 3
#define ATMO_MIE_MURKY 4
#define ATMO_MIE_RAYLEIGH 5
#ifndef MIE_PHASE
#define MIE_PHASE ATMO_MIE_CS
#endif
#ifndef EYE_OUTSIDE
#define EYE_OUTSIDE 0
#endif

uniform float u_lat_scale;

float rayleigh_phase(float c) { return 3.0 * (1.0 + c * c) / (16.0 * PI); }

// Mie's normalised phase function at cos(alpha) (sh_phase_eval).
float mie_phase(float c) {
  float g = u_mie_g;
#if MIE_PHASE == ATMO_MIE_HG
  float den = 1.0 + g * g - 2.0 * g * c;
  return (1.0 - g * g) / (4.0 * PI * den * sqrt(den));
#elif MIE_PHASE == ATMO_MIE_CS
  return phase_cornette_shanks(g, c);
#elif MIE_PHASE == ATMO_MIE_HAZY
  float x = 0.5 * (1.0 + c), x2 = x * x, x4 = x2 * x2;
  return (1.0 + 9.0 * x4 * x4) / (8.0 * PI);
#elif MIE_PHASE == ATMO_MIE_MURKY
  float y = 0.5 * (1.0 + c);
  y *= y; y *= y; y *= y; y *= y; y *= y;
  return 33.0 * (1.0 + 50.0 * y) / (332.0 * PI);
#elif MIE_PHASE == ATMO_MIE_RAYLEIGH
  return rayleigh_phase(c);
#else
  return 1.0 / (4.0 * PI);
#endif
}

// sigma_s times the phase mixture at height h, for the phase values pr
// (Rayleigh's) and pm (Mie's) of the pixel: sum of sigma_s p.
vec3 scatter_at(float h, float pr, float pm) {
  return u_ray_s * (exp(-h / u_ray_h) * pr) + u_mie_s * (exp(-h / u_mie_h) * pm);
}

// The transmittance from a point at radius r (rho2) towards the sun, at the
// cosine mu_s between the sun's direction and the vertical there: 0 where
// the ground blocks.
vec3 sun_tr(float r, float rho2, float mu_s) {
  return hits_ground(r, rho2, mu_s) ? vec3(0.0) : exp(-tau_top(r, rho2, mu_s));
}

// A pixel's ray about the planet.
struct Ray {
  vec3 d;      // unit direction
  float mu;    // d . u_up
  float nu;    // d . u_lsun: cos alpha of the sun's light scattered to the eye
  float mu_s;  // u_up . u_lsun
  float pr, pm; // the phase values at nu
};

Ray make_ray(vec3 d) {
  Ray ry;
  ry.d = d;
  ry.mu = dot(d, u_up);
  ry.nu = dot(d, u_lsun);
  ry.mu_s = dot(u_up, u_lsun);
  ry.pr = rayleigh_phase(ry.nu);
  ry.pm = mie_phase(ry.nu);
  return ry;
}

// rho^2 = r^2 - R_g^2 at distance t along the ray, without cancellation.
float rho2_at(Ray ry, float t) { return u_ce + t * (2.0 * u_re * ry.mu + t); }

// The distance along the ray to the ground (the first meeting), or -1.
float ground_t(Ray ry) {
  float b = u_re * ry.mu, disc = b * b - u_ce;
  if (ry.mu >= 0.0 || disc < 0.0) return -1.0;
  return u_ce / (-b + sqrt(disc));
}

// The distance along the ray to the top where it leaves (the far meeting),
// or -1 if it misses the top sphere.
float top_exit_t(Ray ry) {
  float b = u_re * ry.mu, c = u_ce - u_hh * u_hh; // r_e^2 - R_t^2
  float disc = b * b - c;
  if (disc < 0.0) return -1.0;
  return -b + sqrt(disc);
}

// The part of the ray in the planet's shadow (the half-cylinder of radius
// R_g behind the planet along the sun's direction), as [s0, s1]; (BIG,
// BIG) if none. Points there see no sun; the sweep integrates the
// lit parts only, so the shadow's edge is exact.
vec2 shadow_span(Ray ry) {
  // The centre is c = -u_re u_up. A point p = t d: q = p - c; in the
  // shadow where q . l < 0 and |q|^2 - (q . l)^2 < R_g^2.
  vec3 c = -u_re * u_up;
  vec3 dp = ry.d - ry.nu * u_lsun;      // d's part across l
  vec3 cp = -c - dot(-c, u_lsun) * u_lsun; // (0 - c)'s part across l
  float a = dot(dp, dp), b = dot(cp, dp);
  // |cp|^2 - R_g^2 = |q0|^2 - (q0.l)^2 - R_g^2 with q0 = -c = u_re u_up:
  // r_e^2 (1 - mu_s^2) - R_g^2 = u_ce - r_e^2 mu_s^2.
  float cc = u_ce - u_re * u_re * ry.mu_s * ry.mu_s;
  float disc = b * b - a * cc;
  if (a < 1e-20 || disc <= 0.0) {
    // Parallel to the axis: inside the cylinder all along, or never.
    if (a < 1e-20 && cc < 0.0) {
      // In the shadow where q . l < 0: t nu + u_re mu_s < 0.
      float tq = -u_re * ry.mu_s / ry.nu;
      return ry.nu > 0.0 ? vec2(-BIG, tq) : vec2(tq, BIG);
    }
    return vec2(BIG);
  }
  float sq = sqrt(disc);
  float q = -b - sign(b) * sq;
  float t0 = q / a, t1 = cc / q;
  vec2 s = vec2(min(t0, t1), max(t0, t1));
  // Keep the half behind the planet: q . l = u_re mu_s + t nu < 0.
  if (abs(ry.nu) < 1e-20) {
    if (u_re * ry.mu_s >= 0.0) return vec2(BIG);
  } else {
    float tl = -u_re * ry.mu_s / ry.nu; // where q . l = 0
    if (ry.nu > 0.0) s.y = min(s.y, tl); else s.x = max(s.x, tl);
  }
  return s.x < s.y ? s : vec2(BIG);
}

// What the ray ends on: 0 nothing (it misses the air), 1 the air alone
// (it leaves through the top), 2 the ground (3: near the limb, below). The in-scattered radiance is
// smooth in the direction within a class and jumps between classes (the
// horizon, the limb), so the lattice is interpolated within a class only.
// From space the ground's class is split where the air column seen on
// it starts to climb steeply towards the limb (the limb's brightening,
// growing as 1 / cos of the ground's zenith angle): at cos = 0.4, b^2 =
// 0.84 R_g^2; bilinear interpolation over a lattice step of 0.23 degrees
// at 30 000 km erred by 3.1% across that band.
int ray_class(Ray ry) {
#if EYE_OUTSIDE
  float b = u_re * length(cross(u_up, ry.d));
  return ry.mu >= 0.0 || b >= u_rt ? 0 : b >= u_rg ? 1 : b * b < 0.84 * u_rg * u_rg ? 2 : 3;
#else
  return ground_t(ry) > 0.0 ? 2 : 1;
#endif
}

// The pixel position (GL's window coordinates of the whole image's
// drawn window) of a fragment: gl_FragCoord scaled by u_lat_scale, the
// lattice's step (1 when the image is drawn at full resolution).
vec2 frag_pos() { return gl_FragCoord.xy * u_lat_scale; }

// The point at distance t along the ray: its radius r, rho2 = r^2 - R_g^2
// and height h, and the cosines to its vertical of the ray (mu_p) and of
// the sun (mu_sp).
struct Pt {
  float r, rho2, h, mu_p, mu_sp;
};

// Inside the atmosphere (the sky), rho^2 by rho2_at; from outside (space,
// EYE_OUTSIDE), where u_ce and the terms of rho2_at are a thousand million
// and would cancel, from the point's offset from the centre, q = r_e u_up +
// t d, whose float error is that of r_e (2 mm at 36 000 km), and so is h's.
Pt point_at(Ray ry, float t) {
  Pt p;
#if EYE_OUTSIDE
  vec3 q = u_re * u_up + t * ry.d;
  p.r = length(q);
  p.h = p.r - u_rg;
  p.rho2 = p.h * (p.r + u_rg);
  p.mu_p = dot(q, ry.d) / p.r;
  p.mu_sp = dot(q, u_lsun) / p.r;
#else
  p.rho2 = rho2_at(ry, t);
  p.r = sqrt(p.rho2 + u_rg * u_rg);
  p.h = p.rho2 / (p.r + u_rg);
  p.mu_p = (u_re * ry.mu + t) / p.r;
  p.mu_sp = (u_re * ry.mu_s + t * ry.nu) / p.r;
#endif
  return p;
}

// The Gauss-Legendre nodes on [-1, 1] and weights of 3 points.
const float GL3_X = 0.7745966692;
const float GL3_W0 = 0.5555555556, GL3_W1 = 0.8888888889;

// The eye's optical depth to a point p on the ray (a Pt). Inside the
// atmosphere: the difference of the depths to the top from the eye and
// from the point, along the ray, or, when the ray meets the ground, along
// its reverse (which reaches the top). From space: before the ray's lowest
// point the depth from the point back to the top (the ray came in that
// way); after it the whole chord's less the rest to the top. The globals
// are the pixel's (setup_tau).
bool g_down;
vec3 g_tau_e, g_tau_chord;
#if EYE_OUTSIDE
#define EYE_TAU(p) (p.mu_p <= 0.0 ? tau_top(p.r, p.rho2, -p.mu_p) \
                                  : g_tau_chord - tau_top(p.r, p.rho2, p.mu_p))
#else
#define EYE_TAU(p) (g_down ? tau_top(p.r, p.rho2, -p.mu_p) - g_tau_e \
                           : g_tau_e - tau_top(p.r, p.rho2, p.mu_p))
#endif

// The scattered radiance per unit irradiance and length at distance t
// along the ray, the sun unblocked but for the ground.
vec3 inscatter_at(Ray ry, float t) {
  Pt p = point_at(ry, t);
  // Both legs' optical depths summed, one exponential: the sun's (0 where
  // the ground blocks it) and the eye's.
  vec3 tau = tau_top(p.r, p.rho2, p.mu_sp) + max(EYE_TAU(p), vec3(0.0));
  return hits_ground(p.r, p.rho2, p.mu_sp) ? vec3(0.0)
                                           : scatter_at(p.h, ry.pr, ry.pm) * exp(-tau);
}

// The scattered radiance per unit irradiance of the ray's lit stretch
// [ta, tb] (3-point Gauss-Legendre).
vec3 inscatter(Ray ry, float ta, float tb) {
  if (!(tb > ta)) return vec3(0.0);
  float half_len = 0.5 * (tb - ta), mid = 0.5 * (ta + tb);
  vec3 sum = vec3(0.0);
  for (int i = -1; i <= 1; i++)
    sum += inscatter_at(ry, mid + float(i) * GL3_X * half_len) * (i == 0 ? GL3_W1 : GL3_W0);
  return sum * half_len;
}

// inscatter over [ta, tb] without the planet's shadow sh (shadow_span):
// over the part before the shadow and the part after it, those that are
// not empty. Optional work is a loop rather than a branch throughout the
// atmosphere's shaders: llvmpipe runs both sides of a branch for every
// pixel of a SIMD vector, but leaves a loop as soon as none of the vector's
// pixels continues it, so a part no pixel of the vector has costs nothing.
vec3 inscatter_open(Ray ry, float ta, float tb, vec2 sh) {
  vec2 p0 = vec2(ta, min(tb, sh.x)), p1 = vec2(max(ta, sh.y), tb);
  vec3 L = vec3(0.0);
  for (int i = p0.y > p0.x ? 0 : 1; i < (p1.y > p1.x ? 2 : 1); i++) {
    vec2 p = i == 0 ? p0 : p1;
    L += inscatter(ry, p.x, p.y);
  }
  return L;
}

// Shapes in the air: inscatter_lit, inscatter_open where the ray ends on
// a surface and the shapes' shadows leave out; g_tsurf.
#include "atmo_shapes.glsl"

// What every layer of a pixel's ray shares.
struct Setup {
  Ray ry;
  float vl;   // inside: |view_ray|, view depth to distance along the ray
  float tend; // inside: where the ray leaves the air (the ground or the top)
  float b;    // outside: the impact parameter (least distance from the centre)
  float tp;   // outside: the distance to the ray's lowest point
  bool ground; // the ray meets the ground
  vec2 sh;    // the planet's shadow (shadow_span)
};

// The geometry of the pixel at frag (frag_pos's coordinates). From space
// the impact parameter comes from a cross product, which keeps its
// precision at the disc's centre.
Setup setup_ray(vec2 frag) {
  Setup s;
  vec3 v = view_ray(frag);
  s.vl = length(v);
  s.ry = make_ray(v / s.vl);
#if EYE_OUTSIDE
  s.b = u_re * length(cross(u_up, s.ry.d));
  s.tp = -u_re * s.ry.mu;
  s.ground = s.b < u_rg;
  s.tend = BIG;
#else
  float tg = ground_t(s.ry);
  s.ground = tg > 0.0;
  s.tend = s.ground ? tg : top_exit_t(s.ry);
#endif
  g_tsurf = surface_t(frag, s.vl);
  return s;
}

// The pixel's optical depths to the eye (EYE_TAU's globals) and shadow.
void setup_tau(inout Setup s) {
#if EYE_OUTSIDE
  g_tau_chord = s.ground ? vec3(0.0) : 2.0 * tau_top(s.b, (s.b - u_rg) * (s.b + u_rg), 0.0);
#else
  g_down = s.ground;
  g_tau_e = tau_top(u_re, u_ce, g_down ? -s.ry.mu : s.ry.mu);
#endif
  s.sh = shadow_span(s.ry);
}

// Whether the layer [lo, hi] holds none of the ray: inside, the view
// depths of a sampling plane's slab; from space, the radii of a sampling
// sphere's shell.
bool layer_empty(Setup s, float lo, float hi) {
#if EYE_OUTSIDE
  return s.ry.mu >= 0.0 || s.b >= hi;
#else
  return !(min(hi * s.vl, s.tend) > lo * s.vl);
#endif
}

// The scattered radiance per unit irradiance of the ray's part in the
// layer [lo, hi]: a slab's part in the air, or a shell's parts in front
// of and behind the ray's lowest point (split there; none behind it where
// the ground stops the ray), out of the planet's shadow.
vec3 layer_radiance(Setup s, float lo, float hi) {
  if (layer_empty(s, lo, hi)) return vec3(0.0);
#if EYE_OUTSIDE
  float sb = sqrt((hi - s.b) * (hi + s.b));
  float sa = s.b < lo ? sqrt((lo - s.b) * (lo + s.b)) : 0.0;
  vec3 L = vec3(0.0);
  for (int i = 0; i < (s.ground ? 1 : 2); i++) {
    vec2 p = i == 0 ? vec2(s.tp - sb, s.tp - sa) : vec2(s.tp + sa, s.tp + sb);
    L += inscatter_lit(s.ry, p.x, p.y, s.sh);
  }
  return L;
#else
  return inscatter_lit(s.ry, lo * s.vl, min(hi * s.vl, s.tend), s.sh);
#endif
}

// The layers' bounds (view depths or radii, u_nlayers + 1 of them,
// ascending), uniforms set by gs_atmo_render.c.
uniform float u_layers[GS_ATMO_MAX_LAYERS + 1];
uniform int u_nlayers;

// The scattered radiance per unit irradiance of the whole ray: the sum of
// every layer's (layer_radiance), with setup_tau done once for them all.
// The loop runs over the layers the ray meets alone (a loop, so that
// layers no pixel of a SIMD vector meets cost nothing: inscatter_open):
// from space from the innermost shell the ray reaches, inside the air up
// to the slab where the ray ends.
vec3 layers_radiance(inout Setup s) {
  setup_tau(s);
  int k = 0;
#if EYE_OUTSIDE
  if (s.ry.mu >= 0.0) k = u_nlayers;
  for (; k < u_nlayers && s.b >= u_layers[k + 1]; k++) {}
#endif
  vec3 L = vec3(0.0);
  for (; k < u_nlayers && !layer_empty(s, u_layers[k], u_layers[k + 1]); k++)
    L += layer_radiance(s, u_layers[k], u_layers[k + 1]);
  return L;
}
