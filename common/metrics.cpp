#include "common/metrics.h"

#include <algorithm>
#include <cstdlib>
#include <string>

#include "common/error.h"

namespace lp {

std::uint64_t query_result_u64(GLuint query) {
  GLuint64 value = 0;
  glGetQueryObjectui64v(query, GL_QUERY_RESULT, &value);
  return value;
}

int query_counter_bits(GLenum target) {
  GLint bits = 0;
  glGetQueryiv(target, GL_QUERY_COUNTER_BITS, &bits);
  return bits;
}

PassMetrics::Scope::Scope(PassMetrics* owner, std::size_t index, double* cpu_ms)
    : owner_(owner), index_(index), cpu_ms_(cpu_ms) {
  if (cpu_ms_) {
    glFinish();
    start_ = std::chrono::steady_clock::now();
  }
}

PassMetrics::Scope::~Scope() {
  if (owner_) owner_->end_scope(index_, cpu_ms_, start_);
}

void PassMetrics::end_scope(std::size_t index, double* cpu_ms, std::chrono::steady_clock::time_point start) noexcept {
  if (cpu_ms) {
    glFinish();
    *cpu_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  glEndQuery(GL_TIME_ELAPSED);
  glEndQuery(GL_SAMPLES_PASSED);
  // Say which pass went wrong, not just that something did. Recorded, never thrown: this
  // runs in a destructor, perhaps while another exception unwinds the frame, or inside a
  // noexcept one (std::optional<Scope>); the frame loop reports it (throw_if_error()).
  if (GLenum e = glGetError(); e != GL_NO_ERROR) record_error(e, "in pass '" + passes_[index].name + "'");
}

void PassMetrics::record_error(GLenum e, const std::string& where) noexcept {
  if (!error_.empty()) return;  // the first one is the one that explains the rest
  try {
    error_ = std::string("OpenGL reported ") + gl::error_name(e) + " " + where;
  } catch (...) {
    error_ = "OpenGL error";  // out of memory naming it: 12 characters need no allocation
  }
}

void PassMetrics::throw_if_error() const {
  if (!error_.empty()) throw Error(error_);
}

PassMetrics::Scope PassMetrics::pass(const std::string& name) {
  auto it = std::find_if(passes_.begin(), passes_.end(), [&](const Pass& p) { return p.name == name; });
  if (it == passes_.end()) {
    passes_.emplace_back();
    passes_.back().name = name;
    stats_.push_back(Stats{.name = name});
    it = passes_.end() - 1;
  }
  if (it->last_frame == frame_) throw Error("internal: pass '" + name + "' measured twice in one frame");
  if (software_ < 0) {
    std::string renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    software_ = renderer.find("llvmpipe") != std::string::npos || renderer.find("softpipe") != std::string::npos;
    // LIGHTPASS_TIMER=queries: GL_TIME_ELAPSED queries even on llvmpipe, no glFinish (to see
    // what they say there, and for tests of results that arrive frames late, as on a GPU).
    if (const char* timer = std::getenv("LIGHTPASS_TIMER"); timer && std::string(timer) == "queries") software_ = 0;
    samples_bits_ = query_counter_bits(GL_SAMPLES_PASSED);
    // Tests of the error path: a deliberate GL error inside the named pass of any program.
    if (const char* inject = std::getenv("LIGHTPASS_TEST_GL_ERROR_IN_PASS")) inject_error_in_ = inject;
  }
  // An error left by what ran before this pass belongs to no pass: say so, not this one.
  if (GLenum e = glGetError(); e != GL_NO_ERROR) record_error(e, "before pass '" + name + "'");
  it->last_frame = frame_;
  Slot& slot = it->slots[frame_ % kRing];
  if (slot.pending) collect(*it, static_cast<int>(it - passes_.begin()), slot, true);  // the GPU is kRing frames behind
  glBeginQuery(GL_TIME_ELAPSED, slot.time.id());
  glBeginQuery(GL_SAMPLES_PASSED, slot.samples.id());
  slot.pending = true;
  slot.frame = frame_;
  slot.cpu_ms = -1;
  Scope scope(this, static_cast<std::size_t>(it - passes_.begin()), software_ ? &slot.cpu_ms : nullptr);
  if (!inject_error_in_.empty() && inject_error_in_ == name) glEnable(GL_NONE);  // GL_INVALID_ENUM
  return scope;
}

void PassMetrics::collect(Pass& pass, int index, Slot& slot, bool wait) {
  if (!wait) {
    GLint ready = 0;
    glGetQueryObjectiv(slot.time.id(), GL_QUERY_RESULT_AVAILABLE, &ready);
    if (!ready) return;
  }
  const std::uint64_t ns = query_result_u64(slot.time.id());
  const std::uint64_t samples = query_result_u64(slot.samples.id());
  slot.pending = false;
  Stats& s = stats_[index];
  double ms = slot.cpu_ms >= 0 ? slot.cpu_ms : double(ns) * 1e-6;
  s.last_ms = ms;
  s.min_ms = s.frames ? std::min(s.min_ms, ms) : ms;
  s.samples = samples;
  s.samples_saturated = samples_bits_ > 0 && samples_bits_ < 64 && samples == (std::uint64_t(1) << samples_bits_) - 1;
  pass.sum_ms += ms;
  s.frames += 1;
  s.mean_ms = pass.sum_ms / s.frames;
}

void PassMetrics::end_frame() {
  // Results arrive in order, so the oldest pending slot is tried first.
  for (size_t i = 0; i < passes_.size(); ++i)
    for (std::uint64_t f = frame_ + 1; f <= frame_ + kRing; ++f) {
      Slot& slot = passes_[i].slots[f % kRing];
      if (slot.pending && slot.frame == f - kRing) collect(passes_[i], static_cast<int>(i), slot, false);
    }
  ++frame_;
}

void PassMetrics::wait_all() {
  // Oldest first, so "last" really is the last frame.
  for (size_t i = 0; i < passes_.size(); ++i) {
    std::vector<Slot*> pending;
    for (Slot& slot : passes_[i].slots)
      if (slot.pending) pending.push_back(&slot);
    std::sort(pending.begin(), pending.end(), [](const Slot* a, const Slot* b) { return a->frame < b->frame; });
    for (Slot* slot : pending) collect(passes_[i], static_cast<int>(i), *slot, true);
  }
}

void PassMetrics::reset() {
  wait_all();
  for (auto& p : passes_) p.sum_ms = 0;
  for (auto& s : stats_) s = Stats{.name = s.name};
}

void PassMetrics::clear() {
  wait_all();
  passes_.clear();
  stats_.clear();
  allocations_.clear();
}

void PassMetrics::count(const std::string& pass, const std::string& what, std::uint64_t value) {
  auto it = std::find_if(stats_.begin(), stats_.end(), [&](const Stats& s) { return s.name == pass; });
  if (it == stats_.end()) throw Error("internal: a count for pass '" + pass + "', which was never measured");
  for (auto& [name, v] : it->counts)
    if (name == what) { v = value; return; }
  it->counts.emplace_back(what, value);
}

const PassMetrics::Stats* PassMetrics::find(const std::string& name) const {
  for (const auto& s : stats_)
    if (s.name == name) return &s;
  return nullptr;
}

void PassMetrics::set_allocation(const std::string& name, std::size_t bytes) {
  for (auto& a : allocations_)
    if (a.name == name) { a.bytes = bytes; return; }
  allocations_.push_back({name, bytes});
}

std::size_t PassMetrics::allocated_bytes() const {
  std::size_t n = 0;
  for (const auto& a : allocations_) n += a.bytes;
  return n;
}

std::optional<PassMetrics::Scope> timed(PassMetrics* metrics, const std::string& name) {
  if (!metrics) return std::nullopt;
  return metrics->pass(name);
}

}  // namespace lp
