// Pixels that see no surface: the background, attenuated by the medium.
// u_background: the background radiance (a parameter).
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_depth;

void main() {
  vec3 d = normalize(view_ray(gl_FragCoord.xy));
  o_color = vec4(u_background * atten(medium_len_ray(u_eye, d)), 0.0);
  o_depth = vec4(BIG);
}
