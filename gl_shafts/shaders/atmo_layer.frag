// The sampling layers (Dobashi, Yamamoto and Nishita 2002, slides 31-44),
// all of them in one pass, drawn into the lattice or added to the image:
// inside the atmosphere the sampling planes, each standing for its slab of
// view depths; from space (EYE_OUTSIDE) the sampling spheres about the
// planet's centre, each standing for its shell of radii (u_layers,
// u_nlayers: atmo.glsl's layers_radiance). Each fragment integrates the
// single scattering of its pixel's ray over every layer's part of it. The
// slides draw one polygon a plane and add them with blending; on llvmpipe
// each such pass repeated the pixel's set-up (its ray, the eye's optical
// depth, the planet's shadow) and a read and write of the float target, so
// the layers are a loop in one pass, which sums the same slabs.
// The alpha channel holds the ray's class (atmo.glsl's ray_class), which
// atmo_compose.frag reads for the lattice's points.
layout(location = 0) out vec4 o_color;

#include "atmo.glsl"

void main() {
  Setup s = setup_ray(frag_pos());
  o_color = vec4(layers_radiance(s) * u_esun, float(ray_class(s.ry)));
}
