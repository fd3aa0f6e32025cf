#pragma once
// The maths of the HDR stage on the CPU: luminance, the policy for values a float buffer
// should not hold (NaN, infinities, negatives, more than fp16 can store), the log-luminance
// that the average is taken of, the tonemapping operators, eye adaptation and the bloom
// bright pass. shaders/hdr_math.glsl says the same in GLSL; the unit tests hold this file
// to the formulas, the GPU tests hold the GLSL to this file.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace lp::ch05 {

// The largest finite half float: an RGBA16F target cannot hold more.
inline constexpr float kHalfMax = 65504.f;

// [luminance]
// Relative luminance of linear Rec. 709 / sRGB primaries.
inline float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }
// [/luminance]

// [sanitize]
// What the HDR stage does with values a radiance buffer should not contain:
//  - NaN in any channel: the pixel is invalid. It is left out of the average luminance
//    (its weight is 0), shown black, and adds nothing to bloom.
//  - +Inf, or more than fp16's 65504: the value overflowed, so it was at least that bright.
//    It is read as 65504 everywhere (average, bloom, image), as if clamped when written.
//  - Negative values and -Inf: no light is negative; read as 0.
struct Sanitized {
  glm::vec3 rgb{0};
  bool valid = true;
};

inline Sanitized sanitize(const glm::vec3& c) {
  if (std::isnan(c.r) || std::isnan(c.g) || std::isnan(c.b)) return {glm::vec3(0), false};
  return {glm::clamp(c, glm::vec3(0), glm::vec3(kHalfMax)), true};
}
// [/sanitize]

// [log-luminance]
// One pixel's term of the log-average: log(delta + L). delta keeps black pixels finite
// (log 0 = -inf); the average of a black frame is exactly log(delta).
inline float log_luminance(const glm::vec3& sanitized_rgb, float delta) {
  return std::log(delta + luminance(sanitized_rgb));
}
// [/log-luminance]

// [operators]
// Tonemapping operators: exposed scene value x >= 0 in, display value in [0, 1] out,
// applied to each colour channel.
enum class Operator { Clamp, Reinhard, ReinhardExtended, Aces };

// No curve: whatever exposure pushes past 1 is lost (what an 8-bit display does).
inline float tonemap_clamp(float x) { return std::min(x, 1.f); }

// Reinhard's x / (1 + x), the operator of the source: 0 -> 0, 1 -> 1/2, approaches 1 but
// never reaches it, so no value is ever white.
inline float tonemap_reinhard(float x) { return x / (1.f + x); }

// Reinhard's extended form: the same curve bent so that `white` maps to exactly 1; values
// above it burn out to white.
inline float tonemap_reinhard_extended(float x, float white) {
  float y = x * (1.f + x / (white * white)) / (1.f + x);
  return std::min(y, 1.f);
}

// A filmic curve: Narkowicz's rational fit to the ACES reference rendering transform
// (2015). A toe that deepens the darks, a shoulder that rolls off to white at x ~ 7.2.
inline float tonemap_aces(float x) {
  float y = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
  return std::clamp(y, 0.f, 1.f);
}

inline float tonemap(Operator op, float x, float white) {
  switch (op) {
    case Operator::Clamp: return tonemap_clamp(x);
    case Operator::Reinhard: return tonemap_reinhard(x);
    case Operator::ReinhardExtended: return tonemap_reinhard_extended(x, white);
    case Operator::Aces: return tonemap_aces(x);
  }
  return 0.f;
}
// [/operators]

// The slope of each curve, dT/dx, where it is not clamped (0 where it is).
inline double tonemap_slope(Operator op, double x, double white) {
  switch (op) {
    case Operator::Clamp: return x < 1.0 ? 1.0 : 0.0;
    case Operator::Reinhard: return 1.0 / ((1.0 + x) * (1.0 + x));
    case Operator::ReinhardExtended:
      if (x * (1.0 + x / (white * white)) / (1.0 + x) >= 1.0) return 0.0;
      return (1.0 + x * (2.0 + x) / (white * white)) / ((1.0 + x) * (1.0 + x));
    case Operator::Aces: {
      double n = x * (2.51 * x + 0.03), d = x * (2.43 * x + 0.59) + 0.14;
      if (n / d >= 1.0) return 0.0;
      return ((5.02 * x + 0.03) * d - n * (4.86 * x + 0.59)) / (d * d);
    }
  }
  return 0.0;
}

