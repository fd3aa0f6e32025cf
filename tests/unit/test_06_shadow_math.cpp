// Chapter 06's maths without OpenGL (shadow_math.h, the C++ twins of the visibility hook):
// Chebyshev's bound against the brute-force lit fraction of synthetic depth distributions,
// the P_min mapping, log-space ESM against the direct form, the bias formulas against the
// depth a texel spans, and the fitted light frustum against the casters that can shadow a
// visible receiver.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/03_light_volumes/light_instances.h"
#include "chapters/03_light_volumes/volume_meshes.h"
#include "chapters/06_shadows/shadow_math.h"
#include "chapters/06_shadows/shadow_stage.h"
#include "chapters/06_shadows/shadow_truth.h"
#include "chapters/06_shadows/shadow_volumes.h"
#include "common/error.h"

using namespace lp;
using namespace lp::ch06;

namespace {

// The moments of a weighted set of depths, and the fraction of the weight at or beyond d.
glm::vec2 moments_of(const std::vector<float>& z, const std::vector<float>& w) {
  double m1 = 0, m2 = 0;
  for (std::size_t i = 0; i < z.size(); ++i) m1 += w[i] * z[i], m2 += w[i] * z[i] * z[i];
  return {float(m1), float(m2)};
}
float lit_fraction(const std::vector<float>& z, const std::vector<float>& w, float d) {
  float lit = 0;
  for (std::size_t i = 0; i < z.size(); ++i) lit += z[i] >= d ? w[i] : 0.f;
  return lit;
}

}  // namespace

// One-sided Chebyshev (Cantelli) holds for every distribution: random ones, 8 depths each.
TEST(ShadowMath, ChebyshevBoundsTheLitFractionOfAnyDistribution) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<float> z(8), w(8);
    float total = 0;
    for (int i = 0; i < 8; ++i) z[i] = u(rng), w[i] = u(rng) + 1e-3f, total += w[i];
    for (float& x : w) x /= total;
    const float d = u(rng);
    const float bound = chebyshev_upper_bound(moments_of(z, w), d, 0.f);
    // 1e-4: float rounding of the moments (M2 - M1^2 loses about 2^-24 / variance of it).
    EXPECT_GE(bound + 1e-4f, lit_fraction(z, w, d)) << "trial " << trial << ", d " << d;
  }
}

// One occluder over one receiver (two depths): the bound is the lit fraction exactly.
TEST(ShadowMath, ChebyshevIsExactForOneOccluderOverOneReceiver) {
  for (float p : {0.1f, 0.25f, 0.5f, 0.9f}) {
    const std::vector<float> z = {0.3f, 0.7f}, w = {1.f - p, p};  // occluder at 0.3 covers 1 - p of the filter
    EXPECT_NEAR(chebyshev_upper_bound(moments_of(z, w), 0.7f, 0.f), p, 1e-5f) << "p " << p;
  }
  EXPECT_EQ(chebyshev_upper_bound({0.5f, 0.25f}, 0.4f, 0.f), 1.f);  // in front of the mean: lit
}

// Two overlapping occluders over a receiver fully in shadow: the bound lets light through
// (bleeding); P_min at or above the bleeding value removes it, and costs true penumbra.
TEST(ShadowMath, OverlappingOccludersBleedAndPminRemovesIt) {
  const std::vector<float> z = {0.2f, 0.5f}, w = {0.5f, 0.5f};
  const float d = 0.8f;  // the receiver, behind both: truly in shadow
  ASSERT_EQ(lit_fraction(z, w, d), 0.f);
  const float bleed = chebyshev_upper_bound(moments_of(z, w), d, 0.f);
  // mean 0.35, variance 0.0225, (d - mean)^2 = 0.2025: 0.0225 / 0.225 = 0.1
  EXPECT_NEAR(bleed, 0.1f, 1e-5f);
  EXPECT_EQ(reduce_light_bleeding(bleed, 0.1f), 0.f);
  EXPECT_GT(reduce_light_bleeding(bleed, 0.05f), 0.f);
  // The cost: a true penumbra of 30 % lit (one occluder over the receiver) reads 0.3 -> 0.222.
  EXPECT_NEAR(reduce_light_bleeding(0.3f, 0.1f), 0.2f / 0.9f, 1e-6f);
}

TEST(ShadowMath, PminMapsItselfToZeroOneToOneAndIsMonotone) {
  for (float pmin : {0.f, 0.2f, 0.5f, 0.9f}) {
    EXPECT_EQ(reduce_light_bleeding(pmin, pmin), 0.f);
    EXPECT_FLOAT_EQ(reduce_light_bleeding(1.f, pmin), 1.f);
    float previous = -1;
    for (float p = 0; p <= 1.f; p += 0.01f) {
      const float r = reduce_light_bleeding(p, pmin);
      EXPECT_GE(r, previous);
      if (p < pmin) { EXPECT_EQ(r, 0.f); }
      if (pmin == 0.f) { EXPECT_FLOAT_EQ(r, p); }
      previous = r;
    }
  }
}

// Where exp(c z) fits in a float (c z < 88), the log-space filter is the log of the direct one.
TEST(ShadowMath, EsmLogSpaceEqualsTheDirectFormWhereItDoesNotOverflow) {
  std::mt19937 rng(60);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (float c : {5.f, 20.f, 40.f, 80.f}) {
    for (int trial = 0; trial < 200; ++trial) {
      std::vector<float> z(9), l(9), w(9, 1.f / 9.f);
      for (int i = 0; i < 9; ++i) z[i] = u(rng), l[i] = c * z[i];
      const float direct = esm_filter_direct(z, w, c);
      ASSERT_TRUE(std::isfinite(direct));
      const float log_space = esm_filter_log(l, w);
      // Both round each term to float: a few ulps of exp's result, relative 1e-6 of E.
      EXPECT_NEAR(log_space, std::log(direct), 1e-5f * std::max(1.f, std::abs(log_space)));
      const float d = u(rng);
      EXPECT_NEAR(esm_visibility_log(log_space, c, d), esm_visibility_direct(direct, c, d), 1e-4f);
    }
  }
}

