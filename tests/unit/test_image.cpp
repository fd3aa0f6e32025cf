#include "common/image.h"

#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>

#include "common/error.h"

namespace fs = std::filesystem;

namespace {

lp::ImageRGBA8 noise_image(int width, int height, unsigned seed = 1) {
  lp::ImageRGBA8 image = lp::ImageRGBA8::blank(width, height);
  std::mt19937 rng(seed);
  for (auto& v : image.pixels) v = std::uint8_t(rng() & 0xff);
  return image;
}

lp::ImageRGBA8 grey_image(int width, int height, std::uint8_t value) {
  lp::ImageRGBA8 image = lp::ImageRGBA8::blank(width, height);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = i % 4 == 3 ? 255 : value;
  return image;
}

bool is_black(const std::uint8_t* px) { return px[0] == 0 && px[1] == 0 && px[2] == 0; }

// Runs `load` and checks it throws lp::Error naming `path` (and `detail`, if given).
template <class Load>
void expect_load_error(Load load, const fs::path& path, const std::string& detail = {}) {
  try {
    load(path);
    ADD_FAILURE() << "no lp::Error for " << path;
  } catch (const lp::Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(detail), std::string::npos) << message;
  }
}

// A fresh directory per test, removed afterwards.
class ImageFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("lightpass_image_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path file(const std::string& name) const { return dir_ / name; }

  fs::path write_bytes(const std::string& name, const std::string& bytes) const {
    fs::create_directories(dir_);
    std::ofstream(file(name), std::ios::binary) << bytes;
    return file(name);
  }

  fs::path dir_;
};

}  // namespace

// ---- compare ----------------------------------------------------------------------------

TEST(Compare, IdenticalImagesPassWithInfinitePsnr) {
  const auto image = noise_image(64, 48);
  const auto r = lp::compare(image, image);
  EXPECT_TRUE(r.passed);
  EXPECT_FALSE(r.size_mismatch);
  EXPECT_TRUE(std::isinf(r.psnr_db) && r.psnr_db > 0);
  EXPECT_EQ(r.mean_error, 0);
  EXPECT_EQ(r.p99_error, 0);
  EXPECT_EQ(r.max_error, 0);
  EXPECT_EQ(r.failing_pixels, 0u);
  EXPECT_EQ(r.failing_fraction, 0);
}

TEST(Compare, SinglePixelOverThresholdIsDetected) {
  const auto expected = grey_image(100, 100, 128);
  auto actual = expected;
  actual.at(37, 81)[1] += 10;

  const auto lenient = lp::compare(actual, expected);  // allows 0.1% of 10000 px = 10 px
  EXPECT_EQ(lenient.failing_pixels, 1u);
  EXPECT_DOUBLE_EQ(lenient.failing_fraction, 1e-4);
  EXPECT_EQ(lenient.max_error, 10);
  EXPECT_TRUE(lenient.passed);

  const auto strict = lp::compare(actual, expected, {.threshold = 3, .max_failing_fraction = 0});
  EXPECT_EQ(strict.failing_pixels, 1u);
  EXPECT_FALSE(strict.passed);
}

TEST(Compare, AllowedFractionIsInclusive) {
  const auto expected = grey_image(100, 100, 128);
  auto actual = expected;
  for (int x = 0; x < 10; ++x) actual.at(x, 0)[0] = 0;
  EXPECT_TRUE(lp::compare(actual, expected).passed);  // 10 of 10000 = exactly 0.1%
  actual.at(10, 0)[0] = 0;
  EXPECT_FALSE(lp::compare(actual, expected).passed);
}

TEST(Compare, ChangeWithinThresholdDoesNotFail) {
  const auto expected = grey_image(100, 100, 128);
  auto actual = expected;
  actual.at(5, 5)[2] -= 3;  // exactly the threshold: not more than it
  const auto r = lp::compare(actual, expected, {.threshold = 3, .max_failing_fraction = 0});
  EXPECT_EQ(r.failing_pixels, 0u);
  EXPECT_EQ(r.max_error, 3);
  EXPECT_TRUE(r.passed);
  EXPECT_TRUE(std::isfinite(r.psnr_db));
}

// An edge one pixel over (a dark half-plane whose boundary moved by a row) is excused with
// edge_radius 1, counted apart; a colour the expected image has nowhere near is not, nor is a
// row moved by two with radius 1.
TEST(Compare, AnEdgeMovedByOnePixelIsExcusedWithinTheRadiusAlone) {
  auto edge_at = [](int row) {
    auto image = grey_image(40, 40, 200);
    for (int y = row; y < 40; ++y)
      for (int x = 0; x < 40; ++x) image.at(x, y)[0] = image.at(x, y)[1] = image.at(x, y)[2] = 20;
    return image;
  };
  const auto expected = edge_at(20);
  const lp::CompareOptions strict{.threshold = 3, .max_failing_fraction = 0}, moved{.threshold = 3, .max_failing_fraction = 0, .edge_radius = 1};
  const auto plain = lp::compare(edge_at(19), expected, strict);
  EXPECT_EQ(plain.failing_pixels, 40u);
  const auto one = lp::compare(edge_at(19), expected, moved);
  EXPECT_EQ(one.failing_pixels, 0u);
  EXPECT_EQ(one.moved_edge_pixels, 40u);
  EXPECT_TRUE(one.passed);
  EXPECT_NE(one.summary().find("40 px excused as an edge moved by at most 1 px"), std::string::npos) << one.summary();
  const auto two = lp::compare(edge_at(18), expected, moved);
  EXPECT_EQ(two.failing_pixels, 40u) << "the row two pixels away from the edge is not a moved edge";
  EXPECT_EQ(two.moved_edge_pixels, 40u);
  auto foreign = expected;
  foreign.at(5, 5)[0] = 90;  // a colour found nowhere in the expected image
  const auto f = lp::compare(foreign, expected, moved);
  EXPECT_EQ(f.failing_pixels, 1u);
  EXPECT_EQ(f.moved_edge_pixels, 0u);
}

