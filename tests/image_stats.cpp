// image_stats: what a program test asserts about an image it wrote, beyond "it was written".
//
//   image_stats IMAGE.png [--size WxH] [--background R,G,B] [--mean LO HI] [--lit LO HI]
//               [--matches REFERENCE.png] [--differs-from OTHER.png MIN_MEAN_STEPS] [--near OTHER.png MAX_MEAN_STEPS]
//               [--matches-right-of X REFERENCE.png] [--region X Y W H] [--other-at X Y]
//               [--nearer-than X Y TRUTH.png RATIO]
//
// Prints the image's statistics, then checks each one asked for:
//   --mean LO HI       the mean over every pixel's R, G and B, in 8-bit steps, lies in [LO, HI]
//   --lit LO HI        the fraction of pixels whose brightest channel is more than 8 steps above
//                      the background's (--background, default 0,0,0) lies in [LO, HI]: a black,
//                      blank or all-white image fails
//   --size WxH         the image has this size
//   --matches REF      compare() with the defaults of --check: at most 0.1 % of the pixels off
//                      by more than 3 steps
//   --matches-right-of X REF   --matches over the columns from X on (a window's screenshot
//                      beside its panel against the headless image)
//   --differs-from OTHER MIN   the mean per-pixel difference (largest channel, 8-bit steps)
//                      from OTHER is at least MIN: two images that must not look the same
//   --near OTHER MAX   that mean difference is at most MAX: two images that must look the same
//                      where a pixel-by-pixel threshold would be the wrong test
//   --region X Y W H   the checks after it (--mean, --lit, --matches, --differs-from, --near) see
//                      only this rectangle (top-left X, Y) of the image and of the other image
//                      (which must hold it): one part of a split picture
//   --other-at X Y     the checks after it take the other image's rectangle from (X, Y) instead:
//                      a part of a picture moved (a split of two images' middles, a tile of a
//                      mosaic against the picture at the tile's size)
//   --nearer-than X Y TRUTH RATIO   on TRUTH's edge pixels (its rectangle's pixels whose 3x3
//                      neighbourhood spans more than 0.1 of the range in a channel: chapter 11's
//                      edge_mask), the region's mean difference from TRUTH is at most RATIO times
//                      that of this image's own rectangle at (X, Y): one half of a split nearer a
//                      truth than the other half
// Exit code 0 when every check holds, 1 when one fails or an image cannot be read, 2 for a bad
// command line.
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/image.h"

using namespace lp;

namespace {

constexpr int kLitSteps = 8;  // above the background: more than a GPU's few steps of noise

double number(const std::string& s, const char* what) {
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end) throw UsageError(std::string(what) + " expects a number, got '" + s + "'");
  return v;
}

struct Stats {
  double mean = 0, lit = 0;
};

Stats stats(const ImageRGBA8& img, const int background[3]) {
  Stats s;
  const std::size_t n = std::size_t(img.width) * img.height;
  std::size_t lit = 0;
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* p = img.pixels.data() + i * 4;
    int above = -255;
    for (int c = 0; c < 3; ++c) {
      sum += p[c];
      above = std::max(above, int(p[c]) - background[c]);
    }
    lit += above > kLitSteps;
  }
  s.mean = n ? sum / (3.0 * n) : 0;
  s.lit = n ? double(lit) / n : 0;
  return s;
}

