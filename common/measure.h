#pragma once
// The one way the book measures a frame: every sweep and --bench call it.
//
//   Measurement m = measure(metrics, [&] { { auto p = metrics.pass("forward"); draw(); } });
//   m.pass("forward").mean_ms;  m.pass("forward").fragments;  m.frames;
//
// The frame callback draws one frame with its passes in PassMetrics scopes (measure() ends
// each frame). Warm-up first, then `frames` frames, every one of them read back before
// measure() returns: the means are over exactly `Measurement::frames` frames.
//
// [warm-up]
// Warm-up, until the times settle: a GPU raises its clocks only under load, and a short
// pass timed from cold can read several times slower. Frames
// are rendered in blocks of at least `block_frames` frames and `block_seconds` of wall
// clock, each block's mean frame time (the sum of its passes' mean times) read back at its
// end. Warm-up ends at the first block, once at least `min_seconds` have passed, whose mean is
// within `tolerance` of the previous block's; it ends anyway after `max_seconds` (then
// Measurement::settled is false: measure() warns, --bench's JSON says so).
// [/warm-up]
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/metrics.h"

namespace lp {

struct WarmupPolicy {
  int block_frames = 3;         // a block: at least this many frames ...
  double block_seconds = 0.1;   // ... and at least this much wall-clock time
  double min_seconds = 0.5;     // never settle before this much warm-up
  double tolerance = 0.03;      // settled: |block mean - previous block mean| <= 3 % of it
  double max_seconds = 5.0;     // give up waiting for it to settle (settled = false)
};

struct MeasureOptions {
  WarmupPolicy warmup = {};
  int frames = 20;            // measured frames after the warm-up (at least 1)
  bool skip_warmup = false;   // e.g. one frame to read its fragment counts, no times wanted
  // Also time each whole measured frame by the wall clock, with glFinish before and after
  // (the frame then never overlaps the next: what a frame costs end to end).
  bool wall_clock = false;
};

struct PassMeasurement {
  std::string name;
  double mean_ms = 0, min_ms = 0;  // over the measured frames (GPU time; CPU time on llvmpipe)
  std::uint64_t fragments = 0;     // GL_SAMPLES_PASSED of the last frame: fragments that passed
                                   // the depth and stencil tests, in every draw of the pass
  bool fragments_saturated = false;  // the query counter's largest value: it may be more
  int frames = 0;                  // frames this pass was measured in
  std::vector<std::pair<std::string, std::uint64_t>> counts;  // the chapter's own (PassMetrics::count)
  std::optional<std::uint64_t> count(const std::string& what) const;
};

struct Measurement {
  std::vector<PassMeasurement> passes;  // in the order they were first drawn
  int frames = 0;           // frames measured and read back (what the means are over)
  int warmup_frames = 0;    // frames rendered before them
  double warmup_seconds = 0;
  bool settled = false;     // the warm-up ended because times settled (false: it stopped at
                            // max_seconds with times still moving, or was skipped)
  double wall_ms = 0;       // with MeasureOptions::wall_clock: mean wall-clock ms per frame
  // Mean CPU (wall-clock) ms per measured frame from the frame's start to its end, without
  // the measurement's own read-back: the time to submit it. A read-back that waits for the GPU
  // inside the frame shows here, where the GPU's pass times cannot show it. On llvmpipe it
  // holds the rendering too (the CPU draws).
  double cpu_ms = 0;
  bool software = false;    // llvmpipe: the times are CPU times (glFinish around each pass)

  const PassMeasurement& pass(const std::string& name) const;  // throws Error if never measured
  const PassMeasurement* find(const std::string& name) const;
  double total_ms() const;  // sum of the passes' mean times
};

// The measurement as a loop the caller drives, for a frame loop that is not a callback
// (App's --bench): call frame_done() after each frame (it ends the frame in `metrics`);
// it returns false when no more frames are wanted, then result() has the numbers.
class MeasureLoop {
 public:
  MeasureLoop(PassMetrics& metrics, MeasureOptions options);
  bool frame_done();  // throws Error with the first OpenGL error a pass saw
  Measurement result() const;
  bool warming_up() const { return warming_; }

 private:
  bool step();  // frame_done() without its CPU clock
  double block_mean_ms() const;
  void start_block();
  PassMetrics& metrics_;
  MeasureOptions options_;
  bool warming_ = true;
  int warmup_frames_ = 0, block_count_ = 0, block_frames_ = 0, measured_ = 0;
  double previous_block_ms_ = -1;
  bool settled_ = false;
  double warmup_seconds_ = 0, wall_ms_ = 0, cpu_ms_ = 0;
  std::chrono::steady_clock::time_point start_, block_start_, frame_start_, cpu_start_;
};

// Warm-up, then options.frames frames of `frame`, all read back.
Measurement measure(PassMetrics& metrics, const std::function<void()>& frame, const MeasureOptions& options = {});

// What every CSV a sweep writes ends each row with, so that a table always says what
// measured it: the columns "renderer,width,height,frames" (the context's GL_RENDERER, the
// size rendered, the frames measured: 1 for a row from one frame), and one row's values,
// the renderer quoted as CSV wants when it holds a comma ("llvmpipe (LLVM 15.0.6, 256 bits)").
std::string csv_measure_columns();
std::string csv_measure_values(const std::string& renderer, int width, int height, int frames);
std::string csv_quoted(const std::string& text);  // as a CSV field: quoted when it needs to be

}  // namespace lp
