// Shadow maps: surfaces seen from the light, depth only.
layout(location = 0) in vec3 a_pos;
uniform mat4 u_mvp;
#if SPHERE
// An exact sphere's inscribed mesh, inflated to cover the sphere.
uniform vec3 u_inflate_center;
uniform float u_inflate;
#else
// u_dilate: how far (in normalised device units) an open caster's
// triangles are pushed out in the map, each edge moved outward and the
// depth extended along the triangle's plane; 0: none. The triangle's other
// corners are read from the vertex buffer itself (6 floats a vertex,
// position first; the draws are non-indexed triangle lists).
uniform float u_dilate;
layout(std430, binding = 0) readonly buffer gs_vertices { float gs_vert[]; };

vec4 clip_of(int i) {
  int b = 6 * i;
  return u_mvp * vec4(gs_vert[b], gs_vert[b + 1], gs_vert[b + 2], 1.0);
}
#endif

void main() {
#if SPHERE
  vec3 pos = u_inflate_center + (a_pos - u_inflate_center) * u_inflate;
  gl_Position = u_mvp * vec4(pos, 1.0);
#else
  gl_Position = u_mvp * vec4(a_pos, 1.0);
  if (u_dilate <= 0.0) return;
  int k = gl_VertexID % 3, t0 = gl_VertexID - k;
  vec4 c0 = clip_of(t0), c1 = clip_of(t0 + 1), c2 = clip_of(t0 + 2);
  if (min(c0.w, min(c1.w, c2.w)) <= 0.0) return; // crosses the light's plane
  vec3 p0 = c0.xyz / c0.w, p1 = c1.xyz / c1.w, p2 = c2.xyz / c2.w;
  vec2 e1 = p1.xy - p0.xy, e2 = p2.xy - p0.xy;
  float area = e1.x * e2.y - e1.y * e2.x;
  if (abs(area) < 1e-12) return; // edge-on: nothing to extend
  // This corner and its neighbours in counter-clockwise order.
  vec3 p = k == 0 ? p0 : (k == 1 ? p1 : p2);
  vec3 nx = k == 0 ? p1 : (k == 1 ? p2 : p0);
  vec3 pv = k == 0 ? p2 : (k == 1 ? p0 : p1);
  float s = sign(area);
  vec2 a = normalize(nx.xy - p.xy), b = normalize(p.xy - pv.xy);
  vec2 na = s * vec2(a.y, -a.x), nb = s * vec2(b.y, -b.x); // outward
  // Each edge moves by u_dilate: the corner goes to the edges' miter point,
  // u_dilate / sin(angle / 2) away. Clamped at 0.25 (at most 2 sqrt(2)
  // u_dilate), the corners sharper than 41 degrees moved less and their
  // edges' ends not at all in effect: a wall that the sun grazes, drawn as
  // two triangles of 20-degree corners, left its foot bare within 0.2 units
  // of its end and lit a floor pixel there (surface_room.json). At 0.01 a
  // corner of 8 degrees still moves fully (14 u_dilate at most).
  float c = max(1.0 + dot(na, nb), 0.01);
  vec2 xy = p.xy + u_dilate * (na + nb) / c;
  // The depth along the triangle's plane (affine in the map's xy).
  vec2 d = xy - p0.xy;
  float u = (d.x * e2.y - d.y * e2.x) / area, v = (e1.x * d.y - e1.y * d.x) / area;
  float z = p0.z + u * (p1.z - p0.z) + v * (p2.z - p0.z);
  gl_Position = vec4(xy, z, 1.0);
#endif
}
