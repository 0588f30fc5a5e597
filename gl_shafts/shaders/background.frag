// Pixels that see no surface: the background and the sun's disks,
// attenuated by the medium.
// u_background: the background radiance (a parameter); SUN_DISKS(d): the
// disks' radiance in the unit direction d (gs_surface.c, sun_disks).
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_depth;

// The radiance of one disk: `radiance` where d lies within the chord
// dir_chord2.w of the direction dir_chord2.xyz the light comes from.
vec3 sun_disk(vec3 d, vec4 dir_chord2, vec3 radiance) {
  vec3 e = d - dir_chord2.xyz;
  return dot(e, e) <= dir_chord2.w ? radiance : vec3(0.0);
}

#ifndef SUN_DISKS
#define SUN_DISKS(d) vec3(0.0)
#endif

void main() {
  vec3 d = view_ray(gl_FragCoord.xy);
  vec3 tr = atten(medium_len_eye(view_origin(gl_FragCoord.xy), d, BIG));
  o_color = vec4((u_background + SUN_DISKS(normalize(d))) * tr,
                 0.0);
  o_depth = vec4(BIG);
}
