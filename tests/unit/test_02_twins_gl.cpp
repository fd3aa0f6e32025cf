// Chapter 02's GLSL functions against their C++ twins (encoding.h), on the GPU (glsl_twin.h):
// encoding.glsl's octahedral fold and unfold, the xyz decode and the exponent's code. (The
// octahedral codes are held to their error bounds by GBufferGl.GlslNormalEncodersStayWithin-
// TheirBoundsOverTheWholeSphere, decoded by the C++ twin.)
#include <gtest/gtest.h>

#include <cmath>

#include "chapters/02_gbuffer/encoding.h"
#include "tests/unit/glsl_twin.h"

namespace lp::ch02 {
namespace {

using test::TwinCase;
using test::ulps;
const std::vector<std::string> kEncoding = {"02_gbuffer/shaders/encoding.glsl"};

TEST(GlslTwins, OctahedralFoldAndUnfoldMatchTheirCppTwins) {
  // fold: random unit vectors, the axes and the folds' edges (a zero component); n / |n|_1 is
  // a division (GLSL 2.5 ulp) of sums of |components| (1 ulp), and the lower half's 1 - |p| a
  // subtraction: within 5 ulp of 1 absolutely on the GLSL side, 2 on the C++: 7.
  // unfold: random points of the square and its corners and edges; a few sums and a normalize
  // (GLSL: inversesqrt 2 ulp and products): within 8 ulp of 1 absolutely, 3 on the C++: 11.
  test::TwinRandom r(2);
  std::vector<TwinCase> cases;
  for (glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0), glm::vec3(0, -1, 0),
                      glm::normalize(glm::vec3(1, 1, 0)), glm::normalize(glm::vec3(-1, 0, -1))})
    cases.push_back({glm::vec4(n, 0), glm::vec4(n.x, n.y, 0, 0)});
  while (cases.size() < 10000 + 6) cases.push_back({glm::vec4(r.unit(), 0), glm::vec4(r.uniform(-1, 1), r.uniform(-1, 1), 0, 0)});
  const auto fold = test::run_glsl_twin({kEncoding, "octahedral_fold(a.xyz), 0.0, 0.0"}, cases);
  const auto unfold = test::run_glsl_twin({kEncoding, "octahedral_unfold(b.xy), 0.0"}, cases);
  std::vector<glm::vec4> cpu_fold, cpu_unfold;
  for (const auto& c : cases) {
    cpu_fold.push_back(glm::vec4(octahedral_fold(glm::vec3(c.a)), 0, 0));
    cpu_unfold.push_back(glm::vec4(octahedral_unfold(glm::vec2(c.b)), 0));
  }
  auto describe = [&](std::size_t i) { return "n " + test::str(cases[i].a) + " p " + test::str(cases[i].b); };
  EXPECT_TRUE(test::twins_agree(fold, cpu_fold, 2, {ulps(7), 0}, describe)) << "fold";
  EXPECT_TRUE(test::twins_agree(unfold, cpu_unfold, 3, {ulps(11), 0}, describe)) << "unfold";
}

TEST(GlslTwins, XyzDecodeMatchesItsCppTwin) {
  // Every 10-bit code triple on a 22^3 grid (and the extremes): code / 1023 * 2 - 1 and a
  // normalize, within 8 ulp of 1 absolutely on the GLSL side, 3 on the C++. The all-middle code
  // (511.5 is not a code) never gives a zero vector.
  std::vector<TwinCase> cases;
  for (int x = 0; x < 1024; x += 48)
    for (int y = 0; y < 1024; y += 48)
      for (int z = 0; z < 1024; z += 48) cases.push_back({glm::vec4(x, y, z, 0)});
  for (int k : {0, 511, 512, 1023}) cases.push_back({glm::vec4(k, 1023 - k, k, 0)});
  ASSERT_GE(cases.size(), 10000u);
  const auto gpu = test::run_glsl_twin({kEncoding, "decode_xyz(a.xyz / 1023.0), 0.0"}, cases);
  std::vector<glm::vec4> cpu;
  for (const auto& c : cases) cpu.push_back(glm::vec4(decode_xyz({std::uint32_t(c.a.x), std::uint32_t(c.a.y), std::uint32_t(c.a.z)}, 10), 0));
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 3, {ulps(11), 0}, [&](std::size_t i) { return "codes " + test::str(cases[i].a); }));
}

TEST(GlslTwins, ExponentCodeMatchesItsCppTwin) {
  // Exponents log-uniform over 0.5 .. 10^4 (below 1 and above 8192: the clamps) and every
  // code's decode. Encode: the same code, except where log2(n) / 13 x 255 lies within rounding
  // of a half (GLSL's log2: 3 ulp, or 2^-21 absolutely near 1; times 255 / 13), where either
  // neighbour is right. Decode: exp2 of code x 13 / 255, GLSL's exp2 within 3 + 2|x| ulp, the
  // C++ one 1: relative 3 + 2 x 13 + 2 ulp.
  test::TwinRandom r(3);
  std::vector<TwinCase> cases;
  for (float n : {1.f, 8192.f, 0.5f, 1e4f}) cases.push_back({glm::vec4(n, 0, 0, 0)});
  for (int code = 0; code < 256; ++code) cases.push_back({glm::vec4(1, float(code), 0, 0)});
  while (cases.size() < 10000 + 260) cases.push_back({glm::vec4(r.log_uniform(0.5f, 1e4f), 0, 0, 0)});
  const auto gpu = test::run_glsl_twin({kEncoding, "encode_exponent(a.x) * 255.0, decode_exponent(a.y / 255.0), 0.0, 0.0"}, cases);
  std::vector<glm::vec4> cpu_code, gpu_code, cpu_n, gpu_n;
  std::vector<double> slack;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const float n = cases[i].a.x;
    const double unrounded = std::clamp(std::log2(std::max(double(n), 1.0)) / 13.0, 0.0, 1.0) * 255.0;
    const double to_half = std::abs(unrounded - std::floor(unrounded) - 0.5);
    slack.push_back(to_half <= (0x1p-21 + ulps(3) * std::abs(std::log2(std::max(double(n), 1.0)))) * 255.0 / 13.0 + ulps(4) * 255 ? 1 : 0);
    cpu_code.push_back(glm::vec4(float(encode_exponent(n))));
    gpu_code.push_back(glm::vec4(std::round(gpu[i].x)));
    cpu_n.push_back(glm::vec4(decode_exponent(std::uint32_t(cases[i].a.y))));
    gpu_n.push_back(glm::vec4(gpu[i].y));
  }
  auto describe = [&](std::size_t i) { return "n, code " + test::str(cases[i].a); };
  EXPECT_TRUE(test::twins_agree(gpu_code, cpu_code, 1, [&](std::size_t i) { return test::TwinTolerance{slack[i], 0}; }, describe))
      << "encode";
  EXPECT_TRUE(test::twins_agree(gpu_n, cpu_n, 1, {0, ulps(31)}, describe)) << "decode";
}

}  // namespace
}  // namespace lp::ch02
