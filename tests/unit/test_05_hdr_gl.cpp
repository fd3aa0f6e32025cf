// Chapter 05 on the GPU (llvmpipe in CI): the log-average methods against the exact
// double-precision reduction, the hard cases (black frame, one pixel at 1e6, NaN and Inf,
// fp16 overflow, 1x1 and 1x1080 frames), the GLSL operators and adaptation against their
// C++ twins, and bloom against a full-resolution CPU reference. Bounds hold on any
// conforming OpenGL 4.5 implementation; each says where it comes from.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

#include "chapters/05_hdr/hdr_pipeline.h"
#include "chapters/05_hdr/radiance_source.h"
#include "chapters/05_hdr/reference.h"
#include "common/paths.h"
#include "tests/unit/gl_environment.h"

using namespace lp;
using namespace lp::ch05;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kDelta = 1e-4f;

// [log-average-bound]
// How far a GPU log-average may be from the exact one, as |mean log - exact mean log| (which
// is also the relative error of exp(mean log) to first order). Per pixel, GLSL's log() may
// be off by 3 ulp (|log| < 16 here: 3 x 2^-20 = 2.9e-6). The mip chain then takes <= 11
// levels of weighted means of <= 9 values: each level rounds by <= 11 float operations of
// 2^-24 relative to a mean below 12, and the errors of the levels add up:
// 11 x 11 x 2^-24 x 12 = 8.7e-5. The compute reduction rounds far less (sums of <= 10
// pairwise levels). Together: 1e-4.
constexpr double kLogAverageBound = 1e-4;
// [/log-average-bound]

const AverageMethod kExactMethods[] = {AverageMethod::MipChain, AverageMethod::Compute};



// Deterministic log-normal "scene" values between about 1e-3 and 1e2.
ImageF noise_image(int w, int h, std::uint32_t seed = 1) {
  ImageF img = ImageF::blank(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        seed = seed * 1664525u + 1013904223u;
        img.at(x, y, c) = std::pow(10.f, -3.f + 5.f * float(seed >> 8) / 16777216.f);
      }
  return img;
}

bool any_nan(const ImageF& img) {
  for (float v : img.data) if (std::isnan(v)) return true;
  return false;
}

class HdrGl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    pipeline_ = new HdrPipeline();
  }
  static void TearDownTestSuite() {  // GL objects go before the context (gl_environment.h)
    delete pipeline_;
  }
  void TearDown() override { EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)); }

  // The log-average of `image` (stored as `format`) by `method`, and the exact one of the
  // same stored values (read back, so fp16 rounding is the same for both).
  struct Averages {
    LogAverageResult gpu;
    ExactLogAverage exact;
  };
  Averages average(const ImageF& image, AverageMethod method, GLenum format = GL_RGBA16F) {
    gl::Texture t = upload_radiance(image, format);
    LogAverage& la = log_average();
    la.compute(t.id(), image.width, image.height, method, kDelta);
    return {la.read(), exact_log_average(read_texture(t.id(), image.width, image.height), kDelta)};
  }

  // The whole stage into an RGBA32F image, so NaN, Inf and values above 1 stay visible.
  struct Output {
    ImageF image;
    ExposureState state;
  };
  Output run(const ImageF& image, HdrSettings s, GLenum format = GL_RGBA16F) {
    gl::Texture in = upload_radiance(image, format);
    return run_texture(in.id(), image.width, image.height, s);
  }
  Output run_texture(GLuint texture, int w, int h, HdrSettings s) {
    gl::Texture colour = gl::make_texture_2d(GL_RGBA32F, w, h);
    gl::Framebuffer fbo;
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, colour.id(), 0);
    s.adaptation.tau = 0;  // these tests look at one frame: adapted = that frame's average
    // ... at the fixed key: the hard cases at their largest exposure (a black frame's key /
    // delta), where a dim frame's exposure still follows its average. The floor is
    // GpuAdaptationMatchesTheCpuFormula's.
    s.adaptation.adapt_floor = 0.f;
    pipeline_->process(texture, w, h, s, fbo.id());
    return {read_texture(colour.id(), w, h), pipeline_->adaptation().read()};
  }

  static LogAverage& log_average() {
    static LogAverage* la = nullptr;
    if (!la) la = new LogAverage();  // lives as long as the context (the process)
    return *la;
  }

  static HdrPipeline* pipeline_;
};
HdrPipeline* HdrGl::pipeline_ = nullptr;

}  // namespace

