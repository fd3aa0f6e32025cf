#include "chapters/01_forward/light_buffer.h"

#include <cmath>
#include <cstdint>

namespace lp::ch01 {

GpuLight pack_light(const Light& l) {
  float type = l.type == LightType::Directional ? 0.f : l.type == LightType::Point ? 1.f : 2.f;
  float cos_outer = std::cos(l.outer_cone), cos_inner = std::cos(l.inner_cone);
  return {glm::vec4(l.position, type), glm::vec4(l.direction, l.range), glm::vec4(l.color * l.intensity, 0),
          glm::vec4(cos_outer, 1.f / std::max(1e-4f, cos_inner - cos_outer), 0, 0)};
}

std::vector<Light> lights_for_count(const Scene& scene, int count) {
  if (count <= 0) return scene.lights;
  std::vector<Light> out(scene.lights.begin(), scene.lights.begin() + std::min<size_t>(count, scene.lights.size()));
  std::uint32_t state = 0x2545F491u;  // xorshift32: the same lights on every machine
  auto next = [&state] {
    state ^= state << 13; state ^= state >> 17; state ^= state << 5;
    return (state >> 8) * (1.f / 16777216.f);
  };
  glm::vec3 lo = scene.bounds_min, hi = scene.bounds_max;
  while (static_cast<int>(out.size()) < count) {
    Light l;
    l.name = "extra" + std::to_string(out.size());
    l.type = LightType::Point;
    l.position = glm::vec3(lo.x + (hi.x - lo.x) * next(), lo.y + 0.3f + 2.f * next(), lo.z + (hi.z - lo.z) * next());
    float hue = next() * 6.f;
    l.color = glm::clamp(glm::vec3(std::abs(hue - 3.f) - 1.f, 2.f - std::abs(hue - 2.f), 2.f - std::abs(hue - 4.f)), 0.f, 1.f);
    l.intensity = 1.5f;
    l.range = 4.f;
    out.push_back(l);
  }
  return out;
}

void LightBuffer::upload(const std::vector<Light>& lights) {
  std::vector<GpuLight> packed;
  packed.reserve(lights.size());
  for (const auto& l : lights) packed.push_back(pack_light(l));
  buffer_ = gl::make_buffer(packed.data(), packed.size() * sizeof(GpuLight));
  count_ = static_cast<int>(lights.size());
}

}  // namespace lp::ch01
