#pragma once
// How the G-buffer packs a surface into few bits, on the CPU. shaders/encoding.glsl is the
// same maths in GLSL (the geometry pass encodes, gbuffer.glsl decodes); the unit tests hold
// this file to its error bounds over the whole sphere, and a GPU test holds the GLSL one to
// the same bounds.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

namespace lp::ch02 {

// [signed-codes]
// A value in [-1, 1] stored in a `bits`-bit unsigned normalised channel. The codes used are
// 0 .. 2^bits - 2 with the middle one, 2^(bits-1) - 1, meaning exactly 0: then 0, -1 and +1
// survive unchanged (the octahedron's poles and folds sit there). The plain v * 0.5 + 0.5
// mapping puts 0 between two codes.
inline float code_scale(int bits) { return float((1u << (bits - 1)) - 1u); }  // m: code of +1 is 2m

inline std::uint32_t signed_code(float v, int bits) {
  float m = code_scale(bits);
  return static_cast<std::uint32_t>(std::round(std::clamp(v, -1.f, 1.f) * m + m));
}

inline float signed_value(std::uint32_t code, int bits) {
  float m = code_scale(bits);
  return std::clamp((float(code) - m) / m, -1.f, 1.f);
}
// [/signed-codes]

// [octahedral]
// Octahedral mapping: project the unit sphere onto the octahedron |x|+|y|+|z| = 1, then
// unfold the lower half (z < 0) over the corners of the square so the whole sphere covers
// [-1, 1]^2 (Meyer et al. 2010; Cigolle et al. 2014).
inline glm::vec2 sign_not_zero(glm::vec2 v) { return {v.x >= 0.f ? 1.f : -1.f, v.y >= 0.f ? 1.f : -1.f}; }

inline glm::vec2 octahedral_fold(const glm::vec3& n) {
  glm::vec2 p = glm::vec2(n.x, n.y) / (std::abs(n.x) + std::abs(n.y) + std::abs(n.z));
  if (n.z < 0.f) p = (1.f - glm::abs(glm::vec2(p.y, p.x))) * sign_not_zero(p);
  return p;
}

inline glm::vec3 octahedral_unfold(const glm::vec2& p) {
  glm::vec3 n(p.x, p.y, 1.f - std::abs(p.x) - std::abs(p.y));
  float t = std::max(-n.z, 0.f);  // > 0 on the folded-over lower half
  n.x += n.x >= 0.f ? -t : t;
  n.y += n.y >= 0.f ? -t : t;
  return glm::normalize(n);
}
// [/octahedral]

// [octahedral-codes]
// The octahedral point rounded to `bits` per axis. Rounding each axis to its nearest code is
// not always the nearest direction on the sphere (the map stretches); trying the four codes
// around the point and keeping the best lowers the worst error by about a third.
struct OctCode {
  std::uint32_t x = 0, y = 0;
};

inline glm::vec3 decode_octahedral(OctCode c, int bits) {
  return octahedral_unfold({signed_value(c.x, bits), signed_value(c.y, bits)});
}

inline OctCode encode_octahedral(const glm::vec3& n, int bits, bool best_of_four = true) {
  glm::vec2 p = octahedral_fold(n);
  float m = code_scale(bits);
  if (!best_of_four) return {signed_code(p.x, bits), signed_code(p.y, bits)};
  glm::vec2 c = glm::clamp(p * m + m, 0.f, 2.f * m);
  glm::vec2 lo = glm::floor(c);
  OctCode best;
  float best_distance = 1e30f;
  for (int i = 0; i < 4; ++i) {
    glm::vec2 k = glm::min(lo + glm::vec2(i & 1, i >> 1), glm::vec2(2.f * m));
    OctCode candidate{std::uint32_t(k.x), std::uint32_t(k.y)};
    // Closest by squared chord, not by largest dot product: near 1 a float cosine cannot
    // tell angles below ~0.02 degrees apart, a 16-bit code's whole error.
    glm::vec3 e = decode_octahedral(candidate, bits) - n;
    float distance = glm::dot(e, e);
    if (distance < best_distance) { best_distance = distance; best = candidate; }
  }
  return best;
}
// [/octahedral-codes]

// [xyz-codes]
// The source's normal: each component mapped from [-1, 1] to [0, 1] and stored in an
// unsigned normalised channel (10 bits in RGB10A2), renormalised after reading.
struct XyzCode {
  std::uint32_t x = 0, y = 0, z = 0;
};

inline XyzCode encode_xyz(const glm::vec3& n, int bits) {
  float top = float((1u << bits) - 1u);
  auto q = [top](float v) { return static_cast<std::uint32_t>(std::round(std::clamp(v * 0.5f + 0.5f, 0.f, 1.f) * top)); };
  return {q(n.x), q(n.y), q(n.z)};
}

inline glm::vec3 decode_xyz(XyzCode c, int bits) {
  float top = float((1u << bits) - 1u);
  return glm::normalize(glm::vec3(float(c.x), float(c.y), float(c.z)) / top * 2.f - 1.f);
}
// [/xyz-codes]

// [normal-error-bounds]
// Worst angular error (radians) of each encoding, from the step between codes:
// - octahedral, step s = 1/m per axis: rounding moves the point by at most s/sqrt(2), and the
//   unfolding stretches a move by at most 3 (near the octahedron's face centres, where
//   |(x, y, 1-|x|-|y|)| is smallest, 1/sqrt(3), and along the diagonal |dv| = sqrt(3)), so
//   the error is at most 3 s / sqrt(2).
// - xyz: each component moves by at most half a step, 1/(2^bits - 1), so the vector by
//   sqrt(3) of that; renormalising turns a move e of a unit vector into an angle of at most
//   asin(e) (for e < 1).
inline double octahedral_error_bound(int bits) { return 3.0 / std::sqrt(2.0) / code_scale(bits); }
inline double xyz_error_bound(int bits) { return std::asin(std::sqrt(3.0) / double((1u << bits) - 1u)); }
// [/normal-error-bounds]

// [exponent-code]
// The Blinn-Phong exponent n in 1..8192 (see ch01's exponent_from_roughness) as 8 bits on a
// log2 scale: equal steps of relative sharpness, 2^(13/255) = 3.6 % apart, so a stored
// exponent is within 1.8 % of the true one whatever its size. (Linear steps of n/255 could
// not hold n = 510 at all, and would be 100 % apart at n = 1.)
inline constexpr float kMaxLog2Exponent = 13.f;

inline std::uint32_t encode_exponent(float n) {
  return static_cast<std::uint32_t>(std::round(std::clamp(std::log2(std::max(n, 1.f)) / kMaxLog2Exponent, 0.f, 1.f) * 255.f));
}

inline float decode_exponent(std::uint32_t code) { return std::exp2(float(code) / 255.f * kMaxLog2Exponent); }

inline double exponent_relative_error_bound() { return std::exp2(kMaxLog2Exponent / 255.0 / 2.0) - 1.0; }
// [/exponent-code]

}  // namespace lp::ch02