// --- The log-average against the exact reduction -------------------------------------------

TEST_F(HdrGl, LogAverageIsExactOnEverySize) {
  // Powers of two, odd sizes, one-pixel-wide frames: the fixed mip chain and the compute
  // reduction count every pixel once.
  const int sizes[][2] = {{1, 1}, {2, 2}, {3, 3}, {7, 5}, {1, 1080}, {1080, 1}, {256, 256},
                          {320, 180}, {321, 181}, {333, 77}, {1023, 3}};
  for (auto [w, h] : sizes)
    for (const ImageF& img : {ramp_image(w, h), noise_image(w, h)})
      for (AverageMethod m : kExactMethods) {
        Averages a = average(img, m);
        EXPECT_EQ(a.gpu.count, float(a.exact.count)) << kAverageMethodNames[int(m)] << ' ' << w << 'x' << h;
        EXPECT_NEAR(a.gpu.mean_log, a.exact.mean_log, kLogAverageBound) << kAverageMethodNames[int(m)] << ' ' << w << 'x' << h;
      }
}

TEST_F(HdrGl, NaiveMipChainAveragesOnlyThePowerOfTwoCorner) {
  for (auto [w, h] : {std::pair{321, 181}, {1, 1080}, {640, 360}}) {
    ImageF img = ramp_image(w, h);
    Averages a = average(img, AverageMethod::NaiveMipChain);
    // It counts exactly the pixels the model says ...
    EXPECT_EQ(a.gpu.count, float(naive_chain_pixels(w, h))) << w << 'x' << h;
    // ... and its result is the exact average of that corner: texture row 0 is the image's
    // bottom row, so the kept rectangle is the bottom-left one.
    int kw = 1, kh = 1;
    while (kw * 2 <= w) kw *= 2;
    while (kh * 2 <= h) kh *= 2;
    gl::Texture t = upload_radiance(img);
    ImageF stored = read_texture(t.id(), w, h), corner = ImageF::blank(kw, kh, 4);
    for (int y = 0; y < kh; ++y)
      for (int x = 0; x < kw; ++x)
        for (int c = 0; c < 4; ++c) corner.at(x, y, c) = stored.at(x, h - kh + y, c);
    EXPECT_NEAR(a.gpu.mean_log, exact_log_average(corner, kDelta).mean_log, kLogAverageBound) << w << 'x' << h;
    // On this image the dropped part is the bright one: the naive result is far too dark.
    if (w > 1) {
      EXPECT_LT(std::exp(a.gpu.mean_log) / a.exact.luminance, 0.5) << w << 'x' << h;
    }
  }
}

