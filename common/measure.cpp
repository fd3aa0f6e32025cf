#include "common/measure.h"

#include <algorithm>
#include <cmath>
#include <iostream>

#include "common/error.h"

namespace lp {

namespace {
double seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }
}  // namespace

std::optional<std::uint64_t> PassMeasurement::count(const std::string& what) const {
  for (const auto& [name, value] : counts)
    if (name == what) return value;
  return std::nullopt;
}

const PassMeasurement* Measurement::find(const std::string& name) const {
  for (const auto& p : passes)
    if (p.name == name) return &p;
  return nullptr;
}

const PassMeasurement& Measurement::pass(const std::string& name) const {
  if (const PassMeasurement* p = find(name)) return *p;
  throw Error("internal: no pass '" + name + "' was measured");
}

double Measurement::total_ms() const {
  double t = 0;
  for (const auto& p : passes) t += p.mean_ms;
  return t;
}

MeasureLoop::MeasureLoop(PassMetrics& metrics, MeasureOptions options) : metrics_(metrics), options_(options) {
  if (options_.frames < 1) throw Error("internal: measure() needs at least one frame");
  metrics_.reset();
  warming_ = !options_.skip_warmup;
  start_ = block_start_ = frame_start_ = std::chrono::steady_clock::now();
  if (!warming_ && options_.wall_clock) {
    glFinish();
    frame_start_ = std::chrono::steady_clock::now();
  }
  cpu_start_ = std::chrono::steady_clock::now();
}

double MeasureLoop::block_mean_ms() const {
  double t = 0;
  for (const auto& s : metrics_.stats())
    if (s.frames > 0) t += s.mean_ms;
  return t;
}

void MeasureLoop::start_block() {
  block_frames_ = 0;
  block_start_ = std::chrono::steady_clock::now();
}

bool MeasureLoop::frame_done() {
  // The frame's CPU time ends here, before this function's own glFinish and read-backs.
  if (!warming_) cpu_ms_ += 1e3 * seconds(std::chrono::steady_clock::now() - cpu_start_);
  const bool more = step();
  cpu_start_ = std::chrono::steady_clock::now();
  return more;
}

bool MeasureLoop::step() {
  if (!warming_ && options_.wall_clock) {
    glFinish();
    wall_ms_ += 1e3 * seconds(std::chrono::steady_clock::now() - frame_start_);
  }
  metrics_.end_frame();
  metrics_.throw_if_error();
  const auto now = std::chrono::steady_clock::now();
  if (warming_) {
    ++warmup_frames_;
    ++block_frames_;
    const WarmupPolicy& w = options_.warmup;
    if (block_frames_ < w.block_frames || seconds(now - block_start_) < w.block_seconds) return true;
    // A block is complete: its mean frame time, every frame of it read back.
    metrics_.wait_all();
    metrics_.throw_if_error();
    const double mean = block_mean_ms();
    const double elapsed = seconds(now - start_);
    const bool settled = previous_block_ms_ >= 0 && elapsed >= w.min_seconds &&
                         std::abs(mean - previous_block_ms_) <= w.tolerance * previous_block_ms_;
    ++block_count_;
    previous_block_ms_ = mean;
    metrics_.reset();
    if (!settled && elapsed < w.max_seconds) {
      start_block();
      return true;
    }
    warming_ = false;
    settled_ = settled;
    warmup_seconds_ = elapsed;
    if (options_.wall_clock) glFinish();
    frame_start_ = std::chrono::steady_clock::now();
    return true;
  }
  if (++measured_ < options_.frames) {
    if (options_.wall_clock) {
      glFinish();
      frame_start_ = std::chrono::steady_clock::now();
    }
    return true;
  }
  metrics_.wait_all();  // every frame reported is a frame read back
  metrics_.throw_if_error();
  return false;
}

Measurement MeasureLoop::result() const {
  Measurement m;
  for (const auto& s : metrics_.stats()) {
    if (s.frames == 0) continue;  // drawn in the warm-up only
    m.passes.push_back({.name = s.name, .mean_ms = s.mean_ms, .min_ms = s.min_ms, .fragments = s.samples,
                        .fragments_saturated = s.samples_saturated, .frames = s.frames, .counts = s.counts});
    m.frames = std::max(m.frames, s.frames);
  }
  m.warmup_frames = warmup_frames_;
  m.warmup_seconds = warmup_seconds_;
  m.settled = settled_;
  m.wall_ms = measured_ > 0 && options_.wall_clock ? wall_ms_ / measured_ : 0.0;
  m.cpu_ms = measured_ > 0 ? cpu_ms_ / measured_ : 0.0;
  m.software = metrics_.software();
  return m;
}

Measurement measure(PassMetrics& metrics, const std::function<void()>& frame, const MeasureOptions& options) {
  MeasureLoop loop(metrics, options);
  do frame();
  while (loop.frame_done());
  Measurement m = loop.result();
  if (!m.settled && !options.skip_warmup)
    std::cerr << "warning: frame times had not settled after " << m.warmup_seconds << " s of warm-up ("
              << m.warmup_frames << " frames); measuring anyway\n";
  return m;
}

std::string csv_measure_columns() { return "renderer,width,height,frames"; }

std::string csv_quoted(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string q = "\"";
  for (char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string csv_measure_values(const std::string& renderer, int width, int height, int frames) {
  return csv_quoted(renderer) + ',' + std::to_string(width) + ',' + std::to_string(height) + ',' + std::to_string(frames);
}

}  // namespace lp