int run(int argc, char** argv) {
  if (argc < 2) throw UsageError("expects an image");
  const std::string path = argv[1];
  std::vector<std::string> args(argv + 2, argv + argc);
  int background[3] = {0, 0, 0};
  for (std::size_t i = 0; i < args.size(); ++i)
    if (args[i] == "--background") {
      int r = 0, g = 0, b = 0;
      if (i + 1 >= args.size() || std::sscanf(args[i + 1].c_str(), "%d,%d,%d", &r, &g, &b) != 3)
        throw UsageError("--background expects R,G,B");
      background[0] = r, background[1] = g, background[2] = b;
    }
  const ImageRGBA8 img = load_png(path);
  const Stats s = stats(img, background);
  std::printf("%s: %dx%d, mean %.2f steps, lit %.2f %% (brightest channel > %d steps above %d,%d,%d)\n", path.c_str(),
              img.width, img.height, s.mean, 100.0 * s.lit, kLitSteps, background[0], background[1], background[2]);
  int failed = 0;
  struct { int x = 0, y = 0, w = -1, h = -1, other_x = -1, other_y = -1; } region;  // w < 0: the whole image
  auto cut_at = [&](const ImageRGBA8& in, int x0, int y0) {
    if (region.w < 0) return in;
    if (x0 + region.w > in.width || y0 + region.h > in.height) return ImageRGBA8::blank(1, 1);  // a size mismatch, reported
    ImageRGBA8 out = ImageRGBA8::blank(region.w, region.h);
    for (int y = 0; y < region.h; ++y) std::copy_n(in.at(x0, y0 + y), std::size_t(region.w) * 4, out.at(0, y));
    return out;
  };
  auto cut = [&](const ImageRGBA8& in) { return cut_at(in, region.x, region.y); };
  auto cut_other = [&](const ImageRGBA8& in) {
    return region.other_x < 0 ? cut(in) : cut_at(in, region.other_x, region.other_y);
  };
  auto fail = [&](const std::string& why) {
    std::printf("FAIL: %s\n", why.c_str());
    failed = 1;
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](std::size_t k) -> const std::string& {
      if (i + k >= args.size()) throw UsageError(a + " expects more values");
      return args[i + k];
    };
    if (a == "--background") {
      ++i;
    } else if (a == "--mean" || a == "--lit") {
      const double lo = number(value(1), a.c_str()), hi = number(value(2), a.c_str());
      const Stats r = region.w < 0 ? s : stats(cut(img), background);
      const double v = a == "--mean" ? r.mean : r.lit;
      if (v < lo || v > hi) fail(a.substr(2) + " " + std::to_string(v) + " outside [" + value(1) + ", " + value(2) + "]");
      i += 2;
    } else if (a == "--size") {
      int w = 0, h = 0;
      if (std::sscanf(value(1).c_str(), "%dx%d", &w, &h) != 2) throw UsageError("--size expects WxH");
      if (w != img.width || h != img.height)
        fail("size " + std::to_string(img.width) + "x" + std::to_string(img.height) + ", expected " + value(1));
      i += 1;
    } else if (a == "--matches") {
      const CompareResult r = compare(cut(img), cut_other(load_png(value(1))));
      std::printf("against %s: %s\n", value(1).c_str(), r.summary().c_str());
      if (!r.passed) fail("does not match " + value(1));
      i += 1;
    } else if (a == "--matches-right-of") {
      const int x0 = static_cast<int>(number(value(1), "--matches-right-of"));
      const ImageRGBA8 ref = load_png(value(2));
      if (ref.width != img.width || ref.height != img.height || x0 < 0 || x0 >= img.width) {
        fail("--matches-right-of " + value(1) + ": " + value(2) + " is not the image's size, or X is outside it");
      } else {
        auto crop = [x0](const ImageRGBA8& in) {
          ImageRGBA8 out = ImageRGBA8::blank(in.width - x0, in.height);
          for (int y = 0; y < in.height; ++y) std::copy_n(in.at(x0, y), std::size_t(out.width) * 4, out.at(0, y));
          return out;
        };
        const CompareResult r = compare(crop(img), crop(ref));
        std::printf("columns %d.. against %s: %s\n", x0, value(2).c_str(), r.summary().c_str());
        if (!r.passed) fail("columns from " + value(1) + " on do not match " + value(2));
      }
      i += 2;
    } else if (a == "--differs-from" || a == "--near") {
      const bool differ = a == "--differs-from";
      const double bound = number(value(2), a.c_str());
      const CompareResult r = compare(cut(img), cut_other(load_png(value(1))));
      std::printf("against %s: mean difference %.3f steps (%s %s wanted)\n", value(1).c_str(), r.mean_error,
                  differ ? "at least" : "at most", value(2).c_str());
      if (r.size_mismatch) fail("not the size of " + value(1));
      else if (differ ? r.mean_error < bound : r.mean_error > bound) fail(std::string(differ ? "too close to " : "too far from ") + value(1));
      i += 2;
    } else if (a == "--nearer-than") {
      const int x = static_cast<int>(number(value(1), a.c_str())), y = static_cast<int>(number(value(2), a.c_str()));
      const double ratio = number(value(4), a.c_str());
      if (region.w < 0) throw UsageError("--nearer-than needs a --region before it");
      if (x < 0 || y < 0 || x + region.w > img.width || y + region.h > img.height)
        throw UsageError("--nearer-than " + value(1) + " " + value(2) + ": the rectangle is not inside the image");
      const ImageRGBA8 truth = cut_other(load_png(value(3))), near = cut(img), far = cut_at(img, x, y);
      if (truth.width != near.width || truth.height != near.height) {
        fail("not the size of " + value(3));
      } else {
        double near_sum = 0, far_sum = 0;
        std::size_t edges = 0;
        for (int py = 0; py < truth.height; ++py)
          for (int px = 0; px < truth.width; ++px) {
            int range = 0;
            for (int c = 0; c < 3; ++c) {
              int lo = 255, hi = 0;
              for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                  const int v = truth.at(std::clamp(px + dx, 0, truth.width - 1), std::clamp(py + dy, 0, truth.height - 1))[c];
                  lo = std::min(lo, v), hi = std::max(hi, v);
                }
              range = std::max(range, hi - lo);
            }
            if (range <= 255 / 10) continue;
            ++edges;
            for (int c = 0; c < 3; ++c) {
              near_sum += std::abs(int(near.at(px, py)[c]) - int(truth.at(px, py)[c]));
              far_sum += std::abs(int(far.at(px, py)[c]) - int(truth.at(px, py)[c]));
            }
          }
        const double near_mean = edges ? near_sum / (3.0 * edges) : 0, far_mean = edges ? far_sum / (3.0 * edges) : 0;
        std::printf("on %zu edge pixels of %s: %.3f steps from it, the rectangle at %d,%d %.3f (ratio %.3f, at most %s wanted)\n",
                    edges, value(3).c_str(), near_mean, x, y, far_mean, far_mean > 0 ? near_mean / far_mean : 0.0, value(4).c_str());
        if (edges == 0) fail(value(3) + " has no edge pixels in the region");
        else if (near_mean > ratio * far_mean) fail("not nearer " + value(3) + " than the rectangle at " + value(1) + "," + value(2));
      }
      i += 4;
    } else if (a == "--region") {
      int v[4];
      for (int k = 0; k < 4; ++k) v[k] = static_cast<int>(number(value(k + 1), "--region"));
      if (v[0] < 0 || v[1] < 0 || v[2] < 1 || v[3] < 1 || v[0] + v[2] > img.width || v[1] + v[3] > img.height)
        throw UsageError("--region " + value(1) + " " + value(2) + " " + value(3) + " " + value(4) + " is not inside the " +
                         std::to_string(img.width) + "x" + std::to_string(img.height) + " image");
      region = {v[0], v[1], v[2], v[3], region.other_x, region.other_y};
      std::printf("region %d,%d %dx%d:\n", v[0], v[1], v[2], v[3]);
      i += 4;
    } else if (a == "--other-at") {
      const int x = static_cast<int>(number(value(1), "--other-at")), y = static_cast<int>(number(value(2), "--other-at"));
      if (region.w < 0) throw UsageError("--other-at needs a --region before it");
      if (x < 0 || y < 0) throw UsageError("--other-at " + value(1) + " " + value(2) + ": negative");
      region.other_x = x, region.other_y = y;
      std::printf("region %d,%d %dx%d against the other image's at %d,%d:\n", region.x, region.y, region.w, region.h, x, y);
      i += 2;
    } else {
      throw UsageError("unknown option '" + a + "'");
    }
  }
  return failed;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "image_stats: %s\nusage: image_stats IMAGE.png [--size WxH] [--background R,G,B] [--mean LO HI] "
                         "[--lit LO HI] [--matches REF.png] [--differs-from OTHER.png MIN_MEAN_STEPS] [--near OTHER.png MAX_MEAN_STEPS] "
                         "[--matches-right-of X REF.png] [--region X Y W H] [--other-at X Y] [--nearer-than X Y TRUTH.png RATIO]\n",
                 e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "image_stats: %s\n", e.what());
    return 1;
  }
}