TEST_F(HdrGl, LogAverageOfTheStreetScene) {
  // A real frame, the chapter's: chapter 03's deferred path into RGBA16F, lamps and windows
  // at 8x, at an odd size.
  Scene scene = load_scene(from_root("assets/street/street.gltf"));
  DeferredRadiance source(scene);
  source.set_scales(1.f, 8.f);
  source.set_cut_exposure(4.f);
  RadianceTarget target(321, 181, GL_RGBA16F, false);
  source.render(frame_camera(scene.camera("street_level"), 321.f / 181.f), target);
  ImageF stored = target.read();
  ExactLogAverage exact = exact_log_average(stored, kDelta);
  for (AverageMethod m : kExactMethods) {
    log_average().compute(target.texture(), 321, 181, m, kDelta);
    EXPECT_NEAR(log_average().read().mean_log, exact.mean_log, kLogAverageBound) << kAverageMethodNames[int(m)];
  }
  // What an 8-bit target loses: the float buffer holds radiance above 1 that RGBA8 clips.
  std::size_t above_one = 0;
  for (int i = 0; i < 321 * 181; ++i) above_one += std::max({stored.data[4 * i], stored.data[4 * i + 1], stored.data[4 * i + 2]}) > 1.f;
  EXPECT_GT(above_one, std::size_t(321 * 181 / 50)) << "more than 2% of the street is brighter than 1";
  RadianceTarget low(321, 181, GL_RGBA8, false);
  source.render(frame_camera(scene.camera("street_level"), 321.f / 181.f), low);
  ImageF clipped = low.read();
  EXPECT_LE(*std::max_element(clipped.data.begin(), clipped.data.end()), 1.f);
}

// --- Hard cases ---------------------------------------------------------------------------

TEST_F(HdrGl, BlackFrameStaysFiniteAndBlack) {
  ImageF black = constant_image(37, 23, glm::vec3(0));
  for (AverageMethod m : {AverageMethod::MipChain, AverageMethod::Compute, AverageMethod::NaiveMipChain}) {
    Averages a = average(black, m);
    EXPECT_NEAR(a.gpu.mean_log, std::log(double(kDelta)), kLogAverageBound) << kAverageMethodNames[int(m)];
  }
  for (Operator op : {Operator::Clamp, Operator::Reinhard, Operator::ReinhardExtended, Operator::Aces})
    for (BloomMode bloom : {BloomMode::Off, BloomMode::AfterTonemap, BloomMode::BeforeTonemap}) {
      HdrSettings s;
      s.tonemap.op = op;
      s.bloom = bloom;
      Output out = run(black, s);
      // exposure = key / delta = 1800: large, finite, and 0 x 1800 = 0.
      EXPECT_NEAR(out.state.exposure, 0.18 / kDelta, 0.18 / kDelta * 2 * kLogAverageBound);
      for (int i = 0; i < 37 * 23; ++i)
        for (int c = 0; c < 3; ++c) ASSERT_EQ(out.image.data[4 * i + c], 0.f) << "operator " << int(op) << " bloom " << int(bloom);
    }
}

TEST_F(HdrGl, OnePixelAtAMillionDoesNotMoveTheAverage) {
  // 1e6 fits in RGBA32F; the stage reads anything above 65504 as 65504 (the fp16 policy).
  ImageF dark = constant_image(64, 36, glm::vec3(0.01f)), spike = dark;
  for (int c = 0; c < 3; ++c) spike.at(40, 10, c) = 1e6f;
  for (AverageMethod m : kExactMethods) {
    Averages a = average(spike, m, GL_RGBA32F);
    EXPECT_NEAR(a.gpu.mean_log, a.exact.mean_log, kLogAverageBound);
    // One pixel of N moves the mean log by (log 65504 - log 0.01) / N = 0.0068 here.
    double shift = (std::log(kDelta + 65504.0) - std::log(kDelta + double(0.01f))) / (64 * 36);
    EXPECT_NEAR(a.gpu.mean_log - average(dark, m, GL_RGBA32F).gpu.mean_log, shift, 2 * kLogAverageBound);
  }
  HdrSettings s;
  Output with = run(spike, s, GL_RGBA32F), without = run(dark, s, GL_RGBA32F);
  EXPECT_GT(with.image.at(40, 10, 0), 0.999f) << "the spike is white";
  // Every other pixel changes only by the exposure's shift: Reinhard's slope is below 1, so
  // by at most x (1 - exp(-0.0068)) with x = 0.18 exposed: 1.3e-3.
  for (int y = 0; y < 36; ++y)
    for (int x = 0; x < 64; ++x)
      if (x != 40 || y != 10) {
        ASSERT_NEAR(with.image.at(x, y, 0), without.image.at(x, y, 0), 1.3e-3) << x << ',' << y;
      }
  // With bloom the spike glows but stays bounded: each bloom texel holds at most the limit
  // (64 exposed) and the output is clamped to 1 -- no NaN, no Inf.
  s.bloom = BloomMode::AfterTonemap;
  Output glow = run(spike, s, GL_RGBA32F);
  for (float v : glow.image.data) ASSERT_TRUE(std::isfinite(v) && v >= 0.f && v <= 1.f);
  EXPECT_GT(glow.image.at(44, 10, 0), with.image.at(44, 10, 0)) << "the bloom reaches the neighbours";
}

