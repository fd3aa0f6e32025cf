#pragma once
// The image a chapter renders into: sRGB8 colour and 24-bit depth + 8-bit stencil, as
// textures. The window blits it to the screen; headless runs and tests read it back.
#include <cstddef>

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

// A colour texture of any renderable format (GL_RGBA16F for float light, GL_RGBA32F for a
// measurement, GL_RGBA8) with an optional DEPTH24_STENCIL8, to render into and read back as
// floats: chapter 05's radiance, the sweeps' linear images.
class ColourTarget {
 public:
  ColourTarget(int width, int height, GLenum format, bool with_depth = true);
  GLuint framebuffer() const { return fbo_.id(); }
  GLuint texture() const { return colour_.id(); }
  GLenum format() const { return format_; }
  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t bytes() const;  // colour and depth
  void bind() const;          // binds it and sets the viewport; no sRGB encoding
  ImageF read() const;        // RGBA floats as stored, top row first

 private:
  int width_, height_;
  GLenum format_;
  bool has_depth_;
  gl::Framebuffer fbo_;
  gl::Texture colour_, depth_;
};

// A colour texture read back as RGBA floats, top row first.
ImageF read_texture(GLuint texture, int width, int height);

// The pictures a program draws instead of its frame (a truth, an error map): `picture` (rows
// top first, sRGB bytes) copied into `framebuffer`'s lower-left corner as it is, byte for byte
// (no sRGB encoding: the bytes are encoded already); and an RGBA8 framebuffer read back.
void put_picture(const ImageRGBA8& picture, GLuint framebuffer);
ImageRGBA8 read_framebuffer(GLuint framebuffer, int width, int height);  // rows top first

// A CPU picture (a ray-traced truth, an error map, a hand-made radiance; rows top first) in a
// new float texture of `format`: one channel (GL_R16F/GL_R32F: the picture's first channel)
// or four (GL_RGBA16F/GL_RGBA32F: its channels, the last repeated into those it lacks, alpha 1).
gl::Texture upload_picture(const ImageF& picture, GLenum format);

// The same, kept for a pass that draws a new picture of the same size often: one channel
// (GL_R32F) or four (GL_RGBA32F); the texture follows the picture's size.
class PictureTexture {
 public:
  explicit PictureTexture(int channels) : channels_(channels == 1 ? 1 : 4) {}
  void upload(const ImageF& picture);
  GLuint id() const { return texture_.id(); }

 private:
  int channels_;
  int width_ = 0, height_ = 0;
  gl::Texture texture_{GL_TEXTURE_2D};
};

}  // namespace lp
