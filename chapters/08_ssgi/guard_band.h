#pragma once
// Chapter 08's guard band, the cheaper of the source's fixes for off-screen emitters (the other
// is a half-cube of views around the eye): the whole frame (G-buffer, lights, the SSGI pass)
// drawn `pixels` wider on every side than the screen with the same focal length, so its inner
// pixels are the screen's pixels, and the screen's part cut out. The gather reads the band: an
// emitter just off the screen still sends its light.
//
//   GuardBand band{guard_band_pixels(option, height)};
//   frame.render(band.widen(camera, width, height), {wide.framebuffer(), band.width(width), band.height(height)});
//   band.crop(wide.framebuffer(), screen_framebuffer, width, height);
#include "common/camera.h"
#include "common/gl.h"
#include "common/image.h"

namespace lp::ch08 {

// The most pixels a band may add on each side (bounded work: a 4x larger frame at 1080p).
inline constexpr int kMaxGuardBand = 1080;

// [guard-band]
struct GuardBand {
  int pixels = 0;  // on every side
  int width(int screen_width) const { return screen_width + 2 * pixels; }
  int height(int screen_height) const { return screen_height + 2 * pixels; }
  // The camera of the wide frame: the projection's x and y rows scaled by screen / wide size, so
  // every screen pixel's centre keeps its ray (pixel (x, y) of the screen is (x + pixels, y +
  // pixels) of the wide frame) and the band sees past the screen's edges.
  FrameCamera widen(const FrameCamera& camera, int screen_width, int screen_height) const;
  // The screen's part of the wide image into `to` (screen_width x screen_height), byte for byte:
  // a copy of the stored sRGB bytes, no decoding.
  void crop(GLuint wide_framebuffer, GLuint to_framebuffer, int screen_width, int screen_height) const;
  ImageF crop(const ImageF& wide) const;
  ImageRGBA8 crop(const ImageRGBA8& wide) const;
};
// The program's --guard-band: 0 none; a value in (0, 1) a fraction of the screen's height; 1 or
// more pixels (rounded). Throws lp::Error naming the option for what it cannot be.
int guard_band_pixels(double option, int screen_height);
// [/guard-band]

}  // namespace lp::ch08
