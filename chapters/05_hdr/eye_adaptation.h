#pragma once
// Eye adaptation on the GPU: each frame, one thread moves the adapted luminance towards the
// frame's log-average (hdr_math.h: adapt) and turns it into an exposure, key / adapted
// (exposure_for: adapted no further into the dark than a floor).
// The state lives in a storage buffer that the bloom and tonemapping passes read, so the
// frame never waits for a read-back.
#include "chapters/05_hdr/hdr_buffers.h"
#include "common/gl.h"
#include "common/shader.h"

namespace lp::ch05 {


struct AdaptationSettings {
  float key = 0.18f;          // the exposed value the average maps to ("middle grey")
  // The darkest luminance the eye adapts to (exposure_for, hdr_math.h): a scene darker than
  // this is shown darker than middle grey. 0.18 = key / 1: the exposure never exceeds 1, the
  // exposure at which the scenes were lit for the display (assets/README.md). 0: the fixed key.
  float adapt_floor = 0.18f;
  float tau = 0.5f;           // time constant in seconds; 0 adapts at once
  float dt = 1.f / 60.f;      // seconds since the last frame (fixed when headless)
};

class EyeAdaptation {
 public:
  EyeAdaptation();
  void reload_shaders() { update_.reload(); }

  // The next update starts from scratch: adapted = start_scale x that frame's log-average
  // (1: already adapted; 30: coming from a scene 30 times brighter).
  void reset(float start_scale = 1.f) { reset_ = true; start_scale_ = start_scale; }
  // Reads the LogAverageResult in `log_average_buffer`, writes state_buffer().
  void update(GLuint log_average_buffer, const AdaptationSettings& settings);
  GLuint state_buffer() const { return state_.id(); }
  ExposureState read() const;  // waits for the GPU

 private:
  ShaderProgram update_;
  gl::Buffer state_;
  bool reset_ = true;
  float start_scale_ = 1.f;
};

}  // namespace lp::ch05