// Past c = 88 the direct form is infinite; log space stays finite and right (long double reference).
TEST(ShadowMath, EsmLogSpaceStaysFiniteWhereTheDirectFormOverflows) {
  const float c = 300.f;
  const std::vector<float> z = {0.40f, 0.41f, 0.95f}, w = {0.25f, 0.25f, 0.5f};
  EXPECT_TRUE(std::isinf(esm_filter_direct(z, w, c)));
  std::vector<float> l;
  for (float x : z) l.push_back(c * x);
  const float log_space = esm_filter_log(l, w);
  ASSERT_TRUE(std::isfinite(log_space));
  long double sum = 0;
  for (std::size_t i = 0; i < z.size(); ++i) sum += (long double)w[i] * std::exp((long double)c * z[i]);
  EXPECT_NEAR(log_space, float(std::log(sum)), 1e-4f * log_space);
  const float v = esm_visibility_log(log_space, c, 0.96f);  // behind every depth: half the filter at 0.95
  EXPECT_TRUE(std::isfinite(v));
  EXPECT_NEAR(v, float(sum * std::exp(-(long double)c * 0.96f)), 1e-5f);
  EXPECT_EQ(esm_visibility_log(log_space, c, 0.2f), 1.f);  // in front of every depth: lit, not above 1
}

TEST(ShadowMath, BiasFormulas) {
  const float w = 0.02f;  // 2 cm texels
  EXPECT_FLOAT_EQ(slope_scaled_bias(0.5f, 1.f, 1.f, w), 0.5f * w);          // facing the light: constant only
  EXPECT_NEAR(slope_scaled_bias(0.5f, 1.f, std::sqrt(0.5f), w), 1.5f * w, 1e-6f);  // 45 degrees: tan = 1
  EXPECT_NEAR(slope_scaled_bias(0.f, 1.f, 0.f, w), kMaxSlope * w, 1e-6f);   // grazing: capped
  const glm::vec3 p(1, 2, 3), n(0, 1, 0);
  EXPECT_EQ(normal_offset(p, n, 1.f, 1.f, w), p);
  EXPECT_NEAR(normal_offset(p, n, 0.f, 2.f, w).y, 2.f + 2.f * w, 1e-6f);
}

// The slope term with 0.5 texels covers the depth a texel spans: a plane tilted by theta,
// looked up at any point, against the depth the map stores at its texel's centre (nearest).
TEST(ShadowMath, HalfATexelOfSlopeBiasCoversTheDepthATexelSpans) {
  const float w = 0.03f;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (float degrees : {10.f, 45.f, 70.f, 84.f}) {
    const float theta = glm::radians(degrees), tan_theta = std::tan(theta);
    for (int i = 0; i < 1000; ++i) {
      const float x = u(rng) * 100.f * w;                      // along the tilt, in the map
      const float centre = (std::floor(x / w) + 0.5f) * w;     // the texel's centre
      const float receiver = x * tan_theta, stored = centre * tan_theta;  // depth along the light
      EXPECT_LE(receiver - stored, slope_scaled_bias(0.f, 0.5f, std::cos(theta), w) * 1.0001f + 1e-6f);
    }
  }
}

// Every caster that can shadow a receiver in view lies inside the fitted box: receivers are
// random points of the scene in the camera's frustum, casters anywhere in the scene toward the sun.
TEST(ShadowMath, FittedLightFrustumHoldsEveryCasterOfAVisibleReceiver) {
  const glm::vec3 lo(-8, 0, -12), hi(8, 7, 12), sun = glm::normalize(glm::vec3(-0.4f, -0.8f, -0.3f));
  const glm::mat4 view = glm::lookAt(glm::vec3(0, 1.7f, 11.5f), glm::vec3(0, 1.5f, 0), glm::vec3(0, 1, 0));
  const glm::mat4 projection = glm::perspective(0.8f, 16.f / 9.f, 0.1f, 1000.f);
  const glm::mat4 inverse = glm::inverse(projection * view);
  const LightFrustum f = fit_light_frustum(sun, lo, hi, &inverse);
  const LightFrustum whole = fit_light_frustum(sun, lo, hi);
  // The fit is smaller than the whole scene's box (or the test shows nothing).
  EXPECT_LT((f.box_max.x - f.box_min.x) * (f.box_max.y - f.box_min.y),
            0.9f * (whole.box_max.x - whole.box_min.x) * (whole.box_max.y - whole.box_min.y));
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  int receivers = 0;
  for (int i = 0; i < 20000 && receivers < 2000; ++i) {
    const glm::vec3 r = lo + (hi - lo) * glm::vec3(u(rng), u(rng), u(rng));
    const glm::vec4 clip = projection * view * glm::vec4(r, 1.f);
    if (glm::any(glm::greaterThan(glm::abs(glm::vec3(clip) / clip.w), glm::vec3(1.f))) || clip.w <= 0) continue;
    ++receivers;
    for (float t = 0; t < 40.f; t += 0.5f) {
      const glm::vec3 caster = r - sun * t;
      if (glm::any(glm::lessThan(caster, lo)) || glm::any(glm::greaterThan(caster, hi))) break;
      const glm::vec3 q = glm::vec3(f.view * glm::vec4(caster, 1.f));
      EXPECT_TRUE(glm::all(glm::greaterThanEqual(q, f.box_min)) && glm::all(glm::lessThanEqual(q, f.box_max)))
          << "caster " << caster.x << " " << caster.y << " " << caster.z;
    }
  }
  EXPECT_GT(receivers, 500);
}

TEST(ShadowMath, ConeSamplesStayWithinTheSunsDisk) {
  const glm::vec3 axis = glm::normalize(glm::vec3(0.3f, 0.9f, -0.2f));
  for (float u = 0; u < 1.f; u += 0.1f)
    for (float v = 0; v < 1.f; v += 0.1f) {
      const glm::vec3 d = sample_cone(axis, 0.05f, u, v);
      EXPECT_NEAR(glm::length(d), 1.f, 1e-5f);
      EXPECT_GE(glm::dot(d, axis), std::cos(0.05f) - 1e-6f);
    }
  EXPECT_NEAR(glm::dot(sample_cone(axis, 0.05f, 1.f, 0.f), axis), std::cos(0.05f), 1e-5f);  // u = 1: the rim
}

