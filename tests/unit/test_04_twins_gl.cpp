// Chapter 04's GLSL functions against their C++ twins (neon.h), on the GPU (glsl_twin.h):
// neon.glsl's closest point on the tube and its volume's mask, for a capsule and a cylinder
// unpacked by the GLSL from pack_neon()'s record. (neon_light() and its methods are held by
// NeonGl.GlslMatchesTheCpp, a regression bound: HACKING.md, 'Tolerances'.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "chapters/04_neon/capsule.h"
#include "chapters/04_neon/neon.h"
#include "tests/unit/glsl_twin.h"
#include "tests/unit/test_04_configs.h"

namespace lp::ch04 {
namespace {

using test::TwinCase;
using test::ulps;
using testing::test_tube;
const std::vector<std::string> kNeon = {"04_neon/shaders/neon.glsl"};

// A GLSL function returning the packed record as a constant, so the expression can unpack it.
std::string record(const NeonGpu& g) {
  auto v = [](glm::vec4 x) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "vec4(%.9g, %.9g, %.9g, %.9g)", x.x, x.y, x.z, x.w);
    return std::string(buf);
  };
  return "NeonGpu twin_tube() { return NeonGpu(mat4(" + v(g.rows[0]) + ", " + v(g.rows[1]) + ", " + v(g.rows[2]) + ", " +
         v(g.rows[3]) + "), " + v(g.barn_doors) + ", " + v(g.extra) + "); }";
}

TEST(GlslTwins, ClosestPointAndVolumeMaskMatchTheirCppTwins) {
  // Points within 3 volume radii of a 2 m tube, as a capsule and as a cylinder, plus its ends,
  // its centre and points on its axis beyond the ends. closest_on_segment: t = (p - a).(b - a)
  // / |b - a|^2, clamped: the dot within 3 ulp of |p - a| |b - a| on each side and the
  // division 2.5 (GLSL), so t within 8 ulp of |p - a| / |b - a| + 1 absolutely; and the GLSL
  // reads the tube's ends from its unpacked record (centre -+ axis x half length: 4 ulp of
  // the larger), which moves t by as much again. The mask is 0 or 1: equal, except where the
  // point lies within rounding of the volume's surface (16 ulp of the radius) or, for the
  // cylinder, of an end's plane (16 ulp of the length), where either is right.
  NeonLight capsule = test_tube(), cylinder = test_tube();
  cylinder.caps = false;
  test::TwinRandom r(4);
  for (const NeonLight& light : {capsule, cylinder}) {
    const NeonGpu packed = pack_neon(light, volume_radius(light));
    const UnpackedNeon u = unpack_neon(packed);
    const float R = u.volume_radius, L = u.light.length();
    std::vector<TwinCase> cases;
    for (glm::vec3 p : {u.light.start, u.light.end, 0.5f * (u.light.start + u.light.end), u.light.end + glm::vec3(0.5f, 0, 0),
                        u.light.start - glm::vec3(0.5f, 0, 0)})
      cases.push_back({glm::vec4(p, 0)});
    while (cases.size() < 10000 + 5) {
      const glm::vec3 along = u.light.start + r.uniform(-0.5f, 1.5f) * (u.light.end - u.light.start);
      cases.push_back({glm::vec4(along + r.unit() * r.uniform(0, 3 * R), 0)});
    }
    const std::string helper = record(packed);
    const auto gpu = test::run_glsl_twin(
        {kNeon,
         "neon_closest_on_segment(a.xyz, neon_unpack(twin_tube()).start, neon_unpack(twin_tube()).end), "
         "neon_volume_mask(a.xyz, neon_unpack(twin_tube())), 0.0, 0.0",
         {}, helper},
        cases);
    std::vector<glm::vec4> cpu;
    std::vector<test::TwinTolerance> t_tol, mask_tol;
    for (const auto& c : cases) {
      const glm::vec3 p(c.a);
      const float t = closest_on_segment(p, u.light.start, u.light.end);
      cpu.push_back(glm::vec4(t, volume_mask(p, u.light, R), 0, 0));
      const double reach = glm::distance(p, u.light.start) / L + 1;
      t_tol.push_back({ulps(16) * reach, 0});
      const glm::vec3 closest = u.light.start + t * (u.light.end - u.light.start);
      const double along = glm::dot(p - u.light.start, (u.light.end - u.light.start) / L);
      const bool at_surface = std::abs(double(glm::distance(p, closest)) - R) <= ulps(16) * (R + glm::length(p));
      const bool at_end = !light.caps && (std::abs(along) <= ulps(16) * (L + glm::length(p)) ||
                                          std::abs(along - L) <= ulps(16) * (L + glm::length(p)));
      mask_tol.push_back({at_surface || at_end ? 1.0 : 0.0, 0});
    }
    std::vector<glm::vec4> gpu_t, cpu_t, gpu_mask, cpu_mask;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      gpu_t.push_back(glm::vec4(gpu[i].x)), cpu_t.push_back(glm::vec4(cpu[i].x));
      gpu_mask.push_back(glm::vec4(gpu[i].y)), cpu_mask.push_back(glm::vec4(cpu[i].y));
    }
    auto describe = [&](std::size_t i) { return "point " + test::str(cases[i].a); };
    const char* name = light.caps ? "capsule" : "cylinder";
    EXPECT_TRUE(test::twins_agree(gpu_t, cpu_t, 1, [&](std::size_t i) { return t_tol[i]; }, describe)) << name << ": closest";
    EXPECT_TRUE(test::twins_agree(gpu_mask, cpu_mask, 1, [&](std::size_t i) { return mask_tol[i]; }, describe)) << name << ": mask";
  }
}

}  // namespace
}  // namespace lp::ch04
