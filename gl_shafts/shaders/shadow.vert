// Shadow maps: surfaces seen from the light, depth only.
layout(location = 0) in vec3 a_pos;
uniform mat4 u_mvp;
#if SPHERE
// An exact sphere's inscribed mesh, inflated to cover the sphere.
uniform vec3 u_inflate_center;
uniform float u_inflate;
#endif

void main() {
#if SPHERE
  vec3 pos = u_inflate_center + (a_pos - u_inflate_center) * u_inflate;
#else
  vec3 pos = a_pos;
#endif
  gl_Position = u_mvp * vec4(pos, 1.0);
}
