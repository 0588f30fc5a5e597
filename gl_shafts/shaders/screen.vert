// A screen-space polygon (normalised device coordinates) at a fixed depth.
layout(location = 0) in vec2 a_ndc;
// u_depth: the depth to draw at (a parameter).

void main() { gl_Position = vec4(a_ndc, u_depth, 1.0); }
