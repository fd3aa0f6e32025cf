// A light as the culling and shading passes read it, written once for both languages: GLSL
// includes it in grid.glsl (the Lights buffer, std430), C++ in clustered_lights.cpp, which
// packs it from chapter 03's light set and asserts its size (four vec4: no padding).
// A chapter 04 tube (kind.x 2) is binned as its capsule: position_radius holds the segment's
// start and the tube's volume radius (its cut), direction_cone the end and which tube it is in
// the tubes' own buffer (NeonGpu, shaders/shade.glsl), where neon_light() finds the rest.
struct ClusterLight {
  vec4 position_radius;  // xyz world position (a tube's start), w the cut
  vec4 radiance_range;   // chapter 03's packing (light_instances.h); tubes: unused
  vec4 direction_cone;   // spots; tubes: xyz the end, w the tube's index
  vec4 kind;             // x: 0 a point, 1 a spot, 2 a tube
};
