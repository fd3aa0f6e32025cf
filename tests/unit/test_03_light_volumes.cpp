// Chapter 03's maths, no OpenGL: the volume meshes enclose what they stand for, the light
// radius is where the light really falls below the threshold, and the per-instance records
// carry exactly what chapter 01's shader reads.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/01_forward/blinn_phong.h"
#include "chapters/02_gbuffer/encoding.h"
#include "chapters/03_light_volumes/light_instances.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/03_light_volumes/light_volumes.h"
#include "chapters/03_light_volumes/volume_meshes.h"
#include "common/error.h"

using namespace lp;
using namespace lp::ch03;

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Every directed edge appears once and its reverse once: closed, consistently wound.
void expect_closed(const VolumeMesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (std::size_t t = 0; t < m.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) ++edges[{m.indices[3 * t + k], m.indices[3 * t + (k + 1) % 3]}];
  for (const auto& [e, n] : edges) {
    EXPECT_EQ(n, 1) << "edge " << e.first << "-" << e.second << " used twice in one direction";
    EXPECT_EQ(edges.count({e.second, e.first}), 1u) << "edge " << e.first << "-" << e.second << " has no twin";
  }
}

glm::vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<float> g;
  return glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
}

}  // namespace

// --- Volumes -------------------------------------------------------------------------------

TEST(VolumeMeshes, IcosphereCircumscribesTheUnitSphereAtEverySubdivision) {
  double previous_radius = 1e9;
  for (int s = 0; s <= 5; ++s) {
    SCOPED_TRACE("subdivisions " + std::to_string(s));
    VolumeMesh m = icosphere(s);
    ASSERT_EQ(m.triangle_count(), 20u << (2 * s));
    EXPECT_EQ(m.positions.size(), 10u * (1u << (2 * s)) + 2);
    expect_closed(m);
    // Every face plane lies at distance >= 1 from the centre (the sphere is inside), and the
    // nearest touches it: the scale is not wastefully large (1e-5: float rounding + 1e-6).
    float nearest = 1e9f;
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      float d = -m.plane_distance(t, glm::vec3(0));  // centre is behind every face
      EXPECT_GE(d, 1.f) << "face " << t << " cuts into the unit sphere";
      nearest = std::min(nearest, d);
    }
    EXPECT_LE(nearest, 1.f + 1e-5f);
    // Points of the unit sphere, random and at the vertex directions, are inside.
    std::mt19937 rng(7 + s);
    for (int i = 0; i < (s < 4 ? 2000 : 100); ++i) EXPECT_TRUE(m.contains(random_unit(rng))) << i;
    if (s <= 3) {
      for (const auto& p : m.positions) EXPECT_TRUE(m.contains(glm::normalize(p)));
    }
    // More triangles, a tighter fit.
    double radius = icosphere_circumradius(s);
    EXPECT_NEAR(glm::length(m.positions[0]), radius, 1e-6 * radius);
    EXPECT_LT(radius, previous_radius);
    previous_radius = radius;
  }
  EXPECT_NEAR(icosphere_circumradius(0), 1.2584, 1e-4);  // 1 / inradius of the unit icosahedron
  EXPECT_LT(icosphere_circumradius(2), 1.02);
}

TEST(VolumeMeshes, TheSphereThroughTheVerticesWouldCutTheLightShort) {
  // Why the scale: with the vertices on the sphere (scale 1), a face centre lies inside it.
  VolumeMesh m = icosphere(1);
  const float scale = icosphere_circumradius(1);
  glm::vec3 centroid = (m.positions[m.indices[0]] + m.positions[m.indices[1]] + m.positions[m.indices[2]]) / 3.f;
  EXPECT_LT(glm::length(centroid / scale), 0.97f);
}

TEST(VolumeMeshes, BadSubdivisionsAndSidesAreRefused) {
  EXPECT_THROW(icosphere(-1), Error);
  EXPECT_THROW(icosphere(7), Error);
  EXPECT_THROW(cone(2), Error);
}

