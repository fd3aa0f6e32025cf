#pragma once
// The image a chapter renders into: sRGB8 colour and 24-bit depth + 8-bit stencil, as
// textures. The window blits it to the screen; headless runs and tests read it back.
#include "common/gl.h"
#include "common/image.h"

namespace lp {

class OutputTarget {
 public:
  OutputTarget(int width, int height);
  GLuint framebuffer() const { return fbo_.id(); }
  GLuint colour() const { return colour_.id(); }
  int width() const { return width_; }
  int height() const { return height_; }
  // Binds it, sets the viewport and sRGB encoding of the shader's linear output.
  void bind() const;
  ImageRGBA8 read() const;  // top row first, like a PNG

 private:
  int width_, height_;
  gl::Framebuffer fbo_;
  gl::Texture colour_, depth_;
};

}  // namespace lp
