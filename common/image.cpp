#include "common/image.h"

#include <stb_easy_font.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <string_view>

#include "common/error.h"

namespace lp {
namespace fs = std::filesystem;

namespace {

std::string dims(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

[[noreturn]] void fail(std::string_view verb, std::string_view kind, const fs::path& path,
                       const std::string& why) {
  throw Error("cannot " + std::string(verb) + " " + std::string(kind) + " '" + path.string() + "': " + why);
}

// The buffer-size checks every entry point makes first, so a malformed image becomes an
// lp::Error instead of an out-of-bounds read.
std::string problem(int width, int height, int channels, std::size_t buffer_size) {
  if (width < 0 || height < 0) return "negative size " + dims(width, height);
  if (channels < 1 || channels > 4) return "unsupported channel count " + std::to_string(channels);
  const std::size_t needed = std::size_t(width) * std::size_t(height) * std::size_t(channels);
  if (buffer_size != needed)
    return "buffer holds " + std::to_string(buffer_size) + " values, " + dims(width, height) + "x" +
           std::to_string(channels) + " needs " + std::to_string(needed);
  return {};
}

void require_valid(const ImageRGBA8& image, const std::string& context) {
  if (auto p = problem(image.width, image.height, 4, image.pixels.size()); !p.empty())
    throw Error(context + ": " + p);
}

void require_valid(const ImageF& image, const std::string& context) {
  if (auto p = problem(image.width, image.height, image.channels, image.data.size()); !p.empty())
    throw Error(context + ": " + p);
}

std::vector<unsigned char> read_file(const fs::path& path, std::string_view kind) {
  std::error_code ec;
  if (!fs::exists(path, ec)) fail("read", kind, path, "file not found");
  if (!fs::is_regular_file(path, ec)) fail("read", kind, path, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  const auto size = fs::file_size(path, ec);
  if (ec) fail("read", kind, path, ec.message());
  if (!in) fail("read", kind, path, std::strerror(errno));
  std::vector<unsigned char> bytes(size);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
    fail("read", kind, path, "read error");
  // stb_image takes an int length.
  if (bytes.size() > std::size_t(std::numeric_limits<int>::max())) fail("read", kind, path, "file too large");
  return bytes;
}

void write_file(const fs::path& path, std::string_view kind, const std::vector<unsigned char>& bytes) {
  if (path.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) fail("write", kind, path, "cannot create directory: " + ec.message());
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) fail("write", kind, path, std::strerror(errno));
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  out.close();
  if (!out) fail("write", kind, path, "write error");
}

// stb's writers report to a callback; collecting into memory lets write_file give
// the same error messages for every format.
void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<unsigned char>*>(context);
  const auto* begin = static_cast<const unsigned char*>(data);
  out->insert(out->end(), begin, begin + size);
}

std::string stb_reason() {
  const char* reason = stbi_failure_reason();
  return reason ? reason : "unknown error";
}

struct StbFree {
  void operator()(void* p) const { stbi_image_free(p); }
};

template <class T>
void flip_rows(std::vector<T>& data, int height, std::size_t row_length) {
  for (int y = 0; y < height / 2; ++y) {
    auto top = data.begin() + std::ptrdiff_t(std::size_t(y) * row_length);
    auto bottom = data.begin() + std::ptrdiff_t(std::size_t(height - 1 - y) * row_length);
    std::swap_ranges(top, top + std::ptrdiff_t(row_length), bottom);
  }
}

template <class T>
bool parse(std::string_view text, T& value) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size() && !text.empty();
}

bool is_space(unsigned char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Nearest rank: the ceil(percent/100 * N)-th smallest value. Integer arithmetic keeps
// the rank exact; taking the values by copy leaves the caller's order alone.
template <class T>
T nearest_rank(std::vector<T> values, int percent) {
  if (values.empty()) return T{};
  const std::size_t rank = std::max<std::size_t>((values.size() * std::size_t(percent) + 99) / 100, 1);
  const auto nth = values.begin() + std::ptrdiff_t(rank - 1);
  std::nth_element(values.begin(), nth, values.end());
  return *nth;
}

std::uint8_t to_unorm8(float v) {
  if (!(v > 0.0f)) return 0;  // also NaN
  if (v >= 1.0f) return 255;
  return std::uint8_t(std::lround(v * 255.0f));
}

int max_channel_diff(const std::uint8_t* a, const std::uint8_t* b) {
  int diff = 0;
  for (int c = 0; c < 3; ++c) diff = std::max(diff, std::abs(int(a[c]) - int(b[c])));
  return diff;
}

// Black, blue, green, yellow, red at t = 0, 1/4, 1/2, 3/4, 1.
void ramp(float t, std::uint8_t* rgba) {
  static constexpr std::array<std::array<float, 3>, 5> stops{
      {{0, 0, 0}, {0, 0, 255}, {0, 255, 0}, {255, 255, 0}, {255, 0, 0}}};
  const float s = std::clamp(t, 0.0f, 1.0f) * 4.0f;
  const int i = std::min(int(s), 3);
  const float f = s - float(i);
  for (int c = 0; c < 3; ++c)
    rgba[c] = std::uint8_t(std::lround(stops[i][c] + (stops[i + 1][c] - stops[i][c]) * f));
  rgba[3] = 255;
}

// Where failing pixels start on the ramp (full blue), so none of them looks black.
constexpr float kFailingRampMin = 0.25f;

int colour_channels(int channels) { return channels >= 3 ? 3 : 1; }

}  // namespace

// ---- images ---------------------------------------------------------------------------

ImageRGBA8 ImageRGBA8::blank(int width, int height) {
  if (width < 0 || height < 0) throw Error("ImageRGBA8::blank: negative size " + dims(width, height));
  return {width, height, std::vector<std::uint8_t>(std::size_t(width) * std::size_t(height) * 4)};
}

std::uint8_t* ImageRGBA8::at(int x, int y) {
  assert(x >= 0 && x < width && y >= 0 && y < height);
  return pixels.data() + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4;
}

const std::uint8_t* ImageRGBA8::at(int x, int y) const {
  return const_cast<ImageRGBA8*>(this)->at(x, y);
}

ImageF ImageF::blank(int width, int height, int channels) {
  if (width < 0 || height < 0 || channels < 1 || channels > 4)
    throw Error("ImageF::blank: bad size " + dims(width, height) + "x" + std::to_string(channels));
  return {width, height, channels,
          std::vector<float>(std::size_t(width) * std::size_t(height) * std::size_t(channels))};
}

float& ImageF::at(int x, int y, int c) {
  assert(x >= 0 && x < width && y >= 0 && y < height && c >= 0 && c < channels);
  return data[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * std::size_t(channels) + std::size_t(c)];
}

float ImageF::at(int x, int y, int c) const { return const_cast<ImageF*>(this)->at(x, y, c); }

void flip_vertically(ImageRGBA8& image) {
  require_valid(image, "flip_vertically");
  flip_rows(image.pixels, image.height, std::size_t(image.width) * 4);
}

void flip_vertically(ImageF& image) {
  require_valid(image, "flip_vertically");
  flip_rows(image.data, image.height, std::size_t(image.width) * std::size_t(image.channels));
}

// ---- PNG ------------------------------------------------------------------------------

ImageRGBA8 load_png(const fs::path& path) {
  const auto bytes = read_file(path, "PNG");
  static constexpr unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  // stb_image would also accept JPEG, BMP, ...; a .png that is not one is a mistake.
  if (bytes.size() < 8 || !std::equal(signature, signature + 8, bytes.begin()))
    fail("read", "PNG", path, "not a PNG file");
  int width = 0, height = 0, channels_in_file = 0;
  std::unique_ptr<stbi_uc, StbFree> pixels(
      stbi_load_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels_in_file, 4));
  if (!pixels) fail("read", "PNG", path, "corrupt or unsupported PNG (" + stb_reason() + ")");
  ImageRGBA8 image = ImageRGBA8::blank(width, height);
  std::copy_n(pixels.get(), image.pixels.size(), image.pixels.begin());
  return image;
}

