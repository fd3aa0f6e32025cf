#pragma once
// The exposure a frame will get, known before the frame is drawn, without waiting for the
// GPU. Chapter 03 cuts each light's volume where the light falls below one output step, and
// with HDR that step is divided by the exposure: a frame exposed more needs longer volumes.
// But the exposure is computed on the GPU from the frame's own radiance, after the volumes
// are drawn; reading it back in the same frame would stall the CPU until the GPU finished.
//
// So each frame copies the eye's state into a small ring of persistently mapped slots,
// behind a fence, and a later frame reads the newest slot whose fence has passed, never
// waiting for the frame it draws (the ring also limits the frames in flight to its size,
// as a swap chain does: a reading is at most that many frames old). The adaptation rule
// itself bounds how far the exposure can have risen since that reading
// (exposure_bound_after); before any reading arrives, the stage's own limit holds
// (exposure_limit).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "chapters/05_hdr/eye_adaptation.h"
#include "common/gl.h"

namespace lp::ch05 {

// [exposure-bound]
// adapt() moves the adapted luminance by (target - adapted)(1 - e), e = exp(-dt / tau), and
// the target (a log-average) is never negative, so one frame can shrink it at most to
// e x adapted. After the frames m+1 .. n:
//     adapted_n >= adapted_m exp(-sum dt/tau),   exposure_n = key / max(adapted_n, floor)
//                                                <= key / max(adapted_m exp(-sum dt/tau), floor).
// `decay` is that sum. The GPU's float arithmetic (its exp() is allowed 3 + 2|x| ulp, a few
// roundings more) stays below 10^-6 of the value a frame: that much is added per frame.
// With tau = 0 the eye follows the frame at once and nothing bounds the next exposure.
inline float exposure_bound_after(const AdaptationSettings& s, float adapted_then, double decay, std::uint64_t frames) {
  const double lowest = std::max(double(adapted_then) * std::exp(-decay), double(s.adapt_floor));
  return float(double(s.key) / lowest * (1.0 + 1e-6 * double(frames)));
}

// With nothing known: the log-average exp(mean log(delta + L)) is at least delta, the eye
// starts at start_scale x a log-average and only ever moves between that and later ones,
// so adapted >= delta x min(1, start_scale) and the exposure is at most key over that (or
// over the floor, if higher). (Plus 10^-3 for the GPU's float reduction, which is within
// 10^-4 of the exact mean log.)
inline float exposure_limit(const AdaptationSettings& s, float delta, float start_scale) {
  const double lowest = std::max(double(delta) * std::min(1.0, double(start_scale)), double(s.adapt_floor));
  return float(double(s.key) / lowest * (1.0 + 1e-3));
}
// [/exposure-bound]

struct ExposureEstimate {
  float exposure = 0;  // at least the exposure of the frame it was asked for
  int age = -1;        // frames since the reading it comes from; -1: none (the stage's limit)
  float read = 0;      // the exposure that reading had (0 when none)
};

class ExposureFeedback {
 public:
  explicit ExposureFeedback(int slots = 3);
  ~ExposureFeedback();
  ExposureFeedback(const ExposureFeedback&) = delete;
  ExposureFeedback& operator=(const ExposureFeedback&) = delete;

  // The eye is reset this frame (HdrPipeline::reset_adaptation): earlier readings say nothing.
  void reset() { ++generation_; }
  // Once a frame, before drawing it: an exposure at least as large as the one the stage will
  // compute for this frame with these settings. Never waits for the GPU.
  ExposureEstimate begin_frame(const AdaptationSettings& settings, float delta, float start_scale);
  // After HdrPipeline::process: queue a copy of the eye's state (EyeAdaptation::state_buffer)
  // for a later frame to read.
  void end_frame(GLuint state_buffer);
  // The newest state read back (nullptr before the first), and how many frames old it is:
  // for a panel that must not wait either.
  const ExposureState* latest() const { return last_.valid ? &last_.state : nullptr; }
  int latest_age() const { return last_.valid ? int(frame_ - last_.frame) : -1; }

 private:
  struct Slot {
    GLsync fence = nullptr;
    std::uint64_t frame = 0, generation = 0;
    double decay = 0;
  };
  struct Reading {
    bool valid = false;
    ExposureState state{};
    std::uint64_t frame = 0, generation = 0;
    double decay = 0;
  };
  void poll();
  void limit_frames_in_flight();

  gl::Buffer ring_;
  const ExposureState* mapped_ = nullptr;
  std::vector<Slot> slots_;
  std::uint64_t frame_ = 0, generation_ = 0;
  std::uint64_t last_instant_ = 0;  // the last frame drawn with tau = 0
  double decay_ = 0;                // sum of dt / tau over the frames so far
  Reading last_;
};

}  // namespace lp::ch05
