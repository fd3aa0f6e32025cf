#pragma once
// The deferred frame as one object, owned by chapter 03 and extended by the chapters after
// it: chapter 02's G-buffer, ambient and directional light for every pixel, each local light
// in its volume, and the composite F = albedo * L1 + L2 + emissive. The program, its tests
// and its sweep all draw through it, so what they check is the frame the reader runs.
//
//   DeferredFrame frame(scene_gpu);
//   frame.volumes().set_lights(build_light_set(scene.lights, threshold, frame.volumes().shapes()));
//   frame.render(camera, {output_fbo, width, height}, &metrics);   // G-buffer .. composite
//
// [extending]
// A later chapter extends the frame without editing it, in two ways:
// - a FrameStage (add_stage): C++ hooks at fixed points of render(), and GLSL hooks that
//   chapter 03's light shaders include (ShaderHooks: a visibility term per light, a per-pixel
//   ambient term). Chapter 04 adds its tube lights this way, 06 its shadows, 07 and 08
//   ambient occlusion and indirect light.
// - a LocalLightPass (set_local_lights): another way to bring the local lights into the light
//   buffer than chapter 03's volumes; chapter 09's tiled and clustered culling.
// Every hook does nothing by default: a frame without stages is chapter 03's image, bit for bit.
// [/extending]
#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "chapters/02_gbuffer/gbuffer.h"
#include "chapters/03_light_volumes/light_volumes.h"
#include "common/camera.h"
#include "common/metrics.h"
#include "common/scene_gpu.h"

namespace lp::ch03 {

class DeferredFrame;

// Where the frame draws its image: a framebuffer of width x height (the sRGB output, or a
// float target such as chapter 05's radiance). Stages that draw over the image test against
// its depth-stencil attachment, which copy_depth_to_output() fills with the G-buffer's depth.
struct FrameOutput {
  GLuint framebuffer = 0;
  int width = 0, height = 0;
  // The framebuffer's colour as an RGBA16F texture, where it is one (a float target; 0: not):
  // with the global pass in compute, the composite then runs in compute too, writing it.
  GLuint image = 0;
  void bind() const;  // binds it, sets the viewport, sRGB encoding on (no-op for float targets)
};

// [frame-stage]
// The texture units and uniform-block bindings the frame gives a stage, after its own (the
// G-buffer's units 0..4 and block 7, the light buffer's units 5 and 6) and after the stages
// added before it. The stage names them to its GLSL by defines (shader_hooks()), so no shader
// hard-codes a unit another stage may also use.
struct StageSlots {
  GLuint first_unit = 0, first_block = 0;
  GLuint unit(int i) const { return first_unit + GLuint(i); }
  GLuint block(int i) const { return first_block + GLuint(i); }
};
struct StageNeeds {
  int units = 0, blocks = 0;  // how many of each the stage's passes and hooks read
};

// A stage a later chapter adds to the frame. render() calls the hooks in this order:
//   geometry -> before_lights -> global + local lights -> add_light -> composite -> after_composite
class FrameStage {
 public:
  virtual ~FrameStage() = default;
  // How many texture units and blocks the frame must give it (slots() once added).
  virtual StageNeeds needs() const { return {}; }
  // The GLSL files the light shaders include and the defines they need (see ShaderHooks);
  // empty file names keep chapter 03's.
  virtual ShaderHooks shader_hooks() const { return {"", ""}; }
  // Binds what its GLSL hooks read on its slots. The frame calls it before every pass that
  // includes the hooks (the lights, a forward pass through DeferredFrame::bind_hooks()), so a
  // texture another stage's pass bound in between never reaches them.
  virtual void bind_hook_resources() const {}
  // After the G-buffer, before any light: shadow maps, ambient occlusion...
  virtual void before_lights(DeferredFrame&, PassMetrics*) {}
  // More light added into the light buffer (bound) after chapter 03's own: chapter 04's tubes.
  virtual void add_light(DeferredFrame&, PassMetrics*) {}
  // Draws the image into the bound output instead of chapter 03's composite when it returns
  // true (chapter 04 shows its tubes' diffuse or specular term alone).
  virtual bool composite(DeferredFrame&, PassMetrics*) { return false; }
  // Over the finished image, into the bound output: glass, pictures.
  virtual void after_composite(DeferredFrame&, PassMetrics*) {}