TEST(Compare, AlphaIsIgnored) {
  const auto expected = grey_image(8, 8, 50);
  auto actual = expected;
  actual.at(1, 1)[3] = 0;
  const auto r = lp::compare(actual, expected, {.threshold = 0, .max_failing_fraction = 0});
  EXPECT_TRUE(r.passed);
  EXPECT_TRUE(std::isinf(r.psnr_db));
}

TEST(Compare, SizeMismatchFailsWithoutCrashing) {
  const auto actual = grey_image(320, 180, 0);
  const auto expected = grey_image(640, 360, 0);
  const auto r = lp::compare(actual, expected);
  EXPECT_TRUE(r.size_mismatch);
  EXPECT_FALSE(r.passed);
  EXPECT_EQ(r.summary(), "size differs: 320x180 vs 640x360");

  const auto heat = lp::diff_heatmap(actual, expected);
  ASSERT_EQ(heat.width, 320);
  ASSERT_EQ(heat.height, 180);
  for (int y = 0; y < heat.height; ++y)
    for (int x = 0; x < heat.width; ++x) {
      const std::uint8_t* px = heat.at(x, y);
      ASSERT_TRUE(px[0] == 255 && px[1] == 0 && px[2] == 0) << x << "," << y;
    }
}

// Nearest rank: p99 of N values is the ceil(0.99 N)-th smallest; of 0..99 that is the
// 99th value, 98.
TEST(Compare, P99IsNearestRank) {
  const auto expected = grey_image(10, 10, 0);
  auto actual = expected;
  for (int i = 0; i < 100; ++i) actual.at(9 - i % 10, 9 - i / 10)[0] = std::uint8_t(i);  // scrambled placement
  const auto r = lp::compare(actual, expected);
  EXPECT_EQ(r.p99_error, 98);
  EXPECT_EQ(r.max_error, 99);
  EXPECT_DOUBLE_EQ(r.mean_error, 49.5);
}

TEST(Compare, PsnrOfOneStepEverywhere) {
  const auto expected = grey_image(16, 16, 100);
  const auto actual = grey_image(16, 16, 101);  // MSE 1 over RGB
  EXPECT_NEAR(lp::compare(actual, expected).psnr_db, 20 * std::log10(255.0), 1e-9);
}

TEST(Compare, SummaryLine) {
  const auto expected = grey_image(100, 100, 128);
  auto actual = expected;
  actual.at(0, 0)[0] += 4;  // MSE 16 / 30000: PSNR 10 log10(255^2 * 30000 / 16) = 80.86 dB
  EXPECT_EQ(lp::compare(actual, expected).summary(),
            "mean 0.00  p99 0  max 4  PSNR 80.9 dB  failing 0.010% (1 px) -> PASS (threshold 3, allowed 0.100%)");
}

TEST(Compare, MalformedBufferThrows) {
  auto bad = grey_image(4, 4, 0);
  bad.pixels.pop_back();
  EXPECT_THROW(lp::compare(bad, grey_image(4, 4, 0)), lp::Error);
}

// ---- heat maps --------------------------------------------------------------------------

TEST(Heatmap, BlackWhereEqualVisibleWhereChanged) {
  const auto expected = grey_image(20, 10, 128);
  auto actual = expected;
  actual.at(3, 4)[0] += 4;  // just over the threshold
  actual.at(7, 2)[1] += 1;  // within it
  actual.at(9, 9)[2] += 40;  // past full scale
  const auto heat = lp::diff_heatmap(actual, expected);
  ASSERT_EQ(heat.width, 20);
  ASSERT_EQ(heat.height, 10);
  EXPECT_TRUE(is_black(heat.at(0, 0)));
  EXPECT_TRUE(is_black(heat.at(19, 9)));
  EXPECT_EQ(heat.at(0, 0)[3], 255);
  EXPECT_FALSE(is_black(heat.at(3, 4)));
  EXPECT_EQ(heat.at(3, 4)[2], 255);  // failing pixels are at least full blue
  EXPECT_FALSE(is_black(heat.at(7, 2)));
  EXPECT_LT(heat.at(7, 2)[2], heat.at(3, 4)[2]);
  EXPECT_EQ(heat.at(9, 9)[0], 255);
  EXPECT_EQ(heat.at(9, 9)[1], 0);
  EXPECT_EQ(heat.at(9, 9)[2], 0);
}

