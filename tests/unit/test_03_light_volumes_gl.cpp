// Chapter 03 on the GPU (llvmpipe in CI): every culling strategy against the full-screen
// pass, including the hard cases; exact fragment counts; bad input. Bounds hold on any
// conforming renderer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/01_forward/ground_truth.h"
#include "chapters/02_gbuffer/deferred.h"
#include "chapters/02_gbuffer/gbuffer.h"
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_counts.h"
#include "chapters/03_light_volumes/light_prepass.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/03_light_volumes/light_volumes.h"
#include "common/error.h"
#include "common/metrics.h"
#include "common/paths.h"
#include "common/shader.h"
#include "common/target.h"
#include "tests/unit/book_data.h"
#include "tests/unit/gl_environment.h"

using namespace lp;
using namespace lp::ch03;
using lp::test::book_row;

namespace {

constexpr int kW = 320, kH = 180;

struct Render {
  ImageRGBA8 image;
  FragmentCounts counts;
  DrawStats stats;
  std::uint64_t samples = 0;  // GL_SAMPLES_PASSED over the local-light pass
};

class LightVolumesGl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(load_scene(from_root("assets/street/street.gltf")));
    gpu_ = new SceneGpu(*scene_);
    frame_ = new DeferredFrame(*gpu_);
    volumes_ = &frame_->volumes();
    target_ = new OutputTarget(kW, kH);
  }
  static void TearDownTestSuite() {  // GL objects go before the context (gl_environment.h)
    delete target_;
    delete frame_;
    delete gpu_;
    delete scene_;
  }

  static FrameCamera camera(const std::string& view, float znear = 0, float zfar = 0) {
    FrameCamera c = frame_camera(scene_->camera(view), float(kW) / kH);
    if (znear > 0) c.znear = znear;
    if (zfar > 0) c.zfar = zfar;
    c.projection = glm::perspective(c.yfov, c.aspect, c.znear, c.zfar);
    return c;
  }

  static LightSet light_set(const std::vector<Light>& lights) {
    return build_light_set(lights, cut_threshold(1.f, peak_reflectance(*scene_)), volumes_->shapes());
  }

  // The chapter's frame (the program's own object): G-buffer, global lights, local lights
  // with `strategy`, composite; the fragment counts and GL_SAMPLES_PASSED of the local lights.
  static Render render(const FrameCamera& cam, Strategy strategy,
                       LightVolumes::Output output = LightVolumes::Output::Light, DeferredFrame* frame = nullptr) {
    if (!frame) frame = frame_;
    frame->volumes().set_counting(true);
    frame->set_strategy(strategy);
    const FrameShow show = output == LightVolumes::Output::HeatShaded ? FrameShow::HeatShaded
                           : output == LightVolumes::Output::HeatLit  ? FrameShow::HeatLit
                                                                      : FrameShow::Image;
    PassMetrics metrics;
    frame->render(cam, {target_->framebuffer(), kW, kH}, &metrics, {.show = show});
    metrics.end_frame();
    metrics.wait_all();
    Render r;
    r.counts = frame->volumes().counts();
    r.stats = frame->volumes().draw_stats();
    r.samples = metrics.find("local lights: " + kStrategies[int(strategy)])->samples;
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    r.image = target_->read();
    return r;
  }

  static Scene* scene_;
  static SceneGpu* gpu_;
  static DeferredFrame* frame_;
  static LightVolumes* volumes_;  // the frame's
  static OutputTarget* target_;
};
Scene* LightVolumesGl::scene_ = nullptr;
SceneGpu* LightVolumesGl::gpu_ = nullptr;
DeferredFrame* LightVolumesGl::frame_ = nullptr;
LightVolumes* LightVolumesGl::volumes_ = nullptr;
OutputTarget* LightVolumesGl::target_ = nullptr;

// Strategies add the same lights in the same order (light order) into the light buffer; a
// strategy that skips a pixel only skips lights that add nothing there, and x + 0 = x
// exactly. What can differ: where a depth test meets a volume face within the depth
// buffer's resolution, at the few points where the face touches the cut sphere; there the
// light gives at most the threshold, 1 / (255 * 12.92), which moves the sRGB output by at
// most one step. So: at most one step anywhere.
constexpr CompareOptions kSameImage{.threshold = 1, .max_failing_fraction = 0.0};

double luminance_sum(const ImageRGBA8& img) {
  double s = 0;
  for (std::size_t i = 0; i < img.pixels.size(); i += 4) s += img.pixels[i] + img.pixels[i + 1] + img.pixels[i + 2];
  return s;
}

}  // namespace

TEST_F(LightVolumesGl, TheStreetIsLitNotBlack) {
  volumes_->set_lights(light_set(scene_->lights));
  Render r = render(camera("street_level"), Strategy::Stencil);
  Render unlit;
  volumes_->set_lights(light_set({}));  // ambient only
  unlit = render(camera("street_level"), Strategy::Stencil);
  EXPECT_GT(luminance_sum(r.image), 2.0 * luminance_sum(unlit.image)) << "the local lights should dominate the street";
  EXPECT_GT(r.counts.lit, std::uint64_t(kW) * kH) << "each pixel of the street is lit by about ten lights";
}

