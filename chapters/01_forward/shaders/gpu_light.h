// [light-struct]
// One light as the shaders see it, 64 bytes in std430. Written once for both languages:
// lighting.glsl includes this file, and so does light_buffer.h (inside a namespace where vec4
// is glm::vec4), so the C++ that packs a light and the GLSL that reads it cannot drift.
struct GpuLight {
  vec4 position_type;    // xyz: world position, w: 0 directional, 1 point, 2 spot
  vec4 direction_range;  // xyz: direction the light shines, w: range (0 = unbounded)
  vec4 radiance;         // rgb: colour x intensity
  vec4 spot;             // x: cos(outer cone), y: 1 / (cos(inner) - cos(outer))
};
// [/light-struct]
