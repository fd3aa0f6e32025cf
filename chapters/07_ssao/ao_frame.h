#pragma once
// Chapter 07's frame for the tests and the sweep: chapter 03's deferred frame with the AO
// stage, drawn into an off-screen sRGB target, the AO read back at the image's size.
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/07_ssao/ao_stage.h"
#include "common/measure.h"
#include "common/target.h"

namespace lp::ch07 {

class AoFrame {
 public:
  AoFrame(const SceneGpu& scene, int width, int height);
  // Renders one frame with `settings` (the AO term shown) and returns A at the image's size,
  // rows top to bottom (1 on the sky).
  ImageF ao(const FrameCamera& camera, const AoSettings& settings);
  ImageRGBA8 image(const FrameCamera& camera, const AoSettings& settings, AoShow show, float ambient_scale = 1.f);
  // The AO pass measured (common/measure.h): its mean and fastest over `frames` frames.
  PassMeasurement time(const FrameCamera& camera, const AoSettings& settings, int frames);
  PassMetrics& metrics() { return metrics_; }
  ch03::DeferredFrame& frame() { return frame_; }

 private:
  const SceneGpu& scene_;
  int width_, height_;
  ch03::DeferredFrame frame_;
  AoStage stage_;
  OutputTarget target_;
  PassMetrics metrics_;
};

}  // namespace lp::ch07
