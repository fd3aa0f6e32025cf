// Chapter 04's volume: the capsule mesh encloses the exact capsule, the capsule encloses
// every point the tube lights by more than one 8-bit step, and the packed per-instance
// matrix round-trips.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "chapters/04_neon/capsule.h"
#include "test_04_configs.h"

using namespace lp::ch04;
using namespace lp::ch04::testing;

namespace {

struct Plane {
  glm::vec3 n;
  float c;  // n . x = c on the plane, outward normal
};

std::vector<Plane> planes(const std::vector<glm::vec3>& p, const std::vector<std::uint32_t>& idx) {
  std::vector<Plane> out;
  for (size_t i = 0; i < idx.size(); i += 3) {
    glm::vec3 n = glm::cross(p[idx[i + 1]] - p[idx[i]], p[idx[i + 2]] - p[idx[i]]);
    if (glm::length(n) < 1e-9f) continue;  // a flattened cap's degenerate triangle
    n = glm::normalize(n);
    out.push_back({n, glm::dot(n, p[idx[i]])});
  }
  return out;
}

bool inside(const std::vector<Plane>& hull, const glm::vec3& x) {
  for (const auto& pl : hull)
    if (glm::dot(pl.n, x) > pl.c + 1e-5f) return false;
  return true;
}

NeonLight lit_tube() {
  NeonLight l = test_tube();
  l.start = {0.5f, 1.2f, -0.3f};
  l.end = {2.1f, 1.5f, 0.4f};
  l.door_axis = glm::normalize(glm::cross(l.end - l.start, glm::vec3(0, 0, 1)));
  l.intensity = 0.005f;  // dim, so the volume is small enough to sample densely
  l.color = {1, 0.4f, 0.2f};
  l.specular = 0.7f;
  l.radius = 0.03f;
  l.barn_doors = {0.1f, 3, 0.4f, 0.8f};
  return l;
}

}  // namespace

TEST(NeonCapsule, MeshIsClosedAndFacesOutwards) {
  CapsuleMesh m = make_capsule(16, 4);
  // Closed: every directed edge appears once and its reverse once.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (size_t i = 0; i < m.indices.size(); i += 3)
    for (int k = 0; k < 3; ++k) ++edges[{m.indices[i + k], m.indices[i + (k + 1) % 3]}];
  for (const auto& [e, count] : edges) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(edges.count({e.second, e.first}), 1u) << e.first << "-" << e.second;
  }
  // Counter-clockwise from outside: each normal points away from the axis segment.
  for (size_t i = 0; i < m.indices.size(); i += 3) {
    glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]], c = m.positions[m.indices[i + 2]];
    glm::vec3 centre = (a + b + c) / 3.f, axis_point(0, std::clamp(centre.y, -0.5f, 0.5f), 0);
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), centre - axis_point), 0.f) << "triangle " << i / 3;
  }
  EXPECT_EQ(m.positions.size(), 2u + 2u * 4u * 16u);  // two poles, 2 x 4 rings of 16
}

TEST(NeonCapsule, MeshEnclosesTheUnitCapsuleTightly) {
  for (auto [segments, rings] : {std::pair{6, 1}, std::pair{16, 4}, std::pair{24, 6}}) {
    CapsuleMesh m = make_capsule(segments, rings);
    // The capsule (radius 1 around y in [-0.5, 0.5]) lies inside a face's plane when both
    // ends of the axis are at least 1 below it.
    float nearest = 1e9f;
    for (const auto& pl : planes(m.positions, m.indices))
      nearest = std::min(nearest, pl.c - std::max(glm::dot(pl.n, glm::vec3(0, 0.5f, 0)), glm::dot(pl.n, glm::vec3(0, -0.5f, 0))));
    EXPECT_GE(nearest, 1.f - 1e-5f) << segments << "x" << rings;
    EXPECT_LE(nearest, 1.f + 1e-5f);  // and touches it: pushed out no more than needed
    // The price of a coarse mesh: its vertices stand out by `scale`. 24 x 6: under 2 %.
    if (segments == 24) {
      EXPECT_LT(m.scale, 1.02f);
    }
  }
}

