// One sampling layer (Dobashi, Yamamoto and Nishita 2002, slides 31-44),
// added to the lattice or the image: inside the atmosphere a sampling
// plane, standing for the slab of view depths u_layer; from space
// (EYE_OUTSIDE) a sampling sphere about the planet's centre, standing for
// the shell of radii u_layer. Each fragment integrates the single
// scattering of its pixel's ray over the layer's part of it
// (atmo.glsl's layer_radiance). u_layer is a uniform, so that every layer
// shares the program.
layout(location = 0) out vec4 o_color;
uniform vec2 u_layer;

#include "atmo.glsl"

void main() {
  Setup s = setup_ray(frag_pos());
  if (layer_empty(s, u_layer.x, u_layer.y)) discard;
  setup_tau(s);
  o_color = vec4(layer_radiance(s, u_layer.x, u_layer.y) * u_esun, 0.0);
}