TEST_F(LightVolumesGl, EveryStrategyGivesTheFullScreenImage) {
  volumes_->set_lights(light_set(scene_->lights));
  struct Case {
    std::string name;
    FrameCamera cam;
  };
  const std::vector<Case> cases = {
      {"overview", camera("overview")},
      {"street_level (eye inside several lights, lights behind it)", camera("street_level")},
      {"inside_light", camera("inside_light")},
      {"far plane at 30 m cuts the volumes", camera("street_level", 0, 30)},
      {"near plane at 4 m cuts the volumes", camera("street_level", 4, 0)},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    Render reference = render(c.cam, Strategy::FullScreen);
    ASSERT_GT(reference.counts.lit, 10000u);
    for (Strategy s : {Strategy::Scissor, Strategy::FrontFaces, Strategy::BackFaces, Strategy::Stencil,
                       Strategy::StencilBits}) {
      SCOPED_TRACE(kStrategies[int(s)]);
      Render r = render(c.cam, s);
      CompareResult cmp = compare(r.image, reference.image, kSameImage);
      EXPECT_TRUE(cmp.passed) << cmp.summary();
      // Every fragment lit within 99% of the radius reached the shader: the same count as
      // when every pixel does. (The last 1% is left to the image comparison: see kSameImage.)
      EXPECT_EQ(r.counts.lit_inner, reference.counts.lit_inner);
      EXPECT_LE(r.counts.lit, reference.counts.lit);
    }
  }
}

TEST_F(LightVolumesGl, ReversedDepthWorksTheSame) {
  // Chapter 02's reversed-Z layout (D32F, 1 at the near plane, depth test GREATER): every
  // comparison flips, and depth clamp must clamp to the other ends. Same bounds as above.
  DeferredFrame reversed(*gpu_, ch02::layout_named("reversed-z"));
  reversed.volumes().set_lights(light_set(scene_->lights));
  for (const FrameCamera& cam : {camera("inside_light"), camera("street_level", 0, 30)}) {
    Render reference = render(cam, Strategy::FullScreen, LightVolumes::Output::Light, &reversed);
    ASSERT_GT(reference.counts.lit, 10000u);
    for (Strategy s : {Strategy::FrontFaces, Strategy::BackFaces, Strategy::Stencil, Strategy::StencilBits}) {
      Render r = render(cam, s, LightVolumes::Output::Light, &reversed);
      CompareResult cmp = compare(r.image, reference.image, kSameImage);
      EXPECT_TRUE(cmp.passed) << kStrategies[int(s)] << ": " << cmp.summary();
      EXPECT_EQ(r.counts.lit_inner, reference.counts.lit_inner) << kStrategies[int(s)];
    }
  }
}

// Why llvmpipe's worst pixel of the uncut street is 5 steps where the H200's is 1 (book,
// chapter 03, "The same sweep on llvmpipe"): every pixel there sums 312 lights into the RGBA16F
// light buffer by blending, one rounding to half precision per light. This adds 312 small
// values per pixel the same way and compares the result with two models of that rounding,
// to nearest (even) and toward zero, computed exactly in C++. The addends, (64 + x) / 2^14,
// are exact in half and float, so only the sum's rounding is measured; the renderer must
// match one model at every pixel, and which one it matches, and how far each drifts from
// the exact sum, are the book's numbers.
namespace {
double to_half(double x, bool nearest) {  // x > 0: rounded to a half float (normal range)
  const int e = std::max(int(std::floor(std::log2(x))), -14);
  const double ulp = std::ldexp(1.0, e - 10);
  return (nearest ? std::nearbyint(x / ulp) : std::floor(x / ulp)) * ulp;
}
}  // namespace

TEST(HalfFloatBlending, SumsTheWayOneOfTwoRoundingModelsSays) {
  constexpr int kColumns = 64, kAdditions = 312;
  gl::Texture sum = gl::make_texture_2d(GL_RGBA16F, kColumns, 1);
  gl::Framebuffer fbo;
  glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, sum.id(), 0);
  ASSERT_EQ(glCheckNamedFramebufferStatus(fbo.id(), GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
  ShaderProgram step({{GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"},
                      {GL_FRAGMENT_SHADER, from_root("tests/shaders/half_blend_step.frag").string()}});
  gl::VertexArray vao;
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, zero);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  glViewport(0, 0, kColumns, 1);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  step.use();
  glBindVertexArray(vao.id());
  for (int k = 0; k < kAdditions; ++k) glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisable(GL_BLEND);
  std::vector<float> got(std::size_t(kColumns) * 4);
  glGetTextureImage(sum.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(got.size() * sizeof(float)), got.data());
  ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));

  int nearest_matches = 0, toward_zero_matches = 0;
  double drift_gpu = 0, drift_nearest = 0, drift_toward_zero = 0;  // mean (sum - exact) / exact
  for (int x = 0; x < kColumns; ++x) {
    const double v = (64.0 + x) / 16384.0, exact = kAdditions * v;
    double n = 0, z = 0;
    for (int k = 0; k < kAdditions; ++k) n = to_half(n + v, true), z = to_half(z + v, false);
    nearest_matches += double(got[std::size_t(x) * 4]) == n;
    toward_zero_matches += double(got[std::size_t(x) * 4]) == z;
    drift_gpu += (got[std::size_t(x) * 4] - exact) / exact / kColumns;
    drift_nearest += (n - exact) / exact / kColumns;
    drift_toward_zero += (z - exact) / exact / kColumns;
  }
  EXPECT_TRUE(nearest_matches == kColumns || toward_zero_matches == kColumns)
      << "neither model explains the renderer's half-float sums: " << nearest_matches << " pixels match rounding to nearest, "
      << toward_zero_matches << " rounding toward zero, of " << kColumns;
  std::printf("  %d additions into RGBA16F: %d of %d pixels as rounding to nearest, %d as toward zero; mean drift %.4f %% "
              "(models: %.4f %%, %.4f %%)\n", kAdditions, nearest_matches, kColumns, toward_zero_matches, 100 * drift_gpu,
              100 * drift_nearest, 100 * drift_toward_zero);
  book_row("03_half_blend", {{"additions", std::to_string(kAdditions)}},
           {{"matches_nearest", double(nearest_matches)}, {"matches_toward_zero", double(toward_zero_matches)},
            {"columns", double(kColumns)}, {"drift_renderer", drift_gpu}, {"drift_nearest", drift_nearest},
            {"drift_toward_zero", drift_toward_zero}});
}

