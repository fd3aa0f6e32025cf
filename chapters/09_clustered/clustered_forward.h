#pragma once
// Clustered forward shading as the frame's local-light pass: the clusters' lists built as
// chapter 09's deferred pass builds them (for every cluster: ClusterSettings::all_cells),
// then the opaque scene drawn again, forward, each fragment lit from its cluster's list
// (shaders/clustered_forward.glsl), added into the light buffer. It is the pass chapter 10's
// glass needs (a surface the G-buffer cannot hold); here it lights the opaque street so that
// its cost can be set beside clustered deferred shading of the same lists, and its image
// beside chapter 03's.
//
//   ClusteredForward forward(frame);
//   frame.set_local_lights(&forward);  // assign, depth pre-pass, shade: three passes
#include <string>
#include <vector>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/09_clustered/clustered_lights.h"
#include "common/gl.h"
#include "common/shader.h"

namespace lp::ch09 {

// The opaque scene drawn forward into `framebuffer` (w x h, its depth attachment of the
// G-buffer's format), lit from `lists`: chapter 01's vertex stage and material, the same draws
// in the same order with the same depth test as chapter 02's geometry pass. First a depth
// pre-pass with `depth_program` (forward.vert alone, or `program` itself; colour writes off),
// then `program` with depth test EQUAL and no depth writes: forward.vert's position is
// invariant, so each pixel's nearest fragment alone passes and is shaded once. With `add`,
// the colours are added to what is there (blend ONE, ONE); the colour buffers are not
// cleared, the depth is. Each half timed in `metrics` under the names given.
void draw_forward(const SceneGpu& gpu, const ch02::GBuffer& gbuffer, const FrameCamera& camera, ClusteredLights& lists,
                  const ShaderProgram& depth_program, const ShaderProgram& program, GLuint framebuffer, int w, int h,
                  bool counting, bool add, PassMetrics* metrics = nullptr, const std::string& prepass_name = "",
                  const std::string& shade_name = "");

class ClusteredForward : public ch03::LocalLightPass {
 public:
  explicit ClusteredForward(const ch03::DeferredFrame& frame, const SceneGpu& gpu, ClusterSettings settings = {});
  std::string name() const override { return "clustered-forward"; }
  void draw(const ch03::LightBuffer& light, const ch03::SurfaceView& view, ch03::LightVolumes::Output output) override;
  bool times_own_passes() const override { return true; }
  void set_metrics(PassMetrics* metrics) override;  // this pass's; the lists' stay unset
  // "local lights: clustered-forward: assign", "...: depth pre-pass", "...: shade".
  static std::vector<std::string> pass_names();

  void set_settings(ClusterSettings s);  // clustered, all_cells: forced
  ClusteredLights& lists() { return lists_; }
  void set_counting(bool on) { counting_ = on; }
  EvalCounts counts() const { return lists_.counts(); }
  void reload_shaders();

 private:
  const ch03::DeferredFrame& frame_;
  const SceneGpu& gpu_;
  ClusteredLights lists_;
  PassMetrics* metrics_ = nullptr;
  bool counting_ = false;
  int width_ = 0, height_ = 0;
  GLuint colour_l1_ = 0, colour_l2_ = 0;
  gl::Framebuffer fbo_;
  gl::Texture depth_{GL_TEXTURE_2D};
  ProgramCache programs_;
};

}  // namespace lp::ch09
