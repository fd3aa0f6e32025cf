// Exercise 3 of chapter 01: a spot light's cone.
// `./run 01 --exercise 3` lights the scene with this function; add `--check` to compare.
//
// Return 1 inside the inner angle, 0 outside the outer, and a smooth step between: with
// c = the cosine between the spot's axis (light.direction_range.xyz, pointing away from the
// light) and the direction from the light to the surface (-to_light),
// t = clamp((c - cos(outer)) / (cos(inner) - cos(outer)), 0, 1), and return t squared.
// The light brings both cosines precomputed: light.spot.x = cos(outer),
// light.spot.y = 1 / (cos(inner) - cos(outer)).
float spot_cone(GpuLight light, vec3 to_light) {
  return 1.0;  // a spot that lights all around, like a point light: write the cone
}
