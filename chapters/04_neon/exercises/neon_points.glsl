// Exercise 1 of chapter 04: the tube as point lights.
// `./run 04 --mode points --exercise 1` lights with this function; add `--check` to compare.
//
// Spread the tube's unit intensity over `count` of chapter 01's point lights, evenly along
// the segment from t.start to t.end (light i at the centre of the i-th of count equal
// pieces), each with radiance 1 / count, no range, and light the surface s with each:
// light_incident() and blinn_phong() (s.normal, s.to_eye, s.exponent, s.position). Return
// the summed (diffuse, specular), one channel of each (the light is white).
vec2 neon_points(NeonSurface s, Neon t, int count) {
  return vec2(0.0);  // no light from the tube: write the point lights
}
