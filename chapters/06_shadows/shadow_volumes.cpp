#include "chapters/06_shadows/shadow_volumes.h"

#include <cstdlib>
#include <cstring>
#include <map>
#include <unordered_map>
#include <utility>
#include <algorithm>

namespace lp::ch06 {

namespace {
struct PositionKey {
  std::uint32_t x, y, z;
  bool operator==(const PositionKey&) const = default;
};
struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    return (std::size_t(k.x) * 73856093u) ^ (std::size_t(k.y) * 19349663u) ^ (std::size_t(k.z) * 83492791u);
  }
};
PositionKey key_of(glm::vec3 p) {
  PositionKey k;
  p += glm::vec3(0.f);  // -0 and +0 weld
  std::memcpy(&k.x, &p.x, 4), std::memcpy(&k.y, &p.y, 4), std::memcpy(&k.z, &p.z, 4);
  return k;
}
}  // namespace

// [adjacency-build]
MeshAdjacency build_adjacency(const Scene& scene, const Mesh& mesh) {
  MeshAdjacency m;
  std::unordered_map<PositionKey, std::uint32_t, PositionHash> weld;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edge_of;
  for (const Primitive& prim : mesh.primitives) {
    const bool two_sided = scene.materials[std::size_t(prim.material)].double_sided;
    for (std::uint32_t t = 0; t + 3 <= prim.index_count; t += 3) {
      std::uint32_t c[3];
      for (int i = 0; i < 3; ++i) {
        const glm::vec3 p = scene.vertices[scene.indices[prim.first_index + t + std::uint32_t(i)]].position;
        auto [it, added] = weld.try_emplace(key_of(p), std::uint32_t(m.corners.size()));
        if (added) m.corners.push_back(p);
        c[i] = it->second;
      }
      if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) continue;  // degenerate: casts nothing
      const auto tri = std::uint32_t(m.triangles.size() / 3);
      m.triangles.insert(m.triangles.end(), c, c + 3);
      m.double_sided.push_back(two_sided);
      for (int i = 0; i < 3; ++i) {
        const std::uint32_t from = c[i], to = c[(i + 1) % 3];
        const auto key = std::minmax(from, to);
        auto [it, added] = edge_of.try_emplace({key.first, key.second}, std::uint32_t(m.edges.size()));
        if (added) {
          MeshAdjacency::Edge e;
          e.a = key.first, e.b = key.second;
          m.edges.push_back(std::move(e));
        }
        m.edges[it->second].uses.push_back(MeshAdjacency::Use{tri, from < to ? +1 : -1});
      }
    }
  }
  for (const auto& e : m.edges) {
    m.open_edges += e.uses.size() == 1;
    m.non_manifold_edges += e.uses.size() > 2;
  }
  return m;
}
// [/adjacency-build]

// [volume-build]
VolumeCounts append_sun_volume(const MeshAdjacency& mesh, const glm::mat4& model, glm::vec3 sun_direction,
                               float offset, std::vector<glm::vec4>& out) {
  VolumeCounts counts;
  const glm::vec3 d = glm::normalize(sun_direction);
  std::vector<glm::vec3> world(mesh.corners.size());
  for (std::size_t i = 0; i < world.size(); ++i) world[i] = glm::vec3(model * glm::vec4(mesh.corners[i], 1.f)) + offset * d;
  // Per triangle: 0 casts nothing, +1 casts with its winding, -1 with its winding turned.
  const std::size_t n = mesh.triangles.size() / 3;
  std::vector<signed char> cast(n, 0);
  const bool closed = mesh.open_edges == 0 && mesh.non_manifold_edges == 0;
  for (std::size_t t = 0; t < n; ++t) {
    const glm::vec3 a = world[mesh.triangles[3 * t]], b = world[mesh.triangles[3 * t + 1]],
                    c = world[mesh.triangles[3 * t + 2]];
    const float facing = glm::dot(glm::cross(b - a, c - a), -d);
    if (facing > 0.f) cast[t] = 1;
    else if (facing < 0.f && (mesh.double_sided[t] || !closed)) cast[t] = -1;
    if (!cast[t]) continue;
    // The cap, wound to face the light (outward: the prism lies beyond it).
    out.push_back(glm::vec4(a, 1.f));
    out.push_back(glm::vec4(cast[t] > 0 ? b : c, 1.f));
    out.push_back(glm::vec4(cast[t] > 0 ? c : b, 1.f));
    ++counts.cap_triangles;
  }
  const glm::vec4 infinity(d, 0.f);
  for (const auto& e : mesh.edges) {
    int net = 0;  // casting triangles running a -> b, minus those running b -> a
    for (const auto& u : e.uses) net += cast[u.triangle] * u.direction;
    // A cap running from -> to has the outward side (from, to, to at infinity): a triangle for
    // the sun, whose two far corners are the same point at infinity.
    const glm::vec3 from = world[net > 0 ? e.a : e.b], to = world[net > 0 ? e.b : e.a];
    for (int i = 0; i < std::abs(net); ++i) {
      out.push_back(glm::vec4(from, 1.f));
      out.push_back(infinity);
      out.push_back(glm::vec4(to, 1.f));
      ++counts.side_quads;
    }
  }
  return counts;
}
// [/volume-build]

}  // namespace lp::ch06
