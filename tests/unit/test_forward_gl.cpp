// Chapter 01 on the GPU (llvmpipe in CI): the forward renderer against the CPU ground
// truth, the modes against each other, and the GLSL lighting against its C++ twin on the hard
// cases. Bounds hold on any conforming renderer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "chapters/01_forward/blinn_phong.h"
#include "chapters/01_forward/forward.h"
#include "chapters/01_forward/ground_truth.h"
#include "common/error.h"
#include "common/metrics.h"
#include "common/paths.h"
#include "common/shader.h"
#include "common/target.h"
#include "tests/unit/lighting_cases.h"
#include "tests/unit/gl_environment.h"

using namespace lp;
using namespace lp::ch01;

namespace {

constexpr int kW = 320, kH = 180;

class ForwardGl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(load_scene(from_root("assets/forward/forward.gltf")));
    gpu_ = new SceneGpu(*scene_);
    forward_ = new ForwardRenderer(*gpu_);
  }
  static void TearDownTestSuite() {  // GL objects go before the context (gl_environment.h)
    delete forward_;
    delete gpu_;
    delete scene_;
  }

  ImageRGBA8 render(const std::string& view, ForwardMode mode, int w = kW, int h = kH) {
    const ForwardRenderer& forward = *forward_;
    LightBuffer lights;
    lights.upload(scene_->lights);
    OutputTarget target(w, h);
    target.bind();
    glClearColor(kBackground.r, kBackground.g, kBackground.b, 1.f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    FrameCamera camera = frame_camera(scene_->camera(view), float(w) / h);
    if (mode == ForwardMode::MultiPass) {
      forward.draw_base(camera, lights);
      forward.draw_additive_lights(camera, lights);
    } else {
      forward.draw(camera, mode, lights);
    }
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    return target.read();
  }

  FloatErrorStats error(const std::string& view, ForwardMode mode) {
    GroundTruth truth = render_ground_truth(*scene_, scene_->camera(view), kW, kH, scene_->lights);
    FrameCamera camera = frame_camera(scene_->camera(view), float(kW) / kH);
    auto mask = sphere_mask(*scene_, truth, render_instance_ids(*gpu_, camera, kW, kH));
    return sphere_error(render(view, mode), truth, mask);
  }

  static Scene* scene_;
  static SceneGpu* gpu_;
  static ForwardRenderer* forward_;
};
Scene* ForwardGl::scene_ = nullptr;
SceneGpu* ForwardGl::gpu_ = nullptr;
ForwardRenderer* ForwardGl::forward_ = nullptr;

}  // namespace

TEST_F(ForwardGl, RendersSomethingLit) {
  ImageRGBA8 img = render("overview", ForwardMode::PerPixel);
  int lit = 0;
  for (int i = 0; i < img.width * img.height; ++i) lit += img.pixels[i * 4] + img.pixels[i * 4 + 1] + img.pixels[i * 4 + 2] > 60;
  EXPECT_GT(lit, img.width * img.height / 4) << "the overview should be mostly lit surfaces, not black";
}

TEST_F(ForwardGl, PerPixelConvergesToTheGroundTruth) {
  FloatErrorStats e = error("close_128", ForwardMode::PerPixel);
  ASSERT_GT(e.pixels, 5000u) << "the sphere should fill much of the close-up";
  // What is left: the 128-segment mesh's normals and position vs the exact sphere, and
  // 8-bit rounding of both images.
  EXPECT_LT(e.mean_abs, 0.5) << "mean error in 8-bit steps";
  EXPECT_LE(e.p99, 2.0);
}

TEST_F(ForwardGl, PerVertexErrorFallsAsTessellationGrows) {
  double previous = 1e9;
  for (int segments : {8, 16, 32, 64, 128}) {
    FloatErrorStats e = error("close_" + std::to_string(segments), ForwardMode::PerVertex);
    EXPECT_LT(e.mean_abs, previous) << segments << " segments";
    previous = e.mean_abs;
  }
  // On the same mesh, lighting per vertex is several times further from the truth than per
  // pixel. (At 8 segments both are poor: the facets themselves are far from the sphere.)
  for (int segments : {16, 32}) {
    std::string view = "close_" + std::to_string(segments);
    EXPECT_GT(error(view, ForwardMode::PerVertex).mean_abs, 2.0 * error(view, ForwardMode::PerPixel).mean_abs) << view;
  }
}