TEST(VolumeMeshes, ConeContainsTheSpotLightsCone) {
  for (int sides : {6, 16}) {
    VolumeMesh m = cone(sides);
    expect_closed(m);
    EXPECT_GT(m.volume(), 0.0);
    for (float degrees : {5.f, 30.f, 45.f, 60.f}) {
      SCOPED_TRACE(std::to_string(sides) + " sides, " + std::to_string(degrees) + " degrees");
      Light spot;
      spot.type = LightType::Spot;
      spot.position = {1, 2, 3};
      spot.direction = glm::normalize(glm::vec3(0.3f, -1.f, 0.2f));
      spot.outer_cone = degrees * kPi / 180.f;
      spot.inner_cone = 0.5f * spot.outer_cone;
      const float radius = 5.f;
      SpotInstance s = pack_spot(spot, radius);
      glm::mat4 to_local = glm::inverse(volume_transform(s, true));
      // Every point the spot can light (within `radius`, within the outer cone) is inside,
      // including the sector's round cap and the rim where the cap meets the cone.
      glm::mat3 frame = basis_around(spot.direction);
      std::mt19937 rng(sides * 100 + int(degrees));
      std::uniform_real_distribution<float> u(0.f, 1.f);
      int n = 0;
      for (int i = 0; i < 4000; ++i) {
        float angle = spot.outer_cone * (i < 1000 ? 1.f : std::sqrt(u(rng)));  // a quarter on the rim
        float distance = radius * (i % 2 ? 1.f : u(rng));
        float around = 2 * kPi * u(rng);
        glm::vec3 dir = frame * glm::vec3(std::sin(angle) * std::cos(around), std::sin(angle) * std::sin(around), std::cos(angle));
        glm::vec3 local = glm::vec3(to_local * glm::vec4(spot.position + distance * dir, 1.f));
        n += m.contains(local, 2e-5f);
      }
      EXPECT_EQ(n, 4000);
      // And it is tight: 2% outside the cone's angle, or past the cut along the axis, is out.
      // (Towards the middle of a base edge, where the polygon touches the circle.)
      float wider = std::min(spot.outer_cone * 1.02f + 0.01f, 0.5f * kPi), mid_edge = kPi / sides;
      glm::vec3 outside = frame * glm::vec3(std::sin(wider) * std::cos(mid_edge), std::sin(wider) * std::sin(mid_edge), std::cos(wider)) * (0.9f * radius);
      glm::vec3 local = glm::vec3(to_local * glm::vec4(spot.position + outside, 1.f));
      EXPECT_FALSE(m.contains(local)) << "a much bigger cone would also pass";
      local = glm::vec3(to_local * glm::vec4(spot.position + spot.direction * (1.01f * radius), 1.f));
      EXPECT_FALSE(m.contains(local));
    }
  }
}

TEST(VolumeMeshes, WideSpotsUseTheSphere) {
  VolumeShapes shapes = make_volume_shapes(2, 16);
  auto uses_cone = [&](float degrees) { return spot_uses_cone(degrees * kPi / 180.f, shapes.cone_volume, shapes.sphere_volume); };
  EXPECT_TRUE(uses_cone(10));
  EXPECT_TRUE(uses_cone(45));
  EXPECT_TRUE(uses_cone(60));
  EXPECT_FALSE(uses_cone(65));  // tan^2 > 4 (times the polygons' factors): the sphere is smaller
  EXPECT_FALSE(uses_cone(90));
  EXPECT_FALSE(uses_cone(135));
  EXPECT_FALSE(uses_cone(std::nanf("")));
}

// --- The light radius ----------------------------------------------------------------------

namespace {
// The largest distance on a fine grid where chapter 01's attenuation still gives at least
// the threshold: a brute-force evaluation of the very function the shader uses.
double numerical_radius(float peak, float range, float threshold, double step) {
  double last = 0;
  for (double d = step; d < 1e5; d += step) {
    if (peak * lp::ch01::distance_attenuation(float(d), range) >= threshold) {
      last = d;
    } else if (range > 0 ? d > range : true) {
      break;
    }
  }
  return last;
}
}  // namespace