// The gradient predicts a tilted plane's window depth one step away in the map: project two
// points of the plane through the light's matrix and compare.
TEST(ShadowMath, ReceiverPlaneGradientPredictsThePlanesDepth) {
  const glm::vec3 sun = glm::normalize(glm::vec3(-0.36f, -0.89f, -0.27f));
  const LightFrustum f = fit_light_frustum(sun, glm::vec3(-8, 0, -12), glm::vec3(8, 7, 12));
  const glm::mat4 m = f.view_projection();
  auto window = [&](glm::vec3 p) { glm::vec4 c = m * glm::vec4(p, 1.f); return glm::vec3(c) / c.w * 0.5f + 0.5f; };
  for (glm::vec3 normal : {glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), glm::normalize(glm::vec3(0.3f, 0.5f, 0.8f))}) {
    ASSERT_GT(glm::dot(normal, -sun), 0.1f);
    const glm::vec3 p0(1, 2, 3);
    const glm::vec3 t = glm::normalize(glm::cross(normal, glm::vec3(0.2f, 0.3f, 0.9f)));
    const glm::vec3 p1 = p0 + 0.5f * t;  // another point of the plane
    const glm::vec3 w0 = window(p0), w1 = window(p1);
    const glm::vec2 g = receiver_plane_gradient(f, normal);
    EXPECT_NEAR(w0.z + glm::dot(g, glm::vec2(w1) - glm::vec2(w0)), w1.z, 1e-5f);
  }
}

// The Poisson disk: n points in the unit disk, no two closer than the spacing it reports, which
// stays at least half the even packing's sqrt(pi / n) (it starts at 0.75 of it and shrinks by
// 5 % steps only when darts find no room); the same seed gives the same disk; n out of range
// is an error, not a loop.
TEST(ShadowMath, PoissonDiskIsSpreadAndInTheDisk) {
  for (int n : {1, 8, 16, 32, kMaxPoissonTaps}) {
    float spacing = 0;
    const auto p = poisson_disk(n, 7, &spacing);
    ASSERT_EQ(int(p.size()), n);
    EXPECT_GE(spacing, 0.5f * std::sqrt(3.14159265f / float(n))) << n;
    for (std::size_t i = 0; i < p.size(); ++i) {
      EXPECT_LE(glm::length(p[i]), 1.f + 1e-6f);
      for (std::size_t j = i + 1; j < p.size(); ++j) EXPECT_GE(glm::distance(p[i], p[j]), spacing * (1.f - 1e-6f));
    }
    EXPECT_EQ(p, poisson_disk(n, 7));
  }
  EXPECT_THROW(poisson_disk(0, 7), Error);
  EXPECT_THROW(poisson_disk(kMaxPoissonTaps + 1, 7), Error);
}

// [pcss-tests]
// PCSS's penumbra for the sun (shadow_math.h [pcss]) is Fernando's point-light formula with the
// light moved to infinity: a light of width w = 2 L tan(theta) at distance L from the receiver
// (the sun's angular size seen from it), a blocker delta in front of the receiver, gives
// w delta / (L - delta) = 2 delta tan(theta) (1 + delta / (L - delta)): twice the filter radius,
// and the excess delta / (L - delta) vanishes as L grows.
TEST(ShadowMath, PcssPenumbraIsThePointLightsAtInfinity) {
  const float theta = kSunAngularRadius, receiver = 20.f, delta = 2.f;
  const float r = pcss_filter_radius(receiver, receiver - delta, theta);
  EXPECT_FLOAT_EQ(r, delta * std::tan(theta));
  for (double L : {10.0, 100.0, 1e3, 1e5}) {
    const float w = float(2 * L * std::tan(double(theta)));
    const float penumbra = point_light_penumbra(w, float(L), float(L - delta));  // distances from the light
    EXPECT_NEAR(penumbra / (2 * r), 1 + delta / (L - delta), 1e-5) << L;
  }
  EXPECT_NEAR(point_light_penumbra(float(2e5 * std::tan(double(theta))), 1e5f, 1e5f - delta), 2 * r, 2 * r * 1e-4f);
  EXPECT_EQ(pcss_filter_radius(receiver, receiver + 1.f, theta), 0.f);  // a "blocker" behind: no penumbra
  EXPECT_FLOAT_EQ(pcss_search_radius(receiver, theta), receiver * std::tan(theta));
}