TEST_F(ForwardGl, SkippingTheRenormalisationDarkensTriangleInteriors) {
  FloatErrorStats right = error("close_16", ForwardMode::PerPixel);
  FloatErrorStats wrong = error("close_16", ForwardMode::PerPixelUnnormalized);
  EXPECT_GT(wrong.mean_abs, 2.0 * right.mean_abs);
  // Darker, not just different: the unnormalised image has less light on the sphere.
  ImageRGBA8 a = render("close_16", ForwardMode::PerPixel), b = render("close_16", ForwardMode::PerPixelUnnormalized);
  long sum_a = 0, sum_b = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) { sum_a += a.pixels[i]; sum_b += b.pixels[i]; }
  EXPECT_LT(sum_b, sum_a);
}

TEST_F(ForwardGl, MultiPassEqualsOnePassUpToEightBitAccumulation) {
  // Each additive pass is rounded to 8 bits before the next adds to it: with L lights the
  // sum can drift by up to L/2 steps in linear terms, which sRGB keeps to a few steps.
  ImageRGBA8 one = render("overview", ForwardMode::PerPixel), multi = render("overview", ForwardMode::MultiPass);
  CompareResult r = compare(multi, one, {.threshold = 3, .max_failing_fraction = 0.001});
  EXPECT_TRUE(r.passed) << r.summary();
}

TEST_F(ForwardGl, PassFragmentsAreCountedExactly) {
  // Multi-pass shades every visible pixel once per light (depth test EQUAL against the base
  // pass): its count is an exact multiple of the light count, and per light at most the
  // base pass's count (which also shaded overdraw) and at most the screen.
  LightBuffer lights;
  lights.upload(scene_->lights);
  ForwardRenderer forward(*gpu_);
  OutputTarget target(kW, kH);
  target.bind();
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  FrameCamera camera = frame_camera(scene_->camera("overview"), float(kW) / kH);
  PassMetrics m;
  { auto p = m.pass("base"); forward.draw_base(camera, lights); }
  { auto p = m.pass("lights"); forward.draw_additive_lights(camera, lights); }
  m.end_frame();
  m.wait_all();
  std::uint64_t base = m.find("base")->samples, additive = m.find("lights")->samples;
  ASSERT_GT(base, 0u);
  EXPECT_LE(base, std::uint64_t(2) * kW * kH) << "overdraw is bounded in this scene";
  EXPECT_EQ(additive % scene_->lights.size(), 0u);
  EXPECT_LE(additive / scene_->lights.size(), std::uint64_t(kW) * kH);
  EXPECT_LE(additive / scene_->lights.size(), base);
}

TEST_F(ForwardGl, ShaderCompileErrorNamesFileAndLine) {
  auto dir = std::filesystem::temp_directory_path() / "lightpass_gl_shader_error";
  std::filesystem::create_directories(dir / "chapters" / "t");
  std::ofstream(dir / "chapters" / "t" / "bad.frag") << "#version 450\n#include \"t/inc.glsl\"\nout vec4 c;\nvoid main() { c = vec4(f()); }\n";
  std::ofstream(dir / "chapters" / "t" / "inc.glsl") << "float f() {\n  return 1.0;\n  this is wrong;\n}\n";
  setenv("LIGHTPASS_ROOT", dir.c_str(), 1);
  std::string message;
  try {
    ShaderProgram p({{GL_FRAGMENT_SHADER, "t/bad.frag"}});
  } catch (const Error& e) {
    message = e.what();
  }
  unsetenv("LIGHTPASS_ROOT");
  std::filesystem::remove_all(dir);
  EXPECT_NE(message.find("t/inc.glsl:3"), std::string::npos) << message;
  EXPECT_NE(message.find("bad.frag"), std::string::npos) << message;
}

