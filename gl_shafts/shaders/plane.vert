// The virtual planes: each slab's screen polygon, drawn at the slab's front
// depth so that the depth test drops the parts behind surfaces.
layout(location = 0) in vec4 a_slab; // ndc x, ndc y, slab front z, back z
layout(location = 1) in float a_plane; // the plane's index
// u_near: the camera's near distance (a parameter, gs_sweep.c).
flat out vec2 v_slab;
flat out float v_plane;

void main() {
  v_slab = a_slab.zw;
  v_plane = a_plane;
  gl_Position = vec4(a_slab.xy * a_slab.z, u_near, a_slab.z);
}
