// See glsl_twin.h.
#include "tests/unit/glsl_twin.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "common/error.h"
#include "common/gl.h"
#include "common/paths.h"
#include "common/shader.h"

namespace lp::test {

std::vector<glm::vec4> run_glsl_twin(const GlslTwin& twin, const std::vector<TwinCase>& cases) {
  if (twin.files.size() > 4) throw Error("run_glsl_twin: at most 4 files, not " + std::to_string(twin.files.size()));
  std::vector<std::string> defines = twin.defines;
  for (std::size_t i = 0; i < 4; ++i) {
    const std::string file = i < twin.files.size() ? twin.files[i] : from_root("tests/shaders/twin_nothing.glsl").string();
    defines.push_back("TWIN_FILE_" + std::to_string(i) + " \"" + file + "\"");
  }
  defines.push_back("TWIN_HELPERS " + twin.helpers);
  defines.push_back("TWIN_EXPRESSION " + twin.expression);
  ShaderProgram program({{GL_COMPUTE_SHADER, from_root("tests/shaders/glsl_twin.comp").string()}}, defines);
  std::vector<glm::vec4> out(cases.size(), glm::vec4(0));
  if (cases.empty()) return out;
  gl::Buffer in = gl::make_buffer(cases.data(), cases.size() * sizeof(TwinCase));
  gl::Buffer results = gl::make_buffer(nullptr, cases.size() * sizeof(glm::vec4), GL_DYNAMIC_STORAGE_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, results.id());
  program.use();
  program.set("u_count", int(cases.size()));
  if (twin.uniforms) twin.uniforms(program.id());
  glDispatchCompute(GLuint((cases.size() + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(results.id(), 0, GLsizeiptr(out.size() * sizeof(glm::vec4)), out.data());
  if (GLenum e = glGetError(); e != GL_NO_ERROR) throw Error("run_glsl_twin: GL error " + std::to_string(e));
  return out;
}

glm::vec3 TwinRandom::unit() {
  for (;;) {
    glm::vec3 v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    float l2 = glm::dot(v, v);
    if (l2 > 1e-4f && l2 <= 1.f) return v / std::sqrt(l2);
  }
}

std::string str(const glm::vec4& v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "(%.9g, %.9g, %.9g, %.9g)", v.x, v.y, v.z, v.w);
  return buf;
}

::testing::AssertionResult twins_agree(const std::vector<glm::vec4>& gpu, const std::vector<glm::vec4>& cpu,
                                       int components, TwinTolerance tolerance,
                                       const std::function<std::string(std::size_t)>& describe) {
  return twins_agree(gpu, cpu, components, [tolerance](std::size_t) { return tolerance; }, describe);
}

::testing::AssertionResult twins_agree(const std::vector<glm::vec4>& gpu, const std::vector<glm::vec4>& cpu,
                                       int components, const std::function<TwinTolerance(std::size_t)>& tolerance_of,
                                       const std::function<std::string(std::size_t)>& describe) {
  if (gpu.size() != cpu.size())
    return ::testing::AssertionFailure() << gpu.size() << " GPU results for " << cpu.size() << " cases";
  std::ostringstream failures;
  std::size_t failed = 0, worst_case = 0;
  double worst = 0;  // the largest error as a fraction of its tolerance
  for (std::size_t i = 0; i < gpu.size(); ++i) {
    for (int k = 0; k < components; ++k) {
      const double g = gpu[i][k], c = cpu[i][k];
      bool ok;
      double ratio = 0;
      if (std::isnan(c) || std::isnan(g)) {
        ok = std::isnan(c) && std::isnan(g);
        ratio = ok ? 0 : 1e30;
      } else if (std::isinf(c) || std::isinf(g)) {
        ok = g == c;
        ratio = ok ? 0 : 1e30;
      } else {
        const TwinTolerance tolerance = tolerance_of(i);
        const double allowed = tolerance.absolute + tolerance.relative * std::max(std::abs(g), std::abs(c));
        const double error = std::abs(g - c);
        ratio = allowed > 0 ? error / allowed : (error > 0 ? 1e30 : 0);
        ok = error <= allowed;
      }
      if (ratio > worst) { worst = ratio; worst_case = i; }
      if (!ok && failed++ < 5)
        failures << "\n  case " << i << " component " << k << ": GLSL " << str(gpu[i]) << ", C++ " << str(cpu[i])
                 << "\n    inputs: " << describe(i);
    }
  }
  std::printf("  %zu cases; the worst error is %.3g of its tolerance (case %zu: GLSL %s, C++ %s)\n", gpu.size(), worst,
              worst_case, str(gpu.empty() ? glm::vec4(0) : gpu[worst_case]).c_str(),
              str(cpu.empty() ? glm::vec4(0) : cpu[worst_case]).c_str());
  if (failed == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << failed << " of " << gpu.size() * std::size_t(components)
                                       << " components beyond the tolerance:" << failures.str();
}

}  // namespace lp::test
