#pragma once
// The band of pixels near a local light's shadow edge, each pixel by its own reach, shared by
// the cube maps' test (test_06_point_shadows_gl.cpp [point-band]) and the spot atlas's
// (test_06_spot_atlas_gl.cpp [spot-band]); they differ only in the map's texel at a distance.
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "chapters/06_shadows/shadow_stage.h"
#include "chapters/06_shadows/shadow_truth.h"

namespace lp::ch06 {

// texel_at(d): the width in metres of one of the map's texels at distance d from the light.
// Returns the band (true: excused) over a width x height image and its widest reach in *widest.
inline std::vector<bool> light_edge_band(const std::vector<std::optional<Hit>>& hits, const ImageF& truth,
                                         const Light& l, const FrameCamera& cam, const ShadowSettings& s, int r,
                                         int width, int height, const std::function<float(float)>& texel_at,
                                         int* widest) {
  const auto at = [width](int x, int y) { return std::size_t(y) * std::size_t(width) + std::size_t(x); };
  std::vector<bool> edge = hard_edge_pixels(truth, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const auto& h = hits[at(x, y)];
      for (int dy = -1; dy <= 1 && h; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u < 0 || v < 0 || u >= width || v >= height) continue;
          const auto& o = hits[at(u, v)];
          if (o && glm::dot(o->geometric_normal, h->geometric_normal) < 0.99f) edge[at(x, y)] = true;
        }
    }
  std::vector<bool> band(edge.size(), false);
  *widest = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t i = at(x, y);
      if (truth.at(x, y, 2) < 0.5f) continue;
      const Hit& h = *hits[i];
      const float d = glm::distance(h.position, l.position);
      const float c = std::clamp(std::abs(glm::dot(glm::normalize(l.position - h.position), h.shading_normal)), 1e-4f, 1.f);
      const float tan_theta = std::min(std::sqrt(1.f - c * c) / c, kMaxSlope);
      const float texels = 0.5f + s.constant_bias + s.slope_bias * tan_theta + s.normal_offset + float(r);
      const float footprint = h.t * 2.f * std::tan(cam.yfov / 2.f) / float(height);
      const int reach = int(std::ceil(texels * texel_at(d) / footprint));
      *widest = std::max(*widest, reach);
      if (x < reach || y < reach || x >= width - reach || y >= height - reach) band[i] = true;
      for (int dy = -reach; dy <= reach && !band[i]; ++dy)
        for (int dx = -reach; dx <= reach; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u >= 0 && v >= 0 && u < width && v < height && edge[at(u, v)]) {
            band[i] = true;
            break;
          }
        }
    }
  return band;
}

}  // namespace lp::ch06
