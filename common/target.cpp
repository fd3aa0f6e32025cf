#include "common/target.h"

#include <algorithm>
#include <string>
#include <vector>

#include "common/error.h"

namespace lp {

OutputTarget::OutputTarget(int w, int h)
    : width_(w), height_(h),
      colour_(gl::make_texture_2d(GL_SRGB8_ALPHA8, w, h)),
      depth_(gl::make_texture_2d(GL_DEPTH24_STENCIL8, w, h)) {
  glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, colour_.id(), 0);
  glNamedFramebufferTexture(fbo_.id(), GL_DEPTH_STENCIL_ATTACHMENT, depth_.id(), 0);
  if (glCheckNamedFramebufferStatus(fbo_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("the output framebuffer (" + std::to_string(w) + "x" + std::to_string(h) + ") is incomplete");
}

void OutputTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
  glViewport(0, 0, width_, height_);
  glEnable(GL_FRAMEBUFFER_SRGB);
}

ImageRGBA8 OutputTarget::read() const {
  ImageRGBA8 img;
  img.width = width_;
  img.height = height_;
  img.pixels.resize(std::size_t(width_) * height_ * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(colour_.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(img.pixels.size()), img.pixels.data());
  // OpenGL's first row is the bottom one; PNG's is the top one.
  const std::size_t row = std::size_t(width_) * 4;
  for (int y = 0; y < height_ / 2; ++y)
    std::swap_ranges(img.pixels.begin() + y * row, img.pixels.begin() + (y + 1) * row,
                     img.pixels.begin() + (height_ - 1 - y) * row);
  return img;
}

ColourTarget::ColourTarget(int w, int h, GLenum format, bool with_depth)
    : width_(w), height_(h), format_(format), has_depth_(with_depth),
      colour_(gl::make_texture_2d(format, w, h)),
      depth_(with_depth ? gl::make_texture_2d(GL_DEPTH24_STENCIL8, w, h) : gl::Texture(GL_TEXTURE_2D)) {
  glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, colour_.id(), 0);
  if (with_depth) glNamedFramebufferTexture(fbo_.id(), GL_DEPTH_STENCIL_ATTACHMENT, depth_.id(), 0);
  if (glCheckNamedFramebufferStatus(fbo_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("the colour framebuffer (" + std::to_string(w) + "x" + std::to_string(h) + ", format " +
                std::to_string(format) + ") is incomplete");
}

std::size_t ColourTarget::bytes() const {
  return std::size_t(width_) * std::size_t(height_) *
         (gl::bytes_per_texel(format_) + (has_depth_ ? gl::bytes_per_texel(GL_DEPTH24_STENCIL8) : 0));
}

void ColourTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
  glViewport(0, 0, width_, height_);
  glDisable(GL_FRAMEBUFFER_SRGB);
}

ImageF ColourTarget::read() const { return read_texture(colour_.id(), width_, height_); }

namespace {

// `picture`'s texels into `texture` (its size), one channel or four.
void write_picture(GLuint texture, const ImageF& picture, int channels) {
  if (picture.channels < 1) throw Error("a picture to upload has no channels");
  ImageF up = picture;
  flip_vertically(up);  // OpenGL's rows start at the bottom
  const std::size_t pixels = std::size_t(up.width) * std::size_t(up.height), from = std::size_t(up.channels);
  std::vector<float> texels(pixels * std::size_t(channels), 1.f);
  for (std::size_t i = 0; i < pixels; ++i)
    for (int c = 0; c < std::min(channels, 3); ++c)
      texels[i * std::size_t(channels) + std::size_t(c)] = up.data[i * from + std::size_t(std::min(c, up.channels - 1))];
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(texture, 0, 0, 0, up.width, up.height, channels == 1 ? GL_RED : GL_RGBA, GL_FLOAT, texels.data());
}

}  // namespace

gl::Texture upload_picture(const ImageF& picture, GLenum format) {
  const bool one = format == GL_R16F || format == GL_R32F;
  if (!one && format != GL_RGBA16F && format != GL_RGBA32F) throw Error("upload_picture: a float format of one or four channels");
  gl::Texture t = gl::make_texture_2d(format, picture.width, picture.height);
  write_picture(t.id(), picture, one ? 1 : 4);
  return t;
}

void PictureTexture::upload(const ImageF& picture) {
  if (picture.width != width_ || picture.height != height_) {
    texture_ = gl::make_texture_2d(channels_ == 1 ? GL_R32F : GL_RGBA32F, picture.width, picture.height);
    width_ = picture.width;
    height_ = picture.height;
  }
  write_picture(texture_.id(), picture, channels_);
}

ImageF read_texture(GLuint texture, int w, int h) {
  ImageF img = ImageF::blank(w, h, 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(img.data.size() * sizeof(float)), img.data.data());
  flip_vertically(img);
  return img;
}

void put_picture(const ImageRGBA8& picture, GLuint framebuffer) {
  ImageRGBA8 rows = picture;
  flip_vertically(rows);  // OpenGL's rows start at the bottom
  gl::Texture t = gl::make_texture_2d(GL_SRGB8_ALPHA8, picture.width, picture.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(t.id(), 0, 0, 0, picture.width, picture.height, GL_RGBA, GL_UNSIGNED_BYTE, rows.pixels.data());
  gl::Framebuffer source;
  glNamedFramebufferTexture(source.id(), GL_COLOR_ATTACHMENT0, t.id(), 0);
  GLboolean srgb = glIsEnabled(GL_FRAMEBUFFER_SRGB);
  glDisable(GL_FRAMEBUFFER_SRGB);  // a copy of the bytes, not a decode and encode
  glBlitNamedFramebuffer(source.id(), framebuffer, 0, 0, picture.width, picture.height, 0, 0, picture.width,
                         picture.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  if (srgb) glEnable(GL_FRAMEBUFFER_SRGB);
}

ImageRGBA8 read_framebuffer(GLuint framebuffer, int width, int height) {
  ImageRGBA8 image = ImageRGBA8::blank(width, height);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
  flip_vertically(image);
  return image;
}

}  // namespace lp
