#pragma once
// Chapter 05's stage: from a float radiance texture to the displayed image.
//
//   radiance (RGBA16F) --> log-average --> eye adaptation --> [bloom] --> tonemap --> sRGB8
//
// The input is only "a radiance texture and its size": whatever renders the lit scene
// (chapter 03's deferred path in the program, chapter 01's forward renderer in the tests)
// hands its texture to process(). The pieces are usable alone too: LogAverage,
// EyeAdaptation, Bloom, Tonemapper.
#include <string>
#include <vector>

#include "chapters/05_hdr/bloom.h"
#include "chapters/05_hdr/eye_adaptation.h"
#include "chapters/05_hdr/log_average.h"
#include "chapters/05_hdr/tonemapper.h"
#include "common/metrics.h"

namespace lp::ch05 {


// [settings]
struct HdrSettings {
  AverageMethod average = AverageMethod::MipChain;
  float delta = 1e-4f;              // keeps log(delta + L) finite on black pixels
  AdaptationSettings adaptation;    // key, tau, dt
  TonemapSettings tonemap;          // operator, white point
  BloomMode bloom = BloomMode::Off;
  BloomSettings bloom_chain;        // level (resolution), radius, threshold, limit
  float bloom_strength = 0.08f;
  enum class View { Final, BrightPass, Bloom } view = View::Final;  // debug views of the bloom
};
// [/settings]

class HdrPipeline {
 public:
  HdrPipeline() = default;
  void reload_shaders();

  // Tonemaps `radiance` (width x height) into `output_framebuffer` (an sRGB8 target for the
  // reader; a float one in the tests). With `metrics`, each pass is timed on its own.
  void process(GLuint radiance, int width, int height, const HdrSettings& settings, GLuint output_framebuffer,
               PassMetrics* metrics = nullptr);

  // The next frame's eye starts adapted to start_scale x its own average (see EyeAdaptation).
  void reset_adaptation(float start_scale = 1.f) { adaptation_.reset(start_scale); }

  const LogAverage& log_average() const { return log_average_; }
  const EyeAdaptation& adaptation() const { return adaptation_; }
  const Bloom& bloom() const { return bloom_; }
  std::size_t allocated_bytes() const { return log_average_.allocated_bytes() + bloom_.allocated_bytes(); }

 private:
  LogAverage log_average_;
  EyeAdaptation adaptation_;
  Bloom bloom_;
  Tonemapper tonemapper_;
};

}  // namespace lp::ch05
