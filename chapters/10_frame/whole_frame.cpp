#include "chapters/10_frame/whole_frame.h"

#include "chapters/04_neon/neon_scene.h"
#include "chapters/05_hdr/hdr_math.h"
#include "common/error.h"

namespace lp::ch10 {

namespace {
bool any_glass(const Scene& scene) {
  for (const Material& m : scene.materials)
    if (m.blend) return true;
  return false;
}
}  // namespace

WholeFrame::WholeFrame(const SceneGpu& scene)
    : gpu_(scene), scene_(scene.scene()), has_sun_(ch06::shadowed_sun(scene_) >= 0), has_glass_(any_glass(scene_)),
      neon_lights_(ch04::neon_lights(scene_)) {}

WholeFrame::WholeFrame(const Scene& scene)
    : owned_(std::make_unique<SceneGpu>(scene)), gpu_(*owned_), scene_(scene), has_sun_(ch06::shadowed_sun(scene) >= 0),
      has_glass_(any_glass(scene)), neon_lights_(ch04::neon_lights(scene)) {}

// [plan]
std::vector<PlannedStage> WholeFrame::plan(const WholeFrameSettings& s) const {
  const bool ambient = glm::length(scene_.ambient) > 0.f;
  const bool msaa = s.msaa > 1, glass = s.transparency != Method::Off, clustered = s.clustered && !msaa;
  auto off = [&](bool wanted, bool possible, const std::string& lacking) {  // why not; with MSAA, any stage without it
    return !wanted ? std::string("switched off") : !possible ? lacking : msaa ? "no MSAA yet: --msaa 1 runs it" : "";
  };
  const std::string per_sample = msaa ? "; per sample on edges, chapter 10)" : ")";
  std::vector<PlannedStage> p;
  p.push_back({"G-buffer (chapter 02" + (msaa ? ", " + std::to_string(s.msaa) + " samples)" : ")"), true, "", "scene", "G-buffer"});
  p.push_back({"shadow map of the sun (chapter 06)", s.shadows && has_sun_,
               !s.shadows ? "switched off" : has_sun_ ? "" : "no directional light that casts shadows", "scene", "shadow map"});
  p.push_back({"global light: ambient + directional (chapter 03" + per_sample, true, "", "G-buffer + shadow map", "light buffer"});
  p.push_back({clustered ? "local lights: clusters (chapter 09)" : "local lights: stencil volumes (chapter 03" + per_sample, true, "",
               clustered ? "G-buffer + light lists" : "G-buffer + stencil", "light buffer"});
  const bool tubes_in_clusters = clustered && s.tubes == TubeLight::Clusters;
  p.push_back({tubes_in_clusters ? "neon tubes: in the clusters (chapters 04, 09)" : "neon tubes: capsule volumes (chapter 04" + per_sample,
               s.neon && !neon_lights_.empty(), !s.neon ? "switched off" : neon_lights_.empty() ? "no neon tubes" : "",
               tubes_in_clusters ? "G-buffer + light lists" : "G-buffer + stencil", "light buffer"});
  p.push_back({"ambient occlusion (chapters 07, 08)", s.ao && ambient && !msaa, off(s.ao, ambient, "no ambient light"), "G-buffer",
               "light buffer"});
  p.push_back({"indirect light, one bounce (chapter 08)", s.indirect && !msaa, off(s.indirect, true, ""), "G-buffer + light buffer",
               "light buffer"});
  p.push_back({msaa ? "composite, then the float resolve of the samples (chapters 03, 10)" : "composite into float radiance (chapter 03)",
               true, "", "G-buffer + light buffer", "radiance RGBA16F"});
  p.push_back({msaa ? "glass, into the samples before the resolve (chapter 10)" : "glass (chapter 10)", glass && has_glass_,
               !glass ? "switched off" : has_glass_ ? "" : "no alphaMode BLEND material",
               "light lists + shadow map + depth", "radiance RGBA16F"});
  p.push_back({"log-average, adaptation, bloom, tonemap (chapter 05)", true, "", "radiance RGBA16F", "sRGB8 output"});
  return p;
}
// [/plan]

std::string WholeFrame::key(const std::vector<PlannedStage>& p) {
  std::string k;
  for (const PlannedStage& st : p) k += st.runs ? '1' : '0';
  return k;
}

// [build]
// The stages are added to chapter 03's frame in the order their hooks must run: the shadow
// map before any light reads it, the tubes before the indirect pass reads the lit diffuse
// light, the glass after the composite.
void WholeFrame::build(const std::vector<PlannedStage>& p) {
  const bool shadows = p[kShadowMap].runs, neon = p[kNeon].runs, ao = p[kAo].runs, indirect = p[kIndirect].runs,
             glass = p[kGlass].runs;
  msaa_.reset();  // it reads the lights of the source made below
  glass_.reset();
  gi_.reset();
  shadows_.reset();
  neon_.reset();
  clustered_.reset();
  source_ = std::make_unique<ch05::DeferredRadiance>(gpu_);  // the scene stays on the GPU as it is
  ch03::DeferredFrame& frame = source_->frame();
  // With glass, the lists of every cluster: the glass reads them too, so one set is built a
  // frame (a cell's list is the same whether a surface occupies it or not).
  clustered_ = std::make_unique<ch09::ClusteredLights>(frame.volumes(), ch09::ClusterSettings{.all_cells = glass});
  // [add-stages]
  if (shadows) {
    shadows_ = std::make_unique<ch06::ShadowStage>(gpu_, scene_.lights[std::size_t(ch06::shadowed_sun(scene_))]);
    frame.add_stage(*shadows_);
  }
  if (neon) {
    tubes_ = std::make_unique<ch04::NeonTubes>();
    tubes_->upload(neon_lights_);
    neon_ = std::make_unique<ch04::NeonStage>(source_->scene_gpu(), *tubes_);
    frame.add_stage(*neon_);
  }
  if (ao || indirect) {
    gi_ = std::make_unique<ch08::GiStage>(source_->scene_gpu());
    frame.add_stage(*gi_);
  }
  if (glass) {
    glass_ = std::make_unique<TransparencyStage>(frame, source_->scene_gpu());
    frame.add_stage(*glass_);
  }
  // [/add-stages]
  for (ch03::FrameStage* stage : later_) frame.add_stage(*stage);  // added by a later chapter (11)
  if (gi_) gi_->set_filter(gi_filter_);                             // and its change to chapter 08's result
  radiance_.reset();
  built_ = key(p);
}
// [/build]

void WholeFrame::reload_shaders() {
  if (!source_) return;
  source_->reload_shaders();
  if (neon_) neon_->reload_shaders();
  if (shadows_) shadows_->reload_shaders();
  if (gi_) gi_->reload_shaders();
  if (clustered_) clustered_->reload_shaders();
  if (glass_) glass_->reload_shaders();
  hdr_.reload_shaders();
}

// [render]
void WholeFrame::render(const FrameCamera& camera, const ch03::FrameOutput& output, const WholeFrameSettings& s,
                        float dt, bool new_shot, PassMetrics* metrics) {
  const std::vector<PlannedStage> p = plan(s);
  if (!source_ || key(p) != built_) {
    build(p);
    new_shot = true;
  }
  if (new_shot) {
    hdr_.reset_adaptation(1.f);
    feedback_.reset();
  }
  ch05::HdrSettings hdr = s.hdr;
  hdr.adaptation.dt = dt;
  // 1. The lights cut for the largest exposure this frame can get (chapter 05), scaled.
  const ch05::ExposureEstimate cut = feedback_.begin_frame(hdr.adaptation, hdr.delta, 1.f);
  source_->set_cut_exposure(cut.exposure * ch05::output_slope(hdr.tonemap.op, hdr.tonemap.white));
  source_->set_scales(s.sun, s.glow);
  // 2. The stages' settings: each chapter's defaults.
  ch03::DeferredFrame& frame = source_->frame();
  frame.set_local_lights(s.clustered ? clustered_.get() : nullptr);
  frame.set_global_pass(s.global);  // (MSAA's frame lights its samples with its own passes)
  // [tubes]
  // The tubes' light: binned and shaded with the clustered lights, or chapter 04's volumes.
  const bool tubes_in_clusters = neon_ && s.clustered && s.msaa <= 1 && s.tubes == TubeLight::Clusters;
  if (neon_) neon_->set_light_by_volumes(!tubes_in_clusters);
  clustered_->set_tubes(tubes_in_clusters ? tubes_->packed() : std::vector<ch04::NeonGpu>{},
                        neon_ ? neon_->how() : ch04::NeonDraw{});
  // [/tubes]
  frame.set_strategy(ch03::Strategy::Stencil);
  if (shadows_) shadows_->set(s.sun_shadow ? *s.sun_shadow : ch06::ShadowSettings{.cascades = s.sun_cascades});
  if (gi_) {
    ch08::GiSettings g = s.gi;
    g.ao = p[kAo].runs;
    g.indirect = p[kIndirect].runs;
    gi_->set(g.indirect ? ch08::GiMode::Ssgi : ch08::GiMode::Ssao, g, ch08::GiShow::Image, source_->scene().ambient);
  }
  if (glass_) {
    glass_->set({.method = s.transparency});
    // The frame's lists when its clusters drew the local lights; else (chapter 03's volumes, or
    // MSAA, whose local lights are those volumes) its own, over the same lights.
    glass_->use_frame_lists(s.clustered && s.msaa <= 1 ? clustered_.get() : nullptr);
  }
  // [one-frame]
  // 3. The frame into float radiance: G-buffer, shadow map, lights, tubes, AO + indirect,
  //    composite, glass (chapter 03's DeferredFrame::render with the stages above), or with
  //    MSAA chapter 10's multisampled frame, lit by the same lights, resolved into radiance.
  if (!radiance_ || radiance_->width() != output.width || radiance_->height() != output.height)
    radiance_ = std::make_unique<ch05::RadianceTarget>(output.width, output.height, GL_RGBA16F, neon_ || glass_);
  if (s.msaa > 1) render_msaa(camera, output, s, hdr, cut, metrics);
  else source_->render(camera, *radiance_, metrics);
  // 4. Chapter 05's HDR stage into the sRGB8 output.
  hdr_.process(radiance_->texture(), output.width, output.height, hdr, output.framebuffer, metrics);
  feedback_.end_frame(hdr_.adaptation().state_buffer());
  // [/one-frame]
}
// [/render]

// [msaa-stages]
// MSAA's frame, lit by the source's lights, with the stages the plan runs with it besides the
// sun's map: the tubes' light (their capsules per sample on the edges), and over the samples
// before the resolve, depth-tested against the multisampled depth, the tubes' glass and the panes.
void WholeFrame::make_msaa() {
  msaa_ = std::make_unique<MsaaFrame>(source_->scene_gpu(), source_->volumes());
  if (neon_) msaa_->set_tubes(tubes_.get(), neon_->how());
  if (!glass_ && !neon_) return;
  msaa_->draw_over_samples([this](const ch02::GBuffer& gbuffer, const ch03::SurfaceView& view,
                                  const ch03::FrameOutput& samples, PassMetrics* metrics) {
    if (neon_) neon_->draw_glass(source_->frame().camera(), metrics);
    if (glass_) glass_->draw_over(source_->frame(), {gbuffer, view, samples}, metrics);
  });
}
// [/msaa-stages]

// [msaa]
// With MSAA: chapter 10's multisampled frame lit by chapter 03's frame's lights (its volumes),
// resolved into the radiance chapter 05's chain reads.
void WholeFrame::render_msaa(const FrameCamera& camera, const ch03::FrameOutput& output, const WholeFrameSettings& s,
                             const ch05::HdrSettings& hdr, const ch05::ExposureEstimate& cut, PassMetrics* metrics) {
  if (!later_.empty()) throw Error("--msaa: a later chapter's stages (chapter 11's) run in chapter 03's frame, which has no MSAA");
  source_->update_lights();
  if (!msaa_) make_msaa();
  msaa_->set_emissive_scale(s.glow);
  // The stages' before_lights (the sun's map), their hooks in MSAA's passes; no G-buffer of chapter 03's.
  const ch03::FrameOutput into{radiance_->framebuffer(), output.width, output.height};
  source_->frame().prepare_stages(camera, into, metrics);
  msaa_->use_stages(&source_->frame());
  // The resolve's weights bend where the eye's exposure (the last one read back) puts the curve's
  // knee. A new shot has none: its samples are resolved with the knee at 1, chapter 05 measures
  // that frame's exposure, and (one wait for the GPU, on a new shot only) the samples are
  // resolved again with it, the eye reset to start from the new image.
  MsaaSettings m{.samples = s.msaa, .order = s.msaa_order, .show = s.msaa_edges ? MsaaShow::Edges : MsaaShow::Image,
                 .output = MsaaOutput::Radiance, .exposure = cut.age >= 0 && cut.read > 0.f ? cut.read : 1.f};
  msaa_->render(camera, into, m, metrics);
  if (cut.age < 0 && m.order == ResolveOrder::TonemapFirst) {
    hdr_.process(radiance_->texture(), output.width, output.height, hdr, output.framebuffer);
    m.exposure = hdr_.adaptation().read().exposure;
    hdr_.reset_adaptation(1.f);
    msaa_->resolve(into, m);  // (the first is the one timed: the same pass)
  }
}
// [/msaa]

std::size_t WholeFrame::allocated_bytes() const {
  std::size_t b = source_ ? source_->allocated_bytes() : 0;
  if (radiance_) b += radiance_->bytes();
  if (shadows_) b += shadows_->allocated_bytes();
  if (glass_) b += glass_->allocated_bytes();
  if (msaa_) b += msaa_->allocated_bytes();
  return b + hdr_.allocated_bytes() + (clustered_ ? clustered_->stats().bytes : 0);
}

}  // namespace lp::ch10
