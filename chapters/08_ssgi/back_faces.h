#pragma once
// Chapter 08's back-face layer, the source's first fix for the emitters the screen cannot see:
// a second G-buffer of the nearest BACK face at every pixel (front faces culled: the surfaces
// that face away from the camera, behind what it sees or where nothing faces it), and the
// light arriving there: chapter 03's global and local lights evaluated at those surfaces, with
// their own normals, into a second light buffer. A back face can send only what its own side
// receives: its direct light (no ambient, as the front layer's L1: no_ambient.glsl), times its
// albedo. The SSGI pass then reads emitters from both layers at every sample
// (shaders/ssgi.comp, u_back_faces).
//
//   BackFaceLayer back;  back.draw(frame);                 // after the frame's direct lights
//   ssgi.compute(gbuffer, light, camera, settings, &back.textures());
#include <memory>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "common/shader.h"

namespace lp::ch08 {

// What the SSGI pass reads of the layer: window depth (the sky's value where no back face
// is), encoded normal (the surface's own, facing away from the camera), albedo, and L1.
struct BackFaceTextures {
  GLuint depth = 0, normal = 0, albedo = 0, light = 0;
};

class BackFaceLayer {
 public:
  void reload_shaders() { program_.reset(); }
  // Draws the layer for the frame's camera and size with the frame's lights (chapter 03's
  // volumes, stencil strategy) and its shader hooks; leaves the frame's G-buffer bound to units
  // 0.. again, as render() left it.
  void draw(const SceneGpu& scene, ch03::DeferredFrame& frame);
  BackFaceTextures textures() const;
  const ch02::GBuffer& gbuffer() const { return *gbuffer_; }
  const ch03::LightBuffer& light() const { return *light_; }
  std::size_t allocated_bytes() const;

 private:
  std::unique_ptr<ch02::GBuffer> gbuffer_;
  std::unique_ptr<ch03::LightBuffer> light_;
  std::unique_ptr<ShaderProgram> program_;
};

}  // namespace lp::ch08