TEST(Heatmap, ErrorHeatmapRamp) {
  const std::vector<float> error = {0.0f, 0.5f, 1.0f, 7.0f, std::numeric_limits<float>::quiet_NaN(), -1.0f};
  const auto heat = lp::error_heatmap(error, 3, 2, 1.0f);
  EXPECT_TRUE(is_black(heat.at(0, 0)));
  EXPECT_EQ(heat.at(1, 0)[1], 255);  // half scale: green
  EXPECT_EQ(heat.at(2, 0)[0], 255);  // full scale: red
  EXPECT_EQ(heat.at(2, 0)[1], 0);
  EXPECT_EQ(heat.at(0, 1)[0], 255);  // beyond full scale: red
  EXPECT_EQ(heat.at(1, 1)[0], 255);  // NaN: red, never hidden
  EXPECT_TRUE(is_black(heat.at(2, 1)));
  EXPECT_THROW(lp::error_heatmap(error, 4, 2, 1.0f), lp::Error);
  EXPECT_THROW(lp::error_heatmap(error, 3, 2, 0.0f), lp::Error);
}

// ---- float comparison -------------------------------------------------------------------

TEST(CompareFloat, StatsOverMask) {
  auto expected = lp::ImageF::blank(2, 2, 3);
  auto actual = expected;
  actual.at(0, 0, 0) = 0.3f;   // pixel error 0.1
  actual.at(1, 0, 1) = -0.6f;  // pixel error 0.2
  actual.at(0, 1, 2) = 0.9f;   // pixel error 0.3, masked out below
  actual.at(1, 1, 0) = 0.0f;   // pixel error 0

  const auto all = lp::compare_float(actual, expected);
  EXPECT_EQ(all.pixels, 4u);
  EXPECT_NEAR(all.mean_abs, 0.15, 1e-6);
  EXPECT_NEAR(all.max, 0.3, 1e-6);
  EXPECT_NEAR(all.p99, 0.3, 1e-6);
  EXPECT_NEAR(all.rmse, std::sqrt((0.01 + 0.04 + 0.09) / 4), 1e-6);

  const auto masked = lp::compare_float(actual, expected, {1, 1, 0, 1});
  EXPECT_EQ(masked.pixels, 3u);
  EXPECT_NEAR(masked.mean_abs, 0.1, 1e-6);
  EXPECT_NEAR(masked.max, 0.2, 1e-6);

  EXPECT_THROW(lp::compare_float(actual, expected, {1, 1}), lp::Error);
}

TEST(CompareFloat, AlphaChannelIsIgnoredAndMismatchesThrow) {
  auto rgba = lp::ImageF::blank(3, 2, 4);
  rgba.at(1, 1, 3) = 5.0f;
  const auto rgb = lp::ImageF::blank(3, 2, 3);
  EXPECT_EQ(lp::compare_float(rgba, rgb).max, 0);
  EXPECT_THROW(lp::compare_float(lp::ImageF::blank(3, 2, 1), rgb), lp::Error);
  EXPECT_THROW(lp::compare_float(lp::ImageF::blank(2, 3, 3), rgb), lp::Error);
}

TEST(CompareFloat, NanIsAnInfiniteError) {
  auto actual = lp::ImageF::blank(2, 1, 3);
  actual.at(1, 0, 2) = std::numeric_limits<float>::quiet_NaN();
  const auto stats = lp::compare_float(actual, lp::ImageF::blank(2, 1, 3));
  EXPECT_TRUE(std::isinf(stats.max));
}

// ---- sRGB -------------------------------------------------------------------------------

TEST(Srgb, KnownValues) {
  EXPECT_EQ(lp::linear_to_srgb(0.0f), 0.0f);
  EXPECT_NEAR(lp::linear_to_srgb(1.0f), 1.0f, 1e-7);
  EXPECT_NEAR(lp::linear_to_srgb(0.5f), 0.7354f, 1e-4);
  EXPECT_NEAR(lp::srgb_to_linear(0.5f), 0.2140f, 1e-4);
  EXPECT_NEAR(lp::linear_to_srgb(0.001f), 0.01292f, 1e-7);  // linear segment
}

TEST(Srgb, PiecesMeetAtTheBoundary) {
  const float edge = 0.0031308f;
  EXPECT_NEAR(lp::linear_to_srgb(edge), lp::linear_to_srgb(std::nextafter(edge, 1.0f)), 1e-5);
  EXPECT_NEAR(lp::linear_to_srgb(edge), 0.04045f, 1e-5);
  const float srgb_edge = 0.04045f;
  EXPECT_NEAR(lp::srgb_to_linear(srgb_edge), lp::srgb_to_linear(std::nextafter(srgb_edge, 1.0f)), 1e-6);
}

TEST(Srgb, RoundTrip) {
  for (int i = 0; i <= 10000; ++i) {
    const float linear = float(i) / 10000.0f;
    ASSERT_NEAR(lp::srgb_to_linear(lp::linear_to_srgb(linear)), linear, 1e-6) << linear;
    ASSERT_NEAR(lp::linear_to_srgb(lp::srgb_to_linear(linear)), linear, 1e-6) << linear;
  }
}

TEST(Srgb, ToSrgb8ClampsRoundsAndExpands) {
  auto rgb = lp::ImageF::blank(4, 1, 3);
  rgb.at(0, 0, 0) = -1.0f;
  rgb.at(1, 0, 0) = 2.0f;
  rgb.at(2, 0, 0) = 0.5f;
  rgb.at(3, 0, 0) = std::numeric_limits<float>::quiet_NaN();
  const auto out = lp::to_srgb8(rgb);
  EXPECT_EQ(out.at(0, 0)[0], 0);
  EXPECT_EQ(out.at(1, 0)[0], 255);
  EXPECT_EQ(out.at(2, 0)[0], 188);  // 0.7354 * 255 = 187.5
  EXPECT_EQ(out.at(3, 0)[0], 0);
  EXPECT_EQ(out.at(2, 0)[3], 255);

  auto grey = lp::ImageF::blank(1, 1, 1);
  grey.at(0, 0, 0) = 1.0f;
  const auto g = lp::to_srgb8(grey);
  EXPECT_EQ(g.at(0, 0)[0], 255);
  EXPECT_EQ(g.at(0, 0)[1], 255);
  EXPECT_EQ(g.at(0, 0)[2], 255);

  auto rgba = lp::ImageF::blank(1, 1, 4);
  rgba.at(0, 0, 3) = 0.5f;  // alpha stays linear
  EXPECT_EQ(lp::to_srgb8(rgba).at(0, 0)[3], 128);
}