TEST(NeonCapsule, ContainsEverythingTheTubeLightsByMoreThanOneStep) {
  // Outside the placed mesh no point gets more than the cut (kNeonCut, one sRGB step at black
  // for a white matte surface) from the tube, whatever its normal:
  // the irradiance there is at most (I max(colour) / L) times the integral of ds / r^2,
  // exactly (atan), on a grid 10 cm apart around the volume.
  NeonLight l = lit_tube();
  float radius = volume_radius(l);
  ASSERT_GT(radius, 0.3f);
  ASSERT_LT(radius, 8.f);
  NeonGpu g = pack_neon(l, radius);
  CapsuleMesh m = make_capsule(24, 6);
  std::vector<glm::vec3> placed;
  for (const auto& v : m.positions) placed.push_back(capsule_vertex(v, g));
  std::vector<Plane> hull = planes(placed, m.indices);
  glm::vec3 u = glm::normalize(l.end - l.start);
  auto brightest = [&](const glm::vec3& x) {  // (I / L) x the integral of ds / r^2, exactly
    double s0 = glm::dot(l.start - x, u), s1 = s0 + l.length();
    double d = glm::length(glm::cross(l.start - x, u));
    double integral = d > 1e-6 ? (std::atan(s1 / d) - std::atan(s0 / d)) / d : (s0 * s1 > 0 ? 1 / s0 - 1 / s1 : 1e30);
    return integral * l.intensity / l.length();  // max colour 1
  };
  glm::vec3 lo = glm::min(l.start, l.end) - glm::vec3(radius * 1.1f), hi = glm::max(l.start, l.end) + glm::vec3(radius * 1.1f);
  int outside = 0, lit_inside = 0;
  for (float x = lo.x; x <= hi.x; x += 0.1f)
    for (float y = lo.y; y <= hi.y; y += 0.1f)
      for (float z = lo.z; z <= hi.z; z += 0.1f) {
        glm::vec3 p(x, y, z);
        double e = brightest(p);
        if (!inside(hull, p)) {
          ++outside;
          ASSERT_LE(e, kNeonCut * (1 + 1e-3)) << "lit outside the capsule at " << x << " " << y << " " << z;
        } else if (e > kNeonCut) {
          ++lit_inside;
        }
      }
  EXPECT_GT(outside, 1000);
  EXPECT_GT(lit_inside, 1000);
}

TEST(NeonCapsule, CylinderModeEndsFlatAtTheTubesEnds) {
  NeonLight l = lit_tube();
  l.caps = false;
  float radius = volume_radius(l);
  NeonGpu g = pack_neon(l, radius);
  glm::vec3 u = glm::normalize(l.end - l.start);
  float length = l.length(), top = -1e9f, bottom = 1e9f;
  for (const auto& v : make_capsule(24, 6).positions) {
    float along = glm::dot(capsule_vertex(v, g) - l.start, u);
    top = std::max(top, along);
    bottom = std::min(bottom, along);
  }
  EXPECT_NEAR(bottom, 0.f, 1e-5f);
  EXPECT_NEAR(top, length, 1e-5f);
  // With caps the volume reaches a radius (times the mesh's outward push) beyond each end.
  l.caps = true;
  g = pack_neon(l, radius);
  CapsuleMesh m = make_capsule(24, 6);
  top = -1e9f;
  for (const auto& v : m.positions) top = std::max(top, glm::dot(capsule_vertex(v, g) - l.start, u));
  EXPECT_NEAR(top, length + radius * m.scale, 1e-4f);
}

