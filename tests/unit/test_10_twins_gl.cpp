// Chapter 10's GLSL functions against their C++ twins, on the GPU (glsl_twin.h).
#include <gtest/gtest.h>

#include <limits>

#include "chapters/10_frame/transparency.h"
#include "tests/unit/glsl_twin.h"

namespace lp::ch10 {
namespace {

using test::TwinCase;

TEST(GlslTwins, WboitWeightMatchesItsCppTwin) {
  // wboit_weight.glsl against transparency.cpp over view depths from 1 mm to 10 km (log-uniform:
  // the weight changes over decades) and alphas in [0, 1], plus 0, the clamps' ends and
  // overflow (b^6 = inf gives the floor 1e-2 on both sides). Tolerance, relative: the GLSL
  // side's a = z / 5 and b = z / 200 (2.5 ulp each, GLSL's division), a^2 (2 x 2.5 + 0.5),
  // b^6 (6 x 2.5 + 5 x 0.5), their sum (+ 0.5), 10 / sum (+ 2.5) and x alpha (+ 0.5): 25 ulp,
  // and the C++ side's with correctly rounded division (0.5 ulp each): 10 ulp. 35 ulp in all.
  test::TwinRandom r(10);
  std::vector<TwinCase> cases;
  for (float z : {0.f, 1e-6f, 1.f, 5.f, 200.f, 1e3f, 3e4f, 1e30f, std::numeric_limits<float>::infinity()})
    for (float alpha : {0.f, 0.25f, 1.f}) cases.push_back({glm::vec4(z, alpha, 0, 0)});
  while (cases.size() < 10000 + 27) cases.push_back({glm::vec4(r.log_uniform(1e-3f, 1e4f), r.uniform(0, 1), 0, 0)});
  const auto gpu = test::run_glsl_twin({{"10_frame/shaders/wboit_weight.glsl"}, "wboit_weight(a.x, a.y)"}, cases);
  std::vector<glm::vec4> cpu;
  for (const auto& c : cases) cpu.push_back(glm::vec4(wboit_weight(c.a.x, c.a.y)));
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 1, {0, test::ulps(35)},
                                [&](std::size_t i) { return "z, alpha = " + test::str(cases[i].a); }));
}

}  // namespace
}  // namespace lp::ch10
