// Deterministic random numbers for scenegen: PCG32 (O'Neill, pcg-random.org), written out so
// the sequence is identical on every platform and standard library (std:: distributions are
// implementation-defined).
#pragma once

#include <cstdint>

namespace scenegen {

class Pcg32 {
 public:
  explicit Pcg32(uint64_t seed, uint64_t stream = 0x5eed) : inc_((stream << 1u) | 1u) {
    next();
    state_ += seed;
    next();
  }

  uint32_t next() {
    uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }

  // Uniform in [0, 1), 24 bits, exactly representable as float.
  float uniform() { return static_cast<float>(next() >> 8) * (1.0f / 16777216.0f); }
  float range(float lo, float hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [0, n), n > 0 (multiply-shift; the tiny bias is irrelevant here).
  uint32_t below(uint32_t n) { return static_cast<uint32_t>((static_cast<uint64_t>(next()) * n) >> 32); }

 private:
  uint64_t state_ = 0;
  uint64_t inc_;
};

}  // namespace scenegen
