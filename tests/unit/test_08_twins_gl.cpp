// Chapter 08's GLSL functions against their C++ twins (gi_math.h), on the GPU (glsl_twin.h):
// gi_math.glsl's disk_transfer, pixel_jitter and pattern_point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "chapters/08_ssgi/gi_math.h"
#include "chapters/08_ssgi/ssgi.h"
#include "tests/unit/glsl_twin.h"

namespace lp::ch08 {
namespace {

using test::TwinCase;
using test::ulps;
const std::vector<std::string> kGi = {"08_ssgi/shaders/gi_math.glsl"};

TEST(GlslTwins, DiskTransferMatchesItsCppTwin) {
  // Receivers and emitters in a 4 m box with random unit normals and areas from 1 cm^2 to 1 m^2
  // (log-uniform), plus the same point, no area, an emitter facing away, one behind the
  // receiver, one on its tangent plane and one 1 km away. v = e - p is the same subtraction on
  // both sides; r^2 a dot (1.5 ulp); v / r (GLSL: inversesqrt, 2 ulp, and a product; C++: sqrt
  // and a division, 1): each cosine within 6 ulp of 1 absolutely on either side, so F within
  // 2 x 2 x 6 ulp of A / (pi r^2 + A) absolutely; the products and the division add 4.5 ulp
  // (GLSL) and 2 (C++) relative.
  test::TwinRandom r(8);
  std::vector<TwinCase> cases;
  const glm::vec4 up(0, 0, 1, 0), p(0, 0, 0, 0.1f);  // w of a: the area
  cases.push_back({p, up, glm::vec4(0), -up});                        // the same point
  cases.push_back({glm::vec4(0, 0, 0, 0), up, glm::vec4(0, 0, 1, 0), -up});  // no area
  cases.push_back({p, up, glm::vec4(0, 0, 1, 0), up});                // facing away
  cases.push_back({p, up, glm::vec4(0, 0, -1, 0), up});               // behind the receiver
  cases.push_back({p, up, glm::vec4(1, 0, 0, 0), glm::vec4(-1, 0, 0, 0)});  // on its tangent plane
  cases.push_back({p, up, glm::vec4(0, 0, 1000, 0), -up});            // far
  cases.push_back({p, up, glm::vec4(0, 0, 0.01f, 0), -up});           // close: F -> 1
  while (cases.size() < 10000 + 7) {
    glm::vec3 a(r.uniform(-2, 2), r.uniform(-2, 2), r.uniform(-2, 2)), e(r.uniform(-2, 2), r.uniform(-2, 2), r.uniform(-2, 2));
    cases.push_back({glm::vec4(a, r.log_uniform(1e-4f, 1)), glm::vec4(r.unit(), 0), glm::vec4(e, 0), glm::vec4(r.unit(), 0)});
  }
  const auto gpu = test::run_glsl_twin({kGi, "disk_transfer(a.xyz, b.xyz, c.xyz, d.xyz, a.w)"}, cases);
  std::vector<glm::vec4> cpu;
  for (const auto& c : cases)
    cpu.push_back(glm::vec4(disk_transfer(glm::vec3(c.a), glm::vec3(c.b), glm::vec3(c.c), glm::vec3(c.d), c.a.w)));
  EXPECT_TRUE(test::twins_agree(
      gpu, cpu, 1,
      [&](std::size_t i) {
        const double r2 = glm::dot(glm::vec3(cases[i].c - cases[i].a), glm::vec3(cases[i].c - cases[i].a));
        const double area = cases[i].a.w;
        return test::TwinTolerance{area / (3.14159265358979 * r2 + area) * ulps(24), ulps(7)};
      },
      [&](std::size_t i) {
        return "p, area " + test::str(cases[i].a) + " np " + test::str(cases[i].b) + " e " + test::str(cases[i].c) + " ne " +
               test::str(cases[i].d);
      }));
}

TEST(GlslTwins, PixelJitterMatchesItsCppTwinBitForBit) {
  // Integer hashing and a division by 2^24: exact on both sides, for every pixel of an 8K
  // image's first rows, random pixels up to 65535 and the corners of that range.
  test::TwinRandom r(9);
  std::vector<TwinCase> cases;
  for (float y : {0.f, 1.f, 65535.f})
    for (float x : {0.f, 1.f, 65535.f}) cases.push_back({glm::vec4(x, y, 0, 0)});
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4096; ++x) cases.push_back({glm::vec4(float(x), float(y), 0, 0)});
  while (cases.size() < 10000 + 9) cases.push_back({glm::vec4(std::floor(r.uniform(0, 65536)), std::floor(r.uniform(0, 65536)), 0, 0)});
  const auto gpu = test::run_glsl_twin({kGi, "pixel_jitter(ivec2(a.xy)), 0.0, 0.0"}, cases);
  std::vector<glm::vec4> cpu;
  for (const auto& c : cases) cpu.push_back(glm::vec4(pixel_jitter(glm::uvec2(c.a.x, c.a.y)), 0, 0));
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 2, {0, 0}, [&](std::size_t i) { return "pixel " + test::str(cases[i].a); }));
}

