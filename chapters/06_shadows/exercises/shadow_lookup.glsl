// Exercise 1 of chapter 06: where a pixel looks up the sun's map, and the bias.
// `./run 06 --exercise 1 --mode hard` shadows the atrium with this function; add `--check`.
//
// A map texel covers a patch of the receiver; tilted towards the light by theta, the patch's
// depth spans tan(theta) texels, and half of it lies behind the stored depth: shadow acne.
// Return the lookup (the map's u, v and the receiver's window depth), the depth moved
// towards the light by a bias, and the point first pushed off its surface:
//   cos = clamp(dot(s.normal, to_light), 1e-4, 1), sin = sqrt(1 - cos^2), tan = min(sin / cos, 10);
//   p = s.position + s.normal * (sh.normal_offset * sh_map.texel_metres * sin)   (normal offset)
//   window = the map's clip position of p (sh_map.matrix), divided by w, times 0.5 plus 0.5;
//   bias = sh_map.texel_metres * (sh.constant_bias + sh.slope_bias * tan) / sh.depth_range
//   (texels to metres, then metres to window depth: the light's projection is orthographic).
vec3 shadow_lookup(Surface s, vec3 to_light) {
  vec4 clip = sh_map.matrix * vec4(s.position, 1.0);
  return clip.xyz / clip.w * 0.5 + 0.5;  // no bias, no offset: acne. Write the bias.
}
