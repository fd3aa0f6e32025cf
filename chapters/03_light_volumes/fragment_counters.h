#pragma once
// Exact 64-bit fragment counts from 32-bit atomics: a shader storage buffer of {lo, hi}
// pairs that shaders/fragment_counters.glsl adds to (count_fragment(i) carries into hi when
// lo wraps). Chapter 03's light volumes and chapter 04's capsules count with it.
//
//   FragmentCounters counters(4);
//   counters.reset();  counters.bind();      // before the draws
//   ... draw with a program built with FragmentCounters::defines() ...
//   std::vector<std::uint64_t> n = counters.read();
#include <cstdint>
#include <string>
#include <vector>

#include "common/gl.h"

namespace lp::ch03 {

class FragmentCounters {
 public:
  static constexpr GLuint kBinding = 3;  // layout(std430, binding = FRAGMENT_COUNTERS_BINDING)
  // The defines a counting shader is built with: COUNT_FRAGMENTS and the binding.
  static std::vector<std::string> defines();

  explicit FragmentCounters(int count = 0);
  int size() const { return count_; }
  void resize(int count);  // keeps nothing: reset() before counting again
  // Every counter to `start` (0 to count; tests start near 2^32 to cross it with a few
  // fragments).
  void reset(std::uint64_t start = 0);
  void bind() const;                      // at kBinding
  std::vector<std::uint64_t> read() const;  // waits for the draws that count

 private:
  int count_ = 0;
  gl::Buffer buffer_;
};

}  // namespace lp::ch03
