#include "chapters/03_light_volumes/volume_meshes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "common/error.h"

namespace lp::ch03 {

float VolumeMesh::plane_distance(std::size_t t, const glm::vec3& p) const {
  const glm::vec3 a = positions[indices[3 * t]], b = positions[indices[3 * t + 1]], c = positions[indices[3 * t + 2]];
  const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
  return glm::dot(n, p - a);
}

bool VolumeMesh::contains(const glm::vec3& p, float margin) const {
  for (std::size_t t = 0; t < triangle_count(); ++t)
    if (plane_distance(t, p) > margin) return false;
  return true;
}

double VolumeMesh::volume() const {
  double v = 0;
  for (std::size_t t = 0; t < triangle_count(); ++t) {
    const glm::dvec3 a = positions[indices[3 * t]], b = positions[indices[3 * t + 1]], c = positions[indices[3 * t + 2]];
    v += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return v;
}

namespace {

// The unit icosahedron's vertices on the sphere, in double precision so that the scale
// that makes it circumscribe is exact to float precision.
struct SphereMesh {
  std::vector<glm::dvec3> positions;
  std::vector<std::uint32_t> indices;
};

SphereMesh subdivided_icosahedron(int subdivisions) {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  SphereMesh m;
  for (glm::dvec3 v : {glm::dvec3(-1, phi, 0), glm::dvec3(1, phi, 0), glm::dvec3(-1, -phi, 0), glm::dvec3(1, -phi, 0),
                       glm::dvec3(0, -1, phi), glm::dvec3(0, 1, phi), glm::dvec3(0, -1, -phi), glm::dvec3(0, 1, -phi),
                       glm::dvec3(phi, 0, -1), glm::dvec3(phi, 0, 1), glm::dvec3(-phi, 0, -1), glm::dvec3(-phi, 0, 1)})
    m.positions.push_back(glm::normalize(v));
  m.indices = {0, 11, 5, 0, 5, 1,  0, 1, 7,   0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,  11, 10, 2, 10, 7, 6, 7, 1, 8,
               3, 9, 4,  3, 4, 2,  3, 2, 6,   3, 6, 8,  3, 8, 9,   4, 9, 5, 2, 4, 11,  6, 2, 10,  8, 6, 7,  9, 8, 1};
  for (int s = 0; s < subdivisions; ++s) {
    // Split every edge once (shared edges share their midpoint), each triangle into four.
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      auto key = std::minmax(a, b);
      auto [it, inserted] = midpoints.try_emplace({key.first, key.second}, 0u);
      if (inserted) {
        it->second = static_cast<std::uint32_t>(m.positions.size());
        m.positions.push_back(glm::normalize(m.positions[a] + m.positions[b]));
      }
      return it->second;
    };
    std::vector<std::uint32_t> next;
    for (std::size_t t = 0; t < m.indices.size(); t += 3) {
      std::uint32_t a = m.indices[t], b = m.indices[t + 1], c = m.indices[t + 2];
      std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    m.indices = std::move(next);
  }
  return m;
}

// [circumscribe]
// The vertices lie on the unit sphere, so the flat triangles between them cut inside it.
// The plane of a triangle is nearest the centre at distance n . a (n its unit normal, a one
// of its vertices); scaling by 1 / min(n . a) moves the nearest plane out to distance 1 and
// every other plane beyond it: the polyhedron then contains the whole unit sphere.
double circumscribing_scale(const SphereMesh& m) {
  double nearest = 1.0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const glm::dvec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]], c = m.positions[m.indices[t + 2]];
    nearest = std::min(nearest, glm::dot(glm::normalize(glm::cross(b - a, c - a)), a));
  }
  return 1.0 / nearest;
}
// [/circumscribe]

void check_subdivisions(int subdivisions) {
  if (subdivisions < 0 || subdivisions > 6)
    throw Error("icosphere subdivisions must be between 0 and 6 (got " + std::to_string(subdivisions) + ")");
}

}  // namespace

VolumeMesh icosphere(int subdivisions) {
  check_subdivisions(subdivisions);
  SphereMesh m = subdivided_icosahedron(subdivisions);
  // Rounding to float could pull a plane a hair inside the sphere; one part in 10^6 more
  // keeps every plane at distance >= 1 after it.
  const double scale = circumscribing_scale(m) * (1.0 + 1e-6);
  VolumeMesh out;
  out.indices = m.indices;
  for (const auto& p : m.positions) out.positions.push_back(glm::vec3(p * scale));
  return out;
}

float icosphere_circumradius(int subdivisions) {
  check_subdivisions(subdivisions);
  return static_cast<float>(circumscribing_scale(subdivided_icosahedron(subdivisions)) * (1.0 + 1e-6));
}

VolumeMesh cone(int sides) {
  if (sides < 3 || sides > 1024) throw Error("a cone needs 3 to 1024 sides (got " + std::to_string(sides) + ")");
  // [cone-mesh]
  // The base polygon's edges touch the unit circle at their midpoints when its corners sit
  // at radius 1 / cos(pi / sides).
  const double corner = 1.0 / std::cos(std::numbers::pi / sides);
  VolumeMesh m;
  m.positions.push_back({0, 0, 0});  // 0: apex
  m.positions.push_back({0, 0, 1});  // 1: centre of the base
  for (int i = 0; i < sides; ++i) {
    double a = 2.0 * std::numbers::pi * i / sides;
    m.positions.push_back(glm::vec3(glm::dvec3(corner * std::cos(a), corner * std::sin(a), 1.0)));
  }
  for (std::uint32_t i = 0; i < std::uint32_t(sides); ++i) {
    std::uint32_t a = 2 + i, b = 2 + (i + 1) % sides;
    m.indices.insert(m.indices.end(), {0, b, a});  // side, seen from outside
    m.indices.insert(m.indices.end(), {1, a, b});  // base, facing +Z
  }
  // [/cone-mesh]
  return m;
}

bool spot_uses_cone(float outer_cone_angle, double unit_cone_volume, double unit_sphere_volume) {
  if (!(outer_cone_angle < 0.5f * std::numbers::pi_v<float>)) return false;  // also NaN
  const double t = std::tan(double(outer_cone_angle));
  return t * t * unit_cone_volume < unit_sphere_volume;
}

VolumeShapes make_volume_shapes(int sphere_subdivisions, int cone_sides) {
  VolumeShapes s{.sphere_subdivisions = sphere_subdivisions, .cone_sides = cone_sides,
                 .sphere = icosphere(sphere_subdivisions), .cone = cone(cone_sides)};
  s.sphere_volume = s.sphere.volume();
  s.cone_volume = s.cone.volume();
  return s;
}

}  // namespace lp::ch03
