// A screen-space polygon (normalised device coordinates) at a fixed depth.
layout(location = 0) in vec2 a_ndc;
uniform float u_depth;

void main() { gl_Position = vec4(a_ndc, u_depth, 1.0); }
