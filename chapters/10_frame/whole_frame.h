#pragma once
// The whole frame: every stage of the book in one deferred frame, in the order the sources
// draw it, each a library call into its chapter. This file adds only the assembly:
//
//   1. G-buffer (chapter 02), through chapter 05's float radiance source (chapter 03's frame)
//   2. the sun's shadow map (chapter 06)                       ShadowStage, before the lights
//   3. ambient + directional light, then the local lights: chapter 03's stencil volumes or
//      chapter 09's clusters                                   the frame's LocalLightPass
//   4. chapter 04's neon tubes                                 NeonStage, a light of its own
//   5. AO and one bounce of indirect light in one pass (chapters 07 and 08)   GiStage
//   6. the composite into float radiance, then the glass (chapter 10)   TransparencyStage
//   7. log-average, eye adaptation, bloom, tonemapping, sRGB (chapter 05)    HdrPipeline
//
// With MSAA (WholeFrameSettings::msaa > 1) steps 1, 3 and 6 are chapter 10's MsaaFrame
// (msaa.h) lit by the same lights: a multisampled G-buffer, light per sample on the marked
// edges, and a float resolve into the radiance the HDR chain reads. The sun's shadow map is
// drawn as without MSAA and its hook read by MSAA's light passes, per sample on the edges; the
// tubes light through their capsules at both rates (MsaaFrame::set_tubes), and the tubes' glass
// and the panes are drawn into the samples before the resolve (MsaaFrame::draw_over_samples).
// The other stages do not read a multisampled G-buffer yet: they are not run with it, and plan()
// says so.
//
// What the scene does not need is not run, and plan() says so: no tubes, no neon pass; no
// sun, no shadow map; no glass, no transparency pass; no ambient light, no AO.
//
//   WholeFrame frame(scene_gpu);
//   frame.render(camera, {target, w, h}, settings, dt, new_shot, &metrics);
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "chapters/04_neon/neon_forward.h"
#include "chapters/04_neon/neon_stage.h"
#include "chapters/05_hdr/exposure_feedback.h"
#include "chapters/05_hdr/hdr_pipeline.h"
#include "chapters/05_hdr/radiance_source.h"
#include "chapters/06_shadows/shadow_stage.h"
#include "chapters/08_ssgi/gi_stage.h"
#include "chapters/09_clustered/clustered_lights.h"
#include "chapters/10_frame/msaa.h"
#include "chapters/10_frame/transparency.h"