// PCSS over a straight edge: a half-plane blocker (x > 0) delta above a floor, 20 m from the
// map's near plane. The filter is the disk of radius R = delta tan(theta) around the lookup, so
// the visibility leaves 1 where the first tap crosses the edge (x0 = -R max t.x over the taps t)
// and reaches 0 where the last does (x0 = -R min t.x): the penumbra is R (max t.x - min t.x)
// wide, proportional to delta (contact hardening), up to the scan's step. Outside it: 1 on the
// lit side, beyond the search radius with no blocker found at all, and 0 under the blocker.
TEST(ShadowMath, PcssPenumbraOverAnEdgeGrowsWithTheBlockersDistance) {
  const float theta = kSunAngularRadius, floor = 20.f;
  const std::vector<glm::vec2> disk = poisson_disk(kPcssDefaultTaps, 0x504fu);
  float lo = 1, hi = -1;
  for (const glm::vec2& t : disk) lo = std::min(lo, t.x), hi = std::max(hi, t.x);
  for (float delta : {0.25f, 1.f, 4.f}) {
    auto depth_at = [&](glm::vec2 p) { return p.x > 0.f ? floor - delta : floor; };
    const float R = delta * std::tan(theta), step = R / 1000.f;
    float first_dark = 0, last_lit = 0;
    bool found_dark = false;
    for (float x = -1.5f * R; x <= 1.5f * R; x += step) {
      const PcssResult r = pcss(depth_at, {x, 0.f}, floor, theta, disk, 0.f);
      if (r.visibility < 1.f && !found_dark) first_dark = x, found_dark = true;
      if (r.visibility > 0.f) last_lit = x;
      if (r.blockers > 0) {
        EXPECT_EQ(r.blocker_depth, floor - delta);
        EXPECT_FLOAT_EQ(r.filter_radius, R);
      }
    }
    const float width = last_lit - first_dark;
    std::printf("delta %.2f m: penumbra %.4f m wide (R (max - min) = %.4f m)\n", delta, width, R * (hi - lo));
    EXPECT_NEAR(first_dark, -R * hi, 2 * step) << delta;
    EXPECT_NEAR(last_lit, -R * lo, 2 * step) << delta;
    EXPECT_GT(width, R) << delta;  // the taps span more than the disk's radius
    // The search: beyond d_r tan(theta) on the lit side nothing can hide the sun, and nothing is found.
    const float search = pcss_search_radius(floor, theta);
    EXPECT_EQ(pcss(depth_at, {-1.01f * search, 0.f}, floor, theta, disk, 0.f).blockers, 0);
    const PcssResult near_edge = pcss(depth_at, {-0.5f * search, 0.f}, floor, theta, disk, 0.f);
    EXPECT_GT(near_edge.blockers, 0);           // found, within the search ...
    EXPECT_EQ(near_edge.visibility, 1.f);       // ... but farther than the penumbra: lit
    EXPECT_EQ(pcss(depth_at, {2 * R, 0.f}, floor, theta, disk, 0.f).visibility, 0.f);
  }
  // At contact the filter shrinks to the least radius asked for.
  auto touching = [&](glm::vec2 p) { return p.x > 0.f ? floor - 1e-4f : floor; };
  EXPECT_EQ(pcss(touching, {-0.001f, 0.f}, floor, theta, disk, 0.01f).filter_radius, 0.01f);
}
// [/pcss-tests]

// Shadow volumes' edge table and silhouettes (shadow_volumes.h), on meshes small enough to
// count by hand.
namespace {
// A mesh of the given triangles (corner positions, 3 per triangle), each triangle with its own
// three vertices: the welding must find the shared corners.
lp::Scene soup(const std::vector<glm::vec3>& corners, bool double_sided = false) {
  lp::Scene s;
  for (const glm::vec3& p : corners) {
    lp::Vertex v;
    v.position = p;
    s.indices.push_back(std::uint32_t(s.vertices.size()));
    s.vertices.push_back(v);
  }
  lp::Material m;
  m.double_sided = double_sided;
  s.materials.push_back(m);
  s.meshes.push_back({"soup", {{0, std::uint32_t(s.indices.size()), 0}}});
  return s;
}
// The unit cube's 12 triangles, wound outward.
std::vector<glm::vec3> cube() {
  const glm::vec3 c[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  std::vector<glm::vec3> out;
  for (const auto& q : quads)
    for (int i : {q[0], q[1], q[2], q[0], q[2], q[3]}) out.push_back(c[i]);
  return out;
}
}  // namespace

TEST(ShadowVolumes, ACubeLitFromAboveHasFourSilhouetteEdges) {
  const lp::Scene s = soup(cube());
  const MeshAdjacency a = build_adjacency(s, s.meshes[0]);
  EXPECT_EQ(a.corners.size(), 8u);   // 36 vertices welded to the cube's 8 corners
  EXPECT_EQ(a.edges.size(), 18u);    // 12 edges of the cube + 6 face diagonals
  EXPECT_EQ(a.open_edges, 0u);
  EXPECT_EQ(a.non_manifold_edges, 0u);
  std::vector<glm::vec4> v;
  const VolumeCounts c = append_sun_volume(a, glm::mat4(1), {0, -1, 0}, 0.f, v);
  EXPECT_EQ(c.cap_triangles, 2u);    // the top face
  EXPECT_EQ(c.side_quads, 4u);       // the top face's border: lit top, unlit sides
  EXPECT_EQ(v.size(), 3 * (c.cap_triangles + c.side_quads));
  // Every side has one corner at infinity along the light, the others on the cube's top.
  for (std::size_t i = 3 * c.cap_triangles; i < v.size(); i += 3) {
    EXPECT_EQ(v[i + 1], glm::vec4(0, -1, 0, 0));
    EXPECT_EQ(v[i].w, 1.f);
    EXPECT_EQ(v[i].y, 1.f);
  }
  // Lit along a diagonal, three faces face the light and six edges are the silhouette.
  v.clear();
  const VolumeCounts d = append_sun_volume(a, glm::mat4(1), glm::normalize(glm::vec3(-1, -1, -1)), 0.f, v);
  EXPECT_EQ(d.cap_triangles, 6u);
  EXPECT_EQ(d.side_quads, 6u);
}

TEST(ShadowVolumes, AnOpenQuadCastsFromEitherSideThroughItsBorder) {
  // A one-sided quad facing up, 4 open edges; lit from below it still casts (an open mesh).
  const lp::Scene s = soup({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {0, 0, 0}, {1, 0, 1}, {1, 0, 0}});
  const MeshAdjacency a = build_adjacency(s, s.meshes[0]);
  EXPECT_EQ(a.open_edges, 4u);
  for (float y : {-1.f, 1.f}) {
    std::vector<glm::vec4> v;
    const VolumeCounts c = append_sun_volume(a, glm::mat4(1), {0, y, 0}, 0.f, v);
    EXPECT_EQ(c.cap_triangles, 2u);
    EXPECT_EQ(c.side_quads, 4u);  // the border; the shared diagonal cancels
  }
}

TEST(ShadowVolumes, ANonManifoldEdgeGetsItsNetCount) {
  // Three triangles on the edge (0,0,0)-(1,0,0), all facing up and running the same way along
  // it: the edge's net count is 3, so three sides there (the prisms' walls, not cancelled).
  const lp::Scene s = soup({{0, 0, 0}, {1, 0, 0}, {0.5f, 0, -1}, {0, 0, 0}, {1, 0, 0}, {0.5f, 0.1f, -1},
                            {0, 0, 0}, {1, 0, 0}, {0.5f, 0.2f, -1}});
  const MeshAdjacency a = build_adjacency(s, s.meshes[0]);
  EXPECT_EQ(a.non_manifold_edges, 1u);
  std::vector<glm::vec4> v;
  const VolumeCounts c = append_sun_volume(a, glm::mat4(1), {0, -1, 0}, 0.f, v);
  EXPECT_EQ(c.cap_triangles, 3u);
  EXPECT_EQ(c.side_quads, 3u + 6u);  // 3 on the shared edge, and each triangle's two own edges
}

// [spot-frustum-tests]
// A spot light's perspective frustum (shadow_math.h [spot-frustum]) holds its cone: points in
// directions within the outer cone, between the near plane and the farthest corner of the
// scene's bounds, project inside the map and its depth range; a texel at distance d is
// 2 d tan(cone) / N; a cone wider than kMaxSpotCone is refused.
TEST(ShadowMath, SpotFrustumHoldsTheSpotsCone) {
  const glm::vec3 lo(-8, 0, -12), hi(8, 7, 12), at(1, 3, 1.5f);
  const glm::vec3 axis = glm::normalize(glm::vec3(3.5f, -3.f, 0.f));
  const float cone = 0.8f;
  const SpotFrustum f = fit_spot_frustum(at, axis, cone, 0.f, lo, hi);
  EXPECT_NEAR(f.far, glm::distance(at, glm::vec3(-8, 7, -12)), 1e-4f);  // the farthest corner
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int i = 0; i < 10000; ++i) {
    // a direction within the cone (sample_cone), at a distance along it whose depth is inside [near, far]
    const glm::vec3 d = sample_cone(axis, cone, u(rng), u(rng));
    const float depth = f.near * 1.01f + u(rng) * (f.far * 0.99f - f.near * 1.01f);
    const glm::vec3 p = at + d * (depth / glm::dot(d, axis));
    const glm::vec4 c = f.view_projection() * glm::vec4(p, 1.f);
    ASSERT_GT(c.w, 0.f);
    ASSERT_LE(std::abs(c.x / c.w), 1.f + 1e-5f) << i;
    ASSERT_LE(std::abs(c.y / c.w), 1.f + 1e-5f) << i;
    ASSERT_LE(std::abs(c.z / c.w), 1.f + 1e-5f) << i;
    ASSERT_NEAR(c.w, depth, 1e-3f * depth);  // clip w is the linear depth the hook compares
  }
  EXPECT_FLOAT_EQ(f.texel_world(5.f, 1024), 2.f * 5.f * std::tan(cone) / 1024.f);
  EXPECT_LT(fit_spot_frustum(at, axis, cone, 4.f, lo, hi).far, 4.f + 1e-6f);  // a range nearer than the bounds
  EXPECT_THROW(fit_spot_frustum(at, axis, kMaxSpotCone + 0.01f, 0.f, lo, hi), Error);
}
// [/spot-frustum-tests]

