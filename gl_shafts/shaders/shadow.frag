// Shadow maps write depth only. An exact sphere writes the depth of the
// true sphere's far side along the light's ray through the texel (closed
// casters are stored by their far side, gs_shadow.c), so its shadow has
// the exact outline.
#if SPHERE
uniform mat4 u_mvp, u_mvp_inv;
uniform vec2 u_texel_ndc;   // 2 / the map's size
uniform vec2 u_ray_depths;  // two depths along each texel's ray, far apart
uniform mat4 u_obj_inv;     // world to the sphere's object space
uniform vec3 u_center;
uniform float u_radius;
#endif

void main() {
#if SPHERE
  vec2 ndc = gl_FragCoord.xy * u_texel_ndc - 1.0;
  vec4 a = u_mvp_inv * vec4(ndc, u_ray_depths.x, 1.0);
  vec4 b = u_mvp_inv * vec4(ndc, u_ray_depths.y, 1.0);
  vec3 pa = a.xyz / a.w, pb = b.xyz / b.w;
  vec3 oc = (u_obj_inv * vec4(pa, 1.0)).xyz - u_center;
  vec3 od = (u_obj_inv * vec4(pb - pa, 0.0)).xyz;
  // Along the unit direction, and with the discriminant as r^2 - |f|^2, f
  // the point nearest the centre: B^2 - A C, of the fourth power of the
  // lengths, fell below single precision's least normal number in a scene
  // a billionth of a unit across, and cancels for a sphere far away.
  float len = length(od);
  vec3 u = od / len;
  float B = dot(oc, u);
  vec3 f = oc - B * u;
  float disc = u_radius * u_radius - dot(f, f);
  if (disc < 0.0) discard;
  float t = (-B + sqrt(disc)) / len;
  vec4 c = u_mvp * vec4(pa + t * (pb - pa), 1.0);
  gl_FragDepth = c.z / c.w;
#endif
}