// ---- files ------------------------------------------------------------------------------

TEST_F(ImageFiles, PngRoundTripIsExact) {
  const auto image = noise_image(37, 19);
  const auto path = file("nested/dirs/noise.png");  // save_png creates the directories
  lp::save_png(path, image);
  const auto loaded = lp::load_png(path);
  EXPECT_EQ(loaded.width, 37);
  EXPECT_EQ(loaded.height, 19);
  EXPECT_EQ(loaded.pixels, image.pixels);
}

TEST_F(ImageFiles, PngGreyAndRgbExpandToRgba) {
  fs::create_directories(dir_);
  const std::uint8_t grey[] = {0, 100, 200, 255};  // 2x2, top row first
  ASSERT_TRUE(stbi_write_png(file("grey.png").c_str(), 2, 2, 1, grey, 2));
  const auto g = lp::load_png(file("grey.png"));
  EXPECT_EQ(g.at(1, 0)[0], 100);
  EXPECT_EQ(g.at(1, 0)[2], 100);
  EXPECT_EQ(g.at(0, 1)[1], 200);
  EXPECT_EQ(g.at(0, 1)[3], 255);

  const std::uint8_t rgb[] = {1, 2, 3, 4, 5, 6};  // 2x1
  ASSERT_TRUE(stbi_write_png(file("rgb.png").c_str(), 2, 1, 3, rgb, 6));
  const auto c = lp::load_png(file("rgb.png"));
  const std::vector<std::uint8_t> expected = {1, 2, 3, 255, 4, 5, 6, 255};
  EXPECT_EQ(c.pixels, expected);
}

TEST_F(ImageFiles, PfmRoundTripIsExact) {
  auto image = lp::ImageF::blank(5, 3, 3);
  std::mt19937 rng(7);
  std::normal_distribution<float> dist(0.0f, 1000.0f);
  for (auto& v : image.data) v = dist(rng);
  image.at(0, 0, 0) = -0.0f;
  image.at(4, 2, 2) = std::numeric_limits<float>::denorm_min();
  image.at(2, 1, 1) = -std::numeric_limits<float>::infinity();
  lp::save_pfm(file("rgb.pfm"), image);
  const auto loaded = lp::load_pfm(file("rgb.pfm"));
  ASSERT_EQ(loaded.width, 5);
  ASSERT_EQ(loaded.height, 3);
  ASSERT_EQ(loaded.channels, 3);
  for (std::size_t i = 0; i < image.data.size(); ++i)
    EXPECT_EQ(std::bit_cast<std::uint32_t>(loaded.data[i]), std::bit_cast<std::uint32_t>(image.data[i])) << i;

  auto grey = lp::ImageF::blank(2, 4, 1);
  for (std::size_t i = 0; i < grey.data.size(); ++i) grey.data[i] = -1.5f * float(i);
  lp::save_pfm(file("grey.pfm"), grey);
  const auto grey_loaded = lp::load_pfm(file("grey.pfm"));
  EXPECT_EQ(grey_loaded.channels, 1);
  EXPECT_EQ(grey_loaded.data, grey.data);
}

TEST_F(ImageFiles, PfmWritesRgbOfRgba) {
  auto rgba = lp::ImageF::blank(2, 1, 4);
  for (std::size_t i = 0; i < rgba.data.size(); ++i) rgba.data[i] = float(i);
  lp::save_pfm(file("rgba.pfm"), rgba);
  const auto loaded = lp::load_pfm(file("rgba.pfm"));
  EXPECT_EQ(loaded.channels, 3);
  EXPECT_EQ(loaded.data, (std::vector<float>{0, 1, 2, 4, 5, 6}));
  EXPECT_THROW(lp::save_pfm(file("two.pfm"), lp::ImageF::blank(2, 1, 2)), lp::Error);
}

// A hand-made big-endian file: its first stored row is the bottom of the image.
TEST_F(ImageFiles, PfmBigEndianBottomUp) {
  auto be = [](float v) {
    const auto bits = std::bit_cast<std::uint32_t>(v);
    return std::string{char(bits >> 24), char(bits >> 16), char(bits >> 8), char(bits)};
  };
  const auto path = write_bytes("be.pfm", "Pf\n2 2\n1.0\n" + be(1) + be(2) + be(3) + be(-4));
  const auto image = lp::load_pfm(path);
  ASSERT_EQ(image.channels, 1);
  EXPECT_EQ(image.at(0, 0, 0), 3);
  EXPECT_EQ(image.at(1, 0, 0), -4);
  EXPECT_EQ(image.at(0, 1, 0), 1);
  EXPECT_EQ(image.at(1, 1, 0), 2);
}