TEST(LightRadius, MatchesANumericalEvaluationOfTheAttenuation) {
  for (float threshold : {kLinearEightBitStep, cut_threshold(4.f, 1.f, kLinearEightBitStep), kSrgbFirstStep})
    for (float peak : {0.05f, 0.3f, 1.f, 25.f, 400.f})
      for (float range : {0.f, 0.5f, 2.f, 8.2f, 18.f, 100.f}) {
        SCOPED_TRACE("peak " + std::to_string(peak) + " range " + std::to_string(range) + " threshold " + std::to_string(threshold));
        float r = light_radius(peak, range, threshold);
        double bound = range > 0 ? range : std::sqrt(peak / threshold);
        double step = std::max(bound, 1e-3) / 20000.0;
        double numeric = numerical_radius(peak, range, threshold, step);
        EXPECT_GE(r, numeric) << "the volume would cut the light short";
        EXPECT_LE(r, numeric + step + 1e-5 * r) << "the volume is larger than it needs to be";
        // Just past the radius the light is below the threshold (or zero).
        EXPECT_LT(peak * lp::ch01::distance_attenuation(r * (1 + 1e-5f), range), threshold);
        if (range > 0) {
          EXPECT_LE(r, range * (1 + 1e-6f));
        }
      }
}

TEST(LightRadius, ClosedFormsAtTheEnds) {
  // No range: the inverse square alone, r = sqrt(peak / t); 16x the light, 4x the radius.
  EXPECT_NEAR(light_radius(1.f, 0.f, 1.f / 256.f), 16.f, 1e-4f);
  EXPECT_NEAR(light_radius(16.f, 0.f, 1.f / 256.f), 64.f, 1e-3f);
  // A 4x brighter exposure lowers the threshold 4x and doubles an unbounded light's reach.
  EXPECT_NEAR(light_radius(1.f, 0.f, cut_threshold(4.f)) / light_radius(1.f, 0.f, cut_threshold(1.f)), 2.f, 1e-5f);
  // The sRGB rule's threshold is 12.9x lower: an unbounded light reaches sqrt(12.9) = 3.6x further.
  EXPECT_NEAR(kLinearEightBitStep / kSrgbFirstStep, 12.92f * 255.f / 256.f, 1e-3f);
  // A bright light with a short range: the window decides, the radius is nearly the range.
  EXPECT_NEAR(light_radius(1000.f, 2.f, kLinearEightBitStep), 2.f, 0.01f);
  // The street's lights (range where I/d^2 = 0.015): the linear rule cuts them at 86% of
  // their range, the sRGB rule at 96% (roots of x^4 + a x - 1 with a = 0.51 and 0.14).
  const float range = std::sqrt(0.6f / 0.015f);
  EXPECT_NEAR(light_radius(0.6f, range, kLinearEightBitStep) / range, 0.865f, 0.005f);
  EXPECT_NEAR(light_radius(0.6f, range, kSrgbFirstStep) / range, 0.964f, 0.002f);
}

TEST(LightRadius, LightsThatGiveNoLightHaveNoVolume) {
  EXPECT_EQ(light_radius(0.f, 4.f, kLinearEightBitStep), 0.f);
  EXPECT_EQ(light_radius(-2.f, 4.f, kLinearEightBitStep), 0.f);
  EXPECT_EQ(light_radius(std::nanf(""), 4.f, kLinearEightBitStep), 0.f);
  EXPECT_EQ(light_radius(INFINITY, 4.f, kLinearEightBitStep), 0.f);
  EXPECT_THROW(light_radius(1.f, 4.f, 0.f), Error);
  // A negative range reads as unbounded, as in chapter 01's shader.
  EXPECT_FLOAT_EQ(light_radius(1.f, -3.f, kLinearEightBitStep), light_radius(1.f, 0.f, kLinearEightBitStep));
}

