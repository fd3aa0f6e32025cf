// A test's ambient hook (tests/unit/test_03_light_volumes_gl.cpp): the ambient light scaled by
// a pattern of the pixel it is given, so a pass that hands the hook another pixel than the one
// it writes shows.
vec3 ambient_light(vec3 ambient, Surface s, ivec2 pixel) {
  return ambient * vec3(float(pixel.x % 7) / 6.0, float(pixel.y % 5) / 4.0, 1.0);
}
