// The shading normal, for every pass that shades a surface (chapter 01's forward pass,
// chapter 02's geometry pass, and the passes after them that draw meshes).
// [surface-normal]
// The interpolated normal, renormalised (interpolation shortens unit vectors: the chord
// between two points of a sphere lies inside it), then bent by the normal map in the tangent
// frame: tangent T straightened against N (Gram-Schmidt), bitangent B = sign * N x T.
// A reader's mesh may bring what cannot be used: a zero normal falls back to the triangle's
// own (from the position's derivatives); a tangent along the normal (or none: the loader
// leaves it zero) leaves Gram-Schmidt nothing, so the map is skipped rather than a NaN made.
// A back face reaches this only for a doubleSided material (SceneGpu::draw culls the others):
// glTF lights it with the normal reversed. `renormalize` is false only to show what goes
// wrong without it (chapter 01's mode).
vec3 surface_normal(vec3 normal, vec4 tangent, vec3 position, vec2 uv, bool renormalize, bool has_normal_map,
                    sampler2D normal_map, float normal_scale) {
  vec3 n = normal;
  if (!(dot(n, n) > 1e-20)) n = cross(dFdx(position), dFdy(position));
  else if (!gl_FrontFacing) n = -n;  // a doubleSided material seen from behind (others are culled)
  if (renormalize) n = normalize(n);
  if (!has_normal_map) return n;
  vec3 t = tangent.xyz - n * dot(n, tangent.xyz);
  if (!(dot(t, t) > 1e-12)) return n;
  t = normalize(t);
  vec3 b = cross(n, t) * (tangent.w < 0.0 ? -1.0 : 1.0);
  vec3 m = texture(normal_map, uv).xyz * 2.0 - 1.0;
  m.xy *= normal_scale;
  vec3 bent = mat3(t, b, n) * m;
  return dot(bent, bent) > 1e-20 ? normalize(bent) : n;
}
// [/surface-normal]