TEST(GlslTwins, PatternPointsMatchTheirCppTwins) {
  // Every point of each pattern for every sample count 1..kMaxSamples, at a random pixel
  // each (the randomised pattern's jitter), as ssgi.cpp sets the uniforms: rings =
  // regular_rings(n), spokes = n / rings. The radius sqrt((k + offset) / n) is a division
  // (GLSL 2.5 ulp) and a sqrt (GLSL: 1 / inversesqrt, 4.5 ulp): 8 ulp on the GLSL side, 1 on
  // the C++. The angle a (up to 2.4 x kMaxSamples + 2 pi) may differ by 2 ulp of a (a fused
  // multiply-add on one side only); GLSL 4.50 leaves sin and cos's precision to the
  // implementation, and we allow them 2^-20 absolutely (a bound, not the spec's).
  test::TwinRandom r(10);
  std::vector<TwinCase> cases;
  for (int pattern = 0; pattern < 3; ++pattern)
    for (int n = 1; n <= kMaxSamples; ++n) {
      const int rings = regular_rings(n), spokes = std::max(1, n / rings);
      const int used = pattern == 0 ? rings * spokes : n;
      for (int i = 0; i < used; ++i)
        cases.push_back({glm::vec4(float(pattern), float(i), float(used), float(rings)),
                         glm::vec4(std::floor(r.uniform(0, 4096)), std::floor(r.uniform(0, 4096)), float(spokes), float(n))});
    }
  ASSERT_GE(cases.size(), 10000u);
  const auto gpu = test::run_glsl_twin(
      {kGi, "pattern_point(int(a.x), int(a.y), int(a.z), int(a.w), int(b.z), pixel_jitter(ivec2(b.xy))), 0.0, 0.0"}, cases);
  std::vector<glm::vec4> cpu;
  for (const auto& c : cases)
    cpu.push_back(glm::vec4(pattern_point(Pattern(int(c.a.x)), int(c.a.y), int(c.b.w), glm::uvec2(c.b.x, c.b.y)), 0, 0));
  EXPECT_TRUE(test::twins_agree(
      gpu, cpu, 2,
      [&](std::size_t i) {
        const double angle = 2.4 * cases[i].a.y + 6.3;
        return test::TwinTolerance{ulps(9) + ulps(2) * angle + 0x1p-20, 0};
      },
      [&](std::size_t i) { return "pattern, i, samples, rings " + test::str(cases[i].a) + " pixel, spokes, n " + test::str(cases[i].b); }));
}

}  // namespace
}  // namespace lp::ch08