// [marked-lights-tests]
// Which lights cast (shadow_stage.h [casts-shadows]): unmarked, only the sun (the first
// directional light, wherever it is in the list); a mark overrides, either way; the marked
// spots of at most kMaxSpotCone get a map; and a marked light the chapter has no map for is
// named, with why, the sun and those spots never.
TEST(ShadowLights, TheSunCastsUnlessMarkedAndOtherLightsOnlyWhenMarked) {
  auto light = [](LightType type, const char* name) {
    Light l;
    l.type = type, l.name = name;
    return l;
  };
  Scene s;
  s.lights = {light(LightType::Point, "lamp"), light(LightType::Directional, "sun"), light(LightType::Directional, "moon"),
              light(LightType::Spot, "torch"), light(LightType::Spot, "flood"), light(LightType::Spot, "second")};
  s.lights[4].outer_cone = kMaxSpotCone + 0.1f;
  EXPECT_FALSE(casts_shadows(s, 0));
  EXPECT_TRUE(casts_shadows(s, 1));
  EXPECT_FALSE(casts_shadows(s, 2));
  EXPECT_FALSE(casts_shadows(s, 3));
  EXPECT_TRUE(unshadowed_casters(s).empty());
  EXPECT_EQ(shadowed_spot(s), -1);
  s.lights[1].casts_shadows = false;
  EXPECT_FALSE(casts_shadows(s, 1));
  s.lights[4].casts_shadows = true;
  EXPECT_EQ(shadowed_spot(s), -1);  // the only marked spot is too wide for a perspective map
  for (std::size_t i : {0u, 2u, 3u, 5u}) s.lights[i].casts_shadows = true;
  s.lights[1].casts_shadows = true;
  for (std::size_t i = 0; i < s.lights.size(); ++i) EXPECT_TRUE(casts_shadows(s, i)) << i;
  EXPECT_EQ(shadowed_spot(s), 3);
  // The marked point light gets a cube map (cube_math.h); the others are named.
  EXPECT_EQ(shadowed_point_lights(s), std::vector<int>{0});
  // Both marked spots of a cone a map covers get a tile of the atlas (spot_atlas.h).
  EXPECT_EQ(shadowed_spot_lights(s), (std::vector<int>{3, 5}));
  const std::vector<std::string> notes = unshadowed_casters(s);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("light 'moon'"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("only the first directional light"), std::string::npos) << notes[0];
  EXPECT_NE(notes[1].find("light 'flood'"), std::string::npos) << notes[1];
  EXPECT_NE(notes[1].find("wider than a perspective map covers"), std::string::npos) << notes[1];
}

