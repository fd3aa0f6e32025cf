#include "chapters/05_hdr/reference.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "chapters/05_hdr/hdr_math.h"
#include "common/error.h"

namespace lp::ch05 {

namespace {
glm::vec3 pixel(const ImageF& image, int x, int y) {
  return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
}
}  // namespace

// [exact-log-average-impl]
ExactLogAverage exact_log_average(const ImageF& radiance, float delta) {
  if (radiance.channels < 3) throw Error("exact_log_average needs an RGB or RGBA image");
  ExactLogAverage r;
  double sum = 0;
  for (int y = 0; y < radiance.height; ++y)
    for (int x = 0; x < radiance.width; ++x) {
      Sanitized s = sanitize(pixel(radiance, x, y));
      if (!s.valid) continue;
      double l = 0.2126 * s.rgb.r + 0.7152 * s.rgb.g + 0.0722 * s.rgb.b;
      sum += std::log(double(delta) + l);
      ++r.count;
    }
  r.mean_log = r.count ? sum / double(r.count) : 0.0;
  r.luminance = std::exp(r.mean_log);
  return r;
}
// [/exact-log-average-impl]

std::size_t naive_chain_pixels(int width, int height) {
  auto largest_power_of_two = [](int n) {
    std::size_t p = 1;
    while (p * 2 <= std::size_t(n)) p *= 2;
    return p;
  };
  return largest_power_of_two(width) * largest_power_of_two(height);
}

ImageF reference_bloom(const ImageF& radiance, float exposure, float threshold, float limit, float sigma_px) {
  const int w = radiance.width, h = radiance.height;
  std::vector<double> bright(std::size_t(w) * h * 3), tmp(bright.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::vec3 b = bright_pass(sanitize(pixel(radiance, x, y)).rgb * exposure, threshold, limit);
      for (int c = 0; c < 3; ++c) bright[(std::size_t(y) * w + x) * 3 + c] = b[c];
    }
  int r = sigma_px > 0.01f ? int(std::ceil(3.0 * sigma_px)) : 0;
  std::vector<double> weight(r + 1);
  double total = 0;
  for (int i = -r; i <= r; ++i) total += std::exp(-double(i) * i / (2.0 * sigma_px * sigma_px + 1e-30));
  for (int i = 0; i <= r; ++i) weight[i] = std::exp(-double(i) * i / (2.0 * sigma_px * sigma_px + 1e-30)) / total;
  auto blur = [&](const std::vector<double>& in, std::vector<double>& out, bool horizontal) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) {
          double acc = 0;
          for (int i = -r; i <= r; ++i) {
            int sx = horizontal ? std::clamp(x + i, 0, w - 1) : x;
            int sy = horizontal ? y : std::clamp(y + i, 0, h - 1);
            acc += weight[std::abs(i)] * in[(std::size_t(sy) * w + sx) * 3 + c];
          }
          out[(std::size_t(y) * w + x) * 3 + c] = acc;
        }
  };
  blur(bright, tmp, true);
  blur(tmp, bright, false);
  ImageF out = ImageF::blank(w, h, 3);
  for (std::size_t i = 0; i < bright.size(); ++i) out.data[i] = float(bright[i]);
  return out;
}

ImageF constant_image(int w, int h, glm::vec3 c) {
  ImageF img = ImageF::blank(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < 3; ++k) img.at(x, y, k) = c[k];
  return img;
}

ImageF ramp_image(int w, int h) {
  ImageF img = ImageF::blank(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float v = std::pow(10.f, -3.f + 6.f * float(x) / float(std::max(1, w - 1))) * (1.f + float(h - 1 - y) / float(h));
      img.at(x, y, 0) = v;
      img.at(x, y, 1) = 0.8f * v;
      img.at(x, y, 2) = 0.6f * v;
    }
  return img;
}

}  // namespace lp::ch05