  const StageSlots& slots() const { return slots_; }  // given by DeferredFrame::add_stage

 private:
  friend class DeferredFrame;
  StageSlots slots_;
};
// [/frame-stage]// [/frame-stage]

// [local-light-pass]
// How the local lights reach the light buffer. Chapter 03's volumes (VolumeLights) are the
// default; chapter 09 brings tiled and clustered culling in compute.
class LocalLightPass {
 public:
  virtual ~LocalLightPass() = default;
  virtual std::string name() const = 0;  // for the timings: "stencil", "clustered", ...
  // Adds every local light into `light` (its depth-stencil holds the G-buffer's depth and a
  // zero stencil, which it must leave at zero), reading the surface through `view`.
  virtual void draw(const LightBuffer& light, const SurfaceView& view, LightVolumes::Output output) = 0;
  // A pass made of several GPU passes may time each of them itself: then render() hands it
  // the frame's metrics before draw() instead of timing draw() as one pass (scopes do not nest).
  virtual bool times_own_passes() const { return false; }
  virtual void set_metrics(PassMetrics*) {}
};
// [/local-light-pass]

// Chapter 03's own local lights: its volumes, with one of its six culling strategies.
class VolumeLights : public LocalLightPass {
 public:
  VolumeLights(LightVolumes& volumes, Strategy strategy) : volumes_(volumes), strategy_(strategy) {}
  std::string name() const override { return kStrategies[int(strategy_)]; }
  void draw(const LightBuffer& light, const SurfaceView& view, LightVolumes::Output output) override {
    volumes_.draw_local(light, view, strategy_, output);
  }
  Strategy strategy() const { return strategy_; }
  void set_strategy(Strategy strategy) { strategy_ = strategy; }

 private:
  LightVolumes& volumes_;
  Strategy strategy_;
};

// What render() draws, besides the image itself: chapter 03's pictures of its light buffer.
enum class FrameShow { Image, DiffuseLight, SpecularLight, HeatShaded, HeatLit };
// heat.frag's ramp, its stops as display values (0 at the first, heat_full_scale at the last):
// what the heat maps' keys draw (common/image.h, HeatKey::stops).
inline const std::vector<std::array<float, 3>> kHeatRamp = {
    {0.0f, 0.0f, 0.0f}, {0.0f, 0.1f, 0.6f}, {0.0f, 0.6f, 0.3f}, {0.9f, 0.8f, 0.0f}, {0.9f, 0.1f, 0.0f}, {1.0f, 1.0f, 1.0f}};

struct FrameSettings {
  FrameShow show = FrameShow::Image;
  // Chapter 03's global and local lights; off, the light buffer starts black and only the
  // stages' light is in it (chapter 04's tubes alone).
  bool scene_lights = true;
  float heat_full_scale = 40.f;  // HeatShaded / HeatLit: fragments per pixel drawn white
};

class DeferredFrame {
 public:
  // The first texture unit and uniform-block binding given to the stages (StageSlots): after
  // the G-buffer's (units 0..4, block 7) and the light buffer's (units 5, 6).
  static constexpr GLuint kFirstStageUnit = 8, kFirstStageBlock = 8;

  // The scene's ambient light and chapter 01's background to start with; the icosphere of
  // the point lights' volumes subdivided `sphere_subdivisions` times (LightVolumes).
  explicit DeferredFrame(const SceneGpu& scene, const ch02::Layout& layout = ch02::our_layout(),
                         int sphere_subdivisions = 2);
  void reload_shaders();
  // Every emissive surface's colour times `scale` (chapter 05's glow), in the G-buffer and in
  // the stages that draw surfaces themselves (chapter 10's glass reads emissive_scale()).
  void set_emissive_scale(float scale) { geometry_->set_emissive_scale(scale); }
  float emissive_scale() const { return geometry_->emissive_scale(); }

