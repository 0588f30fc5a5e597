// What both plane shaders (plane_dir.frag, plane_local.frag) share. Each
// draws one virtual plane's in-scattering for one light, added to the image:
//   power * xi * pattern * visibility * dt
// integrated over the part of the plane's slab [z_front, z_back] that the
// pixel's ray spends in the lit medium (the interval texture). A view depth
// step dz is a ray length dt = dz |d|, |d| = 1 / cos(angle to the view
// axis). xi comes from the lattice (as xi r^2) or is evaluated here.
//
// The lights' parts are sampled differently: plane_local.frag for point and
// spot lights, plane_dir.frag for directional ones. In a dense medium
// (TAU_SUB), the transmittance changes within a slab too, and every light's
// part gets a sample per optical depth u_sub_tau / 2 (u_tau_rate = 2
// sigma_t / u_sub_tau).
flat in vec2 v_slab;
flat in float v_plane;
layout(binding = GS_UNIT_INTERVAL) uniform sampler2D u_interval;
layout(binding = GS_UNIT_XI) uniform sampler3D u_xi;
// Parameters (gs_sweep.c): u_xi_xy and u_xi_z map to the lattice texture
// (s = ndc.x * x + y, t = ndc.y * z + w; r = z * x + y); u_inv_sub_angle
// is 1 / the largest angle one sample stands for, u_inv_sub_texels 1 / the
// window texels one sample stands for, u_map_size the light map's size,
// u_tau_rate the samples per unit length a dense medium needs.
layout(location = 0) out vec4 o_color;

vec3 xi_lattice(vec2 ndc, float z) {
  return texture(u_xi, vec3(ndc.x * u_xi_xy.x + u_xi_xy.y,
                            ndc.y * u_xi_xy.z + u_xi_xy.w,
                            z * u_xi_z.x + u_xi_z.y)).rgb;
}

float jitter_offset() {
#if JITTER
  // Interleaved gradient noise, rotated by the golden ratio from plane to
  // plane: a stratified, per-pixel offset in [0, 1).
  float u = fract(52.9829189 * fract(dot(gl_FragCoord.xy + u_frag0, vec2(0.06711056, 0.00583715))));
  return fract(u + 0.618034 * v_plane);
#else
  return 0.5;
#endif
}

// Bisection steps that locate a shadow's edge within a sample's step.
#define EDGE_STEPS 5
