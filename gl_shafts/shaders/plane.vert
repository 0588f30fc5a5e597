// The virtual planes: each slab's screen polygon, drawn at the slab's front
// depth so that the depth test drops the parts behind surfaces.
layout(location = 0) in vec4 a_slab; // ndc x, ndc y, slab front z, back z
layout(location = 1) in float a_plane; // the plane's index
flat out vec2 v_slab;
flat out float v_plane;

void main() {
  v_slab = a_slab.zw;
  v_plane = a_plane;
  // The slab's depths are counted from u_zref, and its depth buffer value
  // rounds as the surfaces' do: the plane is drawn 4e-6 of that value nearer
  // (a few ulps) so that it is never lost behind a surface it lies in front
  // of; the interval texture clips the part behind.
  float w = u_zref + a_slab.z;
  float z = min((u_depth_ab.y - u_depth_ab.x * a_slab.z) * (1.0 + 4e-6), w);
  gl_Position = vec4(a_slab.xy * w, z, w);
}
