// PassMetrics and measure() on a headless context (llvmpipe in CI): what a measurement
// reports is what was drawn, every frame it claims is read back, fragment counts are 64-bit
// end to end, and an OpenGL error inside a pass is reported with its name, never thrown out
// of a destructor.
#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <thread>
#include <stdexcept>
#include <type_traits>

#include "common/context.h"
#include "common/error.h"
#include "common/measure.h"
#include "common/metrics.h"
#include "common/shader.h"

using namespace lp;

namespace {

class MetricsGl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // An empty fragment shader over one triangle that covers the viewport: one fragment per
    // pixel, and nothing else to wait for.
    fill_ = new ShaderProgram({{GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"},
                               {GL_FRAGMENT_SHADER, "03_light_volumes/shaders/stencil.frag"}});
    vao_ = new gl::VertexArray();
  }
  static void TearDownTestSuite() {  // GL objects go before the context (gl_environment.h)
    delete vao_;
    delete fill_;
  }
  void SetUp() override {
    while (glGetError() != GL_NO_ERROR) {}
  }
  // A framebuffer with no attachments, w x h: every covered pixel passes (no depth, no stencil).
  struct Empty {
    gl::Framebuffer fbo;
    Empty(int w, int h) {
      glNamedFramebufferParameteri(fbo.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, w);
      glNamedFramebufferParameteri(fbo.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, h);
      glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
      glViewport(0, 0, w, h);
      glDisable(GL_DEPTH_TEST);
      glDisable(GL_STENCIL_TEST);
    }
  };
  static void fill(int instances = 1) {
    fill_->use();
    glBindVertexArray(vao_->id());
    glDrawArraysInstanced(GL_TRIANGLES, 0, 3, instances);
  }
  static inline ShaderProgram* fill_ = nullptr;
  static inline gl::VertexArray* vao_ = nullptr;
};

// The types on the way from the query to the report are 64-bit: no count is cut to 32 bits.
static_assert(std::is_same_v<decltype(query_result_u64(0)), std::uint64_t>);
static_assert(std::is_same_v<decltype(PassMetrics::Stats::samples), std::uint64_t>);
static_assert(std::is_same_v<decltype(PassMeasurement::fragments), std::uint64_t>);
// No destructor throws (it was noexcept(false), and aborted inside std::optional's).
static_assert(std::is_nothrow_destructible_v<PassMetrics::Scope>);

TEST_F(MetricsGl, MeasureReportsEveryFrameItDrewAndItsFragments) {
  Empty target(40, 30);
  PassMetrics metrics;
  // No warm-up to wait for, three frames: each read back, 40 x 30 fragments in "fill" and
  // twice that in "twice" (two draws in one pass).
  Measurement m = measure(metrics, [&] {
    {
      auto p = metrics.pass("fill");
      fill();
    }
    auto p = metrics.pass("twice");
    fill();
    fill();
  }, {.frames = 3, .skip_warmup = true});
  EXPECT_EQ(m.frames, 3);
  ASSERT_EQ(m.passes.size(), 2u);
  EXPECT_EQ(m.pass("fill").frames, 3);
  EXPECT_EQ(m.pass("twice").frames, 3);
  EXPECT_EQ(m.pass("fill").fragments, 40u * 30u);
  EXPECT_EQ(m.pass("twice").fragments, 2u * 40u * 30u);
  EXPECT_GT(m.pass("fill").mean_ms, 0.0);
  EXPECT_LE(m.pass("fill").min_ms, m.pass("fill").mean_ms);
  EXPECT_EQ(m.warmup_frames, 0);
  EXPECT_THROW(m.pass("never drawn"), Error);
}