TEST(LightRadius, PeakReflectanceIsTheBrightestThatAMaterialCanMakeOfTheLight) {
  Scene scene;
  EXPECT_EQ(peak_reflectance(scene), 1.f);  // nothing reflects more than a white matte surface
  Material m;
  m.base_color = {0.5f, 0.2f, 0.1f, 1.f};
  m.specular_color = {0.04f, 1.f, 0.04f};
  m.roughness = 0.5f;  // exponent 30: the lobe peaks at (30 + 8) / 8
  scene.materials.push_back(m);
  EXPECT_NEAR(peak_reflectance(scene), 0.5f + 1.f * 38.f / 8.f, 1e-4f);
  // It bounds the shading of chapter 01's model: sampled over directions, never above.
  std::mt19937 rng(5);
  const float n = lp::ch01::exponent_from_roughness(m.roughness);
  float most = 0;
  for (int i = 0; i < 20000; ++i) {
    glm::vec3 l = random_unit(rng), v = random_unit(rng);
    auto r = lp::ch01::blinn_phong({0, 0, 1}, v, l, glm::vec3(1), n);
    glm::vec3 out = glm::vec3(m.base_color) * r.diffuse + m.specular_color * r.specular;
    most = std::max({most, out.r, out.g, out.b});
  }
  EXPECT_LE(most, peak_reflectance(scene));
  EXPECT_GT(most, 0.8f * peak_reflectance(scene)) << "and it is nearly reached";
}

TEST(LightRadius, TheTutorialFormulasPrecedenceSlipScalesTheRadiusByTheQuadraticTermSquared) {
  // The widely copied form for attenuation 1 / (c + l d + q d^2), cut where
  // peak / (c + l d + q d^2) = 5/256: the positive root of q d^2 + l d + c - peak 256/5 = 0.
  // Written "(-l + sqrt(...)) / 2 * q" it multiplies by q instead of dividing: q^2 too big a
  // factor. With q = 0.3 the spheres come out 11x too small; with q = 1.8, 3.2x too large.
  const float c = 1.f, l = 0.7f, peak = 1.f, t = 5.f / 256.f;
  for (float q : {0.3f, 1.8f}) {
    float root = std::sqrt(l * l - 4 * q * (c - (256.f / 5.f) * peak));
    float right = (-l + root) / (2.f * q);
    float slipped = (-l + root) / 2.f * q;
    // The right one is where the light meets the threshold, checked by evaluating it.
    EXPECT_NEAR(peak / (c + l * right + q * right * right), t, 1e-6f);
    EXPECT_NEAR(slipped / right, q * q, 1e-5f);
    if (q < 1) {
      EXPECT_GT(peak / (c + l * slipped + q * slipped * slipped), 10 * t) << "cut far too early";
    }
  }
  EXPECT_NEAR(1.f / (0.3f * 0.3f), 11.1f, 0.05f);
}

// --- Per-instance packing ------------------------------------------------------------------

TEST(Instances, SpotDirectionsSurviveTheOctahedralMapInFloats) {
  std::mt19937 rng(3);
  float worst = 0;
  for (int i = 0; i < 20000; ++i) {
    glm::vec3 n = random_unit(rng);
    glm::vec2 e = ch02::octahedral_fold(n);
    EXPECT_LE(std::max(std::abs(e.x), std::abs(e.y)), 1.f);
    worst = std::max(worst, glm::length(ch02::octahedral_unfold(e) - n));
  }
  for (glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0), glm::vec3(0, -1, 0)})
    worst = std::max(worst, glm::length(ch02::octahedral_unfold(ch02::octahedral_fold(n)) - n));
  EXPECT_LT(worst, 1e-6f);
}