namespace lp::ch08 {
namespace {

TEST(GlslTwins, IncidentMatchesChapterOnesLightIncident) {
  // gi_math.h's incident() is the truth's copy of chapter 01's light_incident() for a packed
  // light (the truth evaluates the frame's lights at each hit). Random packed point and spot
  // lights and points within 10 m; the tolerance as chapter 01's twin test derives it
  // (test_01_twins_gl.cpp): the direction within 13 ulp of 1, the radiance within 48 + 26 x
  // the spot's scale ulp of the window over max(d^2, 1e-4) absolutely, 16 ulp relative. And
  // the distance it returns, a length (GLSL's 6 ulp, C++ 2).
  test::TwinRandom r(12);
  std::vector<TwinCase> cases;
  std::vector<glm::vec3> points;
  while (cases.size() < 10000) {
    Light l{.type = r.uniform(0, 1) < 0.5f ? LightType::Point : LightType::Spot, .color = {r.uniform(0, 1), r.uniform(0, 1), r.uniform(0, 1)},
            .intensity = r.log_uniform(0.01f, 100), .position = {r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5)},
            .direction = r.unit(), .range = r.uniform(0, 1) < 0.3f ? 0.f : r.log_uniform(0.5f, 20)};
    l.outer_cone = r.uniform(0.05f, 1.5f);
    l.inner_cone = l.outer_cone * r.uniform(0, 1);
    const ch01::GpuLight g = ch01::pack_light(l);
    const glm::vec3 p(r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5));
    cases.push_back({g.position_type, g.direction_range, glm::vec4(glm::vec3(g.radiance), p.x), glm::vec4(g.spot.x, g.spot.y, p.y, p.z)});
    points.push_back(p);
  }
  const std::vector<std::string> files = {"01_forward/shaders/lighting.glsl"};
  const std::string helper =
      "vec4 twin_incident(vec4 a, vec4 b, vec4 c, vec4 d, bool dir) { vec3 t, r; "
      "light_incident(GpuLight(a, b, vec4(c.xyz, 0.0), vec4(d.xy, 0.0, 0.0)), vec3(c.w, d.zw), t, r); "
      "return vec4(dir ? t : r, length(a.xyz - vec3(c.w, d.zw))); }";
  const auto to_light = test::run_glsl_twin({files, "twin_incident(a, b, c, d, true)", {}, helper}, cases);
  const auto radiance = test::run_glsl_twin({files, "twin_incident(a, b, c, d, false)", {}, helper}, cases);
  std::vector<glm::vec4> cpu_to_light, cpu_radiance;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& c = cases[i];
    const ch01::GpuLight g{c.a, c.b, glm::vec4(glm::vec3(c.c), 0), glm::vec4(c.d.x, c.d.y, 0, 0)};
    glm::vec3 t, rad;
    float distance;
    incident(g, points[i], t, rad, distance);
    cpu_to_light.push_back(glm::vec4(t, distance));
    cpu_radiance.push_back(glm::vec4(rad, distance));
  }
  auto describe = [&](std::size_t i) { return test::str(cases[i].a) + " " + test::str(cases[i].b) + " " + test::str(cases[i].c) + " " + test::str(cases[i].d); };
  std::vector<glm::vec4> gpu_distance, cpu_distance;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    gpu_distance.push_back(glm::vec4(to_light[i].w));
    cpu_distance.push_back(glm::vec4(cpu_to_light[i].w));
  }
  EXPECT_TRUE(test::twins_agree(to_light, cpu_to_light, 3, {ulps(13), 0}, describe)) << "direction";
  EXPECT_TRUE(test::twins_agree(gpu_distance, cpu_distance, 1, {0, ulps(8)}, describe)) << "distance";
  EXPECT_TRUE(test::twins_agree(
      radiance, cpu_radiance, 3,
      [&](std::size_t i) {
        const auto& c = cases[i];
        const double d = cpu_distance[i].x;
        const double peak = std::max({c.c.x, c.c.y, c.c.z});
        const double scale = c.a.w == 2.f ? double(c.d.y) : 0;
        return test::TwinTolerance{peak * ulps(48 + 26 * scale) / std::max(d * d, 1e-4), ulps(16)};
      },
      describe))
      << "radiance";
}

}  // namespace
}  // namespace lp::ch08
