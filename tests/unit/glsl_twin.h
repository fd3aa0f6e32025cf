#pragma once
// Shaders against their C++ twins. A GLSL function and its C++ twin (HACKING.md, "Rules") say the
// same thing; run_glsl_twin() runs the GLSL one on the GPU, in a compute shader that includes
// the shader's own file (tests/shaders/glsl_twin.comp), for every case, so a test can compare
// it with the C++ one case by case. Needs the GL test environment's context.
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "common/rng.h"

namespace lp::test {

struct TwinCase {
  glm::vec4 a{0}, b{0}, c{0}, d{0};
};

struct GlslTwin {
  std::vector<std::string> files;  // relative to chapters/, included in this order (at most 4)
  std::string expression;          // GLSL over `vec4 a, b, c, d`: anything vec4(...) takes
  std::vector<std::string> defines = {};
  std::string helpers = {};        // one line of GLSL after the includes: functions the expression calls
  // Sets the included files' uniforms before the dispatch (given the program's GL id).
  std::function<void(unsigned program)> uniforms = {};
};

// The expression's value for every case, computed on the GPU. Throws lp::Error naming the
// shader file and line when the program does not build.
std::vector<glm::vec4> run_glsl_twin(const GlslTwin& twin, const std::vector<TwinCase>& cases);

// Random inputs: uniform in [lo, hi), and a random unit vector.
struct TwinRandom {
  explicit TwinRandom(std::uint64_t seed) : rng(seed, 23) {}
  float uniform(float lo, float hi) { return lo + (hi - lo) * rng.uniform(); }
  // Log-uniform in [lo, hi], lo > 0: every octave as likely, for inputs that span many.
  float log_uniform(float lo, float hi) { return lo * std::exp2(std::log2(hi / lo) * rng.uniform()); }
  glm::vec3 unit();
  Pcg32 rng;
};

// The tolerance of one comparison: |gpu - cpu| <= absolute + relative * max(|gpu|, |cpu|).
// NaN must match NaN (and only NaN); infinities must match exactly.
struct TwinTolerance {
  double absolute = 0, relative = 0;
};

// Compares the first `components` components of every case; reports the worst case, and
// the first few failures with `describe(i)` (the inputs), as a GoogleTest assertion.
::testing::AssertionResult twins_agree(const std::vector<glm::vec4>& gpu, const std::vector<glm::vec4>& cpu,
                                       int components, TwinTolerance tolerance,
                                       const std::function<std::string(std::size_t)>& describe);
// The same with a tolerance per case (one that depends on the inputs).
::testing::AssertionResult twins_agree(const std::vector<glm::vec4>& gpu, const std::vector<glm::vec4>& cpu,
                                       int components, const std::function<TwinTolerance(std::size_t)>& tolerance,
                                       const std::function<std::string(std::size_t)>& describe);

// A relative error of n ulps: a float's ulp is at most 2^-23 of its value.
inline double ulps(double n) { return n * 0x1p-23; }

std::string str(const glm::vec4& v);

}  // namespace lp::test