TEST_F(ImageFiles, PfmOrientationSurvivesRoundTrip) {
  auto image = lp::ImageF::blank(3, 2, 1);
  image.at(0, 0, 0) = 42;  // top-left
  lp::save_pfm(file("corner.pfm"), image);
  EXPECT_EQ(lp::load_pfm(file("corner.pfm")).at(0, 0, 0), 42);

  // The file itself is bottom-up: 42 is the first value of the last stored row.
  std::ifstream in(file("corner.pfm"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  const auto header = std::string("Pf\n3 2\n-1.0\n").size();
  ASSERT_EQ(bytes.size(), header + 6 * 4);
  EXPECT_EQ(bytes.substr(header + 3 * 4, 4), std::string("\x00\x00\x28\x42", 4));
}

TEST_F(ImageFiles, HdrRoundTripWithinRgbePrecision) {
  auto image = lp::ImageF::blank(7, 4, 3);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> dist(0.001f, 50.0f);
  for (auto& v : image.data) v = dist(rng);
  image.at(6, 3, 0) = 0.0f;
  image.at(6, 3, 1) = 0.0f;
  image.at(6, 3, 2) = 0.0f;
  lp::save_hdr(file("noise.hdr"), image);
  const auto loaded = lp::load_hdr(file("noise.hdr"));
  ASSERT_EQ(loaded.width, 7);
  ASSERT_EQ(loaded.height, 4);
  ASSERT_EQ(loaded.channels, 3);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 7; ++x) {
      // RGBE shares one exponent per pixel: the error scales with the brightest channel.
      const float peak = std::max({image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)});
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(loaded.at(x, y, c), image.at(x, y, c), 0.01f * peak) << x << "," << y;
    }
  EXPECT_EQ(loaded.at(6, 3, 0), 0.0f);
}

TEST_F(ImageFiles, MissingFileErrorNamesThePath) {
  const auto path = file("does-not-exist.png");
  expect_load_error(lp::load_png, path, "file not found");
  expect_load_error(lp::load_pfm, file("does-not-exist.pfm"), "file not found");
  expect_load_error(lp::load_hdr, file("does-not-exist.hdr"), "file not found");
}

TEST_F(ImageFiles, GarbageFileThrows) {
  std::mt19937 rng(11);
  std::string garbage(1000, '\0');
  for (auto& c : garbage) c = char(rng() & 0xff);
  expect_load_error(lp::load_png, write_bytes("garbage.png", garbage), "not a PNG");
  expect_load_error(lp::load_pfm, write_bytes("garbage.pfm", garbage), "not a PFM");
  expect_load_error(lp::load_hdr, write_bytes("garbage.hdr", garbage), "not a Radiance HDR");

  // Right signatures, broken contents.
  expect_load_error(lp::load_png, write_bytes("bad.png", "\x89PNG\r\n\x1a\n" + garbage), "corrupt");
  expect_load_error(lp::load_pfm, write_bytes("short.pfm", "PF\n4 4\n-1.0\n" + garbage.substr(0, 100)),
                    "truncated");
  expect_load_error(lp::load_pfm, write_bytes("header.pfm", "PF\n4 x\n-1.0\n"), "width or height");
}

TEST_F(ImageFiles, WrongFormatThrows) {
  lp::save_png(file("real.png"), noise_image(4, 4));
  expect_load_error(lp::load_hdr, file("real.png"), "not a Radiance HDR");
  expect_load_error(lp::load_pfm, file("real.png"), "not a PFM");
  expect_load_error(lp::load_png, dir_, "not a regular file");
}

TEST_F(ImageFiles, SavingMalformedImagesThrows) {
  auto bad = noise_image(4, 4);
  bad.pixels.resize(10);
  EXPECT_THROW(lp::save_png(file("bad.png"), bad), lp::Error);
  EXPECT_THROW(lp::save_png(file("empty.png"), lp::ImageRGBA8{}), lp::Error);
  EXPECT_THROW(lp::save_hdr(file("empty.hdr"), lp::ImageF{}), lp::Error);
}

TEST(Flip, RowsSwap) {
  auto image = lp::ImageF::blank(2, 3, 1);
  image.data = {1, 2, 3, 4, 5, 6};
  lp::flip_vertically(image);
  EXPECT_EQ(image.data, (std::vector<float>{5, 6, 3, 4, 1, 2}));
  auto rgba = noise_image(3, 2);
  const auto original = rgba;
  lp::flip_vertically(rgba);
  EXPECT_EQ(rgba.at(2, 0)[1], original.at(2, 1)[1]);
  lp::flip_vertically(rgba);
  EXPECT_EQ(rgba.pixels, original.pixels);
}