TEST(NeonCapsule, PackedMatrixRoundTrips) {
  NeonLight l = lit_tube();
  float radius = volume_radius(l);
  NeonGpu g = pack_neon(l, radius);
  // The thesis's layout: rows Ri R | r, Rj H | g, Rk I | b, S | caps.
  EXPECT_NEAR(glm::length(glm::vec3(g.rows[0])), radius, 1e-5f);
  EXPECT_NEAR(glm::length(glm::vec3(g.rows[1])), 0.5f * l.length(), 1e-5f);
  EXPECT_NEAR(glm::length(glm::vec3(g.rows[2])), l.specular, 1e-6f);
  EXPECT_EQ(glm::vec3(g.rows[0].w, g.rows[1].w, g.rows[2].w), l.color * l.intensity);
  EXPECT_EQ(g.rows[3].w, 1.f);
  UnpackedNeon u = unpack_neon(g);
  EXPECT_NEAR(glm::length(u.light.start - l.start), 0.f, 1e-5f);
  EXPECT_NEAR(glm::length(u.light.end - l.end), 0.f, 1e-5f);
  EXPECT_NEAR(u.volume_radius, radius, 1e-5f);
  EXPECT_EQ(u.light.radius, l.radius);
  EXPECT_EQ(u.light.barn_doors.count, 3.f);
  EXPECT_NEAR(glm::length(u.light.door_axis - l.door_axis), 0.f, 1e-5f);
  // An orthonormal, right-handed frame with the axis as its second column.
  glm::mat3 b = u.basis;
  EXPECT_NEAR(glm::determinant(b), 1.f, 1e-5f);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(glm::dot(b[i], b[j]), i == j ? 1.f : 0.f, 1e-5f);
  // The same light for every method, read back.
  NeonSurface s{{1, 0.2f, 0.5f}, glm::normalize(glm::vec3(0.2f, 1, 0.1f)), glm::normalize(glm::vec3(-0.3f, 1, 0.4f)), 40};
  for (Method m : {Method::GroundTruth, Method::Improved, Method::Source, Method::RepresentativePoint}) {
    NeonResult a = neon_light(s, l, m, 128, radius), c = neon_light(s, u.light, m, 128, u.volume_radius);
    EXPECT_NEAR(glm::length(a.diffuse - c.diffuse), 0.f, 1e-4f * glm::length(a.diffuse) + 1e-7f);
    EXPECT_NEAR(glm::length(a.specular - c.specular), 0.f, 1e-4f * glm::length(a.specular) + 1e-7f);
  }
}

TEST(NeonCapsule, ZeroLengthTubePacksToASphere) {
  NeonLight l = lit_tube();
  l.end = l.start;
  l.specular = 0;  // loses Rk too: the frame is rebuilt from Ri alone
  float radius = volume_radius(l);
  NeonGpu g = pack_neon(l, radius);
  UnpackedNeon u = unpack_neon(g);
  EXPECT_NEAR(glm::determinant(u.basis), 1.f, 1e-5f);
  CapsuleMesh m = make_capsule(24, 6);
  for (const auto& v : m.positions) {
    float r = glm::length(capsule_vertex(v, g) - l.start);
    ASSERT_TRUE(std::isfinite(r));
    EXPECT_GE(r, radius * 0.999f);           // the faces enclose the sphere...
    EXPECT_LE(r, radius * m.scale * 1.001f);  // ...and the vertices are pushed out by `scale`
  }
}

TEST(NeonCapsule, GlassUsesTheTubesOwnRadius) {
  NeonLight l = lit_tube();
  NeonGpu g = pack_neon(l, volume_radius(l));
  CapsuleMesh m = make_capsule(24, 6);
  for (const auto& v : m.positions) {
    glm::vec3 p = capsule_vertex(v, g, l.radius);
    float t = closest_on_segment(p, l.start, l.end);
    float r = glm::length(p - glm::mix(l.start, l.end, t));
    EXPECT_GE(r, l.radius * 0.999f);
    EXPECT_LE(r, l.radius * m.scale * 1.001f);
  }
}