TEST_F(LightVolumesGl, TheHardCasesAreReallyThere) {
  // The views above must exercise what they claim to: the eye inside volumes (front faces
  // falls back to back faces for them), and lights behind the eye (scissor skips them).
  volumes_->set_lights(light_set(scene_->lights));
  Render front = render(camera("inside_light"), Strategy::FrontFaces);
  EXPECT_GE(front.stats.lights_camera_inside, 1);
  for (const std::string view : {"inside_light", "street_level"})
    book_row("03_eye_inside", {{"view", view}},
             {{"volumes_around_eye", double(render(camera(view), Strategy::FrontFaces).stats.lights_camera_inside)}});
  Render scissor = render(camera("inside_light"), Strategy::Scissor);
  EXPECT_GT(scissor.stats.lights_skipped, 50) << "the street behind the eye";
  // Without depth clamp the far plane would clip the back faces: the back-face strategy
  // would lose the light of every volume that reaches past 30 m. (Checked by the image
  // equality above; here, that such volumes exist: lights within r of the 30 m plane.)
  FrameCamera c = camera("street_level", 0, 30);
  int crossing = 0;
  for (const auto& p : volumes_->lights().points) {
    float depth = -(c.view * glm::vec4(glm::vec3(p.position_radius), 1.f)).z;
    crossing += std::abs(depth - 30.f) < p.position_radius.w;
  }
  EXPECT_GT(crossing, 10);
  book_row("03_far_plane", {{"view", "street_level"}, {"far", "30"}}, {{"volumes_crossing", double(crossing)}});
}

TEST_F(LightVolumesGl, StencilShadesAtMostTwentyPercentMoreThanItLights) {
  // The deterministic cost the chapter promises, from exact counts (atomic counters in the
  // lighting shader, early fragment tests). Lit: the light adds something to the pixel.
  volumes_->set_lights(light_set(scene_->lights));
  for (const std::string view : {"overview", "street_level", "inside_light"})
    for (Strategy strategy : {Strategy::Stencil, Strategy::StencilBits}) {
      Render r = render(camera(view), strategy);
      ASSERT_GT(r.counts.lit, 0u) << view;
      EXPECT_LE(double(r.counts.shaded), 1.2 * double(r.counts.lit)) << view << ": overshading " << r.counts.overshading();
      if (strategy == Strategy::Stencil)
        book_row("03_stencil_counts", {{"view", view}},
                 {{"shaded", double(r.counts.shaded)}, {"lit", double(r.counts.lit)}, {"pixels", double(kW * kH)}});
    }
}

TEST_F(LightVolumesGl, StrategiesShadeNestedSetsOfFragments) {
  volumes_->set_lights(light_set(scene_->lights));
  const FrameCamera cam = camera("street_level");
  Render full = render(cam, Strategy::FullScreen), scissor = render(cam, Strategy::Scissor),
         front = render(cam, Strategy::FrontFaces), back = render(cam, Strategy::BackFaces),
         stencil = render(cam, Strategy::Stencil);
  const std::uint64_t lights = volumes_->lights().local_count();
  EXPECT_EQ(full.counts.shaded, lights * kW * kH) << "the full-screen pass shades every pixel for every light";
  EXPECT_LT(scissor.counts.shaded, full.counts.shaded);
  // The mask is the intersection of the two depth tests: inside = behind the front face
  // and in front of the back face.
  EXPECT_LE(stencil.counts.shaded, front.counts.shaded);
  EXPECT_LE(stencil.counts.shaded, back.counts.shaded);
  EXPECT_GE(stencil.counts.shaded, stencil.counts.lit);
  Render bits = render(cam, Strategy::StencilBits);
  EXPECT_EQ(bits.counts.shaded, stencil.counts.shaded) << "eight bits at a time: the same masks";
  // Two independent counts agree: the atomic counter and GL_SAMPLES_PASSED (early tests),
  // where the pass draws nothing but the lighting shader.
  EXPECT_EQ(back.samples, back.counts.shaded);
  EXPECT_EQ(front.samples, front.counts.shaded);
  EXPECT_EQ(full.samples, full.counts.shaded);
}

TEST_F(LightVolumesGl, EachLightLeavesTheStencilClean) {
  // The light pass zeroes the stencil where it shades; the stencil pass only marks pixels
  // the light pass covers. After all lights no pixel may keep a mark (it would corrupt the
  // next light's mask).
  volumes_->set_lights(light_set(scene_->lights));
  for (const std::string view : {"street_level", "inside_light"})
    for (Strategy strategy : {Strategy::Stencil, Strategy::StencilBits}) {
      render(camera(view), strategy);
      std::vector<std::uint32_t> texels(std::size_t(kW) * kH);
      glGetTextureImage(frame_->light().depth_stencil(), 0, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8,
                        GLsizei(texels.size() * 4), texels.data());
      std::size_t marked = 0;
      for (auto t : texels) marked += (t & 0xFFu) != 0;
      EXPECT_EQ(marked, 0u) << view << ", " << kStrategies[int(strategy)];
    }
}