// The key under a heat map: the picture unchanged above, the ramp from black to red below,
// and labels drawn (white text) under the bar.
TEST(HeatKey, AddsARampAndLabelsBelowThePicture) {
  lp::ImageRGBA8 heat = lp::ImageRGBA8::blank(320, 180);
  for (std::size_t i = 0; i < heat.pixels.size(); ++i) heat.pixels[i] = std::uint8_t(i * 7);
  const lp::ImageRGBA8 keyed = lp::with_heat_key(heat, {.full_scale = 32, .what = "steps", .threshold = 3});
  ASSERT_EQ(keyed.width, 320);
  ASSERT_GT(keyed.height, 180 + 20);
  EXPECT_TRUE(std::equal(heat.pixels.begin(), heat.pixels.end(), keyed.pixels.begin())) << "the picture changed";
  // The bar's ends: 0 is black, full scale red; just over the threshold, at least full blue.
  const int bar_y = 180 + 8;
  const std::uint8_t* left = keyed.at(6, bar_y);
  const std::uint8_t* right = keyed.at(320 - 7, bar_y);
  EXPECT_EQ(left[0] + left[1] + left[2], 0);
  EXPECT_EQ(right[0], 255);
  EXPECT_EQ(right[1], 0);
  const int over = 6 + int(3.5 / 32 * (320 - 7 - 6)) + 1;
  EXPECT_EQ(keyed.at(over, bar_y)[2], 255) << "failing differences start at full blue";
  int white = 0;
  for (int y = bar_y + 10; y < keyed.height; ++y)
    for (int x = 0; x < keyed.width; ++x) white += keyed.at(x, y)[0] == 255 && keyed.at(x, y)[1] == 255;
  EXPECT_GT(white, 20) << "no labels under the bar";
}

// The key a program draws into its own picture: over the bottom rows only, between the columns
// asked for, on the picture's own ramp (here chapter 03's, which ends white), with its labels.
TEST(HeatKey, DrawnOverTheBottomRowsOnThePicturesOwnRamp) {
  lp::ImageRGBA8 image = lp::ImageRGBA8::blank(320, 180);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = std::uint8_t(i * 7);
  const lp::ImageRGBA8 original = image;
  const lp::HeatKey key{.full_scale = 100, .what = "lights evaluated per pixel", .stops = {{0, 0, 0}, {0, 0.1f, 0.6f}, {1, 1, 1}}};
  const int rows = lp::draw_heat_key(image, key, 160);
  ASSERT_EQ(rows, lp::heat_key_rows(160));
  ASSERT_GT(rows, 10);
  ASSERT_LT(rows, 180 / 4) << "the key hides the picture";
  const int top = 180 - rows;
  EXPECT_TRUE(std::equal(original.pixels.begin(), original.pixels.begin() + std::ptrdiff_t(top) * 320 * 4, image.pixels.begin()))
      << "the picture above the key changed";
  for (int y = top; y < 180; ++y)
    EXPECT_TRUE(std::equal(original.at(0, y), original.at(160, y), image.at(0, y))) << "left of the key changed, row " << y;
  const int bar_y = top + 4;
  const std::uint8_t* left = image.at(160 + 3, bar_y);
  const std::uint8_t* middle = image.at(160 + 3 + (320 - 3 - 1 - 163) / 2, bar_y);
  const std::uint8_t* right = image.at(320 - 4, bar_y);
  EXPECT_EQ(left[0] + left[1] + left[2], 0);
  EXPECT_NEAR(middle[2], 0.6 * 255, 3) << "the middle stop, not error_heatmap's green";
  EXPECT_EQ(right[0] + right[1] + right[2], 3 * 255) << "the ramp's top is the stops' last, white";
  int white = 0;
  for (int y = bar_y + 7; y < 180; ++y)
    for (int x = 160; x < 320; ++x) white += image.at(x, y)[0] == 255 && image.at(x, y)[1] == 255;
  EXPECT_GT(white, 20) << "no labels under the bar";
}

// A picture that mixed the ramp in linear light (a shader into an sRGB target) gets a key
// mixed so too: half way from black to blue is linear 0.5, encoded 188, not 128.
TEST(HeatKey, MixedInLinearLightLikeItsPicture) {
  lp::ImageRGBA8 image = lp::ImageRGBA8::blank(400, 100);
  lp::draw_heat_key(image, {.full_scale = 1, .what = "", .mixed_in_linear = true});
  const int bar_y = 100 - lp::heat_key_rows(400) + 4, x0 = 3, x1 = 400 - 3;
  const int eighth = x0 + int(std::lround(0.125 * (x1 - 1 - x0)));  // half way to the first stop, blue
  EXPECT_NEAR(image.at(eighth, bar_y)[2], 188, 3);
  EXPECT_EQ(image.at(eighth, bar_y)[0], 0);
  lp::ImageRGBA8 plain = lp::ImageRGBA8::blank(400, 100);
  lp::draw_heat_key(plain, {.full_scale = 1, .what = ""});
  EXPECT_NEAR(plain.at(eighth, bar_y)[2], 128, 3);
}

// A label is text on a dark box: readable over a white picture, and nothing outside the box.
TEST(HeatKey, LabelIsTextOnADarkBox) {
  lp::ImageRGBA8 image = lp::ImageRGBA8::blank(320, 180);
  std::fill(image.pixels.begin(), image.pixels.end(), std::uint8_t(255));
  const int w = lp::draw_label(image, 10, 20, "slice 0");
  EXPECT_EQ(w, lp::text_width("slice 0") + 4);
  int dark = 0, white_inside = 0;
  for (int y = 20; y < 20 + 11; ++y)
    for (int x = 10; x < 10 + w; ++x) {
      dark += image.at(x, y)[0] < 50;
      white_inside += image.at(x, y)[0] == 255;
    }
  EXPECT_GT(dark, w * 11 / 2) << "no dark box";
  EXPECT_GT(white_inside, 10) << "no text on it";
  EXPECT_EQ(image.at(9, 20)[0], 255);
  EXPECT_EQ(image.at(10 + w, 20)[0], 255);
  EXPECT_EQ(image.at(10, 19)[0], 255);
}

