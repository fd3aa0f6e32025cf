// png_coverage FILE [--covered LO HI] [--lit MIN] [--bright-share LO HI]
// What a rendered image shows, for the scene-input tests: the pixels that differ from the
// top-left corner (the background) by more than 8 steps in a channel are "covered"; their
// mean brightest channel must reach --lit (0..255); the share of covered pixels whose
// brightest channel is >= 250 ("bright", e.g. emitting) must lie in --bright-share.
// Prints the numbers; exit 0 when every given bound holds, 1 otherwise.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "common/image.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: png_coverage FILE [--covered LO HI] [--lit MIN] [--bright-share LO HI]\n");
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
    bool ok = true;
    for (int i = 2; i < argc; ++i) {
      std::string a = argv[i];
      auto num = [&](int k) { return i + k < argc ? std::atof(argv[i + k]) : 0.0; };
      if (a == "--covered") { ok &= fraction >= num(1) && fraction <= num(2); i += 2; }
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