void save_png(const fs::path& path, const ImageRGBA8& image) {
  require_valid(image, "cannot write PNG '" + path.string() + "'");
  if (image.width == 0 || image.height == 0) fail("write", "PNG", path, "image is empty");
  std::vector<unsigned char> bytes;
  if (!stbi_write_png_to_func(append_bytes, &bytes, image.width, image.height, 4, image.pixels.data(),
                              image.width * 4))
    fail("write", "PNG", path, "PNG encoding failed");
  write_file(path, "PNG", bytes);
}

fs::path numbered_path(const fs::path& base) {
  for (int n = 1; n <= 9999; ++n) {
    char suffix[8];
    std::snprintf(suffix, sizeof suffix, "-%03d", n);
    fs::path candidate = base.parent_path() / (base.stem().string() + suffix + base.extension().string());
    std::error_code ec;
    const bool taken = fs::exists(candidate, ec);
    if (ec) throw Error("cannot look at '" + candidate.string() + "': " + ec.message());
    if (!taken) return candidate;
  }
  throw Error("no free numbered name for '" + base.string() + "': -001 to -9999 all exist; move some away");
}

// ---- PFM ------------------------------------------------------------------------------

ImageF load_pfm(const fs::path& path) {
  const auto bytes = read_file(path, "PFM");
  std::size_t pos = 0;
  auto token = [&]() -> std::string_view {
    while (pos < bytes.size() && is_space(bytes[pos])) ++pos;
    const std::size_t start = pos;
    while (pos < bytes.size() && !is_space(bytes[pos])) ++pos;
    return {reinterpret_cast<const char*>(bytes.data()) + start, pos - start};
  };

  const std::string_view magic = token();
  const int channels = magic == "PF" ? 3 : magic == "Pf" ? 1 : 0;
  if (channels == 0) fail("read", "PFM", path, "not a PFM file (no 'PF' or 'Pf' header)");
  int width = 0, height = 0;
  if (!parse(token(), width) || !parse(token(), height) || width <= 0 || height <= 0)
    fail("read", "PFM", path, "bad width or height in header");
  float scale = 0;
  if (!parse(token(), scale) || !std::isfinite(scale) || scale == 0)
    fail("read", "PFM", path, "bad scale in header");
  ++pos;  // exactly one whitespace byte separates the header from the data

  const std::size_t row_values = std::size_t(width) * std::size_t(channels);
  const std::size_t available = pos < bytes.size() ? (bytes.size() - pos) / 4 : 0;
  if (available / row_values < std::size_t(height))
    fail("read", "PFM", path, "truncated: header says " + dims(width, height) + " but the data ends early");

  const bool little_endian = scale < 0;
  ImageF image = ImageF::blank(width, height, channels);
  const unsigned char* src = bytes.data() + pos;
  for (int row = 0; row < height; ++row) {
    float* dst = image.data.data() + std::size_t(height - 1 - row) * row_values;  // PFM is bottom-up
    for (std::size_t i = 0; i < row_values; ++i, src += 4) {
      const std::uint32_t bits =
          little_endian ? std::uint32_t(src[0]) | std::uint32_t(src[1]) << 8 | std::uint32_t(src[2]) << 16 |
                              std::uint32_t(src[3]) << 24
                        : std::uint32_t(src[3]) | std::uint32_t(src[2]) << 8 | std::uint32_t(src[1]) << 16 |
                              std::uint32_t(src[0]) << 24;
      dst[i] = std::bit_cast<float>(bits);
    }
  }
  return image;
}