TEST(HeatKey, TextIsDrawnAndClipped) {
  lp::ImageRGBA8 image = lp::ImageRGBA8::blank(20, 10);
  const std::uint8_t white[3] = {255, 255, 255};
  const int w = lp::draw_text(image, 15, 2, "0123", white);  // runs past the right edge
  EXPECT_GT(w, 15);
  int lit = 0;
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 20; ++x) lit += image.at(x, y)[0] == 255;
  EXPECT_GT(lit, 3);
  EXPECT_THROW(lp::with_heat_key(image, {.full_scale = 0}), lp::Error);
  EXPECT_THROW(lp::draw_heat_key(image, {.full_scale = 0}), lp::Error);
}

// stb_easy_font's own 'w' joins its middle stroke only in the bottom two rows, so at scale 1 a
// 'w' reads as a 'u' (chapter 02's "forward" caption read "foruard"). A 'w' reads as one when its
// middle stroke rises at least three of the five rows of the x-height, apart from the sides.
TEST(HeatKey, TheLetterWHasAMiddleStrokeAUDoesNot) {
  const std::uint8_t white[3] = {255, 255, 255};
  auto middle_rows = [&](const std::string& letter) {
    lp::ImageRGBA8 image = lp::ImageRGBA8::blank(16, 12);
    lp::draw_text(image, 0, 0, letter, white);
    int left = 16, right = -1;  // the glyph's columns
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 16; ++x)
        if (image.at(x, y)[0] == 255) left = std::min(left, x), right = std::max(right, x);
    const int middle = (left + right) / 2;
    int rows = 0;  // rows lit in the middle column with a dark pixel either side of it
    for (int y = 0; y < 12; ++y)
      rows += image.at(middle, y)[0] == 255 && image.at(middle - 1, y)[0] == 0 && image.at(middle + 1, y)[0] == 0;
    return rows;
  };
  EXPECT_GE(middle_rows("w"), 3) << "the 'w' reads as a 'u'";
  EXPECT_EQ(middle_rows("u"), 0);
  EXPECT_EQ(lp::text_width("forward"), lp::text_width("for") + lp::text_width("w") + lp::text_width("ard"));
}

// A legend: a dark box in the bottom-left corner with a swatch per entry; on a picture where the
// box would hide more than a quarter of it, nothing.
TEST(Legend, DrawnInTheCornerOrNotAtAllOnASmallPicture) {
  const std::vector<lp::LegendEntry> key = {{std::array<std::uint8_t, 3>{255, 0, 0}, "history dropped (off screen)"},
                                            {std::nullopt, "elsewhere: the image at a third"}};
  lp::ImageRGBA8 large = lp::ImageRGBA8::blank(320, 180);
  const lp::LegendPlace p = lp::draw_legend(large, key);
  EXPECT_EQ(p.x, 0);
  EXPECT_EQ(p.y + p.height, 180);
  EXPECT_GT(p.width, lp::text_width("elsewhere: the image at a third"));
  EXPECT_EQ(large.at(p.x + 1, p.y)[0], 24) << "no dark box";
  EXPECT_EQ(large.at(4, p.y + 4)[0], 255) << "no red swatch";
  EXPECT_EQ(large.at(4, p.y + 4)[1], 0);
  EXPECT_EQ(large.at(p.width, p.y)[3], 0) << "drawn outside its box";
  // Six short lines: each fits the width (about 90 of 160 pixels) and the height (58 of 90), but
  // the box would hide more than a quarter of the picture.
  lp::ImageRGBA8 small = lp::ImageRGBA8::blank(160, 90);
  const std::vector<lp::LegendEntry> longer(6, {std::array<std::uint8_t, 3>{255, 0, 0}, "history dropped"});
  ASSERT_LT(lp::text_width("history dropped") + 20, 160) << "the premise: the text fits the width";
  const lp::LegendPlace none = lp::draw_legend(small, longer);
  EXPECT_EQ(none.width * none.height, 0);
  EXPECT_TRUE(std::all_of(small.pixels.begin(), small.pixels.end(), [](std::uint8_t v) { return v == 0; }));
}

// Text that would run past the picture's edge: the entries' short texts where they have them,
// the box and every drawn pixel inside the picture; without short texts that fit, nothing.
TEST(Legend, TooWideATextSaysItsShortTextOrNothing) {
  const std::string wide = "a key text wider than a hundred and sixty pixels";
  ASSERT_GT(lp::text_width(wide) + 20, 160) << "the premise: it does not fit";
  auto drawn_right_of = [](const lp::ImageRGBA8& image, int x0) {
    for (int y = 0; y < image.height; ++y)
      for (int x = x0; x < image.width; ++x)
        if (image.at(x, y)[3] != 0) return true;
    return false;
  };
  lp::ImageRGBA8 small = lp::ImageRGBA8::blank(160, 90);
  const lp::LegendPlace p = lp::draw_legend(small, {{std::array<std::uint8_t, 3>{255, 0, 0}, wide, "short"}});
  ASSERT_GT(p.width * p.height, 0) << "the short text fits: drawn";
  EXPECT_LE(p.x + p.width, 160);
  EXPECT_LT(p.width, lp::text_width(wide)) << "the short text, not the long one";
  EXPECT_FALSE(drawn_right_of(small, p.x + p.width)) << "drawn outside its box";
  for (int y = p.y; y < p.y + p.height; ++y) ASSERT_EQ(small.at(p.x + p.width - 1, y)[0], 24) << "text at the box's edge, row " << y;
  lp::ImageRGBA8 large = lp::ImageRGBA8::blank(640, 360);
  EXPECT_GT(lp::draw_legend(large, {{std::nullopt, wide, "short"}}).width, lp::text_width(wide)) << "room: the long text";
  lp::ImageRGBA8 bare = lp::ImageRGBA8::blank(160, 90);
  EXPECT_EQ(lp::draw_legend(bare, {{std::nullopt, wide}}).width, 0) << "no short text: nothing rather than cut words";
  EXPECT_TRUE(std::all_of(bare.pixels.begin(), bare.pixels.end(), [](std::uint8_t v) { return v == 0; }));
}

