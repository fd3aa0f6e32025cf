#include "chapters/11_temporal/motion_picture.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.h"

namespace lp::ch11 {

std::array<std::uint8_t, 3> motion_colour(float dx, float dy, float full_scale) {
  const float len = std::min(std::sqrt(dx * dx + dy * dy) / full_scale, 1.f);
  const float a = std::atan2(dy, dx);
  std::array<std::uint8_t, 3> rgb{};
  for (int c = 0; c < 3; ++c) {
    const float hue = 0.5f + 0.5f * std::cos(a - float(c) * 2.0944f);  // three cosines a third apart
    rgb[std::size_t(c)] = std::uint8_t(std::lround(255.f * linear_to_srgb(len * hue)));
  }
  return rgb;
}

ImageRGBA8 motion_picture(const std::vector<float>& motion, int width, int height, float full_scale) {
  if (width <= 0 || height <= 0 || motion.size() / 4 / std::size_t(width) != std::size_t(height) ||
      motion.size() != std::size_t(width) * std::size_t(height) * 4)
    throw Error("motion_picture: " + std::to_string(motion.size()) + " floats for a " + std::to_string(width) + "x" +
                std::to_string(height) + " RGBA target");
  ImageRGBA8 out = ImageRGBA8::blank(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float* v = &motion[(std::size_t(height - 1 - y) * std::size_t(width) + std::size_t(x)) * 4];  // GL rows bottom first
      const std::array<std::uint8_t, 3> c = motion_colour(v[0] * float(width), v[1] * float(height), full_scale);
      std::uint8_t* p = out.at(x, y);
      p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
    }
  return out;
}

DirectionKey motion_key(float full_scale) {
  // The key's vectors point down the picture where GL's point up.
  return {.full_scale = full_scale, .unit = "px/frame", .what = "moving this way",
          .colour = [full_scale](float x, float y) { return motion_colour(x, -y, full_scale); }};
}

std::vector<LegendEntry> rejected_key() {
  return {{std::array<std::uint8_t, 3>{255, 0, 0}, "history dropped (off screen or disoccluded)", "history dropped"},
          {std::nullopt, "elsewhere: the image at a third", "the rest: a third"}};
}

}  // namespace lp::ch11
