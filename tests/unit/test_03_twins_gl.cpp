// Chapter 03's GLSL functions against their C++ twins (light_instances.h), on the GPU
// (glsl_twin.h): light_instance.glsl's unpack_point, unpack_spot and basis_around.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "chapters/01_forward/blinn_phong.h"
#include "chapters/02_gbuffer/gbuffer.h"
#include "chapters/02_gbuffer/layout.h"
#include "chapters/03_light_volumes/light_instances.h"
#include "tests/unit/glsl_twin.h"

namespace lp::ch03 {
namespace {

using test::TwinCase;
using test::ulps;
// light_instance.glsl needs chapter 01's GpuLight and chapter 02's octahedral_unfold first.
const std::vector<std::string> kInstance = {"01_forward/shaders/lighting.glsl", "02_gbuffer/shaders/encoding.glsl",
                                            "03_light_volumes/shaders/light_instance.glsl"};

glm::vec4 part(const ch01::GpuLight& l, int k) {
  return k == 0 ? l.position_type : k == 1 ? l.direction_range : k == 2 ? l.radiance : l.spot;
}

TEST(GlslTwins, UnpackedLightsMatchTheirCppTwins) {
  // Random points and spots (packed by the C++, as build_light_set does) unpacked by both.
  // Copies are exact; the spot's direction is chapter 02's octahedral_unfold, a few sums and
  // a normalize (GLSL: inversesqrt, 2 ulp, and a product), within 6 ulp of 1 on each side
  // absolutely: 12. Edge cases: the axes (the octahedron's corners) and straight down (its fold).
  test::TwinRandom r(3);
  std::vector<Light> spots;
  for (glm::vec3 d : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0), glm::vec3(0, -1, 0)})
    spots.push_back(Light{.type = LightType::Spot, .intensity = 1, .direction = d, .outer_cone = 0.5f});
  while (spots.size() < 10000 + 4) {
    Light l{.type = LightType::Spot, .color = {r.uniform(0, 1), r.uniform(0, 1), r.uniform(0, 1)},
            .intensity = r.log_uniform(0.01f, 100), .position = {r.uniform(-50, 50), r.uniform(-50, 50), r.uniform(-50, 50)},
            .direction = r.unit(), .range = r.uniform(0, 20)};
    l.outer_cone = r.uniform(0.05f, 1.5f);
    l.inner_cone = l.outer_cone * r.uniform(0, 1);
    spots.push_back(l);
  }
  std::vector<TwinCase> point_cases, spot_cases;
  std::vector<ch01::GpuLight> cpu_points, cpu_spots;
  for (const Light& l : spots) {
    const float radius = r.uniform(0.1f, 30);
    PointInstance p = pack_point(l, radius);
    SpotInstance s = pack_spot(l, radius);
    point_cases.push_back({p.position_radius, p.radiance_range});
    spot_cases.push_back({s.position_radius, s.radiance_range, s.direction_cone});
    cpu_points.push_back(unpack(p));
    cpu_spots.push_back(unpack(s));
  }
  const std::string helper =
      "vec4 twin_part(GpuLight l, int k) { return k == 0 ? l.position_type : k == 1 ? l.direction_range : k == 2 ? l.radiance : l.spot; }";
  for (int k = 0; k < 4; ++k) {
    const std::string which = std::to_string(k);
    const auto gpu_point = test::run_glsl_twin({kInstance, "twin_part(unpack_point(a, b), " + which + ")", {}, helper}, point_cases);
    const auto gpu_spot = test::run_glsl_twin({kInstance, "twin_part(unpack_spot(a, b, c), " + which + ")", {}, helper}, spot_cases);
    std::vector<glm::vec4> want_point, want_spot;
    for (std::size_t i = 0; i < spots.size(); ++i) {
      want_point.push_back(part(cpu_points[i], k));
      want_spot.push_back(part(cpu_spots[i], k));
    }
    auto describe = [&](std::size_t i) { return test::str(spot_cases[i].a) + " " + test::str(spot_cases[i].b) + " " + test::str(spot_cases[i].c); };
    EXPECT_TRUE(test::twins_agree(gpu_point, want_point, 4, {0, 0}, describe)) << "point, vec4 " << k;
    // the direction's xyz (k = 1) carries the unfold's rounding; its w, the range, is a copy
    std::vector<glm::vec4> g = gpu_spot, w = want_spot;
    if (k == 1) {
      for (std::size_t i = 0; i < g.size(); ++i) EXPECT_EQ(g[i].w, w[i].w) << describe(i);
    }
    EXPECT_TRUE(test::twins_agree(g, w, k == 1 ? 3 : 4, {k == 1 ? ulps(12) : 0, 0}, describe)) << "spot, vec4 " << k;
  }
}

TEST(GlslTwins, BasisAroundMatchesItsCppTwin) {
  // Random unit vectors, the poles (n.z = +-1, and -0: the sign picks +1 on both sides), the
  // equator and a vector 1e-4 from the south pole. s has n.z's sign, so |s + n.z| >= 1 and
  // |a| = 1 / |s + n.z| <= 1 (GLSL's division: 2.5 ulp): each entry, a few products of
  // values <= 1 and a sum, is within 8 ulp of 1 absolutely on the GLSL side, 4 on the C++.
  test::TwinRandom r(4);
  std::vector<TwinCase> cases;
  for (glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, -0.f), glm::vec3(0, 1, 0),
                      glm::normalize(glm::vec3(1e-4f, 0, -1))})
    cases.push_back({glm::vec4(n, 0)});
  while (cases.size() < 10000 + 5) cases.push_back({glm::vec4(r.unit(), 0)});
  for (int k = 0; k < 3; ++k) {
    const auto gpu = test::run_glsl_twin({kInstance, "basis_around(a.xyz)[" + std::to_string(k) + "], 0.0"}, cases);
    std::vector<glm::vec4> cpu;
    for (const auto& c : cases) cpu.push_back(glm::vec4(basis_around(glm::vec3(c.a))[k], 0));
    EXPECT_TRUE(test::twins_agree(gpu, cpu, 3, {ulps(12), 0}, [&](std::size_t i) { return "n = " + test::str(cases[i].a); }))
        << "column " << k;
  }
}

}  // namespace
}  // namespace lp::ch03

