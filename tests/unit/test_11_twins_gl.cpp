// Chapter 11's GLSL against its C++ twin (glsl_twin.h): disocclusion.glsl's test (disoccluded and
// depth_slack, as taa_resolve.frag and ao_accumulate.comp call them) against measure.h's
// disocclusion_mask, on motion targets made up here.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "chapters/11_temporal/measure.h"
#include "common/gl.h"
#include "common/image.h"
#include "tests/unit/glsl_twin.h"

namespace lp::ch11 {
namespace {

using test::TwinCase;
using test::ulps;

// An RGBA32F texture of an image whose rows run top first (ImageF's order), bottom row first as GL's.
gl::Texture upload(const ImageF& image) {
  gl::Texture t(GL_TEXTURE_2D);
  glTextureStorage2D(t.id(), 1, GL_RGBA32F, image.width, image.height);
  std::vector<float> rows(image.data.size());
  const std::size_t row = std::size_t(image.width) * 4;
  for (int y = 0; y < image.height; ++y)
    std::copy_n(image.data.begin() + std::ptrdiff_t(row * std::size_t(image.height - 1 - y)), row, rows.begin() + std::ptrdiff_t(row * std::size_t(y)));
  glTextureSubImage2D(t.id(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT, rows.data());
  return t;
}

TEST(GlslTwins, DisocclusionMatchesItsCppTwin) {
  // Two frames' motion targets, 128 x 96 (12 288 pixels): depths of a few tilted planes with
  // steps between them (edges, where the one-sided slope matters), the last frame's depths
  // those of the pixel's own surface, of a nearer one (hidden) or off by a random part of
  // twice the threshold (either side of it), and motions of up to 4 pixels, a twentieth of
  // them leaving the image. Each motion is a whole number of pixels plus 0.05 to 0.45 or 0.55
  // to 0.95, so uv then x size - 0.5 stays 0.05 pixels from a texel's edge and uv then x size
  // from a pixel's: both twins read the same four texels and agree on the image's bounds (the
  // GPU's division by the size is 2.5 ulp of a pixel index below 128: 1e-4 pixels).
  // The answers must be equal except where the exact margin (nearest depth minus threshold)
  // lies within both twins' rounding of it: each of |then - d|, tolerance x d, the slope's two
  // differences and their sum rounds by at most 0.5 ulp of its terms' size, and the pixel's
  // centre through the division, so 2 x 4 ulp of (nearest + threshold) bounds the difference.
  constexpr int kW = 128, kH = 96;
  constexpr float kTolerance = 0.05f, kSlope = 1.5f;
  test::TwinRandom r(111);
  ImageF now = ImageF::blank(kW, kH, 4), then = ImageF::blank(kW, kH, 4);
  const auto plane = [](int x, int y) {
    const int k = (x / 37 + y / 29) % 3;  // three surfaces, steps between them
    return 2.f + 3.f * float(k) + 0.013f * float(x) * float(k + 1) + 0.021f * float(y);
  };
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float d = plane(x, y);
      const auto part = [&] { return r.uniform(0.05f, 0.45f) + (r.uniform(0, 1) < 0.5f ? 0.5f : 0.f); };
      float mx = float(int(r.uniform(-4, 4))) + part(), my = float(int(r.uniform(-4, 4))) + part();
      if (r.uniform(0, 1) < 0.05f) mx += r.uniform(0, 1) < 0.5f ? -float(kW) : float(kW);
      now.at(x, y, 0) = mx / kW;
      now.at(x, y, 1) = my / kH;
      now.at(x, y, 2) = d;  // the depth then of this pixel's surface: its own, here
      now.at(x, y, 3) = d;
      const float choice = r.uniform(0, 1);
      then.at(x, y, 3) = choice < 0.3f ? d : choice < 0.5f ? 0.5f * d : d * (1.f + r.uniform(-2, 2) * kTolerance);
    }
  const gl::Texture motion = upload(now), previous = upload(then);
  std::vector<TwinCase> cases;
  for (int j = 0; j < kH; ++j)
    for (int i = 0; i < kW; ++i) cases.push_back({glm::vec4(i, j, 0, 0)});
  // As ao_accumulate.comp calls it: outside the last image, or disoccluded.
  const std::string helper =
      "float twin_hidden(vec4 a) { ivec2 p = ivec2(a.xy); ivec2 size = textureSize(u_motion, 0); vec4 own = texelFetch(u_motion, p, 0);"
      " vec2 uv_then = (vec2(p) + 0.5) / vec2(size) - own.xy;"
      " if (any(lessThan(uv_then, vec2(0.0))) || any(greaterThan(uv_then, vec2(1.0)))) return 1.0;"
      " return disoccluded(uv_then, own.z, depth_slack(p, size, own.z)) ? 1.0 : 0.0; }";
  glBindTextureUnit(2, motion.id());
  glBindTextureUnit(3, previous.id());
  const auto gpu = test::run_glsl_twin({{"11_temporal/shaders/disocclusion.glsl"}, "twin_hidden(a), 0.0, 0.0, 0.0", {}, helper,
                                        [&](unsigned program) {
                                          glProgramUniform1f(program, glGetUniformLocation(program, "u_depth_tolerance"), kTolerance);
                                          glProgramUniform1f(program, glGetUniformLocation(program, "u_depth_slope"), kSlope);
                                        }},
                                       cases);
  std::vector<float> margin;
  const std::vector<std::uint8_t> cpu = disocclusion_mask(now, then, kTolerance, kSlope, &margin);
  std::size_t failed = 0, in_band = 0, hidden = 0;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const int x = int(cases[k].a.x), y = kH - 1 - int(cases[k].a.y);
    const std::size_t at = std::size_t(y) * kW + std::size_t(x);
    hidden += cpu[at];
    if ((gpu[k].x > 0.5f) == (cpu[at] != 0)) continue;
    const float d = now.at(x, y, 2);
    // margin is (nearest - threshold) / d; nearest + threshold is below 2 threshold + |margin| d.
    const double threshold = kTolerance * d + kSlope * 2.0 * 0.05 * d;  // slack: the planes change < 5 % a pixel
    if (std::isfinite(margin[at]) && std::abs(double(margin[at]) * d) <= 2 * ulps(4) * (2 * threshold + std::abs(margin[at]) * d)) {
      ++in_band;
      continue;
    }
    if (failed++ < 5)
      ADD_FAILURE() << "pixel (" << x << ", " << y << "): GLSL " << gpu[k].x << ", C++ " << int(cpu[at]) << ", margin " << margin[at]
                    << ", motion " << test::str(glm::vec4(now.at(x, y, 0), now.at(x, y, 1), now.at(x, y, 2), now.at(x, y, 3)));
  }
  EXPECT_EQ(failed, 0u);
  EXPECT_GT(hidden, cases.size() / 10);  // both answers occur often
  EXPECT_LT(hidden, cases.size() * 9 / 10);
  std::printf("disocclusion: %zu pixels, %zu hidden, %zu differ within the rounding band\n", cases.size(), hidden, in_band);
}

// Catmull-Rom's per-axis weights at a fraction t of the way from texel 1 to texel 2 of four,
// expanded from the spline through four points with tangents (p2 - p0) / 2 and (p3 - p1) / 2.
std::array<double, 4> catmull_rom_weights(double t) {
  const double t2 = t * t, t3 = t2 * t;
  return {-0.5 * t3 + t2 - 0.5 * t, 1.5 * t3 - 2.5 * t2 + 1.0, -1.5 * t3 + 2.0 * t2 + 0.5 * t, 0.5 * t3 - 0.5 * t2};
}

TEST(GlslTwins, CatmullRomInNineReadsIsTheSixteenTapFilter) {
  // catmull_rom.glsl reads a 4 x 4 block of texels in 9 bilinear reads (the middle two weights
  // of each axis merged into one read between their texels); the filter it stands for reads
  // the 16 texels one by one. A 41 x 29 texture of random values in [0, 1] (RGBA32F: exact),
  // read at 10 000 random points (some beyond the edges: the sampler clamps, as the 16 taps'
  // indices do) and at every texel's centre and corner.
  // The tolerance: a bilinear read weighs its texels by fractions the texture unit rounds to
  // its sub-texel precision, 8 bits on the GPUs we know (llvmpipe's float path is exact); a
  // read's value then moves by at most 2^-8 (half a step per axis, texel values differing by
  // at most 1), and each read is weighed by its two axes' weights, so the filtered value moves
  // by at most 2^-8 (|w0| + |w12| + |w3|)_x (|w0| + |w12| + |w3|)_y; plus float rounding
  // of the weights (1e-5).
  constexpr int kW = 41, kH = 29;
  test::TwinRandom r(1211);
  ImageF texels = ImageF::blank(kW, kH, 4);
  for (float& v : texels.data) v = r.uniform(0, 1);
  gl::Texture texture = upload(texels);
  glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  std::vector<TwinCase> cases;
  for (int k = 0; k < 10000; ++k) cases.push_back({glm::vec4(r.uniform(-0.03f, 1.03f), r.uniform(-0.03f, 1.03f), 0, 0)});
  for (int j = 0; j <= 2 * kH; ++j)
    for (int i = 0; i <= 2 * kW; ++i) cases.push_back({glm::vec4(0.5f * float(i) / kW, 0.5f * float(j) / kH, 0, 0)});
  glBindTextureUnit(6, texture.id());
  const auto gpu = test::run_glsl_twin({{"11_temporal/shaders/catmull_rom.glsl"}, "catmull_rom(twin_texture, a.xy), 0.0", {},
                                        "layout(binding = 6) uniform sampler2D twin_texture;"},
                                       cases);
  // The 16 taps; the texture's rows run bottom first in GL (upload() flips them).
  const auto texel = [&](int x, int y, int c) {
    return double(texels.at(std::clamp(x, 0, kW - 1), kH - 1 - std::clamp(y, 0, kH - 1), c));
  };
  std::vector<glm::vec4> cpu;
  std::vector<double> bound;
  for (const TwinCase& c : cases) {
    const double px = double(c.a.x) * kW, py = double(c.a.y) * kH;
    const double x1 = std::floor(px - 0.5), y1 = std::floor(py - 0.5);
    const auto wx = catmull_rom_weights(px - x1 - 0.5), wy = catmull_rom_weights(py - y1 - 0.5);
    glm::vec4 v(0);
    for (int ch = 0; ch < 3; ++ch) {
      double sum = 0;
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) sum += wx[std::size_t(i)] * wy[std::size_t(j)] * texel(int(x1) - 1 + i, int(y1) - 1 + j, ch);
      v[ch] = float(std::max(sum, 0.0));
    }
    cpu.push_back(v);
    const auto spread = [](const std::array<double, 4>& w) { return std::abs(w[0]) + std::abs(w[1] + w[2]) + std::abs(w[3]); };
    bound.push_back(0x1p-8 * spread(wx) * spread(wy) + 1e-5);
  }
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 3, [&](std::size_t i) { return test::TwinTolerance{bound[i], 0}; },
                                [&](std::size_t i) { return "uv " + test::str(cases[i].a); }));
}

}  // namespace
}  // namespace lp::ch11
