#pragma once
// Forward shading: each object is drawn once and lit by every light as it is drawn.
// Four ways, switchable: per pixel in one pass (lights in a storage buffer), per vertex
// (Gouraud), per pixel without renormalising the normal (to see why one must), and one
// additive pass per light (the classic multi-pass forward renderer).
#include <string>
#include <vector>

#include "chapters/01_forward/light_buffer.h"
#include "common/camera.h"
#include "common/scene_gpu.h"
#include "common/shader.h"

namespace lp::ch01 {

enum class ForwardMode { PerPixel, PerVertex, PerPixelUnnormalized, MultiPass };
inline const std::vector<std::string> kForwardModes = {"per-pixel", "per-vertex", "unnormalized", "multi-pass"};
ForwardMode forward_mode(const std::string& name);  // throws Error for an unknown name

class ForwardRenderer {
 public:
  explicit ForwardRenderer(const SceneGpu& scene);
  void reload_shaders();

  // One pass: all `lights` for every fragment (or every vertex), plus ambient and emissive.
  void draw(const FrameCamera& camera, ForwardMode mode, const LightBuffer& lights) const;
  // Multi-pass, first pass: depth, ambient and emissive.
  void draw_base(const FrameCamera& camera, const LightBuffer& lights) const;
  // Multi-pass, then one additive pass per light over the same depth (test EQUAL, no writes).
  void draw_additive_lights(const FrameCamera& camera, const LightBuffer& lights) const;
  // Every material's emitted colour times `scale` (1: the scene's own).
  void set_emissive_scale(float scale) { emissive_scale_ = scale; }

 private:
  void draw_scene(const ShaderProgram& program, const FrameCamera& camera, bool renormalize, bool include_base,
                  int first_light, int light_count) const;
  const SceneGpu& scene_;
  ShaderProgram per_pixel_, per_vertex_;
  float emissive_scale_ = 1.f;
};

}  // namespace lp::ch01
