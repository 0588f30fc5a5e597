// Pixels that see no surface: the background and the sun's disks,
// attenuated by the medium.
// u_background: the background radiance (a parameter); SUN_DISKS(d): the
// disks' radiance in the unit direction d (common.glsl, gs__sun_disks).
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_depth;

void main() {
  vec3 d = view_ray(gl_FragCoord.xy);
  vec3 tr = transmittance(optical_depth_eye(view_origin(gl_FragCoord.xy), d, BIG));
  o_color = vec4((u_background + SUN_DISKS(normalize(d))) * tr,
                 0.0);
  o_depth = vec4(BIG);
}