TEST_F(LightVolumesGl, MatchesChapterTwosFullScreenShading) {
  // Chapter 02 lights every pixel with every light in one pass, in float32, uncut. Ours cuts
  // each light where it gives less than 1 / (255 * 12.92) (one sRGB step at black) and sums
  // in half floats. With the street's ranges the cut drops almost nothing; what remains is
  // rounding: at most 2 steps, in at most 0.1% of pixels more than 1.
  std::vector<Light> lights = scene_->lights;
  volumes_->set_lights(light_set(lights));
  const FrameCamera cam = camera("street_level");
  Render ours = render(cam, Strategy::Stencil);
  ch01::LightBuffer all;
  all.upload(lights);
  ch02::DeferredLighting deferred;
  target_->bind();  // the frame's G-buffer still holds `cam`'s surfaces
  deferred.draw(frame_->gbuffer(), all, scene_->ambient, ch01::kBackground, ch02::LightSelection::All);
  ImageRGBA8 theirs = target_->read();
  CompareResult loose = compare(ours.image, theirs, {.threshold = 2, .max_failing_fraction = 0.0});
  CompareResult tight = compare(ours.image, theirs, {.threshold = 1, .max_failing_fraction = 0.001});
  EXPECT_TRUE(loose.passed) << loose.summary();
  EXPECT_TRUE(tight.passed) << tight.summary();
}

TEST_F(LightVolumesGl, BadLightsRenderNothingAndBreakNothing) {
  std::vector<Light> lights = scene_->lights;
  const FrameCamera cam = camera("street_level");
  volumes_->set_lights(light_set(lights));
  Render good = render(cam, Strategy::Stencil);
  // Lights with no light: zero intensity and a black colour (dark), and a negative intensity
  // (against the loader's rule, light_defect). Left out: the image is the same, bit for bit.
  Light bad = lights[1];
  bad.position = cam.position + glm::vec3(0, 0, -5);
  for (float intensity : {0.f, -3.f}) {
    bad.intensity = intensity;
    lights.push_back(bad);
  }
  bad.intensity = 1.f;
  bad.color = glm::vec3(0);
  lights.push_back(bad);
  LightSet set = light_set(lights);
  EXPECT_EQ(set.local_count(), volumes_->lights().local_count());
  ASSERT_EQ(set.warnings.size(), 2u);
  EXPECT_NE(set.warnings[0].find("is left out: its intensity -3 is negative"), std::string::npos) << set.warnings[0];
  EXPECT_NE(set.warnings[1].find("give no light"), std::string::npos) << set.warnings[1];
  volumes_->set_lights(std::move(set));
  Render same = render(cam, Strategy::Stencil);
  EXPECT_EQ(compare(same.image, good.image, {.threshold = 0, .max_failing_fraction = 0.0}).max_error, 0.0);
}

TEST_F(LightVolumesGl, WideSpotsAndUnboundedLightsStillMatchTheFullScreenPass) {
  // A spot of 120 degrees (past glTF's 90: drawn with a sphere) and a light with no range
  // (unbounded: its radius comes from its intensity alone).
  std::vector<Light> lights;
  Light spot;
  spot.name = "wide";
  spot.type = LightType::Spot;
  spot.position = {0, 3, 40};
  spot.direction = glm::normalize(glm::vec3(0.2f, -1, -0.3f));
  spot.color = {1, 0.5f, 0.2f};
  spot.intensity = 2;
  spot.range = 10;
  spot.inner_cone = 0.8f;
  spot.outer_cone = 120.f * std::numbers::pi_v<float> / 180.f;
  lights.push_back(spot);
  Light unbounded;
  unbounded.name = "unbounded";
  unbounded.position = {-3, 2, 35};
  unbounded.color = {0.3f, 0.6f, 1};
  unbounded.intensity = 0.05f;
  unbounded.range = 0;
  lights.push_back(unbounded);
  LightSet set = light_set(lights);
  EXPECT_EQ(set.wide_spots.size(), 1u);
  EXPECT_EQ(set.points.size(), 1u);
  volumes_->set_lights(std::move(set));
  const FrameCamera cam = camera("street_level");
  Render reference = render(cam, Strategy::FullScreen);
  EXPECT_GT(reference.counts.lit, 5000u);
  for (Strategy s : {Strategy::Scissor, Strategy::FrontFaces, Strategy::BackFaces, Strategy::Stencil,
                     Strategy::StencilBits}) {
    Render r = render(cam, s);
    EXPECT_TRUE(compare(r.image, reference.image, kSameImage).passed) << kStrategies[int(s)];
    EXPECT_EQ(r.counts.lit_inner, reference.counts.lit_inner) << kStrategies[int(s)];
  }
}

