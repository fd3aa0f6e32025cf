#pragma once
// Chapter 10's transparency: the glass (materials with glTF alphaMode BLEND) that a G-buffer
// cannot hold, one surface per pixel as it is. Chapter 02's geometry pass skips it; this stage
// draws it after the deferred passes, over the finished image, with a forward pass lit by the
// frame's own lights: the directional ones as chapter 03's global pass lights them, the local
// ones from chapter 09's cluster lists (clustered forward: the same cut, the same
// local_light(), the same visibility hook), depth-tested against the G-buffer's depth and
// writing none. Two ways to blend, as a knob:
//   sorted  whole surfaces back to front by the view depth of their centres, each blended over
//           what is there ("over": C = alpha c + (1 - alpha) C_behind, premultiplied);
//   wboit   weighted blended order-independent transparency (McGuire & Bavoil 2013): in any
//           order, a weighted sum of the premultiplied colours and the product of (1 - alpha)
//           into two float targets, and a full-screen pass that puts their average over the image.
// The exact order (every fragment of every surface at every pixel, sorted by depth, composited
// in double on the CPU) is the ground truth both are measured against (exact_composite()).
//
//   ch03::DeferredFrame frame(scene_gpu);   TransparencyStage glass(frame, scene_gpu);
//   frame.add_stage(glass);
//   glass.set({.method = Method::Wboit});
//   frame.render(camera, output, &metrics);
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/09_clustered/clustered_lights.h"
#include "common/gl.h"
#include "common/image.h"
#include "common/shader.h"

namespace lp::ch10 {

enum class Method { Off, Sorted, Wboit };
inline const std::vector<std::string> kMethods = {"off", "sorted", "wboit"};
Method method_named(const std::string& name);  // throws Error for an unknown name

// The order the surfaces are drawn in. BackToFront is what sorting means; the others are for
// the tests (a method that is order independent must not care).
enum class DrawOrder { BackToFront, FrontToBack, AsListed, Shuffled };

// What is drawn: the image, or one of WBOIT's two targets in its place.
enum class TransparencyShow { Image, Accumulation, Revealage };

struct TransparencySettings {
  Method method = Method::Sorted;
  DrawOrder order = DrawOrder::BackToFront;
  std::uint32_t shuffle_seed = 1;  // DrawOrder::Shuffled
  TransparencyShow show = TransparencyShow::Image;
};

// One blended primitive of one instance, and where its centre is (world space).
struct BlendedDraw {
  std::size_t instance = 0, primitive = 0;
  glm::vec3 centre{0};
};
// The scene's blended primitives, in scene order.
std::vector<BlendedDraw> blended_draws(const Scene& scene);
// The draws in `order`; BackToFront by the view depth of their centres (farthest first, ties
// in scene order). Per surface, not per pixel: two panes that cross are each in front of the
// other on one side of the crossing line, and any order of the two is wrong on one side.
std::vector<BlendedDraw> ordered(std::vector<BlendedDraw> draws, const glm::mat4& view, DrawOrder order,
                                 std::uint32_t seed = 1);

// [wboit-weight]
// WBOIT's weight of a fragment at view depth z (metres, > 0) with coverage alpha: McGuire and
// Bavoil's first depth weight, w = alpha * clamp(10 / (1e-5 + (z/5)^2 + (z/200)^6), 1e-2, 3e3).
// Near surfaces weigh more, so the nearest layer dominates the average as "over" would make it.
// The C++ twin of wboit_weight() in shaders/transparent.frag.
float wboit_weight(float view_depth, float alpha);
// [/wboit-weight]

// The exact per-pixel order, composited on the CPU.
struct ExactComposite {
  ImageRGBA8 image;                  // rows top to bottom, as the output reads back
  std::vector<int> layers;           // per pixel: transparent fragments in front of the opaque surface
  // per pixel: the back-to-front order of whole surfaces (ordered()) is this pixel's depth order
  std::vector<std::uint8_t> surface_order_right;
  std::size_t fragments = 0;
  bool overflow = false;             // more fragments than the capture holds (then not exact)
};

// Where the glass is drawn: over `image`, whose depth-stencil holds `gbuffer`'s depth sample for
// sample, with `gbuffer`'s camera and layout and `view` (its defines with the frame's hooks).
// after_composite() draws over the frame's output with the frame's G-buffer; chapter 10's MSAA
// over its multisampled light target with its multisampled G-buffer, before the resolve, so the
// glass's edges are resolved with the rest (whole_frame.cpp).
struct GlassTarget {
  const ch02::GBuffer& gbuffer;
  const ch03::SurfaceView& view;
  ch03::FrameOutput image;
};

class TransparencyStage : public ch03::FrameStage {
 public:
  // Lit by `frame`'s lights (frame.volumes().lights(), as use_lights() set them).
  TransparencyStage(const ch03::DeferredFrame& frame, const SceneGpu& scene);
  void reload_shaders();
  void set(const TransparencySettings& settings) { settings_ = settings; }
  // The frame's own clusters, when its local lights are drawn by them (chapter 09, clustered,
  // all_cells on): the glass reads the lists the frame built this frame instead of building a
  // second set. nullptr (chapter 03's volumes): the stage builds lists of its own.
  void use_frame_lists(ch09::ClusteredLights* lists);
  const TransparencySettings& settings() const { return settings_; }
  std::size_t blended_count() const { return draws_.size(); }

