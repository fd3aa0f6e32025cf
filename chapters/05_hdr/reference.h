#pragma once
// Ground truths for chapter 05, on the CPU in double precision: the exact log-average of a
// float buffer, how much of it the naive mip chain reaches, and a full-resolution bloom.
// The GPU passes are measured against these.
#include <cstddef>

#include <glm/glm.hpp>

#include "common/image.h"

namespace lp::ch05 {

struct ExactLogAverage {
  double mean_log = 0;    // (1/N) sum log(delta + L) over the valid pixels
  double luminance = 0;   // exp(mean_log)
  std::size_t count = 0;  // valid pixels (not NaN)
};

// [exact-log-average]
// exp(mean(log(delta + L))) over an RGB or RGBA float image, in double precision, with the
// chapter's policy for NaN / Inf / negative values (hdr_math.h: sanitize).
ExactLogAverage exact_log_average(const ImageF& radiance, float delta);
// [/exact-log-average]

// Pixels that a mip chain of 2x2 box filters, halving each size with floor, carries to its
// 1x1 level. Texel x of level k covers the base columns [x 2^k, (x + 1) 2^k), so the top
// texel covers [0, 2^floor(log2 w)) x [0, 2^floor(log2 h)): the largest power-of-two
// rectangle in the corner. The rest never reaches the average.
std::size_t naive_chain_pixels(int width, int height);

// Bloom at full resolution: the bright pass of every pixel of `radiance` times `exposure`,
// then a separable Gaussian of standard deviation sigma_px pixels, cut at ceil(3 sigma)
// and renormalised, clamped at the edges. RGB, top row first, like the input.
ImageF reference_bloom(const ImageF& radiance, float exposure, float threshold, float limit, float sigma_px);

// Synthetic buffers shared by the tests and the sweep.
// A uniform colour.
ImageF constant_image(int width, int height, glm::vec3 colour);
// Luminance rising from 1e-3 on the left to 1e3 on the right, a little brighter at the top:
// the right and top edges, which the naive chain drops, are the brightest.
ImageF ramp_image(int width, int height);

}  // namespace lp::ch05
