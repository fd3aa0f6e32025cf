#pragma once
// Per-pixel motion: where each pixel's surface was in the last frame's image. A stage of
// chapter 03's frame (before the lights, after the G-buffer): one full-screen pass moves every
// pixel's G-buffer position by the camera alone (the sky included), then the opaque geometry
// is drawn again against the G-buffer's depth with each instance's last model matrix, so an
// object that moves carries its own motion. The scenes of the book are static: the previous
// models default to the current ones, and the second pass agrees with the first.
//
//   MotionStage motion(scene_gpu);
//   frame.add_stage(motion);
//   motion.set_cameras(camera, last_camera);   // both without jitter
//   frame.render(jittered(camera, ...), output);
//   motion.current();   // RGBA32F: xy = uv now - uv then, z = view depth then, w = view depth now
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "common/gl.h"
#include "common/shader.h"

namespace lp::ch11 {

class MotionStage : public ch03::FrameStage {
 public:
  explicit MotionStage(const SceneGpu& scene);
  void reload_shaders();
  // This frame's camera and the last one's, both without jitter: motion is the surface's, not
  // the jitter's. The first frame (or after reset()) gives the same camera twice.
  void set_cameras(const FrameCamera& current, const FrameCamera& previous);
  // Each instance's model matrix in the last frame, in the scene's instance order; empty: the
  // scene did not move. Throws lp::Error when the count differs from the scene's.
  void set_previous_models(std::vector<glm::mat4> models);
  // Off: no pass, and the next frame on has no last frame (a frame without TAA needs none).
  void set_enabled(bool on) { enabled_ = on; if (!on) frames_ = 0; }
  bool enabled() const { return enabled_; }

  void before_lights(ch03::DeferredFrame& frame, PassMetrics* metrics) override;

  // After render(): this frame's motion target and the last frame's (0 before two frames).
  GLuint current() const { return targets_[cur_].id(); }
  GLuint previous() const { return frames_ > 1 ? targets_[1 - cur_].id() : 0; }
  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t allocated_bytes() const { return std::size_t(width_) * height_ * 16 * 2; }

 private:
  void resize(int width, int height);
  const SceneGpu& scene_;
  std::unique_ptr<ShaderProgram> camera_pass_;
  ShaderProgram object_pass_;
  gl::Texture targets_[2] = {gl::Texture(GL_TEXTURE_2D), gl::Texture(GL_TEXTURE_2D)};  // sized by resize()
  gl::Framebuffer colour_only_[2], with_depth_[2];
  GLuint attached_depth_[2] = {0, 0};
  gl::VertexArray empty_;
  int width_ = 0, height_ = 0, cur_ = 0, frames_ = 0;
  bool enabled_ = true;
  FrameCamera current_, previous_;
  std::vector<glm::mat4> previous_models_;
};

}  // namespace lp::ch11