TEST_F(HdrGl, NanAndInfDoNotPoisonTheAverageOrTheImage) {
  ImageF img = noise_image(45, 31);
  auto set = [&](int x, int y, glm::vec3 v) { for (int c = 0; c < 3; ++c) img.at(x, y, c) = v[c]; };
  set(3, 4, glm::vec3(kNaN));
  set(20, 15, glm::vec3(0.5f, kNaN, 0.5f));
  set(44, 30, glm::vec3(kInf));
  set(10, 25, glm::vec3(-kInf, 1.f, 1.f));
  set(30, 2, glm::vec3(-5.f));
  for (AverageMethod m : kExactMethods) {
    Averages a = average(img, m);
    EXPECT_EQ(a.gpu.count, float(45 * 31 - 2)) << "the two NaN pixels are left out";
    EXPECT_NEAR(a.gpu.mean_log, a.exact.mean_log, kLogAverageBound) << kAverageMethodNames[int(m)];
  }
  // The source's method, with no policy, is poisoned: one NaN makes the average NaN.
  EXPECT_TRUE(std::isnan(average(img, AverageMethod::NaiveMipChain).gpu.mean_log));

  for (BloomMode bloom : {BloomMode::Off, BloomMode::AfterTonemap, BloomMode::BeforeTonemap}) {
    HdrSettings s;
    s.bloom = bloom;
    s.bloom_chain.level = 1;
    Output out = run(img, s);
    ASSERT_FALSE(any_nan(out.image)) << "bloom " << int(bloom);
    for (float v : out.image.data) ASSERT_TRUE(v >= 0.f && v <= 1.f);
    if (bloom == BloomMode::Off) {
      EXPECT_EQ(out.image.at(3, 4, 0), 0.f) << "NaN is shown black";
      EXPECT_GT(out.image.at(44, 30, 0), 0.999f) << "+Inf is 65504: white";
      EXPECT_EQ(out.image.at(30, 2, 1), 0.f) << "negative is black";
    }
  }
}

TEST_F(HdrGl, ValuesAboveHalfMaxReadAs65504) {
  ImageF over = noise_image(33, 17), at_max = over;
  for (int c = 0; c < 3; ++c) { over.at(5, 5, c) = 1e5f; at_max.at(5, 5, c) = 65504.f; }
  // Into RGBA16F: fp16 has no 1e5. The conversion gives +Inf (round to nearest) or 65504
  // (saturating); either must read as 65504. Into RGBA32F the 1e5 stays 1e5, and must too.
  gl::Texture t = upload_radiance(over);
  float stored = read_texture(t.id(), 33, 17).at(5, 5, 0);
  EXPECT_TRUE(stored == kInf || stored == 65504.f) << stored;
  for (GLenum format : {GL_RGBA16F, GL_RGBA32F}) {
    for (AverageMethod m : kExactMethods)
      EXPECT_NEAR(average(over, m, format).gpu.mean_log, average(at_max, m, format).gpu.mean_log, 1e-6) << kAverageMethodNames[int(m)];
    HdrSettings s;
    s.bloom = BloomMode::BeforeTonemap;
    Output a = run(over, s, format), b = run(at_max, s, format);
    EXPECT_FALSE(any_nan(a.image));
    for (std::size_t i = 0; i < a.image.data.size(); ++i) ASSERT_EQ(a.image.data[i], b.image.data[i]) << i;
  }
  // An explicit +Inf (what a shader's overflow writes) reads the same way.
  ImageF inf = over;
  for (int c = 0; c < 3; ++c) inf.at(5, 5, c) = kInf;
  EXPECT_NEAR(average(inf, AverageMethod::MipChain).gpu.mean_log, average(at_max, AverageMethod::MipChain).gpu.mean_log, 1e-6);
}

