// A test's ambient hook (tests/unit/test_03_light_volumes_gl.cpp): no ambient light, as if
// every pixel were fully occluded.
vec3 ambient_light(vec3 ambient, Surface s, ivec2 pixel) { return vec3(0.0); }