  void after_composite(ch03::DeferredFrame& frame, PassMetrics* metrics) override;
  // The glass over `target` instead of the frame's output, lit by the frame's lights and hooks
  // (the caller fills its depth; the frame's camera is set, e.g. by prepare_stages()).
  void draw_over(const ch03::DeferredFrame& frame, const GlassTarget& target, PassMetrics* metrics);

  // The exact order over the image the frame's last render() left in its output (which must
  // hold the opaque image only: render with Method::Off first). Reads the output back as sRGB8
  // bytes: it is the truth for the sRGB8 output (a float radiance target would need its own).
  ExactComposite exact_composite(const ch03::DeferredFrame& frame, std::size_t max_fragments_per_pixel = 16);
  // WBOIT's targets after the last wboit frame (RGBA16F accumulation, R16F revealage).
  GLuint accumulation() const { return accum_.id(); }
  GLuint revealage() const { return reveal_.id(); }
  std::size_t allocated_bytes() const;  // WBOIT's targets and their depth, every sample

 private:
  enum Output { kOver, kWboit, kCapture };
  void resize(const GlassTarget& target);
  void build_lights(const GlassTarget& target, PassMetrics* metrics);
  const ShaderProgram& program(Output output, const GlassTarget& target);
  void draw_surfaces(const ch03::DeferredFrame& frame, const GlassTarget& target, Output output,
                     const std::vector<BlendedDraw>& draws, bool ranks);
  void draw_sorted(const ch03::DeferredFrame& frame, const GlassTarget& target, PassMetrics* metrics);
  void draw_wboit(const ch03::DeferredFrame& frame, const GlassTarget& target, PassMetrics* metrics);
  GlassTarget frame_target(const ch03::DeferredFrame& frame) const { return {frame.gbuffer(), frame.view(), frame.output()}; }

  const SceneGpu& scene_;
  std::vector<BlendedDraw> draws_;
  const ch03::DeferredFrame& frame_;
  // Every cluster's list (all_cells): glass may lie in any of them. The frame's (use_frame_lists)
  // or, made when first needed, the stage's own.
  ch09::ClusteredLights* frame_lists_ = nullptr;
  std::unique_ptr<ch09::ClusteredLights> own_lists_;
  ch09::ClusteredLights& lists();
  TransparencySettings settings_;
  ProgramCache programs_;  // per output and the frame's defines
  ShaderProgram composite_;
  std::unique_ptr<ShaderProgram> composite_samples_;  // per sample, for a multisampled target (made when needed)
  gl::VertexArray empty_vao_;
  int width_ = 0, height_ = 0, samples_ = 1;
  int capacity_ = 0;  // the exact composite's fragment list
  GLenum depth_format_ = 0;
  gl::Texture accum_{GL_TEXTURE_2D}, reveal_{GL_TEXTURE_2D}, depth_{GL_TEXTURE_2D};
  gl::Framebuffer fbo_;
};

}  // namespace lp::ch10
