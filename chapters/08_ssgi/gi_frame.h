#pragma once
// Chapter 08's frame for the tests and the sweep: chapter 03's deferred frame with the scene's
// lights (cut as chapter 07's program cuts them) and the GI stage, drawn into an off-screen
// sRGB target; the stage's result read back at the image's size. With a guard band (pixels on
// every side, guard_band.h) the frame is drawn wider and everything returned is the screen's part.
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/08_ssgi/gi_stage.h"
#include "chapters/08_ssgi/guard_band.h"
#include "common/measure.h"
#include "common/target.h"

namespace lp::ch08 {

class GiFrame {
 public:
  GiFrame(const SceneGpu& scene, int width, int height, int guard_band = 0);
  // One frame in `mode`; returns rgb L1_ind and a = A (rows top to bottom; 0 and 1 when off).
  ImageF indirect(const FrameCamera& camera, GiMode mode, const GiSettings& settings);
  ImageRGBA8 image(const FrameCamera& camera, GiMode mode, const GiSettings& settings, GiShow show = GiShow::Image,
                   float ambient_scale = 1.f, float exposure = 1.f);
  // The SSGI pass measured (common/measure.h): its mean and fastest over `frames` frames.
  PassMeasurement time(const FrameCamera& camera, GiMode mode, const GiSettings& settings, int frames);
  // Every pass of the frame measured (the whole frame's cost: total_ms()).
  Measurement measure_frame(const FrameCamera& camera, GiMode mode, const GiSettings& settings, int frames);
  static std::string pass_name(GiMode mode, const GiSettings& settings);
  ch03::DeferredFrame& frame() { return frame_; }
  GiStage& stage() { return stage_; }
  const ch03::LightSet& lights() const { return frame_.volumes().lights(); }
  PassMetrics& metrics() { return metrics_; }
  const GuardBand& guard_band() const { return band_; }

 private:
  const SceneGpu& scene_;
  int width_, height_;
  GuardBand band_;
  ch03::DeferredFrame frame_;
  GiStage stage_;
  OutputTarget target_;
  PassMetrics metrics_;
  void render(const FrameCamera& camera, PassMetrics* metrics = nullptr);
};

}  // namespace lp::ch08