TEST_F(LightVolumesGl, HeatMapsCountWhatTheCountersCount) {
  // The heat pictures add 1 per fragment into L1 (exact integers in half floats up to
  // 2048); their sum is the counter's total.
  volumes_->set_lights(light_set(scene_->lights));
  const FrameCamera cam = camera("overview");
  for (auto output : {LightVolumes::Output::HeatShaded, LightVolumes::Output::HeatLit}) {
    Render r = render(cam, Strategy::Stencil, output);
    std::vector<float> l1(std::size_t(kW) * kH * 4);
    glGetTextureImage(frame_->light().diffuse(), 0, GL_RGBA, GL_FLOAT, GLsizei(l1.size() * 4), l1.data());
    // The program's heat picture starts from a black light buffer (no global pass): L1 holds
    // the counts alone.
    double sum = 0;
    for (std::size_t i = 0; i < l1.size(); i += 4) sum += l1[i];
    const double want = double(output == LightVolumes::Output::HeatShaded ? r.counts.shaded : r.counts.lit);
    EXPECT_NEAR(sum, want, 0.01 * want);
  }
}

TEST_F(LightVolumesGl, DeferredLightingLosesTheColourOfHighlightsOnly) {
  // With white lights the one-number specular of the light pre-pass is exact, and the image
  // is deferred shading's up to two things: deferred shading rounds albedo and specular
  // colour to 8 bits in its G-buffer, the pre-pass reads the material itself (up to 2 steps
  // in dark pixels); and where two surfaces lie within the second pass's one depth unit of
  // offset (a window pane 3 cm before a far facade) that pass may draw the other one, in a
  // few pixels. With coloured lights the highlights go white and the images part.
  const FrameCamera cam = camera("street_level");
  auto prepass_image = [&](const std::vector<Light>& lights, PrePassSpecular mode) {
    LightPrePass prepass(*gpu_);
    LightBuffer light(kW, kH, LightPrePass::kDepthFormat, LightBuffer::Kind::PrePass);
    volumes_->set_lights(light_set(lights));
    prepass.render(*volumes_, light, cam, {target_->framebuffer(), kW, kH}, scene_->ambient, ch01::kBackground, mode);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    return target_->read();
  };
  std::vector<Light> white = scene_->lights;
  for (auto& l : white) l.color = glm::vec3(std::max({l.color.r, l.color.g, l.color.b}));
  ImageRGBA8 pre_white = prepass_image(white, PrePassSpecular::White);
  volumes_->set_lights(light_set(white));
  ImageRGBA8 deferred_white = render(cam, Strategy::Stencil).image;
  CompareResult same = compare(pre_white, deferred_white, {.threshold = 2, .max_failing_fraction = 0.001});

  EXPECT_TRUE(same.passed) << same.summary();

  ImageRGBA8 pre_colour = prepass_image(scene_->lights, PrePassSpecular::White);
  volumes_->set_lights(light_set(scene_->lights));
  ImageRGBA8 deferred_colour = render(cam, Strategy::Stencil).image;
  CompareResult parted = compare(pre_colour, deferred_colour, {.threshold = 1, .max_failing_fraction = 0.0});
  EXPECT_GE(parted.max_error, 10.0) << "coloured lights: the white highlights should show";
  EXPECT_GT(parted.failing_fraction, 10 * same.failing_fraction) << parted.summary();
}

// --- The frame as later chapters extend it (deferred_frame.h) ----------------------------

namespace {

std::string test_hook(const std::string& file) { return from_root("tests/hooks/" + file).string(); }

struct HookStage : FrameStage {
  ShaderHooks hooks{"", ""};
  ShaderHooks shader_hooks() const override { return hooks; }
};

// Scene lights without the local ones, or without the directional ones.
LightSet without_local(LightSet s) {
  s.points.clear();
  s.cones.clear();
  s.wide_spots.clear();
  return s;
}

}  // namespace

TEST_F(LightVolumesGl, AStageWithNoOverridesChangesNoPixel) {
  // Every hook is a no-op by default: chapters 01-05 keep their images bit for bit.
  DeferredFrame frame(*gpu_);
  frame.volumes().set_lights(light_set(scene_->lights));
  const FrameCamera cam = camera("street_level");
  Render plain = render(cam, Strategy::Stencil, LightVolumes::Output::Light, &frame);
  FrameStage nothing;
  frame.add_stage(nothing);
  Render staged = render(cam, Strategy::Stencil, LightVolumes::Output::Light, &frame);
  EXPECT_EQ(plain.image.pixels, staged.image.pixels);
  EXPECT_EQ(plain.counts.shaded, staged.counts.shaded);
}

TEST_F(LightVolumesGl, TheVisibilityHookReachesEveryLight) {
  // A stage whose visibility is 0 everywhere (chapter 06's shadows plug in here) must leave
  // exactly the image of a frame with no lights but the ambient: the same volumes are drawn
  // and shaded, none of their fragments is lit.
  const FrameCamera cam = camera("street_level");
  DeferredFrame blocked(*gpu_), ambient_only(*gpu_);
  blocked.volumes().set_lights(light_set(scene_->lights));
  HookStage stage;
  stage.hooks.visibility = test_hook("no_light_reaches.glsl");
  blocked.add_stage(stage);
  LightSet none = light_set(scene_->lights);
  none = without_local(std::move(none));
  none.directional.clear();
  ambient_only.volumes().set_lights(std::move(none));
  Render dark = render(cam, Strategy::Stencil, LightVolumes::Output::Light, &blocked);
  Render truth = render(cam, Strategy::Stencil, LightVolumes::Output::Light, &ambient_only);
  EXPECT_GT(dark.counts.shaded, 10000u) << "the volumes are still drawn";
  EXPECT_EQ(dark.counts.lit, 0u);
  EXPECT_EQ(dark.image.pixels, truth.image.pixels);
}

