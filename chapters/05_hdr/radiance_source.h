#pragma once
// Where the chapter's HDR radiance comes from. The HDR stage only needs a radiance texture;
// until chapter 03's deferred light buffer exists, chapter 01's forward renderer draws the
// lit scene into a RadianceTarget of our own: RGBA16F (the float path) or RGBA8 (what an
// 8-bit light accumulation keeps).
#include <memory>
#include <vector>

#include "chapters/01_forward/forward.h"
#include "chapters/01_forward/light_buffer.h"
#include "common/camera.h"
#include "common/gl.h"
#include "common/image.h"
#include "common/scene.h"
#include "common/scene_gpu.h"

namespace lp::ch05 {

// A colour texture (GL_RGBA16F or GL_RGBA8) and a depth buffer to render the lit scene into.
class RadianceTarget {
 public:
  RadianceTarget(int width, int height, GLenum format);
  GLuint framebuffer() const { return fbo_.id(); }
  GLuint texture() const { return colour_.id(); }
  GLenum format() const { return format_; }
  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t bytes() const;
  void bind() const;  // binds it and sets the viewport
  ImageF read() const;  // RGBA floats as stored, top row first

 private:
  int width_, height_;
  GLenum format_;
  gl::Framebuffer fbo_;
  gl::Texture colour_, depth_;
};

// An RGBA16F (or RGBA32F) texture holding `image` (RGB or RGBA, top row first): the tests
// and the sweep feed hand-made radiance buffers to the stage with it.
gl::Texture upload_radiance(const ImageF& image, GLenum format = GL_RGBA16F);
// A colour texture read back as RGBA floats, top row first.
ImageF read_texture(GLuint texture, int width, int height);

// The scene with its lights rescaled for this chapter: directional lights ("the sun") times
// `sun`, emissive surfaces times `glow`. The assets are tuned for chapters 1-4, which show
// radiance as it is; a high dynamic range needs a brighter sun and brighter lamps.
Scene rescaled_scene(const Scene& scene, float sun, float glow);

// [forward-radiance]
// Chapter 01's forward renderer as the radiance source: all lights in one pass, per pixel.
class ForwardRadiance {
 public:
  explicit ForwardRadiance(const Scene& scene);
  void set_scales(float sun, float glow);  // cheap when unchanged
  void reload_shaders() { forward_->reload_shaders(); }
  // Clears `target` to chapter 01's background and draws the scene into it.
  void render(const FrameCamera& camera, const RadianceTarget& target) const;

 private:
  const Scene& original_;
  std::unique_ptr<Scene> scene_;  // the rescaled copy the GPU scene points at
  std::unique_ptr<SceneGpu> gpu_;
  std::unique_ptr<ch01::ForwardRenderer> forward_;
  ch01::LightBuffer lights_;
  float sun_ = -1, glow_ = -1;
};
// [/forward-radiance]

}  // namespace lp::ch05
