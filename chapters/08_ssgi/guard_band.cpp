#include "chapters/08_ssgi/guard_band.h"

#include <cmath>
#include <string>

#include "common/error.h"

namespace lp::ch08 {

FrameCamera GuardBand::widen(const FrameCamera& camera, int screen_width, int screen_height) const {
  if (pixels == 0) return camera;
  FrameCamera wide = camera;
  const float sx = float(screen_width) / float(width(screen_width));
  const float sy = float(screen_height) / float(height(screen_height));
  for (int column = 0; column < 4; ++column) {  // x_ndc and y_ndc shrink; z and w stay
    wide.projection[column][0] *= sx;
    wide.projection[column][1] *= sy;
  }
  wide.yfov = 2.f * std::atan(std::tan(camera.yfov * 0.5f) / sy);
  wide.aspect = float(width(screen_width)) / float(height(screen_height));
  return wide;
}

void GuardBand::crop(GLuint wide_framebuffer, GLuint to_framebuffer, int w, int h) const {
  // sRGB conversion off: the blit copies the stored bytes (OpenGL 4.5 decodes and encodes an
  // sRGB attachment in a blit only when GL_FRAMEBUFFER_SRGB is on)
  const GLboolean srgb = glIsEnabled(GL_FRAMEBUFFER_SRGB);
  glDisable(GL_FRAMEBUFFER_SRGB);
  glBlitNamedFramebuffer(wide_framebuffer, to_framebuffer, pixels, pixels, pixels + w, pixels + h, 0, 0, w, h,
                         GL_COLOR_BUFFER_BIT, GL_NEAREST);
  if (srgb) glEnable(GL_FRAMEBUFFER_SRGB);
}

ImageF GuardBand::crop(const ImageF& wide) const {
  if (pixels == 0) return wide;
  ImageF out = ImageF::blank(wide.width - 2 * pixels, wide.height - 2 * pixels, wide.channels);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < wide.channels; ++c) out.at(x, y, c) = wide.at(x + pixels, y + pixels, c);
  return out;
}

ImageRGBA8 GuardBand::crop(const ImageRGBA8& wide) const {
  if (pixels == 0) return wide;
  ImageRGBA8 out = ImageRGBA8::blank(wide.width - 2 * pixels, wide.height - 2 * pixels);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 4; ++c) out.at(x, y)[c] = wide.at(x + pixels, y + pixels)[c];
  return out;
}

int guard_band_pixels(double option, int screen_height) {
  if (!std::isfinite(option) || option < 0.0)
    throw Error("--guard-band must be 0, a fraction of the height below 1, or pixels (got " + std::to_string(option) + ")");
  const double px = option < 1.0 ? option * double(screen_height) : option;
  const long pixels = std::lround(px);
  if (pixels > kMaxGuardBand)
    throw Error("--guard-band " + std::to_string(option) + " is " + std::to_string(pixels) + " pixels a side; at most " +
                std::to_string(kMaxGuardBand) + " are drawn");
  return int(pixels);
}

}  // namespace lp::ch08
