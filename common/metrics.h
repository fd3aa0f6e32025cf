#pragma once
// What a frame cost, per pass: GPU time from GL_TIME_ELAPSED queries (read a few frames
// later from a ring, so the frame never waits for them). llvmpipe rasterises lazily, so
// its timer queries miss most of the work: there each pass is timed with glFinish and the
// CPU clock instead (honest, at the cost of a stall that a software renderer hardly notices)
// and fragments that passed the depth and stencil tests, counted exactly with
// GL_SAMPLES_PASSED occlusion queries, read as 64-bit numbers. Counts are deterministic: CI
// can assert them. To measure a frame (warm-up, frames, means) use common/measure.h.
//
// No destructor here throws: an OpenGL error seen when a pass ends is recorded (the first
// one, with its pass's name) and error() reports it; the frame loop (App::next_frame,
// measure()) turns it into an Error outside any destructor.
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/gl.h"

namespace lp {

// The result of a finished query as a 64-bit number (glGetQueryObjectui64v): every query
// read in the tree goes through here, so no count is ever truncated to 32 bits on the way.
std::uint64_t query_result_u64(GLuint query);
// GL_QUERY_COUNTER_BITS of a query target (e.g. GL_SAMPLES_PASSED): how wide the
// implementation's counter is. A count equal to 2^bits - 1 may have saturated.
int query_counter_bits(GLenum target);

class PassMetrics {
 public:
  static constexpr int kRing = 4;

  struct Stats {
    std::string name;
    double last_ms = 0, mean_ms = 0, min_ms = 0;
    std::uint64_t samples = 0;  // fragments passed in the last collected frame (GL_SAMPLES_PASSED)
    bool samples_saturated = false;  // `samples` is the counter's largest value: it may be more
    int frames = 0;             // frames collected since reset()
    // Exact counts the chapter made itself in this pass (e.g. with atomic counters: fragments
    // shaded, stencil-marking fragments), reported beside `samples`; see count().
    std::vector<std::pair<std::string, std::uint64_t>> counts;
  };

  class Scope {
   public:
    Scope(Scope&& o) noexcept
        : owner_(o.owner_), index_(o.index_), cpu_ms_(o.cpu_ms_), start_(o.start_) { o.owner_ = nullptr; }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;
    Scope& operator=(Scope&&) = delete;
    ~Scope();  // ends the queries; records an OpenGL error in the pass (never throws)
   private:
    friend class PassMetrics;
    Scope(PassMetrics* owner, std::size_t index, double* cpu_ms);
    PassMetrics* owner_;  // null once moved from
    std::size_t index_;   // the pass
    double* cpu_ms_;      // software renderer: where the CPU-clock time goes; else null
    std::chrono::steady_clock::time_point start_;
  };

  // Measures everything drawn until the returned Scope ends. One scope at a time, and each
  // pass name at most once a frame (wrap a loop of draws in one scope).
  [[nodiscard]] Scope pass(const std::string& name);
  void end_frame();  // gathers results that are ready; never waits
  void wait_all();   // gathers everything still in flight (end of a benchmark or a test)
  void reset();      // forget the statistics (e.g. after warm-up frames)
  void clear();      // forget every pass and allocation too (a new scene: new stages)

  // An exact count the chapter made itself inside pass `pass` (measured this frame or
  // before), reported with the pass's statistics under `what` (replacing an earlier value).
  void count(const std::string& pass, const std::string& what, std::uint64_t value);

  const std::vector<Stats>& stats() const { return stats_; }
  const Stats* find(const std::string& name) const;
  // Times are CPU times with glFinish around each pass (llvmpipe, softpipe; known after the
  // first pass). The environment variable LIGHTPASS_TIMER=queries turns this off.
  bool software() const { return software_ == 1; }

  // The first OpenGL error seen in a pass since the start ("OpenGL reported GL_X in pass
  // 'name'"), or empty. throw_if_error() throws it as an Error: call it from a frame loop.
  const std::string& error() const { return error_; }
  void throw_if_error() const;

  // Render targets the chapter allocated, for the "what does this cost in memory" report.
  void set_allocation(const std::string& name, std::size_t bytes);
  struct Allocation { std::string name; std::size_t bytes; };
  const std::vector<Allocation>& allocations() const { return allocations_; }
  std::size_t allocated_bytes() const;

 private:
  struct Slot {
    gl::Query time{GL_TIME_ELAPSED}, samples{GL_SAMPLES_PASSED};
    bool pending = false;
    std::uint64_t frame = 0;
    double cpu_ms = -1;  // set on software renderers, used instead of the timer query
  };
  struct Pass {
    std::string name;
    Slot slots[kRing];
    std::uint64_t last_frame = ~0ull;
    double sum_ms = 0;
  };
  void collect(Pass& pass, int stats_index, Slot& slot, bool wait);
  void end_scope(std::size_t index, double* cpu_ms, std::chrono::steady_clock::time_point start) noexcept;
  void record_error(GLenum e, const std::string& where) noexcept;

  std::vector<Pass> passes_;
  std::vector<Stats> stats_;
  std::vector<Allocation> allocations_;
  std::uint64_t frame_ = 0;
  int software_ = -1;  // unknown until the first pass: 1 on llvmpipe/softpipe
  int samples_bits_ = 64;
  std::string error_;
  std::string inject_error_in_;  // tests: LIGHTPASS_TEST_GL_ERROR_IN_PASS, see metrics.cpp
};

// A pass timed in `metrics` while the returned scope lives; nothing without metrics (the
// stages that run with or without measurement).
std::optional<PassMetrics::Scope> timed(PassMetrics* metrics, const std::string& name);

}  // namespace lp