void save_pfm(const fs::path& path, const ImageF& image) {
  require_valid(image, "cannot write PFM '" + path.string() + "'");
  if (image.width == 0 || image.height == 0) fail("write", "PFM", path, "image is empty");
  if (image.channels == 2) fail("write", "PFM", path, "PFM holds 1 or 3 channels, the image has 2");
  const int channels = image.channels == 1 ? 1 : 3;

  const std::string header = std::string(channels == 1 ? "Pf" : "PF") + "\n" + std::to_string(image.width) +
                             " " + std::to_string(image.height) + "\n-1.0\n";
  std::vector<unsigned char> bytes(header.begin(), header.end());
  bytes.reserve(header.size() + std::size_t(image.width) * std::size_t(image.height) * std::size_t(channels) * 4);
  for (int y = image.height - 1; y >= 0; --y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < channels; ++c) {
        const auto bits = std::bit_cast<std::uint32_t>(image.at(x, y, c));
        for (int shift = 0; shift < 32; shift += 8) bytes.push_back(std::uint8_t(bits >> shift));
      }
  write_file(path, "PFM", bytes);
}

// ---- Radiance HDR ---------------------------------------------------------------------

ImageF load_hdr(const fs::path& path) {
  const auto bytes = read_file(path, "HDR");
  // stbi_loadf would also load a PNG, silently linearised with gamma 2.2.
  if (!stbi_is_hdr_from_memory(bytes.data(), int(bytes.size())))
    fail("read", "HDR", path, "not a Radiance HDR file");
  int width = 0, height = 0, channels_in_file = 0;
  std::unique_ptr<float, StbFree> data(
      stbi_loadf_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels_in_file, 3));
  if (!data) fail("read", "HDR", path, "corrupt or unsupported HDR (" + stb_reason() + ")");
  ImageF image = ImageF::blank(width, height, 3);
  std::copy_n(data.get(), image.data.size(), image.data.begin());
  return image;
}