TEST(Instances, PackingRoundTripGivesChapterOnesLight) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int i = 0; i < 500; ++i) {
    Light l;
    l.type = i % 2 ? LightType::Spot : LightType::Point;
    l.position = {40 * u(rng) - 20, 5 * u(rng), 100 * u(rng) - 50};
    l.color = {u(rng), u(rng), u(rng)};
    l.intensity = 10 * u(rng) + 0.01f;
    l.range = i % 3 ? 20 * u(rng) : 0.f;
    l.direction = random_unit(rng);
    l.outer_cone = 0.05f + 1.4f * u(rng);
    l.inner_cone = l.outer_cone * u(rng);
    ch01::GpuLight want = ch01::pack_light(l);
    float radius = light_radius(l, kLinearEightBitStep);
    ch01::GpuLight got = l.type == LightType::Spot ? unpack(pack_spot(l, radius)) : unpack(pack_point(l, radius));
    // What chapter 01's light_incident() reads: position and type, range, radiance, and for
    // a spot its direction and cone terms.
    EXPECT_EQ(got.position_type, want.position_type);
    EXPECT_EQ(got.direction_range.w, want.direction_range.w);
    EXPECT_EQ(glm::vec3(got.radiance), glm::vec3(want.radiance));
    if (l.type == LightType::Spot) {
      EXPECT_LT(glm::length(glm::vec3(got.direction_range) - glm::vec3(want.direction_range)), 1e-6f);
      EXPECT_EQ(got.spot.x, want.spot.x);
      EXPECT_EQ(got.spot.y, want.spot.y);
      // The light's incident radiance at a random point agrees to float precision.
      glm::vec3 p = l.position + 3.f * random_unit(rng);
      auto in_want = [&](const ch01::GpuLight& g) {
        Light back = l;
        back.direction = glm::vec3(g.direction_range);
        return ch01::incident(back, p).radiance;
      };
      EXPECT_LT(glm::length(in_want(got) - in_want(want)), 1e-5f * (1.f + glm::length(in_want(want))));
    }
  }
}

TEST(Instances, TheVolumeTransformPlacesTheUnitMeshesAroundTheLight) {
  Light l;
  l.position = {3, 1, -2};
  PointInstance p = pack_point(l, 4.f);
  glm::mat4 m = volume_transform(p);
  EXPECT_EQ(glm::vec3(m * glm::vec4(0, 0, 0, 1)), l.position);
  EXPECT_EQ(glm::vec3(m * glm::vec4(1, 0, 0, 1)), l.position + glm::vec3(4, 0, 0));
  l.type = LightType::Spot;
  l.direction = glm::normalize(glm::vec3(1, -1, 0));
  l.outer_cone = kPi / 4;
  SpotInstance s = pack_spot(l, 4.f);
  glm::mat4 c = volume_transform(s, true);
  EXPECT_LT(glm::length(glm::vec3(c * glm::vec4(0, 0, 1, 1)) - (l.position + 4.f * l.direction)), 1e-5f);
  glm::mat3 b = basis_around(l.direction);
  EXPECT_NEAR(glm::determinant(b), 1.f, 1e-5f);  // right-handed: the cone keeps its winding
  EXPECT_NEAR(glm::dot(b[0], b[1]), 0.f, 1e-6f);
}

TEST(Instances, BadLightsAreLeftOutWithAWarning) {
  VolumeShapes shapes = make_volume_shapes();
  auto light = [](LightType type, float intensity, float range, float outer = 0.5f) {
    Light l;
    l.name = "l";
    l.type = type;
    l.intensity = intensity;
    l.range = range;
    l.outer_cone = outer;
    l.inner_cone = 0.f;
    return l;
  };
  // A negative intensity or range breaks the loader's rule (light_defect): left out here too,
  // by name and why, as the loader leaves it out of a file; zero intensity is valid and dark.
  LightSet set = build_light_set({light(LightType::Point, 0.f, 4.f), light(LightType::Point, -1.f, 4.f),
                                  light(LightType::Point, 1.f, -2.f), light(LightType::Point, 1.f, 0.f),
                                  light(LightType::Spot, 1.f, 4.f, 0.5f * kPi), light(LightType::Spot, 1.f, 4.f, 2.f),
                                  light(LightType::Spot, 1.f, 4.f, 0.4f), light(LightType::Directional, 1.f, 0.f)},
                                 kLinearEightBitStep, shapes);
  EXPECT_EQ(set.points.size(), 1u);      // the unbounded one (range 0)
  EXPECT_EQ(set.cones.size(), 1u);
  EXPECT_EQ(set.wide_spots.size(), 2u);  // 90 degrees and 115 degrees
  EXPECT_EQ(set.directional.size(), 1u);
  ASSERT_EQ(set.warnings.size(), 4u);
  EXPECT_NE(set.warnings[0].find("is left out: its intensity -1 is negative"), std::string::npos) << set.warnings[0];
  EXPECT_NE(set.warnings[1].find("is left out: its range -2 is negative"), std::string::npos) << set.warnings[1];
  EXPECT_NE(set.warnings[2].find("give no light"), std::string::npos) << set.warnings[2];
  EXPECT_NE(set.warnings[2].find("(1)"), std::string::npos) << set.warnings[2];
  EXPECT_NE(set.warnings[3].find("90 degrees or more"), std::string::npos) << set.warnings[3];
  EXPECT_EQ(set.points[0].radiance_range.w, 0.f);
  EXPECT_NEAR(set.points[0].position_radius.w, 16.f, 1e-4f);
}

