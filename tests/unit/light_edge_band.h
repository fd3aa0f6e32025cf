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

// How far, in the map's texels, the map may move a shadow edge for the receiver `h`: half a
// texel (the nearest texel), the biases with its tan(theta) capped as the hook caps it, the
// normal offset and the filter's radius r.
inline float reach_texels(const Hit& h, const Light& l, const ShadowSettings& s, int r) {
  const float c = std::clamp(std::abs(glm::dot(glm::normalize(l.position - h.position), h.shading_normal)), 1e-4f, 1.f);
  const float tan_theta = std::min(std::sqrt(1.f - c * c) / c, kMaxSlope);
  return 0.5f + s.constant_bias + s.slope_bias * tan_theta + s.normal_offset + float(r);
}

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
      const float texels = reach_texels(h, l, s, r);
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

// [receiver-probe]
// What the image's pixel centres cannot show: a lit gap between two casters' shadows (or a
// shadow as thin) narrower than a pixel's footprint lies between the truth's samples, so the
// truth's image has no edge there, yet the map's texels and PCF's taps, a texel apart on the
// receiver, reach it. So a pixel is also in the band when a lit/shadowed boundary lies within
// its reach on the receiver itself: the hit's tangent plane probed on a square grid of half a
// texel (`texel` metres at the receiver) out to `reach` metres, one occlusion ray from each
// point toward the light, as the truth's own. A gap narrower than half a texel could still fall
// between the probes; a probe that leaves the receiver's face (past a corner, into another
// surface) may find a boundary that is not there, which only widens the band near geometry.
inline bool boundary_on_receiver(const RayScene& rays, const Hit& h, const Light& l, float reach, float texel,
                                 bool lit) {
  const glm::vec3 n = h.geometric_normal;
  const glm::vec3 a = glm::normalize(glm::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0)) : glm::cross(n, glm::vec3(0, 1, 0)));
  const glm::vec3 b = glm::cross(n, a);
  const float step = 0.5f * texel;
  const int k = int(std::ceil(reach / step));
  for (int j = -k; j <= k; ++j)
    for (int i = -k; i <= k; ++i) {
      const glm::vec3 q = h.position + (float(i) * a + float(j) * b) * step;
      const SurfacePoint p{q, glm::dot(n, l.position - q) > 0.f ? n : -n, h.error};
      if (rays.occluded(p.ray_towards(l.position)) == lit) return true;
    }
  return false;
}
// [/receiver-probe]

// The probe where it matters: at each pixel outside `band` that the light reaches (the truth's
// blue channel) and where the map's visibility `v` and the truth differ, the band on the
// receiver added to `band` (elsewhere it would change nothing but the count compared, which is
// then an upper bound). texel_at(d) as light_edge_band's. Returns the pixels probed and those
// it excused.
struct ProbeCount {
  std::size_t probed = 0, excused = 0;
};
inline ProbeCount probe_receivers(const RayScene& rays, const std::vector<std::optional<Hit>>& hits, const ImageF& truth,
                                  const ImageF& v, const Light& l, const ShadowSettings& s, int r, int width,
                                  int height, const std::function<float(float)>& texel_at, std::vector<bool>& band) {
  ProbeCount n;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
      if (band[i] || truth.at(x, y, 2) < 0.5f || v.at(x, y, 0) == truth.at(x, y, 0)) continue;
      const Hit& h = *hits[i];
      const float texel = texel_at(glm::distance(h.position, l.position));
      ++n.probed;
      if (boundary_on_receiver(rays, h, l, reach_texels(h, l, s, r) * texel, texel, truth.at(x, y, 0) > 0.5f))
        band[i] = true, ++n.excused;
    }
  return n;
}

}  // namespace lp::ch06
