#pragma once
// [csm]
// Convolution shadow maps (Annen et al. 2007, which the source names among the filtered maps):
// the shadow test is a step of the difference between the occluder's depth z and the receiver's
// d, lit = H(z - d), and the step on (-1, 1) has a Fourier series of odd sines,
//   H(x) = 1/2 + 2 sum_k sin(c_k x) / c_k,   c_k = (2k - 1) pi,  k = 1, 2, ...
// Cut after `terms` terms and expanded, sin(c_k (z - d)) = sin(c_k z) cos(c_k d) - cos(c_k z)
// sin(c_k d): the map stores the 2 terms basis values sin(c_k z), cos(c_k z) per texel, which a
// filter may average (the reconstruction is linear in them), and the lookup weighs the filtered
// values with the receiver's cos(c_k d), sin(c_k d). Few terms ring near the step (Gibbs: the
// overshoot stays near 9 % of the jump whatever the count, and moves towards the edge as 1 /
// (2 terms)) and leave the step's slope finite: a receiver just behind its occluder reads
// partly lit. Each term costs two channels of the map.
#include <vector>

namespace lp::ch06 {

inline constexpr int kMaxCsmTerms = 8;  // 16 channels: four RGBA maps
float csm_coefficient(int k);           // c_k = (2k - 1) pi, k from 1
// The truncated series of H(x), x = z - d in (-1, 1), unclamped (it overshoots).
float csm_step(float x, int terms);
// The stored values of depth z: sin(c_k z), cos(c_k z) for k = 1..terms, interleaved.
std::vector<float> csm_basis(float z, int terms);
// Lit fraction from (filtered) basis values and the receiver's depth d: twice the series,
// clamped to [0, 1] (a receiver on its occluder, where the series reads 1/2, is lit).
float csm_visibility(const std::vector<float>& basis, float d, int terms);
// The series' squared L2 distance from the step over one period, Parseval's tail:
// sum over k > terms of (2 / c_k)^2.
double csm_l2_error_squared(int terms);

}  // namespace lp::ch06
// [/csm]
