#pragma once
// Sub-pixel jitter: frame i's projection moved by a fraction of a pixel, so that successive
// frames sample different points of each pixel and their average is a supersampled image.
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "common/camera.h"

namespace lp::ch11 {

// [halton]
// The radical inverse of i in `base`: the digits of i mirrored behind the point
// (base 2: 1 -> 0.5, 2 -> 0.25, 3 -> 0.75, ...). Halton(2, 3) pairs two bases: a
// low-discrepancy sequence, evenly spread for any number of points taken from its start.
inline float radical_inverse(unsigned i, unsigned base) {
  float f = 1.f, r = 0.f;
  while (i > 0) {
    f /= float(base);
    r += f * float(i % base);
    i /= base;
  }
  return r;
}

// The mean of Halton(base) over indices 1..period: the first b^k - 1 points are exactly
// {1 .. b^k - 1} / b^k, mean 1/2, but a period of 8 in base 2 adds 1/16 and moves the
// mean to 57/128. The offsets subtract it, so the history converges on the pixel's centre.
inline float halton_mean(unsigned period, unsigned base) {
  float sum = 0.f;
  for (unsigned i = 1; i <= period; ++i) sum += radical_inverse(i, base);
  return sum / float(period);
}

// Frame `frame`'s offset in pixels: Halton(2, 3) from index 1 (index 0 is the corner),
// repeating every `period` frames, centred on the period's mean.
inline glm::vec2 jitter_offset(unsigned frame, unsigned period = 8) {
  if (period == 0) period = 1;
  const unsigned i = frame % period + 1;
  return {radical_inverse(i, 2) - halton_mean(period, 2), radical_inverse(i, 3) - halton_mean(period, 3)};
}
// [/halton]

// [jitter-projection]
// The camera with its image moved by `offset` pixels on a width x height target: a shift of
// the clip-space x, y by 2 * offset / size after the perspective divide (a translation applied
// after the projection, scaled by w).
inline FrameCamera jittered(const FrameCamera& camera, glm::vec2 offset, int width, int height) {
  FrameCamera c = camera;
  const glm::vec3 shift(2.f * offset.x / float(width), 2.f * offset.y / float(height), 0.f);
  c.projection = glm::translate(glm::mat4(1), shift) * camera.projection;
  return c;
}
// [/jitter-projection]

}  // namespace lp::ch11