namespace lp::ch10 {

// [whole-settings]
// Where chapter 04's tubes add their light: chapter 09's clusters (binned as capsules with the
// local lights and shaded in its compute pass, when those are clustered), or chapter 04's
// capsule volumes through the stencil (a fragment pass per tube, kept for teaching).
enum class TubeLight { Volumes, Clusters };
struct WholeFrameSettings {
  bool shadows = true;     // chapter 06: the sun's shadow map (PCF 3x3), when the scene has a sun
  bool clustered = true;   // chapter 09's clusters for the local lights; false: chapter 03's stencil volumes
  // The full-screen passes, chapter 03's global pass (ambient + directional), chapter 08's add of
  // the indirect light and chapter 03's composite into the float radiance, in compute or as their
  // fragment passes: the same bodies, light buffer and radiance (ch03::GlobalPass). Compute,
  // because a GPU may run fragment shaders on a few of its cores only and compute on all (the
  // H200: the book's budget); elsewhere the same work.
  ch03::GlobalPass global = ch03::GlobalPass::Compute;
  bool ao = true;          // chapters 07/08: AO on the ambient light (the narrow disk)
  bool indirect = true;    // chapter 08: one bounce of diffuse indirect light (the wide disk)
  bool neon = true;        // chapter 04's tubes, when the scene has any
  TubeLight tubes = TubeLight::Clusters;  // their light; volumes when the local lights are
  // Chapter 06's cascades for the sun: four snapped maps, the count chapter 06 measures against
  // one map (up to ch06::kMaxCascades; 1: one map fitted to the view).
  int sun_cascades = 4;
  // Chapter 06's settings for the sun's map in full (a later chapter's: chapter 11's PCSS); empty:
  // PCF 3x3 with sun_cascades.
  std::optional<ch06::ShadowSettings> sun_shadow;
  Method transparency = Method::Sorted;  // chapter 10's glass, when the scene has any
  float sun = 1.f, glow = 8.f;           // chapter 05's scales of the sun and the emissive surfaces
  ch05::HdrSettings hdr;                 // chapter 05: its defaults (Reinhard, key 0.18, floor 0.18, no bloom)
  // MSAA's samples per pixel (1, 2, 4 or 8; 1: no MSAA, the frame above), the order of its
  // resolve, and the marked edges drawn red.
  int msaa = 1;
  ResolveOrder msaa_order = ResolveOrder::TonemapFirst;
  bool msaa_edges = false;
  // Chapter 08's pass as its chapter sets it (32 randomised samples, blurred); its ao and
  // indirect are the two switches above.
  ch08::GiSettings gi;
};
// [/whole-settings]

// The plan's lines, in frame order: plan() pushes one per step in this order, so
// plan()[kShadowMap] is the shadow map's line.
enum PlanStep { kGBufferStep, kShadowMap, kGlobalLight, kLocalLights, kNeon, kAo, kIndirect, kComposite, kGlass, kHdr };

// One line of the plan: a stage, whether it runs this frame, and why not.
struct PlannedStage {
  std::string stage;
  bool runs = false;
  std::string why;     // what the scene lacks, or which setting turned it off
  std::string reads;   // the buffers it reads, "+"-separated (the pass diagram, tools/figures_10.py)
  std::string writes;  // the buffers it writes
};

class WholeFrame {
 public:
  explicit WholeFrame(const SceneGpu& scene);  // the program's scene, as uploaded
  explicit WholeFrame(const Scene& scene);     // uploads it once (tests)
  void reload_shaders();
  // A later chapter's stage (chapter 11's motion vectors and TAA): added to chapter 03's frame
  // after this chapter's own, on every rebuild, so its after_composite sees the glass drawn.
  void add_stage(ch03::FrameStage& stage) { later_.push_back(&stage); built_.clear(); }
  // A later chapter's change to chapter 08's result before the light buffer adds it (chapter
  // 11's accumulation over frames), on every rebuild; nullptr: none.
  void set_gi_filter(ch08::GiFilter* filter) { gi_filter_ = filter; if (gi_) gi_->set_filter(filter); }
  std::vector<PlannedStage> plan(const WholeFrameSettings& s) const;
  // The frame into `output` (sRGB8, any size); each pass timed in `metrics`. `dt`: seconds
  // since the last frame (eye adaptation); `new_shot`: the eye starts adapted.
  void render(const FrameCamera& camera, const ch03::FrameOutput& output, const WholeFrameSettings& s, float dt,
              bool new_shot, PassMetrics* metrics = nullptr);
  std::size_t allocated_bytes() const;
  const ch05::DeferredRadiance& source() const { return *source_; }
  // The float radiance the last render() tonemapped (nullptr before the first).
  const ch05::RadianceTarget* radiance() const { return radiance_.get(); }
  ch05::DeferredRadiance& source() { return *source_; }
  const ch05::HdrPipeline& hdr() const { return hdr_; }  // its eye's state: the exposure it tonemapped with
  // The stages the last render() ran (nullptr when its plan left one out): the tests compare
  // each stage's own output with its chapter's (test_10_stages_gl.cpp).
  const ch06::ShadowStage* shadow_stage() const { return shadows_.get(); }
  ch06::ShadowStage* shadow_stage() { return shadows_.get(); }  // for a later chapter's stage (11) in the frame
  const ch08::GiStage* gi_stage() const { return gi_.get(); }
  const ch09::ClusteredLights* clustered_lights() const { return clustered_.get(); }
  const MsaaFrame* msaa() const { return msaa_.get(); }  // after a render() with msaa > 1

 private:
  void build(const std::vector<PlannedStage>& p);  // the radiance source with the stages the plan runs
  static std::string key(const std::vector<PlannedStage>& p);  // which stages run: one character each
  // Step 3 with MSAA: its frame into radiance_, the resolve weighted at the eye's exposure.
  void make_msaa();  // MSAA's frame with the stages it runs (the tubes, the glass)
  void render_msaa(const FrameCamera& camera, const ch03::FrameOutput& output, const WholeFrameSettings& s,
                   const ch05::HdrSettings& hdr, const ch05::ExposureEstimate& cut, PassMetrics* metrics);

  std::unique_ptr<SceneGpu> owned_;  // when made from a Scene
  const SceneGpu& gpu_;
  const Scene& scene_;
  bool has_sun_ = false, has_glass_ = false;
  std::vector<ch04::NeonLight> neon_lights_;
  std::string built_;
  std::unique_ptr<ch05::DeferredRadiance> source_;
  std::unique_ptr<ch04::NeonTubes> tubes_;
  std::unique_ptr<ch04::NeonStage> neon_;
  std::unique_ptr<ch06::ShadowStage> shadows_;
  std::unique_ptr<ch08::GiStage> gi_;
  std::unique_ptr<ch09::ClusteredLights> clustered_;
  std::unique_ptr<TransparencyStage> glass_;
  std::unique_ptr<MsaaFrame> msaa_;  // lit by source_'s lights: made again with it
  std::vector<ch03::FrameStage*> later_;
  ch08::GiFilter* gi_filter_ = nullptr;
  std::unique_ptr<ch05::RadianceTarget> radiance_;
  ch05::HdrPipeline hdr_;
  ch05::ExposureFeedback feedback_;
};

}  // namespace lp::ch10
