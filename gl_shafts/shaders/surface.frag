// One light's contribution to the surfaces (Lambert + Phong with shadows,
// as the reference shades them), attenuated by the medium towards the eye;
// the first pass adds emission and ambient. Also writes the view depth.
in vec3 v_pos;
in vec3 v_nrm;
uniform vec3 u_kd, u_ks, u_base;
uniform float u_shininess;
uniform int u_lit;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_depth;

void main() {
  vec3 p = v_pos;
  vec3 view = p - u_eye;
  vec3 n = normalize(v_nrm);
  if (dot(n, view) > 0.0) n = -n; // shade the side the camera sees
  vec3 L = u_base;
  if (u_lit != 0) {
    vec3 wi;
    vec3 e = light_incident(p, wi);
    float cosl = dot(n, wi);
    if (cosl > 0.0 && max(e.r, max(e.g, e.b)) > 0.0) {
      float vis = shadow_at(p); // the shadow pass biases depths
      vec3 f = u_kd * (cosl / PI);
      float rv = dot(reflect(-wi, n), -normalize(view));
      if (rv > 0.0) f += u_ks * pow(rv, u_shininess);
      L += f * e * vis;
    }
  }
  o_color = vec4(L * exp(-u_sigma_t * medium_len(u_eye, p)), 0.0);
  o_depth = vec4(dot(view, u_fwd));
}
