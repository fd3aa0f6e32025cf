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

// [neon-gpu]
// One tube as the shaders see it (std430, 96 bytes): the thesis's per-instance matrix M,
// the barn doors and what it has no room for.
//
//   row 0:  Ri x volume radius    | colour.r x intensity       Ri, Rj, Rk: orthonormal and
//   row 1:  Rj x half length      | colour.g x intensity       right-handed; Rj is the axis,
//   row 2:  Rk x specular         | colour.b x intensity       Ri the first door's side
//   row 3:  centre S = (A + B)/2  | caps (1 capsule, 0 cylinder)
//
// GLSL's m[i] is a column, so `rows` holds the ROWS of M: rows[0] is row 0 above. As a
// vertex attribute (mat4, locations k .. k+3) each row arrives as one vec4, as in the thesis.
struct NeonGpu {
  glm::mat4 rows{0};
  glm::vec4 barn_doors{0};  // distance, count, transmittance, softness (count 0: none)
  glm::vec4 extra{0};       // x: the glass tube's radius; y: the doors' radius; zw: 0
};
static_assert(sizeof(NeonGpu) == 96);
// [/neon-gpu]

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