namespace lp::ch03 {
namespace {

TEST(GlslTwins, LocalLightsDiffuseMatchesItsCppTwin) {
  // local_light.glsl's diffuse term for a point light: chapter 01's light_incident and Lambert,
  // ended at the light's cut (the radius light_radius() gives its volume). Its C++ statement is
  // chapter 01's incident() and n . l, zero beyond the cut (as chapter 08's direct_diffuse).
  // The surface at the origin (normal random; translation changes nothing but rounding), the
  // light at 0 to 2 cuts from it (cuts 0.5 to 20 m, log-uniform; ranges 0 or up to 3 cuts),
  // plus a light on the surface and one exactly at its cut along the normal. Tolerance: the
  // radiance's of LightIncidentMatchesItsCppTwin (48 ulp of the window absolutely, 16 relative)
  // times n . l, plus n . l's 6 ulp of the radiance absolutely. Where the distance is within
  // rounding of the cut (8 ulp of it: GLSL's length 6, C++'s 2) either side is right.
  const std::vector<std::string> files = {"01_forward/shaders/lighting.glsl", "02_gbuffer/shaders/gbuffer.glsl",
                                          "03_light_volumes/shaders/hooks/full_visibility.glsl",
                                          "03_light_volumes/shaders/local_light.glsl"};
  const std::string helper =
      "vec4 twin_local(vec4 a, vec4 b, vec4 c, vec4 d) { Surface s = Surface(vec3(0.0), d.xyz, vec3(1.0), vec3(1.0), 16.0, "
      "vec3(0.0), false, 0.5); vec3 df, sp; local_light(GpuLight(a, b, vec4(c.rgb, 0.0), vec4(0.0)), c.w, 0, s, df, sp); "
      "return vec4(df, 0.0); }";
  test::TwinRandom r(30);
  std::vector<test::TwinCase> cases;
  auto add = [&](glm::vec3 at, glm::vec3 radiance, float range, float cut, glm::vec3 n) {
    cases.push_back({glm::vec4(at, 1.f), glm::vec4(0, 0, -1, range), glm::vec4(radiance, cut), glm::vec4(n, 0)});
  };
  add(glm::vec3(0), glm::vec3(1), 0, 1, glm::vec3(0, 1, 0));
  add(glm::vec3(0, 2, 0), glm::vec3(1), 0, 2, glm::vec3(0, 1, 0));
  while (cases.size() < 10000 + 2) {
    const float cut = r.log_uniform(0.5f, 20);
    glm::vec3 n = r.unit(), to = r.unit();
    if (glm::dot(n, to) < 0) to = -to;  // most lights above the surface
    add(to * r.uniform(0, 2 * cut), glm::vec3(r.uniform(0, 5), r.uniform(0, 5), r.uniform(0, 5)),
        r.uniform(0, 1) < 0.3f ? 0.f : r.uniform(0.5f, 3) * cut, cut, n);
  }
  const std::vector<std::string> defines = ch02::gbuffer_defines(ch02::layouts()[0]);  // ours
  const auto gpu = test::run_glsl_twin({files, "twin_local(a, b, c, d)", defines, helper}, cases);
  std::vector<glm::vec4> cpu;
  std::vector<test::TwinTolerance> tolerance;
  for (const auto& c : cases) {
    Light l{.type = LightType::Point, .color = glm::vec3(c.c), .intensity = 1.f, .position = glm::vec3(c.a), .range = c.b.w};
    const ch01::Incident in = ch01::incident(l, glm::vec3(0));
    const float distance = glm::length(glm::vec3(c.a));
    const float n_dot_l = glm::dot(glm::vec3(c.d), in.to_light);
    const glm::vec3 diffuse = distance <= c.c.w && n_dot_l > 0 ? in.radiance * n_dot_l : glm::vec3(0);
    cpu.push_back(glm::vec4(diffuse, 0));
    const double peak = std::max({c.c.r, c.c.g, c.c.b});
    const double d2 = std::max(double(distance) * distance, 1e-4);
    if (std::abs(double(distance) - c.c.w) <= test::ulps(8) * c.c.w)
      tolerance.push_back({peak / d2, 0});  // at the cut: lit or not
    else
      tolerance.push_back({peak * test::ulps(48) / d2 + glm::length(in.radiance) * test::ulps(6), test::ulps(16)});
  }
  EXPECT_TRUE(test::twins_agree(
      gpu, cpu, 3, [&](std::size_t i) { return tolerance[i]; },
      [&](std::size_t i) {
        return "light " + test::str(cases[i].a) + " range " + test::str(cases[i].b) + " radiance, cut " + test::str(cases[i].c) +
               " normal " + test::str(cases[i].d);
      }));
}

}  // namespace
}  // namespace lp::ch03