namespace {
// A 1 x 1 R32F texture holding `value`.
gl::Texture one_texel(float value) {
  gl::Texture t = gl::make_texture_2d(GL_R32F, 1, 1);
  glTextureSubImage2D(t.id(), 0, 0, 0, 1, 1, GL_RED, GL_FLOAT, &value);
  return t;
}
// A stage whose visibility hook reads its second unit (a texel of 0: no light reaches), bound
// only when the frame asks for it.
struct UnitStage : FrameStage {
  gl::Texture dark = one_texel(0.f);
  StageNeeds needs() const override { return {.units = 2, .blocks = 1}; }
  ShaderHooks shader_hooks() const override {
    return {test_hook("visibility_from_unit.glsl"), "", {"TEST_UNIT " + std::to_string(slots().unit(1))}};
  }
  void bind_hook_resources() const override { glBindTextureUnit(slots().unit(1), dark.id()); }
};
// A stage whose own pass, before the lights, leaves a texel of 1 on units 0..31 (as chapter
// 08's pass once left its light on the unit chapter 06's map was read from).
struct ClobberingStage : FrameStage {
  gl::Texture lit = one_texel(1.f);
  StageNeeds needs() const override { return {.units = 1}; }
  void before_lights(DeferredFrame& frame, PassMetrics*) override {
    for (GLuint unit = 8; unit < 32; ++unit) glBindTextureUnit(unit, lit.id());
    frame.gbuffer().bind_textures(0);
  }
};
}  // namespace

TEST_F(LightVolumesGl, TheFrameBindsEachStagesUnitsBeforeTheLights) {
  // Each stage gets its own units after the frame's and the earlier stages'; and whatever a
  // stage's own pass binds, the frame binds every stage's hook resources again before the
  // lights: the image is the ambient-only frame's (the hook's texel is 0), not the lit one.
  const FrameCamera cam = camera("street_level");
  DeferredFrame hooked(*gpu_), ambient_only(*gpu_);
  hooked.volumes().set_lights(light_set(scene_->lights));
  UnitStage reader;
  ClobberingStage clobber;
  hooked.add_stage(reader);
  hooked.add_stage(clobber);
  EXPECT_EQ(reader.slots().first_unit, DeferredFrame::kFirstStageUnit);
  EXPECT_EQ(reader.slots().first_block, DeferredFrame::kFirstStageBlock);
  EXPECT_EQ(clobber.slots().first_unit, DeferredFrame::kFirstStageUnit + 2);
  EXPECT_EQ(clobber.slots().first_block, DeferredFrame::kFirstStageBlock + 1);
  LightSet none = without_local(light_set(scene_->lights));
  none.directional.clear();
  ambient_only.volumes().set_lights(std::move(none));
  Render dark = render(cam, Strategy::Stencil, LightVolumes::Output::Light, &hooked);
  Render truth = render(cam, Strategy::Stencil, LightVolumes::Output::Light, &ambient_only);
  EXPECT_EQ(dark.counts.lit, 0u);
  EXPECT_EQ(dark.image.pixels, truth.image.pixels);
}

TEST_F(LightVolumesGl, TheVisibilityHookKnowsWhichLightItIs) {
  // The hook gets each light's place in light order: blocking the odd ones must give the
  // image of a frame that only has the even ones, with every strategy (instanced draws
  // included: the index must follow the instance).
  const FrameCamera cam = camera("street_level");
  LightSet all = light_set(scene_->lights), even = all;
  std::size_t index = 0;  // in light order: points, cones, wide spots
  auto keep_even = [&](auto& lights) {
    std::erase_if(lights, [&](const auto&) { return index++ % 2 != 0; });
  };
  keep_even(even.points);
  keep_even(even.cones);
  keep_even(even.wide_spots);
  ASSERT_GT(all.cones.size() + all.wide_spots.size(), 0u) << "the street's spots test the index past the points";
  DeferredFrame hooked(*gpu_), reference(*gpu_);
  hooked.volumes().set_lights(std::move(all));
  reference.volumes().set_lights(std::move(even));
  HookStage stage;
  stage.hooks.visibility = test_hook("every_other_light.glsl");
  hooked.add_stage(stage);
  for (Strategy s : {Strategy::FullScreen, Strategy::BackFaces, Strategy::Stencil, Strategy::StencilBits}) {
    Render r = render(cam, s, LightVolumes::Output::Light, &hooked);
    Render want = render(cam, s, LightVolumes::Output::Light, &reference);
    EXPECT_EQ(r.image.pixels, want.image.pixels) << kStrategies[int(s)];
    EXPECT_EQ(r.counts.lit, want.counts.lit) << kStrategies[int(s)];
  }
}

TEST_F(LightVolumesGl, TheAmbientHookReplacesTheConstantAmbient) {
  // Chapters 07 and 08 bring a per-pixel ambient term here: one that returns 0 must give the
  // image of the frame whose ambient light is 0.
  const FrameCamera cam = camera("street_level");
  ASSERT_GT(glm::length(scene_->ambient), 0.f) << "the street has an ambient light to take away";
  DeferredFrame hooked(*gpu_), dark(*gpu_);
  hooked.volumes().set_lights(light_set(scene_->lights));
  dark.volumes().set_lights(light_set(scene_->lights));
  const Render lit = render(cam, Strategy::Stencil, LightVolumes::Output::Light, &dark);
  dark.set_ambient(glm::vec3(0));
  HookStage stage;
  stage.hooks.ambient = test_hook("no_ambient.glsl");
  hooked.add_stage(stage);
  Render r = render(cam, Strategy::Stencil, LightVolumes::Output::Light, &hooked);
  Render want = render(cam, Strategy::Stencil, LightVolumes::Output::Light, &dark);
  EXPECT_EQ(r.image.pixels, want.image.pixels);
  EXPECT_NE(r.image.pixels, lit.image.pixels) << "the ambient light must have mattered";
}