// The CPU time of a frame is what its callback took, each frame's own: frames that each
// stall 30 ms on the CPU (as a read-back waiting for the GPU would) report at least 30 ms,
// and no more than the whole measurement took per frame (so frames are not summed or counted
// from the start).
TEST_F(MetricsGl, CpuTimeIsEachFramesOwnAndShowsAStall) {
  Empty target(16, 16);
  PassMetrics metrics;
  const int frames = 3;
  const auto began = std::chrono::steady_clock::now();
  Measurement m = measure(metrics, [&] {
    {
      auto p = metrics.pass("fill");
      fill();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
  }, {.frames = frames, .skip_warmup = true});
  const double elapsed_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - began).count();
  EXPECT_GE(m.cpu_ms, 30.0);
  EXPECT_LE(m.cpu_ms * frames, elapsed_ms) << "the frames' CPU times overlap or count the measurement's own";
  // Without the stall the frames' CPU time loses those 30 ms each.
  Measurement quick = measure(metrics, [&] {
    auto p = metrics.pass("fill");
    fill();
  }, {.frames = frames, .skip_warmup = true});
  EXPECT_LT(quick.cpu_ms, m.cpu_ms);
}

TEST_F(MetricsGl, WarmupRunsAtLeastItsMinimumTimeAndTwoBlocks) {
  Empty target(16, 16);
  PassMetrics metrics;
  WarmupPolicy w{.block_frames = 2, .block_seconds = 0.0, .min_seconds = 0.05, .tolerance = 1e9, .max_seconds = 10};
  Measurement m = measure(metrics, [&] {
    auto p = metrics.pass("fill");
    fill();
  }, {.warmup = w, .frames = 2});
  // With any change accepted (tolerance 1e9) it settles at the first block after 0.05 s that
  // has a previous block: so at least two blocks of two frames.
  EXPECT_TRUE(m.settled);
  EXPECT_GE(m.warmup_seconds, 0.05);
  EXPECT_GE(m.warmup_frames, 4);
  EXPECT_EQ(m.warmup_frames % 2, 0) << "warm-up ends at the end of a block";
  EXPECT_EQ(m.frames, 2) << "the warm-up frames are not in the means";
}

TEST_F(MetricsGl, WarmupGivesUpAtItsCapAndSaysSo) {
  Empty target(16, 16);
  PassMetrics metrics;
  // A tolerance no two blocks can meet (< 0): it stops at max_seconds, not settled.
  WarmupPolicy w{.block_frames = 1, .block_seconds = 0.0, .min_seconds = 0.0, .tolerance = -1, .max_seconds = 0.2};
  Measurement m = measure(metrics, [&] {
    auto p = metrics.pass("fill");
    fill();
  }, {.warmup = w, .frames = 1});
  EXPECT_FALSE(m.settled);
  EXPECT_GE(m.warmup_seconds, 0.2);
  EXPECT_EQ(m.frames, 1);
}

// GL_SAMPLES_PASSED past 2^32 in one pass: 4 097 x 1024 x 1024 = 4 296 015 872 fragments
// (2^32 + 1 048 576), a count that a 32-bit read would wrap to 1 048 576 and a saturating
// 32-bit counter would report as 4 294 967 295. Exact only when the implementation's counter
// has more than 32 bits (llvmpipe's has 64; the test says what it found otherwise).
TEST_F(MetricsGl, SamplesPassedCountsPast32Bits) {
  const int bits = query_counter_bits(GL_SAMPLES_PASSED);
  if (bits <= 32) GTEST_SKIP() << "GL_SAMPLES_PASSED has " << bits << " bits here: it cannot count past 2^32";
  Empty target(1024, 1024);
  PassMetrics metrics;
  {
    auto p = metrics.pass("many");
    fill(4097);
  }
  metrics.end_frame();
  metrics.wait_all();
  const std::uint64_t expected = 4097ull * 1024ull * 1024ull;
  ASSERT_GT(expected, std::uint64_t(1) << 32);
  EXPECT_EQ(metrics.find("many")->samples, expected);
  EXPECT_FALSE(metrics.find("many")->samples_saturated);
}