// The direction key: a disc in the bottom-right corner whose points have the picture's colour of
// the vector from its centre (x right, y down; the rim at full scale), the rim's length written
// beside it (another scale, another number), and nothing else of the picture touched.
TEST(DirectionKey, TheDiscColoursEachOffsetAsThePictureDoesAndSaysItsScale) {
  lp::ImageRGBA8 image = lp::ImageRGBA8::blank(320, 180);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = std::uint8_t(i * 7);
  const lp::ImageRGBA8 original = image;
  // A colour that tells right from left and down from up, and the length: R right, G down, B length.
  auto colour = [](float x, float y) {
    return std::array<std::uint8_t, 3>{std::uint8_t(x > 0 ? 255 : 0), std::uint8_t(y > 0 ? 255 : 0),
                                       std::uint8_t(std::lround(std::min(std::hypot(x, y), 8.f) * 30))};
  };
  const lp::DirectionKeyPlace place = lp::draw_direction_key(image, {.full_scale = 8, .unit = "px/frame", .what = "motion", .colour = colour});
  ASSERT_GT(place.radius, 5);
  EXPECT_EQ(place.x + place.width, 320);
  EXPECT_EQ(place.y + place.height, 180);
  EXPECT_LT(place.width, 320 / 2) << "the key hides the picture";
  EXPECT_LT(place.height, 180 / 4) << "the key hides the picture";
  const int cx = place.centre_x, cy = place.centre_y, r = place.radius;
  ASSERT_GE(cx - r, place.x);
  ASSERT_GE(cy - r, place.y);
  // Right of the centre, half way out: moving right at half the full scale (4 units, B = 120).
  const std::uint8_t* right = image.at(cx + r / 2, cy);
  EXPECT_EQ(right[0], 255);
  EXPECT_EQ(right[1], 0);
  EXPECT_NEAR(right[2], 30.0 * (r / 2) * 8.0 / r, 1);
  // Below the centre (y down) on the rim: moving down at the full scale.
  const std::uint8_t* below = image.at(cx, cy + r);
  EXPECT_EQ(below[1], 255);
  EXPECT_EQ(below[0], 0);
  EXPECT_EQ(below[2], 240);
  const std::uint8_t* above_left = image.at(cx - r / 2, cy - r / 2);
  EXPECT_EQ(above_left[0] + above_left[1], 0) << "up and left";
  // The text: white pixels left of the disc, and another scale writes another number.
  int white = 0;
  for (int y = place.y; y < 180; ++y)
    for (int x = place.x; x < cx - r - 2; ++x) white += image.at(x, y)[0] == 255 && image.at(x, y)[1] == 255 && image.at(x, y)[2] == 255;
  EXPECT_GT(white, 20) << "no rim length written";
  lp::ImageRGBA8 other = original;  // a number as wide: the same box, another digit in it
  const lp::DirectionKeyPlace other_place = lp::draw_direction_key(other, {.full_scale = 4, .unit = "px/frame", .what = "motion", .colour = colour});
  ASSERT_EQ(other_place.x, place.x);
  int differ = 0;
  for (int y = place.y; y < 180; ++y)
    for (int x = place.x; x < cx - r - 2; ++x) differ += other.at(x, y)[0] != image.at(x, y)[0];
  EXPECT_GT(differ, 5) << "the rim's length is not written: " << differ << " pixels differ";
  // Outside the box the picture is as it was.
  EXPECT_TRUE(std::equal(original.pixels.begin(), original.pixels.begin() + std::ptrdiff_t(place.y) * 320 * 4, image.pixels.begin()));
  for (int y = place.y; y < 180; ++y)
    EXPECT_TRUE(std::equal(original.at(0, y), original.at(place.x, y), image.at(0, y))) << "left of the key changed, row " << y;
}

// A picture smaller than the key gets what fits; a key without a scale or colours is refused.
TEST(DirectionKey, ClippedToASmallPictureAndRefusedWithoutAScale) {
  lp::ImageRGBA8 small = lp::ImageRGBA8::blank(16, 8);
  auto red = [](float, float) { return std::array<std::uint8_t, 3>{255, 0, 0}; };
  const lp::DirectionKeyPlace place = lp::draw_direction_key(small, {.full_scale = 8, .what = "motion", .colour = red});
  EXPECT_LT(place.x, 0);
  EXPECT_EQ(small.at(15, 7)[3], 255) << "the corner was not drawn";
  EXPECT_THROW(lp::draw_direction_key(small, {.full_scale = 0, .colour = red}), lp::Error);
  EXPECT_THROW(lp::draw_direction_key(small, {.full_scale = std::numeric_limits<float>::infinity(), .colour = red}), lp::Error);
  EXPECT_THROW(lp::draw_direction_key(small, {.full_scale = 8}), lp::Error);
}
