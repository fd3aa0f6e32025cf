#pragma once
// The log-average luminance of a radiance texture on the GPU, exp(mean(log(delta + L))),
// four ways:
//  - MipChain: the source's idea, a mip chain of the log-luminance down to 1x1, with the
//    fix this chapter needs: the last row and column of an odd-sized level are folded into
//    their neighbour, and every texel carries how many pixels it stands for, so each pixel
//    counts once whatever the size (and NaN pixels count zero times).
//  - NaiveMipChain: the same chain with plain 2x2 boxes. Odd sizes drop their last row or
//    column at every level: only the largest power-of-two rectangle in the corner reaches
//    1x1 (51% of 1920x1080). NaN and Inf are not filtered either, as in the source.
//  - GenerateMipmap: literally the source: a log-luminance texture and glGenerateMipmap.
//    For sizes that are not powers of two the filter is the driver's choice.
//  - Compute: beyond the source, a two-stage parallel reduction in compute shaders
//    (workgroup sums in shared memory, then one workgroup sums those).
// Each writes its LogAverageResult (mean log, pixels counted) to a small storage buffer, so
// the exposure is computed on the GPU without reading anything back.
#include <string>
#include <vector>

#include "chapters/05_hdr/hdr_buffers.h"
#include "common/gl.h"
#include "common/shader.h"

namespace lp::ch05 {

enum class AverageMethod { MipChain, Compute, NaiveMipChain, GenerateMipmap };
inline const std::vector<std::string> kAverageMethodNames = {"mip-chain", "compute", "naive-mip-chain", "generate-mipmap"};


class LogAverage {
 public:
  LogAverage();
  void reload_shaders();

  // Reads `radiance` (w x h, any float or normalised format) and leaves the result in
  // result_buffer(). Nothing is read back.
  void compute(GLuint radiance, int width, int height, AverageMethod method, float delta);
  GLuint result_buffer() const { return result_.id(); }
  LogAverageResult read() const;  // waits for the GPU: tests, the sweep and the panel only

  // The log-luminance texture of the mip-chain methods: RG32F, R = mean log of the texels
  // below, G = pixels counted (0 for the compute method).
  GLuint chain_texture() const { return chain_.id(); }
  int chain_levels() const { return levels_; }
  std::size_t allocated_bytes() const;

 private:
  void ensure_chain(int width, int height);
  void ensure_partials(std::size_t groups);
  ShaderProgram log_pass_, log_pass_raw_, downsample_, downsample_naive_, read_top_, reduce_tiles_, reduce_partials_;
  gl::Texture chain_{GL_TEXTURE_2D};
  int width_ = 0, height_ = 0, levels_ = 0;
  gl::Buffer result_, partials_;
  std::size_t partial_capacity_ = 0;
};

}  // namespace lp::ch05
