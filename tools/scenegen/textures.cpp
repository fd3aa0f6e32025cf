#include "textures.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/glm.hpp>
#include <stb_image_write.h>

#include "rng.h"

namespace scenegen {

namespace {

uint8_t to_byte(float v) {
  return static_cast<uint8_t>(std::clamp(static_cast<int>(std::lround(v * 255.0f)), 0, 255));
}

float smoothstep(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

}  // namespace

Image make_checker(int size, int squares, const uint8_t dark[3], const uint8_t light[3]) {
  Image img{size, size, std::vector<uint8_t>(static_cast<size_t>(size) * size * 3)};
  const int cell = size / squares;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const uint8_t* c = ((x / cell + y / cell) % 2 == 0) ? light : dark;
      uint8_t* p = &img.rgb[(static_cast<size_t>(y) * size + x) * 3];
      p[0] = c[0];
      p[1] = c[1];
      p[2] = c[2];
    }
  return img;
}

void make_tiles(int size, int tiles, Image& albedo, Image& normal) {
  albedo = Image{size, size, std::vector<uint8_t>(static_cast<size_t>(size) * size * 3)};
  normal = albedo;
  const float cell = static_cast<float>(size) / static_cast<float>(tiles);
  const float grout = cell * 0.025f;  // half width of the grout line, in pixels
  const float bevel = cell * 0.06f;   // width of the rounded tile edge
  // Height at a continuous pixel position: 0 in the grout, 1 on the tile top.
  auto height = [&](float x, float y) {
    const float fx = std::fmod(x, cell), fy = std::fmod(y, cell);
    const float edge = std::min(std::min(fx, cell - fx), std::min(fy, cell - fy));
    return smoothstep(grout, grout + bevel, edge);
  };
  // Per-tile colour: a checker of two stones, each tile a little lighter or darker.
  Pcg32 rng(20240611u);
  std::vector<float> shade(static_cast<size_t>(tiles) * tiles);
  for (float& s : shade) s = rng.range(0.93f, 1.05f);
  const float stone[2][3] = {{0.86f, 0.82f, 0.74f}, {0.52f, 0.56f, 0.54f}};  // sRGB
  const float grout_col[3] = {0.36f, 0.34f, 0.32f};
  const float strength = 5.0f;  // height units per pixel -> steepness of the bevel
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float px = static_cast<float>(x) + 0.5f, py = static_cast<float>(y) + 0.5f;
      const int tx = std::min(tiles - 1, static_cast<int>(px / cell));
      const int ty = std::min(tiles - 1, static_cast<int>(py / cell));
      const float h = height(px, py);
      const float* base = stone[(tx + ty) % 2];
      const float s = shade[static_cast<size_t>(ty) * tiles + tx];
      uint8_t* a = &albedo.rgb[(static_cast<size_t>(y) * size + x) * 3];
      for (int c = 0; c < 3; ++c) a[c] = to_byte(grout_col[c] + (base[c] * s - grout_col[c]) * h);
      // Central differences; the texture repeats, so wrap the sample positions.
      auto hw = [&](float sx, float sy) {
        const float fs = static_cast<float>(size);
        return height(std::fmod(sx + fs, fs), std::fmod(sy + fs, fs));
      };
      const float dhdx = (hw(px + 1.0f, py) - hw(px - 1.0f, py)) * 0.5f;    // towards +u (right)
      const float dhdrow = (hw(px, py + 1.0f) - hw(px, py - 1.0f)) * 0.5f;  // towards +v (down)
      // Tangent-space normal of the height field: +Y is image up, i.e. against the row order.
      glm::vec3 n(-dhdx * strength, dhdrow * strength, 1.0f);
      const float len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
      uint8_t* q = &normal.rgb[(static_cast<size_t>(y) * size + x) * 3];
      q[0] = to_byte(n.x / len * 0.5f + 0.5f);
      q[1] = to_byte(n.y / len * 0.5f + 0.5f);
      q[2] = to_byte(n.z / len * 0.5f + 0.5f);
    }
}

void write_png(const std::filesystem::path& path, const Image& image) {
  if (!stbi_write_png(path.string().c_str(), image.width, image.height, 3, image.rgb.data(), image.width * 3))
    throw std::runtime_error("cannot write " + path.string());
}

}  // namespace scenegen