TEST_F(ForwardGl, GlErrorsNameThePassThatCausedThem) {
  // The pass records the error (its destructor never throws); the frame loop throws it.
  PassMetrics m;
  {
    auto pass = m.pass("broken pass");
    glEnable(0xFFFF);  // not a capability: GL_INVALID_ENUM
  }
  std::string message;
  try {
    m.throw_if_error();
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("GL_INVALID_ENUM in pass 'broken pass'"), std::string::npos) << message;
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// --- The GLSL twin on the hard cases (tests/unit/lighting_cases.h) -----------------------------

namespace {

// Mirrors `struct Case` in shaders/lighting_eval.comp.
struct GpuCase {
  glm::vec4 position_exponent, normal, to_eye;
};

}  // namespace

TEST(LightingGlsl, HardCasesMatchTheCppTwin) {
  // lighting.glsl's light_incident() and blinn_phong() on every hard case, in a compute
  // shader, against blinn_phong.h. Where no light may reach the eye, exactly 0 (no NaN, no
  // sliver); elsewhere finite and equal to the C++ within float rounding: 10^-5 of the value
  // for a few ulps of normalize/division (GLSL allows 2.5 ulp for a division), plus, for the
  // specular, what pow() does to n . h's rounding: near 1, n . h moves in steps of 6e-8 (2^-24)
  // and the GPU may round normalize() and the dot product differently from the CPU, up to 4
  // such steps, which the exponent multiplies: exponent x 4 x 2^-24 relative.
  const auto cases = lp::test::lighting_hard_cases();
  std::vector<GpuCase> gpu_cases;
  std::vector<GpuLight> lights;
  for (const auto& c : cases) {
    gpu_cases.push_back({glm::vec4(c.position, c.exponent), glm::vec4(c.normal, 0), glm::vec4(c.to_eye, 0)});
    lights.push_back(pack_light(c.light));
  }
  ShaderProgram program({{GL_COMPUTE_SHADER, "01_forward/shaders/lighting_eval.comp"}});
  gl::Buffer in = gl::make_buffer(gpu_cases.data(), gpu_cases.size() * sizeof(GpuCase));
  gl::Buffer light_buffer = gl::make_buffer(lights.data(), lights.size() * sizeof(GpuLight));
  gl::Buffer out = gl::make_buffer(nullptr, cases.size() * 2 * sizeof(glm::vec4), GL_DYNAMIC_STORAGE_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, light_buffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, out.id());
  program.use();
  program.set("u_count", int(cases.size()));
  glDispatchCompute(GLuint((cases.size() + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<glm::vec4> results(cases.size() * 2);
  glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(results.size() * sizeof(glm::vec4)), results.data());
  ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& c = cases[i];
    const glm::vec3 d(results[2 * i]), s(results[2 * i + 1]);
    Incident inc = incident(c.light, c.position);
    const Reflected cpu = blinn_phong(c.normal, c.to_eye, inc.to_light, inc.radiance, c.exponent);
    std::printf("  %-52s GLSL diffuse %-11.6g specular %-11.6g  C++ %-11.6g %-11.6g\n", c.name.c_str(), d.x, s.x, cpu.diffuse.x,
                cpu.specular.x);
    if (c.dark) {
      EXPECT_EQ(d, glm::vec3(0)) << c.name;
      EXPECT_EQ(s, glm::vec3(0)) << c.name;
      continue;
    }
    ASSERT_TRUE(std::isfinite(d.x + d.y + d.z + s.x + s.y + s.z)) << c.name;
    const double spec_tolerance = 1e-5 + double(c.exponent) * 4 * 0x1p-24;
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(d[k], cpu.diffuse[k], 1e-5 * std::abs(cpu.diffuse[k])) << c.name;
      EXPECT_NEAR(s[k], cpu.specular[k], spec_tolerance * std::max(std::abs(cpu.specular[k]), std::abs(s[k]))) << c.name;
    }
  }
}
