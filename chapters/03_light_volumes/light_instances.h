#pragma once
// The lights as the volume shaders receive them: one small record per light, read as
// per-instance vertex attributes (glVertexAttribDivisor 1), so one instanced draw can place
// a volume at every light. The records are packed tighter than chapter 01's 64-byte
// GpuLight; the shaders unpack them into a GpuLight and light with chapter 01's code.
// shaders/light_instance.glsl is the GLSL twin of this file.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "chapters/01_forward/light_buffer.h"
#include "chapters/03_light_volumes/volume_meshes.h"
#include "common/scene.h"

namespace lp::ch03 {

// [instances]
// A point light: where it is, how far its volume reaches, what it emits. 32 bytes.
struct PointInstance {
  glm::vec4 position_radius;  // xyz: world position, w: the volume's radius (the cut)
  glm::vec4 radiance_range;   // rgb: colour x intensity, w: glTF range (0: unbounded)
};
// A spot light adds where it points and its cone. 48 bytes.
struct SpotInstance {
  glm::vec4 position_radius;  // xyz: apex, w: the cut (the cone's height)
  glm::vec4 radiance_range;
  glm::vec4 direction_cone;   // xy: direction, octahedral (chapter 02's map, in floats);
                              // z: cos(outer); w: 1 / (cos(inner) - cos(outer))
};
// [/instances]
static_assert(sizeof(PointInstance) == 32 && sizeof(SpotInstance) == 48);

PointInstance pack_point(const Light& light, float radius);
SpotInstance pack_spot(const Light& light, float radius);
// What the shaders rebuild: chapter 01's GpuLight, to light with chapter 01's code.
ch01::GpuLight unpack(const PointInstance& p);
ch01::GpuLight unpack(const SpotInstance& s);

// An orthonormal basis whose third axis is the unit vector n (Duff et al. 2017).
glm::mat3 basis_around(const glm::vec3& n);
// Object-to-world matrix of a light's volume (the unit icosphere or the unit cone), the
// same transform the vertex shader applies.
glm::mat4 volume_transform(const PointInstance& p);
glm::mat4 volume_transform(const SpotInstance& s, bool as_cone);

// The lights of a frame sorted by the volume they are drawn with. "Light order", which
// every strategy follows, is points, then cones, then wide spots, each in scene order.
struct LightSet {
  std::vector<ch01::GpuLight> directional;  // full screen, in the global pass
  std::vector<PointInstance> points;        // icosphere
  std::vector<SpotInstance> cones;          // cone
  std::vector<SpotInstance> wide_spots;     // spots wider than the cone pays for: icosphere
  std::vector<std::string> warnings;        // bad input, summarised
  std::size_t local_count() const { return points.size() + cones.size() + wide_spots.size(); }
};

// Cuts every light at `threshold` and packs it. A light that breaks the loader's rule
// (light_defect: a negative range or intensity, no direction...) and one that gives no light
// are left out with a warning; a spot of 90 degrees or more is drawn with a sphere.
LightSet build_light_set(const std::vector<Light>& lights, float threshold, const VolumeShapes& shapes);

}  // namespace lp::ch03
