#include "chapters/04_neon/capsule.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lp::ch04 {

namespace {

// A unit vector perpendicular to v (any).
glm::vec3 perpendicular(const glm::vec3& v) {
  glm::vec3 other = std::abs(v.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(v, other));
}

}  // namespace

CapsuleMesh make_capsule(int segments, int rings) {
  segments = std::max(segments, 3);
  rings = std::max(rings, 1);
  constexpr float kPi = std::numbers::pi_v<float>;
  // Latitude rings from the north pole to the equator (upper cap) and on from the equator to
  // the south pole (lower cap): 2 * rings + 1 ring positions, the two equators apart by 1.
  auto ring_point = [&](int ring, int segment) {
    bool upper = ring <= rings;
    int k = upper ? ring : ring - 1;  // the lower cap repeats the equator, one unit lower
    float latitude = kPi / 2 - static_cast<float>(k) * (kPi / 2) / static_cast<float>(rings);
    float longitude = 2 * kPi * static_cast<float>(segment) / static_cast<float>(segments);
    glm::vec3 p(std::cos(latitude) * std::cos(longitude), std::sin(latitude), -std::cos(latitude) * std::sin(longitude));
    return p + glm::vec3(0, upper ? 0.5f : -0.5f, 0);
  };
  CapsuleMesh mesh;
  const int ring_count = 2 * rings + 2;  // north pole .. upper equator, lower equator .. south pole
  for (int r = 0; r < ring_count; ++r) {
    bool pole = r == 0 || r == ring_count - 1;
    for (int s = 0; s < (pole ? 1 : segments); ++s) mesh.positions.push_back(ring_point(r, s));
  }
  // Vertex index of (ring, segment): the poles hold one vertex, the other rings `segments`.
  auto at = [&](int r, int s) -> std::uint32_t {
    if (r == 0) return 0;
    if (r == ring_count - 1) return static_cast<std::uint32_t>(mesh.positions.size() - 1);
    return static_cast<std::uint32_t>(1 + (r - 1) * segments + (s % segments));
  };
  for (int r = 0; r + 1 < ring_count; ++r)
    for (int s = 0; s < segments; ++s) {
      std::uint32_t a = at(r, s), b = at(r, s + 1), c = at(r + 1, s), d = at(r + 1, s + 1);
      if (r == 0) {
        mesh.indices.insert(mesh.indices.end(), {a, c, d});
      } else if (r + 2 == ring_count) {
        mesh.indices.insert(mesh.indices.end(), {a, c, b});
      } else {
        mesh.indices.insert(mesh.indices.end(), {a, c, d, a, d, b});
      }
    }
  // [capsule-circumscribe]
  // Each face is flat, so its middle lies inside the round capsule. Find the face that comes
  // nearest the axis segment (y in [-0.5, 0.5]) and push every vertex out by 1 / that
  // distance: then no face is nearer than 1, and the mesh encloses the unit capsule.
  float nearest = 1;
  for (size_t i = 0; i < mesh.indices.size(); i += 3) {
    glm::vec3 p0 = mesh.positions[mesh.indices[i]], p1 = mesh.positions[mesh.indices[i + 1]],
              p2 = mesh.positions[mesh.indices[i + 2]];
    glm::vec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    // A plane's distance to a segment it does not cross: the nearer of the ends.
    float plane = glm::dot(n, p0);
    nearest = std::min(nearest, std::min(plane - glm::dot(n, glm::vec3(0, 0.5f, 0)), plane - glm::dot(n, glm::vec3(0, -0.5f, 0))));
  }
  mesh.scale = 1.f / nearest;
  for (auto& p : mesh.positions) {
    float centre = p.y > 0 ? 0.5f : -0.5f;  // the cap's centre; the cylinder's rings are on it
    p = glm::vec3(p.x * mesh.scale, centre + (p.y - centre) * mesh.scale, p.z * mesh.scale);
  }
  // [/capsule-circumscribe]
  return mesh;
}

// [pack-neon]
NeonGpu pack_neon(const NeonLight& light, float volume_radius) {
  glm::vec3 axis = light.end - light.start;
  float half_length = 0.5f * glm::length(axis);
  // Rj along the tube; Ri the doors' side made perpendicular to it; Rk completes the frame.
  glm::vec3 rj = half_length > 0 ? axis / (2.f * half_length) : perpendicular(light.door_axis);
  glm::vec3 ri = light.door_axis - glm::dot(light.door_axis, rj) * rj;
  ri = glm::dot(ri, ri) > 1e-12f ? glm::normalize(ri) : perpendicular(rj);
  glm::vec3 rk = glm::cross(ri, rj);
  glm::vec3 power = light.color * light.intensity;
  NeonGpu g{};
  g.rows[0] = glm::vec4(ri * volume_radius, power.r);
  g.rows[1] = glm::vec4(rj * half_length, power.g);
  g.rows[2] = glm::vec4(rk * light.specular, power.b);
  g.rows[3] = glm::vec4(0.5f * (light.start + light.end), light.caps ? 1.f : 0.f);
  const BarnDoors& d = light.barn_doors;
  g.barn_doors = glm::vec4(d.distance, d.count, d.transmittance, d.softness);
  g.extra = glm::vec4(light.radius, doors_radius(light), 0, 0);
  return g;
}
// [/pack-neon]

UnpackedNeon unpack_neon(const NeonGpu& g) {
  UnpackedNeon u;
  glm::vec3 ri_r(g.rows[0]), rj_h(g.rows[1]), rk_i(g.rows[2]);
  u.volume_radius = glm::length(ri_r);
  float half_length = glm::length(rj_h), specular = glm::length(rk_i);
  glm::vec3 ri = ri_r / u.volume_radius;
  // A zero-length tube or a zero specular loses a direction; the others rebuild it.
  glm::vec3 rk = specular > 0 ? rk_i / specular : glm::vec3(0);
  glm::vec3 rj = half_length > 0 ? rj_h / half_length : specular > 0 ? glm::cross(rk, ri) : perpendicular(ri);
  if (specular <= 0) rk = glm::cross(ri, rj);
  u.basis = glm::mat3(ri, rj, rk);
  glm::vec3 centre(g.rows[3]);
  NeonLight& l = u.light;
  l.start = centre - rj * half_length;
  l.end = centre + rj * half_length;
  l.door_axis = ri;
  l.color = glm::vec3(g.rows[0].w, g.rows[1].w, g.rows[2].w);
  l.intensity = 1;
  l.specular = specular;
  l.caps = g.rows[3].w > 0.5f;
  l.radius = g.extra.x;
  u.doors_radius = g.extra.y;
  l.barn_doors = {g.barn_doors.x, g.barn_doors.y, g.barn_doors.z, g.barn_doors.w};
  return u;
}

// [capsule-vertex]
glm::vec3 capsule_vertex(const glm::vec3& v, const NeonGpu& g, float radius_override) {
  UnpackedNeon u = unpack_neon(g);
  float radius = radius_override > 0 ? radius_override : u.volume_radius;
  float half_length = 0.5f * u.light.length();
  float side = v.y >= 0 ? 1.f : -1.f;               // which cap the vertex belongs to
  float cap = (v.y - side * 0.5f) * radius;         // its height above the cap's centre...
  cap *= g.rows[3].w;                             // ...flattened to 0 for a cylinder
  glm::vec3 local(v.x * radius, cap + side * half_length, v.z * radius);
  return u.basis * local + glm::vec3(g.rows[3]);  // rotate into (Ri, Rj, Rk), move to S
}
// [/capsule-vertex]

}  // namespace lp::ch04
