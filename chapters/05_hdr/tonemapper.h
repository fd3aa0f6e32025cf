#pragma once
// The tonemapping pass: radiance x exposure (from the ExposureState buffer), bloom before or
// after the curve, the operator, and sRGB out through GL_FRAMEBUFFER_SRGB. A full-screen
// triangle into the output framebuffer; the only pass of the stage that rasterises.
#include <glm/glm.hpp>

#include "chapters/05_hdr/hdr_math.h"
#include "common/gl.h"
#include "common/shader.h"

namespace lp::ch05 {

enum class BloomMode { Off, AfterTonemap, BeforeTonemap };

struct TonemapSettings {
  Operator op = Operator::Reinhard;
  float white = 4.f;  // extended Reinhard: the exposed value that becomes white
};

struct BloomInput {  // what the tonemapper needs of the bloom (texture 0: none)
  BloomMode mode = BloomMode::Off;
  GLuint texture = 0;
  glm::vec2 uv_scale{1};
  float strength = 0, threshold = 1, limit = 64;
  bool show_alone = false;  // draw the bloom texture itself (a debug view), not the image
};

class Tonemapper {
 public:
  Tonemapper();
  void reload_shaders() { program_.reload(); }
  void draw(GLuint radiance, int width, int height, GLuint exposure_buffer, const TonemapSettings& settings,
            const BloomInput& bloom, GLuint output_framebuffer) const;

 private:
  ShaderProgram program_;
  gl::VertexArray empty_;  // core profile draws need a vertex array, even with no attributes
  gl::Sampler bilinear_;
};

}  // namespace lp::ch05
