#pragma once
// What a frame cost, per pass: GPU time from GL_TIME_ELAPSED queries (read a few frames
// later from a ring, so the frame never waits for them). llvmpipe rasterises lazily, so
// its timer queries miss most of the work: there each pass is timed with glFinish and the
// CPU clock instead (honest, at the cost of a stall that a software renderer hardly notices)
// and fragments that passed the depth and stencil tests, counted exactly with
// GL_SAMPLES_PASSED occlusion queries. Counts are deterministic: CI can assert them.
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "common/gl.h"

namespace lp {

class PassMetrics {
 public:
  static constexpr int kRing = 4;

  struct Stats {
    std::string name;
    double last_ms = 0, mean_ms = 0, min_ms = 0;
    std::uint64_t samples = 0;  // fragments passed in the last collected frame
    int frames = 0;             // frames collected since reset()
  };

  class Scope {
   public:
    Scope(Scope&& o) noexcept : active_(o.active_), name_(o.name_), cpu_ms_(o.cpu_ms_), start_(o.start_) { o.active_ = false; }
    Scope(const Scope&) = delete;
    ~Scope() noexcept(false);  // throws Error naming the pass if OpenGL reported an error in it
   private:
    friend class PassMetrics;
    Scope(const std::string* name, double* cpu_ms);
    bool active_ = true;
    const std::string* name_;
    double* cpu_ms_;  // software renderer: where the CPU-clock time goes; else null
    std::chrono::steady_clock::time_point start_;
  };

  // Measures everything drawn until the returned Scope ends. One scope at a time, and each
  // pass name at most once a frame (wrap a loop of draws in one scope).
  [[nodiscard]] Scope pass(const std::string& name);
  void end_frame();  // gathers results that are ready; never waits
  void wait_all();   // gathers everything still in flight (end of a benchmark or a test)
  void reset();      // forget the statistics (e.g. after warm-up frames)

  const std::vector<Stats>& stats() const { return stats_; }
  const Stats* find(const std::string& name) const;

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

  std::vector<Pass> passes_;
  std::vector<Stats> stats_;
  std::vector<Allocation> allocations_;
  std::uint64_t frame_ = 0;
  int software_ = -1;  // unknown until the first pass: 1 on llvmpipe/softpipe
};

}  // namespace lp
