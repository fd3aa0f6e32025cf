#pragma once
// Measurement support: decode_gbuffer() run over every pixel, with each field of the Surface
// read back as float images. The sweep and the tests compare these between layouts (normal
// angle, position error) without going through 8-bit output.
#include "chapters/02_gbuffer/deferred.h"
#include "common/image.h"

namespace lp::ch02 {

struct SurfaceImages {
  ImageF position;  // xyz world position, w = 1 where the pixel is sky
  ImageF normal;    // xyz world normal, w = exponent
  ImageF albedo;    // rgb
  ImageF specular;  // rgb
  ImageF emissive;  // rgb
  bool sky(int x, int y) const { return position.at(x, y, 3) != 0.f; }
};

class SurfaceProbe {
 public:
  // Decodes every pixel of `gbuffer`; rows top to bottom like every ImageF.
  SurfaceImages read(const GBuffer& gbuffer);

 private:
  std::map<std::string, ShaderProgram> programs_;
  FullScreenPass quad_;
};

}  // namespace lp::ch02