// [output-slope]
// How steeply a curve turns exposed light into output steps, relative to the steepest an
// sRGB output can be without a curve: the largest d/dx srgb(T(x)) over x >= 0, divided by
// 12.92 (the sRGB encoding's slope at black, where chapter 03's kSrgbFirstStep comes from).
// Light that moves x by less than kSrgbFirstStep / output_slope moves no output pixel by a
// whole step. Reinhard, clamp and extended Reinhard (white >= 1) are steepest at black with
// slope 1: 1. ACES's toe is flat (0.21 at black); its steepest point is where its output
// leaves sRGB's linear segment (0.0031308): 0.495. The maximum is searched on a grid of 200
// points a decade, plus 0 and that point, and rounded up by 10^-3 (the unit test checks a
// grid ten times finer).
inline double srgb_encode_slope(double linear) {
  return linear <= 0.0031308 ? 12.92 : 1.055 / 2.4 * std::pow(linear, 1.0 / 2.4 - 1.0);
}
inline float output_slope(Operator op, float white) {
  auto slope = [&](double x) {
    return srgb_encode_slope(tonemap(op, float(x), white)) * tonemap_slope(op, x, white) / 12.92;
  };
  double lo = 0, hi = 1e3;  // the last x in sRGB's linear segment (T is monotonic)
  for (int i = 0; i < 200; ++i) {
    double mid = 0.5 * (lo + hi);
    (double(tonemap(op, float(mid), white)) <= 0.0031308 ? lo : hi) = mid;
  }
  double best = std::max(slope(0.0), slope(lo));
  for (int i = -7 * 200; i <= 3 * 200; ++i) best = std::max(best, slope(std::pow(10.0, i / 200.0)));
  return float(best * (1.0 + 1e-3));
}
// [/output-slope]

// [adapt]
// Eye adaptation: the adapted luminance moves towards the frame's log-average with time
// constant tau (seconds). After tau it has covered 63% of the way, after 3 tau 95%. The
// factor 1 - exp(-dt / tau) makes the result independent of the frame rate: two frames of
// dt end where one frame of 2 dt does. tau = 0 adapts at once.
inline float adapt(float adapted, float target, float dt, float tau) {
  if (tau <= 0.f) return target;
  return adapted + (target - adapted) * (1.f - std::exp(-dt / tau));
}
// [/adapt]

// [exposure]
// The exposure that shows the eye's adapted luminance at `key` (middle grey): key / adapted.
// Alone, that makes every scene average grey, the night street a grey day. An eye (or a
// camera) adapts only so far into the dark: below `adapt_floor` it stops, the exposure stays
// key / adapt_floor, and a darker scene is shown darker. As a key that falls with the scene's
// luminance: the log-average is shown at key x min(1, adapted / adapt_floor).
// adapt_floor = 0 is the fixed key at any light.
inline float exposure_for(float key, float adapted, float adapt_floor) { return key / std::max(adapted, adapt_floor); }
// [/exposure]

// [bright-pass]
// What of an exposed pixel x blooms: the part of its luminance above `threshold`, with
// x's colour, limited to `limit` so that a single extreme pixel (a firefly, an overflowed
// value) cannot flood the screen once blurred.
inline glm::vec3 bright_pass(const glm::vec3& x, float threshold, float limit) {
  float y = luminance(x);
  if (y <= threshold || y <= 0.f) return glm::vec3(0);
  float excess = std::min(y - threshold, limit);
  return x * (excess / y);
}
// [/bright-pass]

// Operator names for the command line and the book.
inline const std::vector<std::string> kOperatorNames = {"clamp", "reinhard", "reinhard-extended", "aces"};

}  // namespace lp::ch05
