// Surfaces seen by the camera. The same vertex shader in every pass gives
// bit-identical depths, which the later passes test with GL_EQUAL.
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_nrm;
// u_viewproj: world to clip space (a parameter, gs_surface.c).
#if SPHERE
// An exact sphere's inscribed mesh, inflated to cover the sphere.
uniform vec3 u_inflate_center;
uniform float u_inflate;
#endif
out vec3 v_pos;
out vec3 v_nrm;
invariant gl_Position;

void main() {
#if SPHERE
  vec3 pos = u_inflate_center + (a_pos - u_inflate_center) * u_inflate;
#else
  vec3 pos = a_pos;
#endif
  v_pos = pos;
  v_nrm = a_nrm;
  gl_Position = u_viewproj * vec4(pos, 1.0);
}
