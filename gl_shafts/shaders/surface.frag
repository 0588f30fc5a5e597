// One light's contribution to the surfaces (Lambert + Phong with shadows,
// as the reference shades them), attenuated by the medium towards the eye;
// the first pass adds emission and ambient. Also writes the view depth
// (counted from u_zref, common.glsl).
in vec3 v_pos;
in vec3 v_nrm;
uniform vec3 u_kd, u_ks, u_base;
uniform float u_shininess;
// u_open: 1.0 for an open shape drawn into the light's shadow map, else
// 0.0 (gs_shadow.c stores a closed one by its far side).
uniform float u_open;
// Parameters: u_lit, 1.0 if the pass has a light; u_shadow_texel, the
// world length of a shadow-map texel (per unit of distance from the light
// for perspective maps; gs_lightvol.h's shadow_span over the map's size).
#if SPHERE
// The sphere drawn: world to object space, and its object-space centre and
// radius.
uniform mat4 u_obj_inv;
uniform vec3 u_center;
uniform float u_radius;
// u_sphere_c0: |oc|^2 - r^2 at the ray origin u_org (in double on the CPU);
// u_sphere_near: 1.0 to solve with it (the eye within 4 radii of the
// centre), 0.0 to solve about the ray's point nearest the centre.
uniform float u_sphere_c0, u_sphere_near;
#endif
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_depth;

// How far along its normal n (on the light's side) a surface point's
// shadow lookup moves, at cosl = n . wi, so that an open shape drawn into
// the map with no bias (gs_shadow.c) does not shadow itself: the point then
// lies b / cosl in front of its plane along the light, against the plane's
// depth at the texels the filtered lookup meets (up to sqrt(2) texels away:
// texel * sqrt(2) tan). b = texel * (0.75 sin + 0.1) clears the nearer
// texels, which carry most of the bilinear weight; twice that moved shadow
// edges on such shapes by b tan, enough to light or darken a pixel at a
// patch's edge (window_room.json: 4.4% against 2.4% at 128 planes), with
// no gain on the reference tests. Moved along wi instead, the lookup of a
// floor next to a wall went through the wall and lit the floor at its foot
// inside a closed room. Other shapes (closed ones are stored by their far
// side, and shapes not in the map) need none.
float receiver_offset(vec3 p, float cosl) {
#if SHADOW == GS_SHADOW_CUBE
  vec3 a = abs(p - u_lpos);
  float texel = u_shadow_texel * max(a.x, max(a.y, a.z));
#elif SHADOW == GS_SHADOW_2D && LIGHT_TYPE != GS_LIGHT_DIRECTIONAL
  float texel = u_shadow_texel * dot(p - u_lpos, u_ldir);
#else
  float texel = u_shadow_texel;
#endif
  return u_open * texel * (0.75 * sqrt(max(1.0 - cosl * cosl, 0.0)) + 0.1);
}

void main() {
  vec3 d = view_ray(gl_FragCoord.xy), o = view_origin(gl_FragCoord.xy);
#if SPHERE
  // The pixel's ray against the true sphere, in object space; the ray
  // parameter is the view depth from u_zref (d . forward = 1). `precise` keeps the depth
  // bit-identical in every pass, which the GL_EQUAL depth test relies on.
  vec3 oc = (u_obj_inv * vec4(o, 1.0)).xyz - u_center;
  vec3 od = (u_obj_inv * vec4(d, 0.0)).xyz;
  // Far from the sphere, the discriminant B^2 - A (|oc|^2 - r^2) as A (r^2 -
  // |f|^2), f the ray's point nearest to the centre: the first form
  // cancels when the camera is far from the sphere (Haines et al., Ray
  // Tracing Gems, ch. 7). Near it, B^2 - A C with C = |oc|^2 - r^2 from
  // u_sphere_c0 (plus the change from u_org to this ray's origin, zero
  // for a camera in the scene) and the roots as q / A and C / q: r^2 and
  // |f|^2 of a planet agree to a few ulps 1 m above its ground.
  precise float A = dot(od, od), B = dot(oc, od);
  precise vec3 f = oc - (B / A) * od;
  vec3 dw = u_zref * (u_rc + (gl_FragCoord.x * u_ndc_scale.x - 1.0) * u_rx +
                      (gl_FragCoord.y * u_ndc_scale.y - 1.0) * u_uy);
  vec3 dlt = mat3(u_obj_inv) * dw;
  precise float C = u_sphere_c0 + dot(dlt, 2.0 * (oc - dlt) + dlt);
  bool near_form = u_sphere_near > 0.5;
  precise float disc = near_form ? B * B - A * C : A * (u_radius * u_radius - dot(f, f));
  if (disc < 0.0) discard;
  precise float q = -(B + (B >= 0.0 ? sqrt(disc) : -sqrt(disc)));
  precise float t0 = near_form ? min(q / A, C / q) : (-B - sqrt(disc)) / A;
  precise float t1 = near_form ? max(q / A, C / q) : (-B + sqrt(disc)) / A;
  precise float t = t0;
  precise float tnear = u_near - u_zref;
  if (t < tnear) t = t1; // the camera is inside
  if (t < tnear) discard;
  precise float depth = (u_depth_ab.y - u_depth_ab.x * t) / (u_zref + t); // depth_at(t)
  gl_FragDepth = depth;
  vec3 p = o + t * d;
  vec3 n = normalize(transpose(mat3(u_obj_inv)) * (oc + t * od));
#else
  vec3 p = v_pos;
  float t = dot(p - u_org, u_fwd);
  vec3 n = normalize(v_nrm);
#endif
  // An atmosphere's ground in front hides the surface (medium.glsl).
  if (medium_hides(o, d, t)) discard;
  // The direction from the eye: the pixel's ray (p - eye cancelled for a
  // camera far away).
  vec3 view = d;
  if (dot(n, view) > 0.0) n = -n; // shade the side the camera sees
  vec3 L = u_base;
  if (u_lit != 0.0) {
    vec3 wi;
    vec3 e = light_incident(p, wi);
    float cosl = dot(n, wi);
    if (cosl > 0.0 && max(e.r, max(e.g, e.b)) > 0.0) {
      vec3 q = p + receiver_offset(p, cosl) * n;
      float vis = shadow_at(q, 1.0);
      // A surface not drawn open into the map has nothing of its own there:
      // behind what the lookup's four texels hold, it is in shadow, however
      // the filtered comparison weighs them (common.glsl, shadow_behind).
      // Filtered alone, a floor point 0.0008 from the foot of a wall the sun
      // grazes, 0.005 behind it along the light, took up to 0.058 inside a
      // closed room (testdata/hard_cases/surface_room*.json). Counted lit
      // only when all four texels say so, as the medium is, shadow edges on
      // surfaces moved by up to a texel (the shadowed spot of
      // reference_test 3.7% from the reference instead of 1.4%). An open
      // shape drawn into the map is checked the same way at its moved
      // lookup point q, which lies in front of its own plane: with a medium
      // below it, the floor of a closed room is such a caster, and a floor
      // point 0.0007 from a wall's foot took 0.0075 at 160 x 120
      // (closed_room.json) through the filtered lookup alone.
      if (vis > 0.0 && shadow_behind(q)) vis = 0.0;
      vec3 f = u_kd * (cosl / PI);
      float rv = dot(reflect(-wi, n), -normalize(view));
      if (rv > 0.0) f += u_ks * pow(rv, u_shininess);
      L += f * e * vis;
    }
  }
  o_color = vec4(L * transmittance(optical_depth_eye(o, d, t)), 0.0);
  o_depth = vec4(t);
}