  // Chapter 03's lights: set_lights(build_light_set(...)), counting, the pictures.
  LightVolumes& volumes() { return volumes_; }
  const LightVolumes& volumes() const { return volumes_; }
  void set_strategy(Strategy strategy);             // which of chapter 03's culling strategies
  void set_local_lights(LocalLightPass* pass);      // another chapter's; nullptr: chapter 03's again
  // The global pass as a fragment pass (chapter 03's default) or in compute: the same light
  // buffer bit for bit (GlobalPass, light_volumes.h); chapter 10's whole frame runs compute. A
  // stage's own full-screen pass into the light buffer follows it (chapter 08's add), and so
  // does the composite where the output gives its colour as an image (FrameOutput::image).
  void set_global_pass(GlobalPass how) { global_ = how; }
  GlobalPass global_pass() const { return global_; }
  // Called in the order added; gives the stage its texture units and blocks (StageSlots).
  void add_stage(FrameStage& stage);
  // Binds every stage's hook resources: for a pass outside render() that includes the hooks
  // (chapter 10's glass, chapter 08's back faces). render() calls it before its light passes.
  void bind_hooks() const;
  // The GLSL hooks of the stages added (chapter 03's where none names its own), with their
  // defines: what a pass outside render() that includes the hooks compiles with.
  ShaderHooks stage_hooks() const { return hooks(); }
  // For a frame drawn elsewhere over these lights and stages (chapter 10's MSAA, whose targets
  // are multisampled): render()'s camera and output set and the stages' before_lights run,
  // with no G-buffer of this frame's drawn. Only stages whose before_lights read no G-buffer
  // may be added then (the sun's shadow map); the caller binds bind_hooks() for its passes.
  void prepare_stages(const FrameCamera& camera, const FrameOutput& output, PassMetrics* metrics = nullptr);
  void set_ambient(const glm::vec3& ambient) { ambient_ = ambient; }
  void set_background(const glm::vec3& background) { background_ = background; }
  const glm::vec3& background() const { return background_; }

  // The frame: G-buffer, lights, composite into `output`; each pass timed in `metrics`.
  void render(const FrameCamera& camera, const FrameOutput& output, PassMetrics* metrics = nullptr,
              const FrameSettings& settings = {});

  // What the last render() left, for the stages and for pictures drawn after it.
  const ch02::GBuffer& gbuffer() const { return *gbuffer_; }
  const LightBuffer& light() const { return *light_; }
  const SurfaceView& view() const { return view_; }  // with the stages' shader hooks
  const FrameOutput& output() const { return output_; }
  const FrameCamera& camera() const { return camera_; }  // as render() was given it
  // The G-buffer's depth into the output's depth-stencil (same format), stencil zeroed, and
  // the output bound: for what is drawn over the image with a depth test.
  void copy_depth_to_output() const;
  std::size_t allocated_bytes() const;  // G-buffer + light buffer

 private:
  void resize(int width, int height);
  ShaderHooks hooks() const;

  const SceneGpu& scene_;
  ch02::Layout layout_;
  std::unique_ptr<ch02::GeometryPass> geometry_;
  LightVolumes volumes_;
  VolumeLights volume_lights_;
  LocalLightPass* local_ = &volume_lights_;
  GlobalPass global_ = GlobalPass::Fragment;
  std::vector<FrameStage*> stages_;
  StageSlots next_slots_{kFirstStageUnit, kFirstStageBlock};
  std::unique_ptr<ch02::GBuffer> gbuffer_;
  std::unique_ptr<LightBuffer> light_;
  SurfaceView view_;
  FrameOutput output_;
  FrameCamera camera_;
  glm::vec3 ambient_{0}, background_;
};

// What every program from chapter 03 on does first: `lights` (the scene's, or a chapter's
// variant of them) cut where they fall below one output step for the scene's glossiest
// material (light_radius.h), set as the frame's local and global lights. The light set's
// warnings (a light it cannot draw, and why) go to std::cerr when `say_warnings`.
void use_lights(DeferredFrame& frame, const Scene& scene, const std::vector<Light>& lights, bool say_warnings = true);

}  // namespace lp::ch03
