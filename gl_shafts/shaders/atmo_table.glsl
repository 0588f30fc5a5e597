// The atmosphere's optical-depth table (gs_atmo_table.h) in GLSL: whether
// a ray meets the ground and its optical depth up to the top. medium.glsl
// includes it for MEDIUM GS_MEDIUM_ATMOSPHERE, so that every pass of an
// atmosphere's scene (the sky's layers, atmo.glsl; the surfaces and the
// lights in the air, medium.glsl's optical depth) reads the one table.
// Parameters (gs_medium.c): u_rg, u_rt (the ground's and the top's radii),
// u_hh (sqrt(R_t^2 - R_g^2)), u_table_size (n_mu, n_r); the table is bound
// at GS_UNIT_ATMO.

layout(binding = GS_UNIT_ATMO) uniform sampler2D u_table;

const float ATMO_TAU_EPS = 1e-6; // GS__ATMO_TAU_EPS

// Whether the ray from radius r (rho2 = r^2 - R_g^2) with cosine mu to the
// vertical meets the ground (gs__atmo_hits_ground).
bool hits_ground(float r, float rho2, float mu) {
  return mu < 0.0 && r * r * mu * mu >= rho2;
}

// The optical depth from radius r along cosine mu to the top
// (gs__atmo_table_lookup without the ground: the caller tests it).
vec3 tau_top(float r, float rho2, float mu) {
  float hh2 = u_hh * u_hh, rho = sqrt(max(rho2, 0.0));
  float top2 = max(hh2 - rho2, 0.0); // R_t^2 - r^2
  float s = sqrt(max(r * r * mu * mu + top2, 0.0));
  float d = mu > 0.0 ? top2 / max(r * mu + s, 1e-30) : s - r * mu;
  float dmin = top2 / (u_rt + r), dmax = rho + u_hh;
  float umu = clamp((d - dmin) / max(dmax - dmin, 1e-30), 0.0, 1.0);
  float ur = clamp(rho / u_hh, 0.0, 1.0);
  vec2 uv = (vec2(umu, ur) * (u_table_size - 1.0) + 0.5) / u_table_size;
  return max(exp(texture(u_table, uv).rgb) - ATMO_TAU_EPS, 0.0);
}