void save_hdr(const fs::path& path, const ImageF& image) {
  require_valid(image, "cannot write HDR '" + path.string() + "'");
  if (image.width == 0 || image.height == 0) fail("write", "HDR", path, "image is empty");
  // RGBE has no sign bit: stb would wrap a negative channel into a bright one.
  std::vector<float> clamped(image.data.size());
  std::transform(image.data.begin(), image.data.end(), clamped.begin(),
                 [](float v) { return v > 0.0f ? std::min(v, std::numeric_limits<float>::max()) : 0.0f; });
  std::vector<unsigned char> bytes;
  if (!stbi_write_hdr_to_func(append_bytes, &bytes, image.width, image.height, image.channels, clamped.data()))
    fail("write", "HDR", path, "HDR encoding failed");
  write_file(path, "HDR", bytes);
}

// ---- sRGB -----------------------------------------------------------------------------

// Double precision keeps a decode/encode round trip within float rounding.
float srgb_to_linear(float srgb) {
  const double s = srgb;
  return float(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4));
}

float linear_to_srgb(float linear) {
  const double l = linear;
  return float(l <= 0.0031308 ? l * 12.92 : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055);
}

ImageRGBA8 to_srgb8(const ImageF& linear) {
  require_valid(linear, "to_srgb8");
  ImageRGBA8 out = ImageRGBA8::blank(linear.width, linear.height);
  const int colours = colour_channels(linear.channels);
  const bool has_alpha = linear.channels == 2 || linear.channels == 4;
  for (int y = 0; y < linear.height; ++y)
    for (int x = 0; x < linear.width; ++x) {
      std::uint8_t* px = out.at(x, y);
      for (int c = 0; c < 3; ++c) px[c] = to_unorm8(linear_to_srgb(linear.at(x, y, colours == 3 ? c : 0)));
      px[3] = has_alpha ? to_unorm8(linear.at(x, y, linear.channels - 1)) : 255;
    }
  return out;
}

// ---- 8-bit comparison -----------------------------------------------------------------

// Whether `image` holds `colour` (each channel within options.threshold) within
// options.edge_radius pixels of (x, y), the square around it: an edge moved that far.
static bool colour_nearby(const ImageRGBA8& image, const std::uint8_t* colour, int x, int y, const CompareOptions& options) {
  const int r = options.edge_radius;
  for (int v = std::max(0, y - r); v <= std::min(image.height - 1, y + r); ++v)
    for (int u = std::max(0, x - r); u <= std::min(image.width - 1, x + r); ++u)
      if (max_channel_diff(image.at(u, v), colour) <= options.threshold) return true;
  return false;
}

CompareResult compare(const ImageRGBA8& actual, const ImageRGBA8& expected, const CompareOptions& options) {
  require_valid(actual, "compare: actual image");
  require_valid(expected, "compare: expected image");
  CompareResult r;
  r.options = options;
  r.actual_width = actual.width;
  r.actual_height = actual.height;
  r.expected_width = expected.width;
  r.expected_height = expected.height;
  if (actual.width != expected.width || actual.height != expected.height) {
    r.size_mismatch = true;
    return r;
  }

  const std::size_t n = std::size_t(actual.width) * std::size_t(actual.height);
  std::vector<int> errors(n);
  std::uint64_t error_sum = 0, squared_sum = 0;
  int max_error = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* a = actual.pixels.data() + i * 4;
    const std::uint8_t* e = expected.pixels.data() + i * 4;
    for (int c = 0; c < 3; ++c) {
      const int d = int(a[c]) - int(e[c]);
      squared_sum += std::uint64_t(d * d);
    }
    errors[i] = max_channel_diff(a, e);
    error_sum += std::uint64_t(errors[i]);
    max_error = std::max(max_error, errors[i]);
    if (errors[i] <= options.threshold) continue;
    if (options.edge_radius > 0 && colour_nearby(expected, a, int(i % std::size_t(actual.width)),
                                                 int(i / std::size_t(actual.width)), options)) {
      ++r.moved_edge_pixels;
      continue;
    }
    ++r.failing_pixels;
  }

  r.psnr_db = squared_sum == 0
                  ? std::numeric_limits<double>::infinity()
                  : 10.0 * std::log10(255.0 * 255.0 * 3.0 * double(n) / double(squared_sum));
  if (n > 0) {
    r.mean_error = double(error_sum) / double(n);
    r.failing_fraction = double(r.failing_pixels) / double(n);
  }
  r.max_error = max_error;
  r.p99_error = nearest_rank(std::move(errors), 99);
  r.passed = r.failing_fraction <= options.max_failing_fraction;
  return r;
}