// The case that aborted chapter 05: a Scope inside std::optional, whose destructor is
// noexcept, with an OpenGL error in the pass. Recorded, named, thrown by the loop instead.
TEST_F(MetricsGl, ErrorInAPassIsRecordedWithItsNameNotThrownFromTheDestructor) {
  Empty target(8, 8);
  PassMetrics metrics;
  {
    std::optional<PassMetrics::Scope> scope(metrics.pass("hdr: broken"));
    glEnable(GL_NONE);  // GL_INVALID_ENUM
  }
  EXPECT_EQ(metrics.error(), "OpenGL reported GL_INVALID_ENUM in pass 'hdr: broken'");
  EXPECT_THROW(metrics.throw_if_error(), Error);
  {
    auto p = metrics.pass("later");  // the first error is the one kept
    glBindBuffer(GL_NONE, 0);
  }
  EXPECT_EQ(metrics.error(), "OpenGL reported GL_INVALID_ENUM in pass 'hdr: broken'");
}

TEST_F(MetricsGl, ErrorWhileAnExceptionUnwindsThePassKeepsThatException) {
  Empty target(8, 8);
  PassMetrics metrics;
  try {
    auto p = metrics.pass("geometry");
    glEnable(GL_NONE);
    throw std::runtime_error("a shader did not compile");
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "a shader did not compile");
  }
  EXPECT_EQ(metrics.error(), "OpenGL reported GL_INVALID_ENUM in pass 'geometry'");
}

TEST_F(MetricsGl, ErrorBeforeAPassIsNotBlamedOnIt) {
  Empty target(8, 8);
  PassMetrics metrics;
  glEnable(GL_NONE);
  {
    auto p = metrics.pass("innocent");
    fill();
  }
  EXPECT_EQ(metrics.error(), "OpenGL reported GL_INVALID_ENUM before pass 'innocent'");
}

TEST_F(MetricsGl, MeasureStopsAtTheFirstErrorAndNamesThePass) {
  Empty target(8, 8);
  PassMetrics metrics;
  int frames = 0;
  try {
    measure(metrics, [&] {
      ++frames;
      auto p = metrics.pass("broken");
      glEnable(GL_NONE);
    }, {.frames = 5, .skip_warmup = true});
    FAIL() << "measure() returned";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "OpenGL reported GL_INVALID_ENUM in pass 'broken'");
  }
  EXPECT_EQ(frames, 1);
}

TEST_F(MetricsGl, ChaptersCountsAreReportedWithTheirPass) {
  Empty target(8, 8);
  PassMetrics metrics;
  Measurement m = measure(metrics, [&] {
    {
      auto p = metrics.pass("local lights");
      fill();
    }
    metrics.count("local lights", "shaded", 5'000'000'000ull);  // a 64-bit count
    metrics.count("local lights", "marked", 7);
  }, {.frames = 1, .skip_warmup = true});
  EXPECT_EQ(m.pass("local lights").count("shaded"), 5'000'000'000ull);
  EXPECT_EQ(m.pass("local lights").count("marked"), 7u);
  EXPECT_FALSE(m.pass("local lights").count("lit").has_value());
  EXPECT_THROW(metrics.count("no such pass", "shaded", 1), Error);
}

TEST(MetricsCsv, ColumnsNameTheRendererSizeAndFrames) {
  EXPECT_EQ(csv_measure_columns(), "renderer,width,height,frames");
  EXPECT_EQ(csv_measure_values("NVIDIA H200/PCIe/SSE2", 1920, 1080, 20), "NVIDIA H200/PCIe/SSE2,1920,1080,20");
  EXPECT_EQ(csv_measure_values("llvmpipe (LLVM 15.0.6, 256 bits)", 640, 360, 5),
            "\"llvmpipe (LLVM 15.0.6, 256 bits)\",640,360,5");
  EXPECT_EQ(csv_quoted("a \"b\", c"), "\"a \"\"b\"\", c\"");
}

}  // namespace
