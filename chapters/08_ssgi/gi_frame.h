#pragma once
// Chapter 08's frame for the tests and the sweep: chapter 03's deferred frame with the scene's
// lights (cut as chapter 07's program cuts them) and the GI stage, drawn into an off-screen
// sRGB target; the stage's result read back at the image's size.
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/08_ssgi/gi_stage.h"
#include "common/measure.h"
#include "common/target.h"

namespace lp::ch08 {

class GiFrame {
 public:
  GiFrame(const SceneGpu& scene, int width, int height);
  // One frame in `mode`; returns rgb L1_ind and a = A (rows top to bottom; 0 and 1 when off).
  ImageF indirect(const FrameCamera& camera, GiMode mode, const GiSettings& settings);
  ImageRGBA8 image(const FrameCamera& camera, GiMode mode, const GiSettings& settings, GiShow show = GiShow::Image,
                   float ambient_scale = 1.f, float exposure = 1.f);
  // The SSGI pass measured (common/measure.h): its mean and fastest over `frames` frames.
  PassMeasurement time(const FrameCamera& camera, GiMode mode, const GiSettings& settings, int frames);
  ch03::DeferredFrame& frame() { return frame_; }
  GiStage& stage() { return stage_; }
  const ch03::LightSet& lights() const { return frame_.volumes().lights(); }
  PassMetrics& metrics() { return metrics_; }

 private:
  const SceneGpu& scene_;
  int width_, height_;
  ch03::DeferredFrame frame_;
  GiStage stage_;
  OutputTarget target_;
  PassMetrics metrics_;
};

}  // namespace lp::ch08