TEST_F(HdrGl, TinyAndOnePixelWideFrames) {
  for (auto [w, h] : {std::pair{1, 1}, {1, 1080}, {1080, 1}, {2, 3}})
    for (int level : {0, 1, 3})
      for (BloomMode bloom : {BloomMode::AfterTonemap, BloomMode::BeforeTonemap}) {
        ImageF img = noise_image(w, h, 7);
        HdrSettings s;
        s.bloom = bloom;
        s.bloom_chain.level = level;
        Output out = run(img, s);
        ASSERT_FALSE(any_nan(out.image)) << w << 'x' << h << " level " << level;
        gl::Texture t = upload_radiance(img);
        EXPECT_NEAR(out.state.mean_log, exact_log_average(read_texture(t.id(), w, h), kDelta).mean_log, kLogAverageBound);
        EXPECT_EQ(out.state.count, float(w * h));
      }
}

// --- The GLSL twins against the C++ ---------------------------------------------------------

TEST_F(HdrGl, GpuOperatorsMatchTheCpuCurves) {
  // Exposure 1 by hand, so the tonemapper sees the ramp's values as they are.
  ExposureState unit{.target = 1, .adapted = 1, .exposure = 1};
  gl::Buffer state = gl::make_buffer(&unit, sizeof(unit));
  const int n = 512;
  ImageF ramp = ImageF::blank(n, 1, 3);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) ramp.at(i, 0, c) = std::pow(10.f, -4.f + 8.f * float(i) / (n - 1)) * (1.f + 0.25f * c);
  gl::Texture in = upload_radiance(ramp, GL_RGBA32F);
  gl::Texture colour = gl::make_texture_2d(GL_RGBA32F, n, 1);
  gl::Framebuffer fbo;
  glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, colour.id(), 0);
  Tonemapper tonemapper;
  for (Operator op : {Operator::Clamp, Operator::Reinhard, Operator::ReinhardExtended, Operator::Aces}) {
    tonemapper.draw(in.id(), n, 1, state.id(), {.op = op, .white = 4.f}, {}, fbo.id());
    ImageF out = read_texture(colour.id(), n, 1);
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        float x = sanitize({ramp.at(i, 0, c), 0, 0}).rgb.r;
        // Values <= 1 from <= 8 float operations: GLSL allows 2.5 ulp for a division and
        // fused multiply-adds; 16 ulp at 1 (1.9e-6) covers them.
        ASSERT_NEAR(out.at(i, 0, c), tonemap(op, x, 4.f), 1.9e-6f) << kOperatorNames[int(op)] << " at x = " << x;
      }
  }
}

