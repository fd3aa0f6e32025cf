// A light as the culling and shading passes read it, written once for both languages: GLSL
// includes it in grid.glsl (the Lights buffer, std430), C++ in clustered_lights.cpp, which
// packs it from chapter 03's light set and asserts its size (four vec4: no padding).
struct ClusterLight {
  vec4 position_radius;  // xyz world position, w the cut
  vec4 radiance_range;   // chapter 03's packing (light_instances.h)
  vec4 direction_cone;   // spots only
  vec4 kind;             // x: 1 for a spot
};
