#pragma once
// Images on disk and in memory, and the comparisons the render tests and the
// speed-versus-error sweeps are built on. Every image here stores its rows top to bottom;
// OpenGL reads back bottom to top, so callers of glReadPixels use flip_vertically().
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace lp {

// 8-bit RGBA image, rows top to bottom (the way PNG stores them).
struct ImageRGBA8 {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 4

  static ImageRGBA8 blank(int width, int height);  // transparent black
  std::uint8_t* at(int x, int y);
  const std::uint8_t* at(int x, int y) const;
};

// Float image with 1..4 channels, rows top to bottom. For HDR buffers and ground truths.
struct ImageF {
  int width = 0, height = 0, channels = 0;
  std::vector<float> data;  // width * height * channels

  static ImageF blank(int width, int height, int channels);  // all zeros
  float& at(int x, int y, int c);
  float at(int x, int y, int c) const;
};

void flip_vertically(ImageRGBA8& image);
void flip_vertically(ImageF& image);

ImageRGBA8 load_png(const std::filesystem::path& path);  // grey, grey+alpha, RGB, RGBA; 8 or 16 bit
void save_png(const std::filesystem::path& path, const ImageRGBA8& image);  // creates parent dirs
// `base` with "-001", "-002", ... before its extension: the first such name no file has yet
// (P in the window: every press a new picture, none overwritten). Throws Error after 9999.
std::filesystem::path numbered_path(const std::filesystem::path& base);

// PFM: 'PF' (3 channels) and 'Pf' (1 channel); byte order from the sign of the scale.
// The scale's magnitude is ignored, as nearly every reader does, so round trips are exact.
ImageF load_pfm(const std::filesystem::path& path);
void save_pfm(const std::filesystem::path& path, const ImageF& image);  // 1 or 3 channels (of 4: RGB)

// Radiance RGBE: about 1% relative precision, no negative values.
ImageF load_hdr(const std::filesystem::path& path);  // always 3 channels
void save_hdr(const std::filesystem::path& path, const ImageF& image);

// sRGB transfer functions, the exact piecewise curves of IEC 61966-2-1.
float srgb_to_linear(float srgb);
float linear_to_srgb(float linear);
// Clamps to [0,1], encodes sRGB, rounds to nearest. One channel is grey, two are grey
// and alpha; alpha stays linear and is 255 when the image has none.
ImageRGBA8 to_srgb8(const ImageF& linear);

// The recipe of mature render-test suites: a pixel fails if any colour channel (alpha is
// ignored) differs by more than `threshold` 8-bit steps; the images match if the fraction
// of failing pixels is at most `max_failing_fraction`.
struct CompareOptions {
  int threshold = 3;
  double max_failing_fraction = 0.001;
  // A rasterised edge that another implementation put one pixel over: OpenGL leaves the
  // sub-pixel precision and the rule for a pixel centre exactly on an edge to the
  // implementation, so on another renderer an edge may land on the neighbouring pixel (a whole
  // row of them along an edge parallel to the pixel grid). With edge_radius > 0 a failing pixel
  // is excused when the expected image holds its colour (within threshold) at most edge_radius
  // pixels away: one for an image at its own size, the magnification for a magnified one.
  // Excused pixels are counted apart (moved_edge_pixels). 0: every difference counts.
  int edge_radius = 0;
};

struct CompareResult {
  bool size_mismatch = false;
  int actual_width = 0, actual_height = 0, expected_width = 0, expected_height = 0;
  double mean_error = 0;  // per pixel: the largest channel difference, in 8-bit steps
  double p99_error = 0;   // nearest rank: the ceil(0.99 N)-th smallest per-pixel error
  double max_error = 0;
  double psnr_db = 0;  // over the RGB values, peak 255; +infinity when identical
  double failing_fraction = 0;
  std::size_t failing_pixels = 0;
  std::size_t moved_edge_pixels = 0;  // over the threshold but excused by edge_radius (not in failing_*)
  bool passed = false;
  CompareOptions options;  // what the verdict was judged against, for summary()

  // "mean 0.12  p99 1  max 4  PSNR 51.3 dB  failing 0.031% (18 px) -> PASS (threshold 3, allowed 0.100%)"
  std::string summary() const;
};

CompareResult compare(const ImageRGBA8& actual, const ImageRGBA8& expected, const CompareOptions& options = {});

// Heat map of the per-pixel largest channel difference: black where equal, then a
// blue -> green -> yellow -> red ramp on which `full_scale` steps is red. Differences
// within `threshold` stay in the dim blues; failing pixels are at least full blue, so a
// single one stands out. Images of different sizes give an all-red image of actual's size.
ImageRGBA8 diff_heatmap(const ImageRGBA8& actual, const ImageRGBA8& expected, int threshold = 3,
                        int full_scale = 32);

// A heat map's key, for the pictures a program writes for a reader (--check's differences,
// error maps): the image with a strip below it that holds the ramp from 0 to `full_scale`,
// its ticks labelled, and a line saying what the values are. With `threshold` >= 0 the bar
// is diff_heatmap()'s ramp (values above it start at full blue) and the threshold is marked;
// without, error_heatmap()'s. Never for a reference image: those stay pictures alone.
struct HeatKey {
  float full_scale = 1;  // the value drawn at the ramp's top; "+" marks that larger values are too
  std::string what;      // e.g. "largest channel difference, 8-bit steps"
  float threshold = -1;  // diff_heatmap's threshold, or < 0 for error_heatmap's plain ramp
  // Another picture's ramp: its colours (display values, 0..1), evenly spaced from 0 to
  // full_scale, e.g. chapter 03's count ramp. Empty: error_heatmap's.
  std::vector<std::array<float, 3>> stops = {};
  // The picture mixed its ramp's colours in linear light (a shader writing to an sRGB target):
  // the key mixes them so too, then encodes.
  bool mixed_in_linear = false;
};
ImageRGBA8 with_heat_key(const ImageRGBA8& heat, const HeatKey& key);
// The same key in one line under the bar, drawn over the bottom rows of `image` between
// columns x_begin and x_end (-1: the right edge), for the pictures a program shows at its own
// size (the window and its PNG). Returns the rows it covered (heat_key_rows).
int draw_heat_key(ImageRGBA8& image, const HeatKey& key, int x_begin = 0, int x_end = -1);
int heat_key_rows(int width);  // the strip's height for a picture `width` pixels wide
// The key of a picture whose colour says which way a vector points and how long it is (chapter
// 11's motion): on a dark box in the picture's bottom-right corner, a disc whose every point has
// the picture's colour of the vector from its centre to that point (the rim at full_scale),
// beside a line saying what it shows and one giving the rim's length.
struct DirectionKey {
  float full_scale = 1;  // the vector's length at the disc's rim, in the picture's units
  std::string unit;      // e.g. "px/frame"
  std::string what;      // e.g. "screen motion"
  // The picture's colour (display RGB) for a vector of (x, y) units: x right, y down.
  std::function<std::array<std::uint8_t, 3>(float x, float y)> colour;
};
struct DirectionKeyPlace {  // where the key went: its box, and its disc's centre and radius
  int x = 0, y = 0, width = 0, height = 0;
  int centre_x = 0, centre_y = 0, radius = 0;
};
DirectionKeyPlace draw_direction_key(ImageRGBA8& image, const DirectionKey& key);
// The key of a picture whose colours are categories (chapter 11's dropped history, chapter 06's
// cascades, chapter 04's waste): on a dark box in the bottom-left corner, a line per entry, each
// a swatch of its colour (display RGB; none: text alone) and what the colour means. On a picture
// too narrow for the texts, every entry says its short text instead (where it has one). Returns
// the box (x, y, width, height), inside the picture; none (all 0) when the texts would still run
// past its edge or the box would cover more than a quarter of it, which is then left as it is.
struct LegendEntry {
  std::optional<std::array<std::uint8_t, 3>> colour;
  std::string text;
  std::string short_text = {};  // for a narrow picture (a 160x90 exercise shot); empty: text
};
struct LegendPlace {
  int x = 0, y = 0, width = 0, height = 0;
};
LegendPlace draw_legend(ImageRGBA8& image, const std::vector<LegendEntry>& entries);
// A linear colour (a shader's, written to an sRGB target) as the display colour a legend shows:
// clamped to [0, 1], encoded, rounded.
std::array<std::uint8_t, 3> srgb_colour(float r, float g, float b);
// A caption over a picture: white text on a dark box, the box's top-left at (x, y); the text
// scaled with the picture as the key's is. Returns the box's width.
int draw_label(ImageRGBA8& image, int x, int y, const std::string& text);
int label_scale(int width);  // the text scale of keys and labels on a picture this wide
// Text drawn into the image (stb_easy_font: about 6 pixels tall times `scale`), top-left at
// (x, y), clipped to the image. Returns the width in pixels it took.
int draw_text(ImageRGBA8& image, int x, int y, const std::string& text, const std::uint8_t rgb[3], int scale = 1);
int text_width(const std::string& text, int scale = 1);  // what draw_text returns, drawing nothing

// Per-pixel error against a ground truth: the mean absolute difference over the RGB
// channels (the one channel of grey images); the channel counts must agree up to alpha.
// NaN counts as an infinite error, so a broken pixel cannot hide.
std::vector<float> pixel_errors(const ImageF& actual, const ImageF& expected);

// Statistics of pixel_errors() over the pixels where mask is non-zero (empty mask: all).
// rmse is the root mean square of those per-pixel errors; p99 is nearest rank, as above.
struct FloatErrorStats {
  double mean_abs = 0, rmse = 0, p99 = 0, max = 0;
  std::size_t pixels = 0;
};
FloatErrorStats compare_float(const ImageF& actual, const ImageF& expected,
                              const std::vector<std::uint8_t>& mask = {});

// Heat map of per-pixel errors on the same ramp: 0 is black, full_scale and above red.
ImageRGBA8 error_heatmap(const std::vector<float>& error, int width, int height, float full_scale);

}  // namespace lp