TEST_F(HdrGl, GpuAdaptationMatchesTheCpuFormula) {
  // A frame average that jumps from bright to dark and back, fed to the adaptation pass: the
  // dark frames below the adaptation floor (0.18), the bright ones above it.
  EyeAdaptation eye;
  gl::Buffer frame = gl::make_buffer(nullptr, sizeof(LogAverageResult), GL_DYNAMIC_STORAGE_BIT);
  AdaptationSettings s{.key = 0.18f, .tau = 0.4f, .dt = 1.f / 60.f};
  float cpu = 0;
  eye.reset(30.f);
  for (int i = 0; i < 240; ++i) {
    float target = i < 120 ? 0.05f : 2.f;
    LogAverageResult r{.mean_log = std::log(target), .count = 100};
    glNamedBufferSubData(frame.id(), 0, sizeof(r), &r);
    eye.update(frame.id(), s);
    ExposureState g = eye.read();
    float gpu_target = g.target;  // exp() on the GPU: compare the step, not exp's rounding
    cpu = i == 0 ? 30.f * gpu_target : adapt(cpu, gpu_target, s.dt, s.tau);
    // Each step rounds by a few ulp (exp() is allowed 3 + 2|x| ulp); the old error shrinks
    // by exp(-dt / tau) = 0.959 per frame, so it stays below 4 ulp / (1 - 0.959) = 100 ulp
    // = 1.2e-5 of the value.
    ASSERT_NEAR(g.adapted / cpu, 1.f, 1.2e-5f) << "frame " << i;
    // One division (2.5 ulp in GLSL): 3e-7 of the value.
    const float expected = exposure_for(0.18f, g.adapted, s.adapt_floor);
    ASSERT_NEAR(g.exposure, expected, expected * 3e-7f) << "frame " << i;
    if (i == 119) {
      EXPECT_NEAR(g.exposure, 1.f, 3e-7f) << "adapted towards 0.05, below the floor: exposure key / floor = 1";
    }
  }
  EXPECT_NEAR(cpu / 2.f, 1.f, 0.02f) << "adapted to the new scene after 3 s = 7.5 tau";
}

// --- Bloom ------------------------------------------------------------------------------------