std::string CompareResult::summary() const {
  char line[256];
  if (size_mismatch) {
    std::snprintf(line, sizeof line, "size differs: %dx%d vs %dx%d", actual_width, actual_height,
                  expected_width, expected_height);
  } else {
    std::snprintf(line, sizeof line,
                  "mean %.2f  p99 %.0f  max %.0f  PSNR %.1f dB  failing %.3f%% (%zu px) -> %s "
                  "(threshold %d, allowed %.3f%%)",
                  mean_error, p99_error, max_error, psnr_db, failing_fraction * 100.0, failing_pixels,
                  passed ? "PASS" : "FAIL", options.threshold, options.max_failing_fraction * 100.0);
  }
  std::string out = line;
  if (options.edge_radius > 0)
    out += "; " + std::to_string(moved_edge_pixels) + " px excused as an edge moved by at most " +
           std::to_string(options.edge_radius) + " px";
  return out;
}

ImageRGBA8 diff_heatmap(const ImageRGBA8& actual, const ImageRGBA8& expected, int threshold, int full_scale) {
  require_valid(actual, "diff_heatmap: actual image");
  require_valid(expected, "diff_heatmap: expected image");
  ImageRGBA8 out = ImageRGBA8::blank(actual.width, actual.height);
  const bool same_size = actual.width == expected.width && actual.height == expected.height;
  const float scale = 1.0f / float(std::max(full_scale, 1));
  for (std::size_t i = 0; i < out.pixels.size(); i += 4) {
    if (!same_size) {
      ramp(1.0f, out.pixels.data() + i);
      continue;
    }
    const int diff = max_channel_diff(actual.pixels.data() + i, expected.pixels.data() + i);
    float t = float(diff) * scale;
    if (diff > threshold) t = std::max(t, kFailingRampMin);
    ramp(t, out.pixels.data() + i);
  }
  return out;
}

// ---- keys -------------------------------------------------------------------------------

namespace {
// stb_easy_font's 'w' has its middle stroke only in the bottom two of five rows, so at scale 1
// "forward" reads "foruard". Drawn instead: the middle stroke three rows tall, in the same
// 5-pixel box and rows (x-height, baseline) as stb's glyph, with stb's advance.
constexpr int kWRows = 5, kWTop = 2;
constexpr const char* kW[kWRows] = {"#...#", "#.#.#", "#.#.#", "#.#.#", ".#.#."};

// The pixels [x0, x1) x [y0, y1) inside the image, opaque rgb (glyphs, keys' grounds and swatches).
void fill(ImageRGBA8& image, int x0, int y0, int x1, int y1, const std::uint8_t rgb[3]) {
  for (int y = std::max(y0, 0); y < std::min(y1, image.height); ++y)
    for (int x = std::max(x0, 0); x < std::min(x1, image.width); ++x) {
      std::uint8_t* p = image.at(x, y);
      p[0] = rgb[0], p[1] = rgb[1], p[2] = rgb[2], p[3] = 255;
    }
}
}  // namespace

int draw_text(ImageRGBA8& image, int x, int y, const std::string& text, const std::uint8_t rgb[3], int scale) {
  require_valid(image, "draw_text");
  scale = std::clamp(scale, 1, 16);
  // Character by character, each at stb's advance of the text before it (the sum of the
  // characters' advances: one line), so that 'w' can be drawn from kW.
  std::vector<float> vertices(270 * 4 + 64);  // far more than stb's worst case for one character
  int cx = x;
  for (const char ch : text) {
    char one[2] = {ch, '\0'};
    if (ch == 'w') {
      for (int r = 0; r < kWRows; ++r)
        for (int c = 0; kW[r][c]; ++c)
          if (kW[r][c] == '#') {
            const int x0 = cx + c * scale, y0 = y + (kWTop + r) * scale;
            fill(image, x0, y0, x0 + scale, y0 + scale, rgb);
          }
    } else {
      // stb_easy_font writes quads (4 vertices of x, y, z and a colour: 16 bytes), axis aligned.
      const int quads = stb_easy_font_print(0, 0, one, nullptr, vertices.data(), int(vertices.size() * sizeof(float)));
      for (int q = 0; q < quads; ++q) {
        const float* v = vertices.data() + q * 16;  // 4 vertices of 4 floats
        fill(image, cx + int(v[0]) * scale, y + int(v[1]) * scale, cx + int(v[8]) * scale, y + int(v[9]) * scale, rgb);
      }
    }
    cx += text_width(one, scale);
  }
  return text_width(text, scale);
}

int text_width(const std::string& text, int scale) {
  std::vector<char> chars(text.begin(), text.end());
  chars.push_back('\0');
  return stb_easy_font_width(chars.data()) * std::clamp(scale, 1, 16);
}

namespace {
std::string short_number(float v) {
  char s[32];
  std::snprintf(s, sizeof s, "%g", double(v));
  return s;
}
}  // namespace