// --- Scissor rectangles ----------------------------------------------------------------------

TEST(Scissor, TheRectangleHoldsTheProjectedSphereAndLittleMore) {
  FrameCamera cam;
  cam.position = {1, 2, 10};
  cam.view = glm::lookAt(cam.position, glm::vec3(0, 1, 0), glm::vec3(0, 1, 0));
  cam.znear = 0.1f;
  cam.projection = glm::perspective(cam.yfov, cam.aspect, cam.znear, cam.zfar);
  const int w = 320, h = 180;
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  int checked = 0;
  for (int i = 0; i < 300; ++i) {
    glm::vec3 centre(6 * u(rng), 1 + u(rng), -8 + 8 * u(rng));
    float radius = 0.3f + 1.5f * (u(rng) + 1);
    auto rect = scissor_rect(cam, centre, radius, w, h);
    // The projections of points on the sphere (those in front of the near plane).
    glm::vec2 lo(1e9f), hi(-1e9f);
    bool any = false;
    for (int k = 0; k < 3000; ++k) {
      glm::vec4 clip = cam.projection * cam.view * glm::vec4(centre + radius * random_unit(rng), 1.f);
      if (clip.w < cam.znear) continue;
      glm::vec2 px = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(w, h);
      if (px.x < 0 || px.y < 0 || px.x >= w || px.y >= h) continue;
      lo = glm::min(lo, px);
      hi = glm::max(hi, px);
      any = true;
    }
    if (!any) continue;  // off screen: the rectangle may be empty or not
    ASSERT_TRUE(rect.has_value()) << i;
    EXPECT_LE(rect->x, std::floor(lo.x));
    EXPECT_LE(rect->y, std::floor(lo.y));
    EXPECT_GE(rect->x + rect->z, std::ceil(hi.x));
    EXPECT_GE(rect->y + rect->w, std::ceil(hi.y));
    float depth = -(cam.view * glm::vec4(centre, 1.f)).z;
    if (depth - radius > cam.znear && rect->z < w && rect->w < h) {  // tight, away from the edges
      EXPECT_LE(rect->z, hi.x - lo.x + 4) << i;
      EXPECT_LE(rect->w, hi.y - lo.y + 4) << i;
      ++checked;
    }
  }
  EXPECT_GT(checked, 50);
}

TEST(Scissor, BehindTheEyeNothingAtTheNearPlaneEverything) {
  FrameCamera cam;  // at the origin, looking down -z
  cam.znear = 0.1f;
  cam.projection = glm::perspective(cam.yfov, cam.aspect, cam.znear, cam.zfar);
  EXPECT_FALSE(scissor_rect(cam, {0, 0, 5}, 2.f, 320, 180).has_value()) << "wholly behind the eye";
  EXPECT_FALSE(scissor_rect(cam, {100, 0, -5}, 2.f, 320, 180).has_value()) << "far off to the side";
  auto all = scissor_rect(cam, {0, 0, 1}, 2.f, 320, 180);  // the eye inside it
  ASSERT_TRUE(all.has_value());
  EXPECT_EQ(*all, glm::ivec4(0, 0, 320, 180));
}