TEST_F(HdrGl, FullResolutionBloomMatchesTheCpuReference) {
  ImageF img = noise_image(70, 46, 3);
  for (int y = 15; y < 19; ++y)
    for (int x = 30; x < 33; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = 500.f * (1.f + c);
  HdrSettings s;
  s.bloom = BloomMode::AfterTonemap;
  s.bloom_chain = {.level = 0, .radius = 0.05f, .threshold = 1.f, .limit = 64.f};
  s.view = HdrSettings::View::Bloom;
  Output out = run(img, s);
  gl::Texture t = upload_radiance(img);
  ImageF ref = reference_bloom(read_texture(t.id(), 70, 46), out.state.exposure, 1.f, 64.f, 0.05f * 46);
  double max_ref = *std::max_element(ref.data.begin(), ref.data.end());
  ASSERT_GT(max_ref, 1.0);
  for (int y = 0; y < 46; ++y)
    for (int x = 0; x < 70; ++x)
      for (int c = 0; c < 3; ++c) {
        double r = ref.at(x, y, c);
        // Three images stored as fp16 (bright pass, horizontal, vertical). OpenGL does not fix
        // the rounding of a conversion to fp16 (llvmpipe truncates), so each store may move a
        // value to either neighbour: < 2^-10 relative. A blur of positive values keeps the
        // largest relative error of its inputs. Float weights and sums add ~1e-6 of the
        // largest value.
        ASSERT_NEAR(out.image.at(x, y, c), r, 3 * 0x1p-10 * r + 1e-6 * max_ref) << x << ',' << y << ',' << c;
      }
}

TEST_F(HdrGl, UniformFrameBloomsUniformlyAtOddSizes) {
  // A frame of one bright colour: its bright pass is one colour, every reduction of it too
  // (the texels that hang over an odd edge are weighted by how much of them is image, not
  // diluted with the void), and a normalised blur of a constant is that constant. Only fp16
  // rounding is left: < 2^-10 per stored image, level + 2 images (level 0: 3).
  for (auto [w, h] : {std::pair{37, 23}, {1, 5}, {45, 1}})
    for (int level : {0, 1, 2, 3}) {
      ImageF img = constant_image(w, h, glm::vec3(2.f, 1.f, 0.5f));
      HdrSettings s;
      s.bloom = BloomMode::AfterTonemap;
      s.bloom_chain = {.level = level, .radius = 0.1f, .threshold = 0.1f, .limit = 1e4f};
      s.view = HdrSettings::View::Bloom;
      Output out = run(img, s);
      glm::vec3 x = sanitize(glm::vec3(2.f, 1.f, 0.5f)).rgb * out.state.exposure;
      glm::vec3 expected = bright_pass(x, 0.1f, 1e4f);
      int stores = level == 0 ? 3 : level + 2;
      for (int y = 0; y < h; ++y)
        for (int px = 0; px < w; ++px)
          for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(out.image.at(px, y, c), expected[c], stores * 0x1p-10 * expected[c])
                << w << 'x' << h << " level " << level << " at " << px << ',' << y;
    }
}

// Bloom before the curve takes the bright part out of each pixel and puts it back spread out,
// so the image before the curve keeps its light: with the clamp curve and every exposed value
// below 1 (the curve is then the identity), the final image's sum is the exposed input's, up to
// the same fp16 roundings as the bloom's own energy (below). Adding the spread light without
// taking it out first counts it twice: the sum grows by the bloom's strength, here 100 %.
TEST_F(HdrGl, BloomBeforeTheCurveKeepsTheImagesLight) {
  const int w = 160, h = 96;
  ImageF img = constant_image(w, h, glm::vec3(0.1f));
  for (int y = 40; y < 52; ++y)
    for (int x = 70; x < 85; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = 0.2f + 0.02f * float(x - 70);
  HdrSettings s;
  s.tonemap.op = Operator::Clamp;
  s.bloom = BloomMode::BeforeTonemap;
  s.bloom_strength = 1.f;
  s.bloom_chain = {.level = 1, .radius = 0.04f, .threshold = 0.f, .limit = 1e4f};  // every pixel's light is spread
  const Output out = run(img, s);
  gl::Texture t = upload_radiance(img);
  const ImageF stored = read_texture(t.id(), w, h);
  double before = 0, after = 0, brightest = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const double v = double(stored.at(x, y, c)) * out.state.exposure;
        before += v;
        brightest = std::max(brightest, v);
        after += out.image.at(x, y, c);
      }
  ASSERT_LT(brightest, 1.0) << "the curve must be the identity for the sums to compare";
  ASSERT_GT(before, 1000.0);
  const int stores = 1 + 2;  // as ReducedResolutionBloomKeepsTheEnergy at level 1: each < 2^-10
  EXPECT_NEAR(after / before, 1.0, stores * 0x1p-10);
}

TEST_F(HdrGl, ReducedResolutionBloomKeepsTheEnergy) {
  // A bright blob far from the edges: each reduction averages (keeps the sum), the blur's
  // weights sum to 1 away from the edges, and bilinear upsampling by an even factor keeps
  // the sum too (the hat function's samples at an even rate sum to the rate). What is left
  // is fp16 rounding of the stored images (the bright pass, the reductions to the level,
  // the two blur passes), each < 2^-10 relative as the rounding mode is not specified.
  const int w = 160, h = 96;
  ImageF img = constant_image(w, h, glm::vec3(0.001f));
  for (int y = 40; y < 52; ++y)
    for (int x = 70; x < 85; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = 20.f + float(x - 70);
  for (int level : {0, 1, 2, 3}) {
    HdrSettings s;
    s.bloom = BloomMode::BeforeTonemap;
    s.bloom_chain = {.level = level, .radius = 0.04f, .threshold = 1.f, .limit = 1e4f};
    s.view = HdrSettings::View::Bloom;
    Output out = run(img, s);
    double bloom = 0, bright = 0;
    gl::Texture t = upload_radiance(img);
    ImageF stored = read_texture(t.id(), w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        glm::vec3 b = bright_pass(sanitize({stored.at(x, y, 0), stored.at(x, y, 1), stored.at(x, y, 2)}).rgb * out.state.exposure, 1.f, 1e4f);
        bright += b.r + b.g + b.b;
        bloom += out.image.at(x, y, 0) + out.image.at(x, y, 1) + out.image.at(x, y, 2);
      }
    ASSERT_GT(bright, 100.0);
    int stores = level == 0 ? 3 : level + 2;
    EXPECT_NEAR(bloom / bright, 1.0, stores * 0x1p-10) << "level " << level;
  }
}