namespace {

// The key's colour at t in [0, 1]: the picture's own stops, or error_heatmap's ramp.
void key_colour(const HeatKey& key, float t, std::uint8_t* rgba) {
  if (key.stops.empty() && !key.mixed_in_linear) return ramp(t, rgba);
  static const std::vector<std::array<float, 3>> error_ramp = {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  const std::vector<std::array<float, 3>>& stops = key.stops.empty() ? error_ramp : key.stops;
  const float s = std::clamp(t, 0.0f, 1.0f) * float(stops.size() - 1);
  const int i = std::max(0, std::min(int(s), int(stops.size()) - 2));
  const float f = stops.size() == 1 ? 0.0f : s - float(i);
  for (int c = 0; c < 3; ++c) {
    float a = stops[std::size_t(i)][c], b = stops[std::min(std::size_t(i) + 1, stops.size() - 1)][c];
    if (key.mixed_in_linear) a = srgb_to_linear(a), b = srgb_to_linear(b);
    float v = a + (b - a) * f;
    if (key.mixed_in_linear) v = linear_to_srgb(v);
    rgba[c] = std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
  }
  rgba[3] = 255;
}

// The strip from row `top` down, between columns x_begin and x_end: a grey ground, the bar,
// its ticks and labels; `what` on a line of its own (two_lines) or between the end labels.
void draw_key_strip(ImageRGBA8& out, const HeatKey& key, int top, int x_begin, int x_end, int scale, bool two_lines) {
  const int margin = (two_lines ? 6 : 3) * scale, bar_h = (two_lines ? 10 : 6) * scale, text_h = 8 * scale;
  const std::uint8_t ground[3] = {48, 48, 48};
  fill(out, x_begin, top, x_end, out.height, ground);
  const int x0 = x_begin + margin, x1 = std::max(x0 + 1, x_end - margin), bar_y = top + margin;
  auto x_of = [&](float value) { return x0 + int(std::lround(double(value) / key.full_scale * (x1 - 1 - x0))); };
  for (int x = x0; x < x1; ++x) {
    const float value = float(x - x0) / float(std::max(1, x1 - 1 - x0)) * key.full_scale;
    float t = value / key.full_scale;
    if (key.threshold >= 0 && value > key.threshold) t = std::max(t, kFailingRampMin);
    std::uint8_t rgba[4];
    key_colour(key, t, rgba);
    for (int y = bar_y; y < bar_y + bar_h && y < out.height; ++y) std::copy_n(rgba, 4, out.at(x, y));
  }
  const std::uint8_t white[3] = {255, 255, 255}, grey[3] = {200, 200, 200};
  const int label_y = bar_y + bar_h + (two_lines ? 3 : 2) * scale;
  int left_end = x0, right_start = x1;
  auto tick = [&](float value, const std::string& label, bool right_aligned) {
    const int x = x_of(value);
    fill(out, x, bar_y + bar_h, x + scale, label_y, white);
    const int w = text_width(label, scale);
    const int lx = right_aligned ? x - w + scale : x;
    draw_text(out, lx, label_y, label, white, scale);
    if (right_aligned) right_start = std::min(right_start, lx);
    else left_end = std::max(left_end, lx + w);
  };
  tick(0, "0", false);
  tick(key.full_scale, short_number(key.full_scale) + "+", true);
  if (key.threshold > 0 && key.threshold < key.full_scale) tick(key.threshold, short_number(key.threshold), false);
  if (two_lines) {
    draw_text(out, x0, label_y + text_h + 2 * scale, key.what, grey, scale);
  } else {
    // between the labels, centred; where it does not fit, it stays left and is clipped
    const int w = text_width(key.what, scale), gap = 4 * scale;
    const int room = right_start - left_end - 2 * gap;
    const int x = w <= room ? left_end + gap + (room - w) / 2 : left_end + gap;
    ImageRGBA8 line = ImageRGBA8::blank(std::max(1, right_start - gap - x), text_h);
    draw_text(line, 0, 0, key.what, grey, scale);
    for (int y = 0; y < line.height && label_y + y < out.height; ++y)
      for (int lx = 0; lx < line.width && x + lx < out.width; ++lx)
        if (line.at(lx, y)[3]) std::copy_n(line.at(lx, y), 4, out.at(x + lx, label_y + y));
  }
}

}  // namespace

ImageRGBA8 with_heat_key(const ImageRGBA8& heat, const HeatKey& key) {
  require_valid(heat, "with_heat_key");
  if (!(key.full_scale > 0.0f)) throw Error("with_heat_key: full_scale must be positive");
  const int scale = std::max(1, heat.width / 400);  // text stays readable on large images
  const int strip = 6 * scale + 10 * scale + 3 * scale + 8 * scale + 2 * scale + 8 * scale + 6 * scale;
  ImageRGBA8 out = ImageRGBA8::blank(heat.width, heat.height + strip);
  std::copy(heat.pixels.begin(), heat.pixels.end(), out.pixels.begin());
  draw_key_strip(out, key, heat.height, 0, out.width, scale, true);
  return out;
}

int label_scale(int width) { return std::max(1, width / 400); }  // text stays readable on large images

int heat_key_rows(int width) {
  const int scale = label_scale(width);
  return 3 * scale + 6 * scale + 2 * scale + 8 * scale + 2 * scale;
}

int draw_heat_key(ImageRGBA8& image, const HeatKey& key, int x_begin, int x_end) {
  require_valid(image, "draw_heat_key");
  if (!(key.full_scale > 0.0f)) throw Error("draw_heat_key: full_scale must be positive");
  if (x_end < 0 || x_end > image.width) x_end = image.width;
  x_begin = std::clamp(x_begin, 0, x_end);
  const int rows = std::min(image.height, heat_key_rows(x_end - x_begin));
  draw_key_strip(image, key, image.height - rows, x_begin, x_end, label_scale(x_end - x_begin), false);
  return rows;
}

int draw_label(ImageRGBA8& image, int x, int y, const std::string& text) {
  require_valid(image, "draw_label");
  const int scale = label_scale(image.width), pad = 2 * scale;
  const int w = text_width(text, scale) + 2 * pad, h = 7 * scale + 2 * pad;
  const std::uint8_t box[3] = {24, 24, 24}, white[3] = {255, 255, 255};
  fill(image, x, y, x + w, y + h, box);
  draw_text(image, x + pad, y + pad + scale, text, white, scale);
  return w;
}

std::array<std::uint8_t, 3> srgb_colour(float r, float g, float b) {
  auto c = [](float v) { return std::uint8_t(std::lround(255.f * linear_to_srgb(std::clamp(v, 0.f, 1.f)))); };
  return {c(r), c(g), c(b)};
}

LegendPlace draw_legend(ImageRGBA8& image, const std::vector<LegendEntry>& entries) {
  require_valid(image, "draw_legend");
  const int s = label_scale(image.width), pad = 2 * s, line = 9 * s, swatch = 6 * s, indent = swatch + 3 * s;
  const std::uint8_t dark[3] = {24, 24, 24}, white[3] = {255, 255, 255};
  auto text_of = [](const LegendEntry& e, bool brief) -> const std::string& {
    return brief && !e.short_text.empty() ? e.short_text : e.text;
  };
  auto width_of = [&](bool brief) {
    int text_w = 0;
    for (const LegendEntry& e : entries) text_w = std::max(text_w, text_width(text_of(e, brief), s));
    return pad + indent + text_w + pad;
  };
  const bool brief = width_of(false) > image.width;
  LegendPlace place{.width = width_of(brief), .height = pad + int(entries.size()) * line + pad};
  place.y = image.height - place.height;
  // A key whose text would run past the picture's edge, or that would hide more than a quarter
  // of it (a 160x90 exercise shot), hides what it explains: none.
  if (place.width > image.width || place.height > image.height ||
      4 * place.width * place.height > image.width * image.height)
    return {};
  fill(image, 0, place.y, place.width, image.height, dark);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const int y = place.y + pad + int(k) * line + s;
    if (entries[k].colour) fill(image, pad, y, pad + swatch, y + swatch, entries[k].colour->data());
    draw_text(image, pad + indent, y, text_of(entries[k], brief), white, s);
  }
  return place;
}

