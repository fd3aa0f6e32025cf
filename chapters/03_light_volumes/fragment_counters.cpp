#include "chapters/03_light_volumes/fragment_counters.h"

#include "common/error.h"

namespace lp::ch03 {

std::vector<std::string> FragmentCounters::defines() {
  return {"COUNT_FRAGMENTS 1", "FRAGMENT_COUNTERS_BINDING " + std::to_string(kBinding)};
}

FragmentCounters::FragmentCounters(int count) { resize(count); }

void FragmentCounters::resize(int count) {
  if (count < 0 || count > (1 << 24)) throw Error("internal: " + std::to_string(count) + " fragment counters");
  if (count == count_ && count_ > 0) return;  // (the constructor's buffer has no storage yet)
  count_ = count;
  buffer_ = gl::make_buffer(nullptr, std::size_t(count) * 2 * sizeof(GLuint), GL_DYNAMIC_STORAGE_BIT);
}

void FragmentCounters::reset(std::uint64_t start) {
  std::vector<GLuint> words(std::size_t(count_) * 2);
  for (std::size_t i = 0; i < words.size(); i += 2) {
    words[i] = GLuint(start & 0xFFFFFFFFu);
    words[i + 1] = GLuint(start >> 32);
  }
  if (!words.empty()) glNamedBufferSubData(buffer_.id(), 0, GLsizeiptr(words.size() * sizeof(GLuint)), words.data());
}

void FragmentCounters::bind() const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBinding, buffer_.id()); }

std::vector<std::uint64_t> FragmentCounters::read() const {
  std::vector<GLuint> words(std::size_t(count_) * 2);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  if (!words.empty()) glGetNamedBufferSubData(buffer_.id(), 0, GLsizeiptr(words.size() * sizeof(GLuint)), words.data());
  std::vector<std::uint64_t> n(static_cast<std::size_t>(count_));
  for (std::size_t i = 0; i < n.size(); ++i) n[i] = std::uint64_t(words[2 * i]) | (std::uint64_t(words[2 * i + 1]) << 32);
  return n;
}

}  // namespace lp::ch03
