// Surfaces seen by the camera. The same vertex shader in every pass gives
// bit-identical depths, which the later passes test with GL_EQUAL.
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_nrm;
uniform mat4 u_viewproj;
out vec3 v_pos;
out vec3 v_nrm;
invariant gl_Position;

void main() {
  v_pos = a_pos;
  v_nrm = a_nrm;
  gl_Position = u_viewproj * vec4(a_pos, 1.0);
}
