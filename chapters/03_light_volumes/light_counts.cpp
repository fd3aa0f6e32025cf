#include "chapters/03_light_volumes/light_counts.h"

#include <cstdint>
#include <string>

#include "chapters/01_forward/light_buffer.h"

namespace lp::ch03 {

std::vector<Light> lights_for_count(const Scene& scene, int count) {
  if (count <= 0) return scene.lights;
  std::vector<Light> out, points;
  int local = 0;
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const Light& l : scene.lights) {
    if (l.type == LightType::Directional) {
      out.push_back(l);
      continue;
    }
    if (l.type == LightType::Point) {
      points.push_back(l);
      lo = glm::min(lo, l.position);
      hi = glm::max(hi, l.position);
    }
    if (local < count) {
      out.push_back(l);
      ++local;
    }
  }
  if (points.empty()) return ch01::lights_for_count(scene, count);
  std::uint32_t state = 0x9E3779B9u;  // xorshift32: the same lights on every machine
  auto next = [&state] {
    state ^= state << 13;
    state ^= state >> 17;
    state ^= state << 5;
    return (state >> 8) * (1.f / 16777216.f);
  };
  for (int k = 0; local < count; ++k, ++local) {
    Light l = points[std::size_t(k) % points.size()];
    l.name = "extra_" + std::to_string(k);
    l.position = lo + (hi - lo) * glm::vec3(next(), next(), next());
    out.push_back(l);
  }
  return out;
}

}  // namespace lp::ch03
