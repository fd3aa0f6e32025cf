// Procedural textures for scenegen, written as 8-bit RGB PNG files with stb_image_write
// (deterministic: stb's own deflate, no timestamps or text chunks).
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace scenegen {

struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // width * height * 3, rows top to bottom
};

// Checkerboard of `squares` x `squares` cells; colours are 8-bit sRGB.
Image make_checker(int size, int squares, const uint8_t dark[3], const uint8_t light[3]);

// Square floor tiles: `tiles` x `tiles` tiles separated by recessed grout lines. The albedo
// (sRGB) alternates two stone colours with a small per-tile variation; the normal map is the
// matching tangent-space normal map (RGB = n * 0.5 + 0.5, +X right, +Y up in the image, i.e.
// the glTF / OpenGL convention) of the bevelled tile height field.
void make_tiles(int size, int tiles, Image& albedo, Image& normal);

void write_png(const std::filesystem::path& path, const Image& image);

}  // namespace scenegen
