// png_coverage FILE [--covered LO HI] [--lit MIN] [--bright-share LO HI]
//              [--shadow UNSHADOWED.png MIN_SHARE MIN_DROP] [--floor-below MAX]
// What a rendered image shows, for the scene-input tests: the pixels that differ from the
// top-left corner (the background) by more than 8 steps in a channel are "covered"; their
// mean brightest channel must reach --lit (0..255); the share of covered pixels whose
// brightest channel is >= 250 ("bright", e.g. emitting) must lie in --bright-share.
// A red object on a grey floor (tests/data/box_on_floor.gltf), against the same view drawn
// without shadows (UNSHADOWED): the object is UNSHADOWED's covered pixels whose red is more
// than 1.5 times their green, the floor its covered grey pixels (channels within 8 steps);
// --shadow: the floor pixels whose brightest channel FILE darkens by at least MIN_DROP (a
// fraction of UNSHADOWED's) number at least MIN_SHARE times the object's pixels (a shadow the
// image shows); --floor-below: no floor pixel of FILE or UNSHADOWED reaches MAX (not clipped).
// Prints the numbers; exit 0 when every given bound holds, 1 otherwise.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>

#include "common/image.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: png_coverage FILE [--covered LO HI] [--lit MIN] [--bright-share LO HI] "
                         "[--shadow UNSHADOWED.png MIN_SHARE MIN_DROP] [--floor-below MAX]\n");
    return 2;
  }
  try {
    lp::ImageRGBA8 img = lp::load_png(argv[1]);
    const std::uint8_t* bg = img.at(0, 0);
    long covered = 0, bright = 0;
    double sum = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const std::uint8_t* p = img.at(x, y);
        int diff = 0, peak = 0;
        for (int c = 0; c < 3; ++c) {
          diff = std::max(diff, std::abs(int(p[c]) - int(bg[c])));
          peak = std::max(peak, int(p[c]));
        }
        if (diff <= 8) continue;
        ++covered;
        sum += peak;
        bright += peak >= 250;
      }
    const double total = double(img.width) * img.height;
    const double fraction = covered / total, mean = covered ? sum / covered : 0, share = covered ? double(bright) / covered : 0;
    std::printf("coverage %.4f, mean brightest channel %.1f, bright share %.4f\n", fraction, mean, share);
    // The shadow against the unshadowed image: object and floor pixels, the floor's darkening.
    struct Shadow {
      long object = 0, floor = 0, darkened = 0;
      int floor_peak = 0;
    };
    auto shadow = [&](const char* unshadowed_path, double min_drop) {
      const lp::ImageRGBA8 plain = lp::load_png(unshadowed_path);
      if (plain.width != img.width || plain.height != img.height) throw std::runtime_error("the images' sizes differ");
      const std::uint8_t* pbg = plain.at(0, 0);
      Shadow s;
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
          const std::uint8_t *p = plain.at(x, y), *q = img.at(x, y);
          int diff = 0, peak = 0, shaded = 0;
          for (int c = 0; c < 3; ++c) {
            diff = std::max(diff, std::abs(int(p[c]) - int(pbg[c])));
            peak = std::max(peak, int(p[c]));
            shaded = std::max(shaded, int(q[c]));
          }
          if (diff <= 8) continue;
          if (p[0] > 1.5 * p[1]) { ++s.object; continue; }
          if (std::abs(int(p[0]) - int(p[1])) > 8 || std::abs(int(p[1]) - int(p[2])) > 8) continue;
          ++s.floor;
          s.floor_peak = std::max({s.floor_peak, peak, shaded});
          s.darkened += shaded <= (1.0 - min_drop) * peak;
        }
      std::printf("object %ld px, floor %ld px (brightest channel up to %d), darkened by %.0f %% or more: %ld px = %.3f x the object\n",
                  s.object, s.floor, s.floor_peak, 100 * min_drop, s.darkened, s.object ? double(s.darkened) / s.object : 0.0);
      return s;
    };
    bool ok = true;
    std::optional<Shadow> last;  // --floor-below reads the --shadow before it
    for (int i = 2; i < argc; ++i) {
      std::string a = argv[i];
      auto num = [&](int k) { return i + k < argc ? std::atof(argv[i + k]) : 0.0; };
      if (a == "--shadow" && i + 3 < argc) {
        last = shadow(argv[i + 1], num(3));
        ok &= last->object > 0 && double(last->darkened) >= num(2) * double(last->object);
        i += 3;
      } else if (a == "--floor-below" && i + 1 < argc) {
        if (!last) { std::fprintf(stderr, "png_coverage: --floor-below needs a --shadow before it\n"); return 2; }
        ok &= last->floor > 0 && last->floor_peak < num(1);
        i += 1;
      }
      else if (a == "--covered") { ok &= fraction >= num(1) && fraction <= num(2); i += 2; }
      else if (a == "--lit") { ok &= mean >= num(1); i += 1; }
      else if (a == "--bright-share") { ok &= share >= num(1) && share <= num(2); i += 2; }
      else { std::fprintf(stderr, "png_coverage: unknown option %s\n", a.c_str()); return 2; }
    }
    std::printf("%s\n", ok ? "within bounds" : "OUT OF BOUNDS");
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "png_coverage: %s\n", e.what());
    return 1;
  }
}
