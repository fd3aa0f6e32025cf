#include "common/metrics.h"

#include <algorithm>
#include <exception>
#include <string>

#include "common/error.h"

namespace lp {

PassMetrics::Scope::Scope(const std::string* name, double* cpu_ms) : name_(name), cpu_ms_(cpu_ms) {
  if (cpu_ms_) {
    glFinish();
    start_ = std::chrono::steady_clock::now();
  }
}

PassMetrics::Scope::~Scope() noexcept(false) {
  if (!active_) return;
  if (cpu_ms_) {
    glFinish();
    *cpu_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }
  glEndQuery(GL_TIME_ELAPSED);
  glEndQuery(GL_SAMPLES_PASSED);
  // Say which pass went wrong, not just that something did (unless already unwinding).
  if (GLenum e = glGetError(); e != GL_NO_ERROR && std::uncaught_exceptions() == 0)
    throw Error(std::string("OpenGL reported ") + gl::error_name(e) + " in pass '" + *name_ + "'");
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
  it->last_frame = frame_;
  Slot& slot = it->slots[frame_ % kRing];
  if (slot.pending) collect(*it, static_cast<int>(it - passes_.begin()), slot, true);  // the GPU is kRing frames behind
  glBeginQuery(GL_TIME_ELAPSED, slot.time.id());
  glBeginQuery(GL_SAMPLES_PASSED, slot.samples.id());
  slot.pending = true;
  slot.frame = frame_;
  if (software_ < 0) {
    std::string renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    software_ = renderer.find("llvmpipe") != std::string::npos || renderer.find("softpipe") != std::string::npos;
  }
  slot.cpu_ms = -1;
  return Scope(&it->name, software_ ? &slot.cpu_ms : nullptr);
}

void PassMetrics::collect(Pass& pass, int index, Slot& slot, bool wait) {
  if (!wait) {
    GLint ready = 0;
    glGetQueryObjectiv(slot.time.id(), GL_QUERY_RESULT_AVAILABLE, &ready);
    if (!ready) return;
  }
  GLuint64 ns = 0, samples = 0;
  glGetQueryObjectui64v(slot.time.id(), GL_QUERY_RESULT, &ns);
  glGetQueryObjectui64v(slot.samples.id(), GL_QUERY_RESULT, &samples);
  slot.pending = false;
  Stats& s = stats_[index];
  double ms = slot.cpu_ms >= 0 ? slot.cpu_ms : ns * 1e-6;
  s.last_ms = ms;
  s.min_ms = s.frames ? std::min(s.min_ms, ms) : ms;
  s.samples = samples;
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

}  // namespace lp