TEST_F(LightVolumesGl, TwoStagesCannotBothOwnAHook) {
  DeferredFrame frame(*gpu_);
  HookStage a, b, c;
  a.hooks.visibility = test_hook("no_light_reaches.glsl");
  b.hooks.visibility = test_hook("every_other_light.glsl");
  c.hooks.ambient = test_hook("no_ambient.glsl");
  frame.add_stage(a);
  frame.add_stage(c);  // different hooks: fine
  EXPECT_NO_THROW(frame.render(camera("street_level"), {target_->framebuffer(), kW, kH}));
  frame.add_stage(b);
  try {
    frame.render(camera("street_level"), {target_->framebuffer(), kW, kH});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("both supply its visibility hook"), std::string::npos) << e.what();
  }
}

TEST_F(LightVolumesGl, AnotherChaptersCullingReplacesTheVolumes) {
  // Chapter 09 brings its own local-light pass: the frame must call it instead of the
  // volumes, name it in the timings, and keep everything else. One that adds nothing gives
  // the frame without local lights.
  struct Nothing : LocalLightPass {
    int calls = 0;
    std::string name() const override { return "nothing"; }
    void draw(const LightBuffer&, const SurfaceView&, LightVolumes::Output) override { ++calls; }
  } nothing;
  const FrameCamera cam = camera("street_level");
  DeferredFrame frame(*gpu_), global_only(*gpu_);
  frame.volumes().set_lights(light_set(scene_->lights));
  global_only.volumes().set_lights(without_local(light_set(scene_->lights)));
  frame.set_local_lights(&nothing);
  PassMetrics metrics;
  frame.render(cam, {target_->framebuffer(), kW, kH}, &metrics);
  metrics.end_frame();
  metrics.wait_all();
  const ImageRGBA8 replaced = target_->read();
  EXPECT_EQ(nothing.calls, 1);
  EXPECT_NE(metrics.find("local lights: nothing"), nullptr);
  EXPECT_EQ(replaced.pixels, render(cam, Strategy::Stencil, LightVolumes::Output::Light, &global_only).image.pixels);
  frame.set_local_lights(nullptr);  // chapter 03's volumes again
  EXPECT_NE(render(cam, Strategy::Stencil, LightVolumes::Output::Light, &frame).image.pixels, replaced.pixels);
  EXPECT_EQ(nothing.calls, 1);
}

// The counters are 64-bit, made of 32-bit atomics (shaders/fragment_counters.glsl): started
// 1000 below 2^32, they carry across it exactly. A 32-bit counter would wrap there to the
// count minus 1000 (how 65 536 lights at 1080p once printed an overshading of 1.209 for 1.026).
TEST_F(LightVolumesGl, CountersCountPast32Bits) {
  volumes_->set_lights(light_set(scene_->lights));
  const FrameCamera cam = camera("street_level");
  auto counts_from = [&](Strategy strategy, std::uint64_t start) {
    volumes_->set_counting(true, start);
    frame_->set_strategy(strategy);
    frame_->render(cam, {target_->framebuffer(), kW, kH});
    const FragmentCounts c = volumes_->counts();
    volumes_->set_counting(true);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    return c;
  };
  const std::uint64_t start = (std::uint64_t(1) << 32) - 1000;
  for (Strategy strategy : {Strategy::Stencil, Strategy::FullScreen}) {
    const FragmentCounts from_zero = counts_from(strategy, 0);
    ASSERT_GT(from_zero.shaded, 1000u) << "too few fragments to cross 2^32 from " << start;
    ASSERT_GT(from_zero.lit, 1000u);
    ASSERT_GT(from_zero.lit_inner, 1000u);
    const FragmentCounts crossed = counts_from(strategy, start);
    EXPECT_EQ(crossed.shaded, start + from_zero.shaded) << kStrategies[int(strategy)];
    EXPECT_EQ(crossed.lit, start + from_zero.lit) << kStrategies[int(strategy)];
    EXPECT_EQ(crossed.lit_inner, start + from_zero.lit_inner) << kStrategies[int(strategy)];
    EXPECT_EQ(crossed.marking, start + from_zero.marking) << kStrategies[int(strategy)];
    EXPECT_GT(crossed.shaded, std::uint64_t(1) << 32);
  }
}

// What GL_SAMPLES_PASSED counts over the local-light pass is shaded plus marking: the stencil
// strategies' marking draws pass fragments too (those in front of the surface, where the mask
// stays unmarked), though they shade nothing; the counters tell the two apart, and --bench
// reports them apart. The strategies without a mask draw nothing else.
TEST_F(LightVolumesGl, SamplesPassedAreShadedPlusMarking) {
  volumes_->set_lights(light_set(scene_->lights));
  for (const std::string view : {"street_level", "overview", "inside_light"}) {
    for (std::size_t k = 0; k < kStrategies.size(); ++k) {
      const Strategy strategy = static_cast<Strategy>(k);
      const Render r = render(camera(view), strategy);
      EXPECT_EQ(r.samples, r.counts.shaded + r.counts.marking) << view << ", " << kStrategies[k];
      if (strategy == Strategy::Stencil || strategy == Strategy::StencilBits)
        EXPECT_GT(r.counts.marking, 0u) << view << ", " << kStrategies[k];
      else
        EXPECT_EQ(r.counts.marking, 0u) << view << ", " << kStrategies[k];
    }
  }
}