// Spot lights: the marked ones get a tile, at most kMaxSpotShadows (the next is named), and every
// spot light with `all`; one wider than kMaxSpotCone never.
TEST(ShadowLights, MarkedSpotLightsGetTilesUpToTheLimit) {
  Scene s;
  for (int i = 0; i <= kMaxSpotShadows + 1; ++i) {
    Light l;
    l.type = LightType::Spot, l.name = "spot" + std::to_string(i), l.intensity = 1.f, l.outer_cone = 0.5f;
    l.casts_shadows = i != 0;  // the first unmarked
    s.lights.push_back(l);
  }
  const std::vector<int> marked = shadowed_spot_lights(s);
  ASSERT_EQ(marked.size(), std::size_t(kMaxSpotShadows));
  EXPECT_EQ(marked.front(), 1);
  EXPECT_EQ(marked.back(), kMaxSpotShadows);
  const std::vector<std::string> notes = unshadowed_casters(s);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("light 'spot" + std::to_string(kMaxSpotShadows + 1) + "'"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("marked spot lights have a tile"), std::string::npos) << notes[0];
  EXPECT_EQ(shadowed_spot_lights(s, true).front(), 0);
  s.lights[0].outer_cone = kMaxSpotCone + 0.1f;
  EXPECT_EQ(shadowed_spot_lights(s, true).front(), 1);
}

// Point lights: the marked ones get cube maps, at most kMaxPointShadows (the next is named), and
// every point light with `all`; a light the light set leaves out (light_defect) gets none.
TEST(ShadowLights, MarkedPointLightsGetCubeMapsUpToTheLimit) {
  Scene s;
  for (int i = 0; i < kMaxPointShadows + 2; ++i) {
    Light l;
    l.type = LightType::Point, l.name = std::string("p").append(std::to_string(i)), l.intensity = 1.f;
    l.casts_shadows = i != 1;  // p1 unmarked
    s.lights.push_back(l);
  }
  std::vector<int> expected = {0};
  for (int i = 2; i <= kMaxPointShadows; ++i) expected.push_back(i);
  EXPECT_EQ(shadowed_point_lights(s), expected);
  const std::vector<std::string> notes = unshadowed_casters(s);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("light 'p9'"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("only the first 8 marked point lights"), std::string::npos) << notes[0];
  std::vector<int> all;
  for (int i = 0; i < kMaxPointShadows; ++i) all.push_back(i);
  EXPECT_EQ(shadowed_point_lights(s, true), all);
  s.lights[0].intensity = -1.f;  // left out of the light set
  EXPECT_EQ(shadowed_point_lights(s, true).front(), 1);
}
// [/marked-lights-tests]

// The sun with a map is the first directional light chapter 03's light set keeps: index 0 of
// its directional lights, which the visibility hook maps. A directional light that breaks the
// rule every chapter keeps (light_defect: here a negative intensity) is left out of the set,
// so the next one is the sun, and casts.
TEST(ShadowLights, TheSunIsTheFirstDirectionalLightTheLightSetKeeps) {
  Scene s;
  Light broken, sun;
  broken.type = sun.type = LightType::Directional;
  broken.name = "broken", sun.name = "sun";
  broken.intensity = -1.f;
  s.lights = {broken, sun};
  EXPECT_EQ(shadowed_sun(s), 1);
  EXPECT_TRUE(casts_shadows(s, 1));
  s.lights[0].intensity = 1.f;  // valid again: it is the sun, the other one is not
  EXPECT_EQ(shadowed_sun(s), 0);
  EXPECT_FALSE(casts_shadows(s, 1));
  s.lights[0].casts_shadows = false;  // the first directional light marked not to cast: no map at all
  EXPECT_EQ(shadowed_sun(s), -1);
}

// The visibility hook shadows the directional light whose index is SHADOW_SUN_INDEX
// (shadowed_sun_index()): it must be where chapter 03's light set put the sun, with lights it
// leaves out before it, and none when no sun casts.
TEST(ShadowLights, TheHooksSunIndexIsWhereTheLightSetPutTheSun) {
  auto directional = [](const char* name, float intensity, glm::vec3 direction) {
    Light l;
    l.type = LightType::Directional, l.name = name, l.intensity = intensity, l.direction = direction;
    return l;
  };
  Light lamp;
  lamp.type = LightType::Point, lamp.name = "lamp";
  Scene s;
  s.lights = {lamp, directional("broken", -1.f, {0, -1, 0}), directional("sun", 2.f, {0.6f, -0.8f, 0}),
              directional("moon", 0.5f, {0, -0.8f, 0.6f})};
  const ch03::VolumeShapes shapes = ch03::make_volume_shapes();
  const ch03::LightSet set = ch03::build_light_set(s.lights, 0.01f, shapes);
  const int index = shadowed_sun_index(s);
  ASSERT_GE(index, 0);
  ASSERT_LT(std::size_t(index), set.directional.size());
  const ch01::GpuLight sun = ch01::pack_light(s.lights[std::size_t(shadowed_sun(s))]);
  EXPECT_EQ(set.directional[std::size_t(index)].direction_range, sun.direction_range);
  EXPECT_EQ(set.directional[std::size_t(index)].radiance, sun.radiance);
  s.lights[2].casts_shadows = false;  // the sun marked not to cast: the hook shadows no light
  EXPECT_EQ(shadowed_sun_index(s), -1);
}

// The view test that decides whether a spot needs its map: a sphere in front of the camera
// is in view, one behind it or beside the frustum is not, one straddling a plane is.
TEST(ShadowMath, SphereInViewAgainstTheFrustumsPlanes) {
  const glm::mat4 proj = glm::perspective(1.0f, 16.f / 9.f, 0.1f, 100.f);
  const glm::mat4 view = glm::lookAt(glm::vec3(0), glm::vec3(0, 0, -1), glm::vec3(0, 1, 0));
  const glm::mat4 vp = proj * view;
  EXPECT_TRUE(sphere_in_view({0, 0, -10}, 1.f, vp));
  EXPECT_FALSE(sphere_in_view({0, 0, 10}, 1.f, vp));   // behind the eye
  EXPECT_TRUE(sphere_in_view({0, 0, 0.5f}, 1.f, vp));  // around the eye, reaching the near plane
  EXPECT_FALSE(sphere_in_view({30, 0, -10}, 1.f, vp));  // far beside the frustum
  EXPECT_TRUE(sphere_in_view({30, 0, -10}, 30.f, vp));  // large enough to reach in
  EXPECT_FALSE(sphere_in_view({0, 0, -200}, 50.f, vp));  // beyond the far plane
}