DirectionKeyPlace draw_direction_key(ImageRGBA8& image, const DirectionKey& key) {
  require_valid(image, "draw_direction_key");
  if (!(key.full_scale > 0.0f) || !std::isfinite(key.full_scale))
    throw Error("draw_direction_key: full_scale must be positive and finite");
  if (!key.colour) throw Error("draw_direction_key: no colour for a direction");
  const int scale = label_scale(image.width), pad = 3 * scale, radius = 12 * scale, text_h = 7 * scale;
  const std::string rim = "rim: " + short_number(key.full_scale) + (key.unit.empty() ? "" : " " + key.unit);
  const int text_w = std::max(text_width(key.what, scale), text_width(rim, scale));
  DirectionKeyPlace place;
  place.width = pad + text_w + 4 * scale + 2 * radius + 3 + pad;  // the rim's ring one pixel outside the disc
  place.height = 2 * radius + 3 + 2 * pad;
  place.x = image.width - place.width;
  place.y = image.height - place.height;
  place.radius = radius;
  place.centre_x = image.width - pad - radius - 2;
  place.centre_y = image.height - pad - radius - 2;
  const std::uint8_t box[3] = {24, 24, 24}, ring[3] = {160, 160, 160}, white[3] = {255, 255, 255}, grey[3] = {200, 200, 200};
  fill(image, place.x, place.y, image.width, image.height, box);
  // The disc: each pixel centre's offset from the centre, scaled so the rim is full_scale.
  const float r2_disc = (float(radius) + 0.5f) * (float(radius) + 0.5f);
  const float r2_ring = (float(radius) + 1.5f) * (float(radius) + 1.5f);
  for (int dy = -radius - 2; dy <= radius + 2; ++dy)
    for (int dx = -radius - 2; dx <= radius + 2; ++dx) {
      const int x = place.centre_x + dx, y = place.centre_y + dy;
      if (x < 0 || y < 0 || x >= image.width || y >= image.height) continue;
      const float r2 = float(dx * dx + dy * dy);
      std::uint8_t* p = image.at(x, y);
      if (r2 <= r2_disc) {
        const float k = key.full_scale / float(radius);
        const std::array<std::uint8_t, 3> c = key.colour(float(dx) * k, float(dy) * k);
        p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
      } else if (r2 <= r2_ring) {
        p[0] = ring[0], p[1] = ring[1], p[2] = ring[2], p[3] = 255;
      }
    }
  // Two lines left of the disc, centred on it vertically.
  const int text_x = place.x + pad, text_y = place.centre_y - text_h - scale;
  draw_text(image, text_x, text_y, key.what, grey, scale);
  draw_text(image, text_x, text_y + text_h + 2 * scale, rim, white, scale);
  return place;
}

