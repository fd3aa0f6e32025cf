#pragma once
// The neon light's volume: a capsule (a cylinder with hemispherical caps) around the tube,
// or, without caps, a cylinder, as in the thesis (section 4.4.5). One unit mesh serves every
// tube; a packed 4x4 matrix per instance places it (shaders/capsule.vert does it on the GPU,
// capsule_vertex() below on the CPU). The same mesh, with the tube's own radius, draws the
// glowing glass.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "chapters/04_neon/neon.h"

namespace lp::ch04 {

// [capsule-mesh]
// The unit capsule, axis +Y: two hemispheres of radius 1 centred at y = -0.5 and y = +0.5,
// joined by a cylinder (the thesis cuts the unit sphere at y = 0 and moves the halves apart
// by one unit). `segments` around the axis, `rings` from each equator to its pole.
// Vertices are pushed outwards so that the faces enclose the exact capsule (a mesh through
// points ON the capsule would cut corners, and a light volume must not miss lit pixels).
struct CapsuleMesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;  // counter-clockwise seen from outside
  float scale = 1;                     // how far the vertices were pushed out
};
CapsuleMesh make_capsule(int segments = 16, int rings = 4);
// [/capsule-mesh]

namespace glsl {
using glm::mat4;
using glm::vec4;
#include "chapters/04_neon/shaders/neon_gpu.h"  // struct NeonGpu, shared with GLSL
}  // namespace glsl
using glsl::NeonGpu;
static_assert(sizeof(NeonGpu) == 96, "std430: a mat4 and two vec4");

NeonGpu pack_neon(const NeonLight& light, float volume_radius);

// What pack_neon() stored, read back as the shaders read it. Colour and intensity come back
// multiplied (colour = colour x intensity, intensity = 1): the same light for every method.
struct UnpackedNeon {
  NeonLight light;
  float volume_radius = 0;
  float doors_radius = 0;  // neon.h's doors_radius()
  glm::mat3 basis{1};  // columns Ri, Rj, Rk
};
UnpackedNeon unpack_neon(const NeonGpu& gpu);

// Where the vertex shader puts a vertex of make_capsule() for this tube (radius_override > 0:
// that radius instead of the volume radius, e.g. the glass tube itself).
glm::vec3 capsule_vertex(const glm::vec3& unit_vertex, const NeonGpu& gpu, float radius_override = 0);

}  // namespace lp::ch04