// [cascade-tests]
// The practical split against its definition, written out here from Zhang et al.'s two schemes:
// the logarithmic split n (f/n)^(i/C), the uniform n + (f - n) i / C, blended by lambda; lambda 0
// and 1 give each alone; the splits rise from near to far.
TEST(ShadowCascades, SplitsAreTheBlendOfTheLogarithmicAndTheUniformSplit) {
  const float n = 0.05f, f = 120.f;
  for (int count : {1, 2, 3, 4})
    for (float lambda : {0.f, 0.25f, 0.75f, 1.f}) {
      const std::vector<float> z = cascade_splits(count, n, f, lambda);
      ASSERT_EQ(z.size(), std::size_t(count) + 1);
      EXPECT_EQ(z.front(), n);
      EXPECT_EQ(z.back(), f);
      for (int i = 1; i < count; ++i) {
        const double log_split = n * std::pow(double(f) / n, double(i) / count);
        const double uniform = n + (double(f) - n) * i / count;
        EXPECT_NEAR(z[std::size_t(i)], lambda * log_split + (1 - lambda) * uniform, 1e-4 * f) << count << " " << lambda;
        EXPECT_GT(z[std::size_t(i)], z[std::size_t(i) - 1]);
      }
    }
  // Logarithmic: every cascade spans the same ratio far / near.
  const std::vector<float> z = cascade_splits(4, 0.1f, 100.f, 1.f);
  for (int i = 1; i < 4; ++i) EXPECT_NEAR(z[std::size_t(i) + 1] / z[std::size_t(i)], z[1] / z[0], 1e-3);
  EXPECT_THROW(cascade_splits(kMaxCascades + 1, n, f, 0.5f), Error);
  EXPECT_THROW(cascade_splits(2, f, n, 0.5f), Error);
  EXPECT_THROW(cascade_splits(2, n, f, 1.5f), Error);
}

// The slice's sphere holds the slice's eight corners, touches one of them (it is no larger than
// it must be for a centre on the axis), and its radius does not change when the camera moves or
// turns: a cascade's texel is the same in every frame.
TEST(ShadowCascades, TheSliceSphereHoldsTheSliceAndKeepsItsSizeAsTheCameraMoves) {
  const float yfov = 0.9f, aspect = 16.f / 9.f;
  float radius = -1.f;
  for (int k = 0; k < 5; ++k) {
    const glm::vec3 eye(1.f + 3.7f * k, 1.7f, 55.f - 11.f * k);
    const glm::mat4 view = glm::lookAt(eye, eye + glm::vec3(std::sin(0.6f * k), -0.1f * k, -1.f), glm::vec3(0, 1, 0));
    const glm::mat4 world = glm::inverse(view);
    for (auto [n, f] : {std::pair{0.05f, 7.8f}, std::pair{7.8f, 17.f}, std::pair{35.f, 120.f}}) {
      const Sphere s = frustum_slice_sphere(world, yfov, aspect, n, f);
      const glm::mat4 projection = glm::perspective(yfov, aspect, n, f);
      const glm::mat4 inverse = glm::inverse(projection * view);
      float farthest = 0.f, near_corner = 0.f, far_corner = 0.f;
      for (int i = 0; i < 8; ++i) {
        glm::vec4 p = inverse * glm::vec4(i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : -1.f, 1.f);
        const float d = glm::distance(glm::vec3(p) / p.w, s.centre);
        farthest = std::max(farthest, d);
        (i & 4 ? far_corner : near_corner) = d;
      }
      EXPECT_LE(farthest, s.radius * (1.f + 1e-4f));
      EXPECT_GE(farthest, s.radius * (1.f - 1e-4f));
      // The smallest: a centre on the axis moved either way would leave the near or the far
      // corners outside, so both are on the sphere; or the centre is on the far rectangle.
      const float depth = glm::dot(s.centre - eye, -glm::vec3(world[2]));
      if (std::abs(depth - f) > 1e-3f * f) { EXPECT_NEAR(near_corner, far_corner, 1e-4f * s.radius) << n << " " << f; }
      else EXPECT_NEAR(far_corner, s.radius, 1e-4f * s.radius);
      if (n == 7.8f) {
        if (radius < 0.f) radius = s.radius;
        EXPECT_EQ(s.radius, radius);  // bit for bit
      }
    }
  }
}

// Snapping: as the sphere moves by small steps, the snapped box moves by whole texels (its corner
// stays on the grid of the first box), keeps its size, and holds the sphere; unsnapped, the
// corner slides off the grid.
TEST(ShadowCascades, SnappedBoxesMoveByWholeTexelsAndHoldTheSphere) {
  const glm::vec3 sun = glm::normalize(glm::vec3(-0.4f, -0.8f, -0.3f));
  const glm::vec3 lo(-20.f, 0.f, -100.f), hi(20.f, 25.f, 60.f);
  const int n = 1024;
  const Sphere start{{2.f, 3.f, 40.f}, 4.6f};
  const LightFrustum first = fit_cascade(sun, lo, hi, start, n, true);
  const float texel = first.texel_world(n);
  EXPECT_NEAR(texel, 2.f * start.radius / float(n - 2), 1e-7f);
  double worst_snapped = 0, worst_unsnapped = 0;
  for (int k = 1; k <= 40; ++k) {
    Sphere s = start;
    s.centre += float(k) * 0.0013f * glm::vec3(1.f, 0.3f, -0.5f);
    const LightFrustum a = fit_cascade(sun, lo, hi, s, n, true), b = fit_cascade(sun, lo, hi, s, n, false);
    for (int axis = 0; axis < 2; ++axis) {
      const double steps = (a.box_min[axis] - first.box_min[axis]) / texel;
      worst_snapped = std::max(worst_snapped, std::abs(steps - std::round(steps)));
      const double slid = (b.box_min[axis] - first.box_min[axis]) / texel;
      worst_unsnapped = std::max(worst_unsnapped, std::abs(slid - std::round(slid)));
      EXPECT_NEAR(a.box_max[axis] - a.box_min[axis], first.box_max[axis] - first.box_min[axis], 1e-4f);
      const float centre = glm::vec3(a.view * glm::vec4(s.centre, 1.f))[axis];
      EXPECT_LE(a.box_min[axis], centre - s.radius);
      EXPECT_GE(a.box_max[axis], centre + s.radius);
    }
  }
  std::printf("box corner off the first grid: snapped %.2e texels, unsnapped %.2f texels\n", worst_snapped, worst_unsnapped);
  EXPECT_LT(worst_snapped, 1e-2);
  EXPECT_GT(worst_unsnapped, 0.2);
}