// ---- float comparison -----------------------------------------------------------------

std::vector<float> pixel_errors(const ImageF& actual, const ImageF& expected) {
  require_valid(actual, "pixel_errors: actual image");
  require_valid(expected, "pixel_errors: expected image");
  if (actual.width != expected.width || actual.height != expected.height)
    throw Error("pixel_errors: size differs: " + dims(actual.width, actual.height) + " vs " +
                dims(expected.width, expected.height));
  const int colours = colour_channels(actual.channels);
  if (colours != colour_channels(expected.channels))
    throw Error("pixel_errors: actual has " + std::to_string(actual.channels) + " channels, expected " +
                std::to_string(expected.channels));

  std::vector<float> errors(std::size_t(actual.width) * std::size_t(actual.height));
  for (int y = 0; y < actual.height; ++y)
    for (int x = 0; x < actual.width; ++x) {
      double sum = 0;
      for (int c = 0; c < colours; ++c) sum += std::abs(double(actual.at(x, y, c)) - double(expected.at(x, y, c)));
      const float error = float(sum / colours);
      errors[std::size_t(y) * std::size_t(actual.width) + std::size_t(x)] =
          std::isnan(error) ? std::numeric_limits<float>::infinity() : error;
    }
  return errors;
}

FloatErrorStats compare_float(const ImageF& actual, const ImageF& expected, const std::vector<std::uint8_t>& mask) {
  std::vector<float> errors = pixel_errors(actual, expected);
  if (!mask.empty()) {
    if (mask.size() != errors.size())
      throw Error("compare_float: mask has " + std::to_string(mask.size()) + " entries, the image " +
                  dims(actual.width, actual.height) + " has " + std::to_string(errors.size()) + " pixels");
    std::size_t kept = 0;
    for (std::size_t i = 0; i < errors.size(); ++i)
      if (mask[i]) errors[kept++] = errors[i];
    errors.resize(kept);
  }

  FloatErrorStats stats;
  stats.pixels = errors.size();
  if (errors.empty()) return stats;
  double sum = 0, squared_sum = 0;
  for (float e : errors) {
    sum += e;
    squared_sum += double(e) * double(e);
    stats.max = std::max(stats.max, double(e));
  }
  stats.mean_abs = sum / double(errors.size());
  stats.rmse = std::sqrt(squared_sum / double(errors.size()));
  stats.p99 = nearest_rank(std::move(errors), 99);
  return stats;
}

ImageRGBA8 error_heatmap(const std::vector<float>& error, int width, int height, float full_scale) {
  if (width < 0 || height < 0 || error.size() != std::size_t(width) * std::size_t(height))
    throw Error("error_heatmap: " + std::to_string(error.size()) + " errors for a " + dims(width, height) + " image");
  if (!(full_scale > 0.0f)) throw Error("error_heatmap: full_scale must be positive");
  ImageRGBA8 out = ImageRGBA8::blank(width, height);
  for (std::size_t i = 0; i < error.size(); ++i)
    ramp(std::isnan(error[i]) ? 1.0f : error[i] / full_scale, out.pixels.data() + i * 4);
  return out;
}

}  // namespace lp
