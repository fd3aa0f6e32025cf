#pragma once
// Where the chapter's HDR radiance comes from. The HDR stage only needs a radiance texture.
// The chapter's is chapter 03's deferred path (DeferredRadiance): chapter 02's G-buffer,
// the lights' volumes into chapter 03's float light buffer, and its composite into a
// RadianceTarget of our own: RGBA16F (the float path) or RGBA8 (what an 8-bit light
// accumulation keeps). Chapter 01's forward renderer (ForwardRadiance) draws the same
// radiance the direct way; the tests hold the two against each other.
#include <memory>
#include <string>
#include <vector>

#include "chapters/01_forward/forward.h"
#include "chapters/01_forward/light_buffer.h"
#include "chapters/02_gbuffer/gbuffer.h"
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_volumes.h"
#include "common/camera.h"
#include "common/gl.h"
#include "common/image.h"
#include "common/metrics.h"
#include "common/scene.h"
#include "common/scene_gpu.h"
#include "common/target.h"

namespace lp::ch05 {

// The lit scene's radiance: a colour target (common/target.h), GL_RGBA16F (the float path)
// or GL_RGBA8 (what an 8-bit light accumulation keeps), with a depth buffer only for
// what is drawn over the composite (chapter 04's glass).
using RadianceTarget = ColourTarget;

// An RGBA16F (or RGBA32F) texture holding `image` (RGB or RGBA, top row first): the tests
// and the sweep feed hand-made radiance buffers to the stage with it.
gl::Texture upload_radiance(const ImageF& image, GLenum format = GL_RGBA16F);

// The scene with its lights rescaled for this chapter: directional lights ("the sun") times
// `sun`, emissive surfaces times `glow`. The assets are tuned for chapters 1-4, which show
// radiance as it is; a high dynamic range needs a brighter sun and brighter lamps.
// The tests' truth; the radiance sources below never copy the scene: they apply the same
// scales where the lights are packed (sun_scaled) and the emissive colours drawn.
Scene rescaled_scene(const Scene& scene, float sun, float glow);
// `lights` with the directional ones times `sun`.
std::vector<Light> sun_scaled(const std::vector<Light>& lights, float sun);

// [forward-radiance]
// Chapter 01's forward renderer as a radiance source: all lights in one pass, per pixel,
// uncut. The cross-check for DeferredRadiance.
class ForwardRadiance {
 public:
  explicit ForwardRadiance(const SceneGpu& scene);
  explicit ForwardRadiance(const Scene& scene);  // uploads `scene` for itself
  void set_scales(float sun, float glow);  // cheap when unchanged
  void reload_shaders() { forward_.reload_shaders(); }
  // Clears `target` to chapter 01's background and draws the scene into it.
  void render(const FrameCamera& camera, const RadianceTarget& target) const;

 private:
  std::unique_ptr<SceneGpu> owned_;  // only when constructed from a Scene
  const SceneGpu& gpu_;
  ch01::ForwardRenderer forward_;
  ch01::LightBuffer lights_;
  float sun_ = -1, glow_ = -1;
};
// [/forward-radiance]

// [deferred-radiance]
// Chapter 03's deferred frame as the radiance source: the same frame object chapter 03's
// program draws (its G-buffer, light volumes into the float light buffer, composite), drawn
// into a RadianceTarget instead of the sRGB output, with the lights cut for this chapter's
// exposure. Stages added to it come along: chapter 04's tubes light the HDR street. The sun
// and glow scales are the frame's parameters: the sun's applied where the lights are packed,
// the glow where the emissive colours are drawn; the scene itself is never copied.
class DeferredRadiance {
 public:
  // Draws the program's scene (`scene`, already on the GPU: nothing is uploaded again).
  explicit DeferredRadiance(const SceneGpu& scene, const ch02::Layout& layout = ch02::our_layout(),
                            ch03::Strategy strategy = ch03::Strategy::Stencil);
  // Uploads `scene` for itself (tests and sweeps that have no SceneGpu of their own).
  explicit DeferredRadiance(const Scene& scene, const ch02::Layout& layout = ch02::our_layout(),
                            ch03::Strategy strategy = ch03::Strategy::Stencil);
  // Directional lights ("the sun") times `sun`, emissive surfaces times `glow` (the assets are
  // tuned for chapters 1-4, which show radiance as it is). Cheap when unchanged.
  void set_scales(float sun, float glow);
  // The exposure the volumes are cut for: a light ends where it gives less than one output
  // step after this exposure (times the curve's output_slope()) on the brightest material.
  // Rounded up to a quarter stop, so the volumes are rebuilt only when it moves by 19 %.
  void set_cut_exposure(float exposure);
  float cut_exposure() const { return cut_exposure_; }  // as rounded
  float cut_threshold() const;                           // chapter 03's threshold for it
  void reload_shaders() { frame_->reload_shaders(); }
  // Draws the scene as `camera` sees it into `target` (any size; the G-buffer and the light
  // buffer follow it). With `metrics`, each pass is timed on its own.
  void render(const FrameCamera& camera, const RadianceTarget& target, PassMetrics* metrics = nullptr);
  // The lights packed for the scales and cut set above, as render() does first: for a pass
  // that reads the frame's lights without drawing the frame (chapter 10's MSAA).
  void update_lights();

  const Scene& scene() const { return gpu_.scene(); }  // as loaded: the scales are not in it
  const SceneGpu& scene_gpu() const { return gpu_; }
  float peak_reflectance() const { return peak_reflectance_; }
  ch03::DeferredFrame& frame() { return *frame_; }  // add_stage() here
  const ch02::GBuffer& gbuffer() const { return frame_->gbuffer(); }
  const ch03::LightBuffer& light_buffer() const { return frame_->light(); }
  ch03::LightVolumes& volumes() { return frame_->volumes(); }
  std::size_t allocated_bytes() const { return frame_->allocated_bytes(); }  // G-buffer + light buffer

 private:
  std::unique_ptr<SceneGpu> owned_;  // when made from a Scene
  const SceneGpu& gpu_;
  std::unique_ptr<ch03::DeferredFrame> frame_;
  float peak_reflectance_;
  float sun_ = -1, glow_ = -1, cut_exposure_ = 1;
  bool lights_changed_ = true, warned_ = false;
};
// [/deferred-radiance]

}  // namespace lp::ch05