// The choice: the first cascade whose far split lies beyond the depth, -1 beyond the last; the
// next cascade's weight rises from 0 to 1 over the last `band` of a cascade's range, and is 0 in
// the last cascade (nothing to fade into).
TEST(ShadowCascades, ChoiceByDepthAndTheBlendBand) {
  const std::vector<float> z = {0.1f, 10.f, 20.f, 40.f};
  EXPECT_EQ(choose_cascade(0.5f, z, 0.1f).cascade, 0);
  EXPECT_EQ(choose_cascade(10.f, z, 0.1f).cascade, 1);
  EXPECT_EQ(choose_cascade(39.9f, z, 0.1f).cascade, 2);
  EXPECT_EQ(choose_cascade(40.f, z, 0.1f).cascade, -1);
  EXPECT_EQ(choose_cascade(8.9f, z, 0.1f).next_weight, 0.f);   // before the band (9.01 to 10)
  EXPECT_NEAR(choose_cascade(9.505f, z, 0.1f).next_weight, 0.5f, 1e-4f);
  EXPECT_NEAR(choose_cascade(19.5f, z, 0.1f).next_weight, 0.5f, 1e-4f);  // band 18 to 20 in the second
  EXPECT_EQ(choose_cascade(39.9f, z, 0.1f).next_weight, 0.f);  // the last: no next one
  EXPECT_EQ(choose_cascade(9.9f, z, 0.f).next_weight, 0.f);    // no band
}
// [/cascade-tests]

// [msm-tests]
// The optimised quantisation: every depth's moments land in [0, 1] (what a 16-bit UNORM channel
// can hold) and come back through the inverse map.
TEST(ShadowMsm, OptimisedMomentsFitUnormAndComeBack) {
  for (int i = 0; i <= 1000; ++i) {
    const float z = float(i) / 1000.f;
    const glm::vec4 b = msm_moments(z), stored = msm_optimize(b), back = msm_unoptimize(stored);
    for (int k = 0; k < 4; ++k) {
      EXPECT_GE(stored[k], -1e-3f) << z;
      EXPECT_LE(stored[k], 1.f + 1e-3f) << z;
      EXPECT_NEAR(back[k], b[k], 1e-4f) << z << " moment " << k;
    }
  }
}

// For any distribution, the Hamburger reconstruction's shadow is at most the true fraction in
// front of the receiver (it is the least any distribution with these moments puts there), so its
// lit fraction is at least the truth; and four moments bound tighter than Chebyshev's two.
TEST(ShadowMsm, HamburgerBoundsTheLitFractionAndIsTighterThanChebyshev) {
  std::mt19937 rng(25);
  std::uniform_real_distribution<float> u(0.05f, 0.95f);
  int tighter = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<float> z(8), w(8);
    float total = 0;
    for (int i = 0; i < 8; ++i) z[std::size_t(i)] = u(rng), w[std::size_t(i)] = u(rng), total += w[std::size_t(i)];
    for (float& x : w) x /= total;
    glm::dvec4 b(0);
    for (int i = 0; i < 8; ++i) b += double(w[std::size_t(i)]) * glm::dvec4(msm_moments(z[std::size_t(i)]));
    const float d = u(rng);
    const float truth = lit_fraction(z, w, d);
    const float msm = msm_hamburger(glm::vec4(b), d, kMsmMomentBias32);
    const float vsm = chebyshev_upper_bound({float(b.x), float(b.y)}, d, 0.f);
    EXPECT_GE(msm, truth - 2e-3f) << trial;
    EXPECT_LE(msm, vsm + 2e-3f) << trial;
    tighter += msm < vsm - 0.01f;
  }
  std::printf("msm tighter than chebyshev by > 0.01 in %d of 2000\n", tighter);
  EXPECT_GT(tighter, 500);
}

// Two occluders over a receiver (the bleeding case of OverlappingOccludersBleedAndPminRemovesIt):
// Chebyshev lets a tenth of the light through, four moments almost none; and the same in 16 bits
// through the optimised map, rounded to 16-bit steps as RGBA16 stores it, with its moment bias.
TEST(ShadowMsm, TwoOccludersDoNotBleed) {
  const std::vector<float> z = {0.2f, 0.5f}, w = {0.5f, 0.5f};
  const glm::vec4 b = 0.5f * (msm_moments(0.2f) + msm_moments(0.5f));
  const float d = 0.8f;
  const float vsm = chebyshev_upper_bound({b.x, b.y}, d, 0.f);
  const float msm = msm_hamburger(b, d, kMsmMomentBias32);
  glm::vec4 stored = msm_optimize(b);
  for (int k = 0; k < 4; ++k) stored[k] = std::round(std::clamp(stored[k], 0.f, 1.f) * 65535.f) / 65535.f;
  const float msm16 = msm_hamburger(msm_unoptimize(stored), d, kMsmMomentBias16);
  std::printf("two occluders, receiver behind: truth 0, chebyshev %.3f, msm %.4f, msm 16-bit %.4f\n", vsm, msm, msm16);
  EXPECT_GT(vsm, 0.09f);
  EXPECT_LT(msm, 0.01f);
  EXPECT_LT(msm16, 0.02f);
  // Between the occluders half the light: the Hamburger reconstruction is exact for two depths.
  EXPECT_NEAR(msm_hamburger(b, 0.35f, kMsmMomentBias32), lit_fraction(z, w, 0.35f), 0.02f);
  // In front of both: lit.
  EXPECT_NEAR(msm_hamburger(b, 0.1f, kMsmMomentBias32), 1.f, 0.01f);
}
// [/msm-tests]