// --- The global pass in compute (GlobalPass, light_volumes.h) --------------------------------

namespace {
// A light-buffer target's half floats as stored, for a comparison bit for bit.
std::vector<std::uint16_t> half_bits(GLuint texture, int width, int height) {
  std::vector<std::uint16_t> bits(std::size_t(width) * std::size_t(height) * 4);
  glGetTextureImage(texture, 0, GL_RGBA, GL_HALF_FLOAT, GLsizei(bits.size() * sizeof(std::uint16_t)), bits.data());
  return bits;
}
// How many of two targets' values differ, and where the first does.
std::string differing(const std::vector<std::uint16_t>& a, const std::vector<std::uint16_t>& b, int width) {
  std::size_t n = 0, first = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i] != b[i] && n++ == 0) first = i;
  if (n == 0) return "";
  return std::to_string(n) + " values differ, the first at pixel (" + std::to_string(first / 4 % std::size_t(width)) +
         ", " + std::to_string(first / 4 / std::size_t(width)) + ")";
}
}  // namespace

TEST_F(LightVolumesGl, TheGlobalPassInComputeWritesTheFragmentPassesLightBuffer) {
  // global.frag and global.comp run one body (global_light.glsl) on the same G-buffer texels, the
  // same light records and hooks, and store the same float values into the same RGBA16F targets:
  // the light buffers must be equal bit for bit (the bound is 0). With an ambient hook that
  // depends on its pixel, so the pixel the pass hands it must be the one it writes; at 320x180
  // the 8x8 groups overhang the image's last row of groups, which must write nothing outside.
  // The local lights are left out: what the light buffer holds is the global pass's alone.
  const FrameCamera cam = camera("street_level");
  DeferredFrame frame(*gpu_);
  frame.volumes().set_lights(without_local(light_set(scene_->lights)));
  ASSERT_FALSE(frame.volumes().lights().directional.empty()) << "the street needs a directional light to test";
  HookStage pattern;
  pattern.hooks.ambient = test_hook("ambient_by_pixel.glsl");
  frame.add_stage(pattern);
  struct LightBits {
    std::vector<std::uint16_t> diffuse, specular;
    std::uint64_t samples = 0;  // GL_SAMPLES_PASSED over the global pass
  };
  auto light_with = [&](GlobalPass how) {
    frame.set_global_pass(how);
    PassMetrics metrics;
    frame.render(cam, {target_->framebuffer(), kW, kH}, &metrics);
    metrics.end_frame();
    metrics.wait_all();
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    return LightBits{half_bits(frame.light().diffuse(), kW, kH), half_bits(frame.light().specular(), kW, kH),
                 metrics.find("global: ambient + directional (chapter 03)")->samples};
  };
  // Compute first, into a new light buffer: a value it failed to write is not the fragment pass's.
  const LightBits compute = light_with(GlobalPass::Compute), fragment = light_with(GlobalPass::Fragment);
  EXPECT_EQ(fragment.samples, std::uint64_t(kW) * kH) << "the fragment pass shades every pixel once";
  EXPECT_EQ(compute.samples, 0u) << "the compute pass draws no fragment: the frame must have run it";
  EXPECT_EQ(differing(compute.diffuse, fragment.diffuse, kW), "") << "L1 (diffuse)";
  EXPECT_EQ(differing(compute.specular, fragment.specular, kW), "") << "L2 (specular)";
  // Not vacuous: the pattern and the specular light are in the buffers.
  frame.set_global_pass(GlobalPass::Fragment);
  DeferredFrame constant(*gpu_);
  constant.volumes().set_lights(without_local(light_set(scene_->lights)));
  constant.render(cam, {target_->framebuffer(), kW, kH});
  EXPECT_NE(differing(half_bits(constant.light().diffuse(), kW, kH), fragment.diffuse, kW), "") << "the hook's pattern shows";
  EXPECT_NE(differing(fragment.specular, std::vector<std::uint16_t>(fragment.specular.size(), 0), kW), "")
      << "the directional lights leave specular light";

  // Deferred lighting's one target (LIGHT_PREPASS): diffuse, and the specular luminance in alpha.
  frame.render(cam, {target_->framebuffer(), kW, kH});
  std::vector<std::uint16_t> prepass[2];
  for (GlobalPass how : {GlobalPass::Compute, GlobalPass::Fragment}) {
    LightBuffer light(kW, kH, ch02::depth_format(frame.gbuffer().layout().depth), LightBuffer::Kind::PrePass);
    frame.gbuffer().bind_textures(0);
    frame.bind_hooks();
    light.begin(frame.gbuffer().framebuffer());
    frame.volumes().draw_global(light, frame.view(), scene_->ambient, how);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    prepass[int(how)] = half_bits(light.diffuse(), kW, kH);
  }
  EXPECT_EQ(differing(prepass[1], prepass[0], kW), "") << "the pre-pass's target";
}
