#pragma once
// A small deterministic random number generator for Monte Carlo ground truths: PCG32
// (O'Neill 2014, the XSH-RR output on a 64-bit LCG). Each pixel gets its own stream chosen
// from (seed, pixel index), so an image is the same whichever thread traced which pixel
// and however many threads there were. Nothing here is meant for cryptography.
#include <cstdint>

namespace lp {

// SplitMix64's finaliser: spreads nearby seeds (0, 1, 2, ...) over the whole state space.
constexpr std::uint64_t mix64(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

class Pcg32 {
 public:
  // `stream` picks one of 2^63 independent sequences (the LCG increment must be odd).
  constexpr Pcg32(std::uint64_t seed, std::uint64_t stream) : inc_((stream << 1) | 1) {
    next();
    state_ += seed;
    next();
  }

  constexpr std::uint32_t next() {
    std::uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    auto xorshifted = static_cast<std::uint32_t>(((old >> 18) ^ old) >> 27);
    auto rot = static_cast<std::uint32_t>(old >> 59);
    return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
  }

  // Uniform in [0, 1): the top 24 bits, so every value is exactly representable and 1 is
  // never returned (a sample at u = 1 would land on the edge of a warped domain).
  constexpr float uniform() { return static_cast<float>(next() >> 8) * 0x1p-24f; }

 private:
  std::uint64_t state_ = 0, inc_;
};

// The generator of one pixel of an image traced with `seed`.
constexpr Pcg32 pixel_rng(std::uint64_t seed, std::uint64_t pixel_index) { return Pcg32(mix64(seed), pixel_index); }

}  // namespace lp
