#pragma once
// Chapter 10's MSAA with deferred shading (the source's chapter 4): a multisampled G-buffer
// (chapter 02's, N samples), the pixels whose samples differ marked in the stencil, light
// computed once per pixel where they do not and once per sample where they do (two
// stencil-tested passes), and each sample tonemapped before the samples are averaged (the
// source's chapter 5: the tonemapping curve is not linear, so resolving first is wrong).
// Chapter 10's whole frame draws it for --msaa N with MsaaOutput::Radiance: the samples
// resolved into float radiance for chapter 05's HDR chain instead (whole_frame.h).
//
//   MsaaFrame msaa(scene_gpu, frame.volumes());           // chapter 03's frame's lights and cuts
//   msaa.render(camera, {output_fbo, w, h}, {.samples = 4}, &metrics);
//   MsaaCounts n = msaa.counts();                         // exact: marked, shaded
//
// The local lights come one of two ways (MsaaSettings::lights). Volumes (the default):
// chapter 03's stencil light volumes over the multisampled G-buffer, each light's stencil
// mask counted in stencil bits 0-6 (write mask kVolumeBits) while the edge mark keeps bit 7
// (kEdgeBit), so neither destroys the other; per light, its per-sample shader runs on the
// marked samples inside it and its per-pixel shader on the unmarked ones. FullScreen: every
// light summed in the two full-screen passes (chapter 03's cut and local_light() in a loop),
// the first version, kept as the cross-check. Volumes is the default because it is the same
// image (MsaaGl.VolumesShareTheStencilWithTheEdgeMark) and on a street of hundreds of lights
// it shades only the pixels each light reaches instead of every light at every pixel (the
// times are book/10c-msaa.md's, from book/figures/10_msaa_llvmpipe.csv). The directional
// lights and the ambient stay one full-screen pass at both rates. With 1 sample nothing is
// marked and the frame is chapter 03's.
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "chapters/02_gbuffer/gbuffer.h"
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_instances.h"
#include "chapters/03_light_volumes/light_volumes.h"
#include "chapters/04_neon/neon_forward.h"
#include "common/camera.h"
#include "common/gl.h"
#include "common/metrics.h"
#include "common/scene_gpu.h"
#include "common/shader.h"

namespace lp::ch10 {

// Where the light is computed: per sample only on the marked pixels (the point), or per
// sample everywhere (what it saves against).
enum class MsaaShading { EdgesPerSample, PerSampleEverywhere };
// The order of the last two steps: each sample tonemapped, then averaged (right), or the
// samples' radiance averaged, then tonemapped (what the source warns against).
enum class ResolveOrder { TonemapFirst, ResolveFirst };
enum class MsaaShow { Image, Edges };  // Edges: the marked pixels drawn red over the image
// What the resolve writes: display values (tonemapped per sample, chapter 03's sRGB frame),
// or radiance for chapter 05's HDR chain (the whole frame's --msaa): a float mean of the
// samples, each weighted by how much the tone curve compresses it (ResolveOrder::TonemapFirst,
// tonemap-resolve-inverse) or not at all (ResolveFirst).
enum class MsaaOutput { Display, Radiance };
// How the local lights reach the samples: chapter 03's stencil light volumes, or one
// full-screen loop over every light (both at the two rates).
enum class MsaaLights { Volumes, FullScreen };

// [stencil-bits]
// The one stencil buffer, shared: the edge pass sets bit 7 on the marked pixels and nothing
// else writes it; chapter 03's volumes count their masks in bits 0-6 (glStencilMask) and
// every test of theirs that must not see the edge mark reads through kVolumeBits.
constexpr unsigned kEdgeBit = 0x80, kVolumeBits = 0x7F;
// [/stencil-bits]

// [settings]
struct MsaaSettings {
  int samples = 4;  // 1, 2, 4 or 8, as the renderer makes them (llvmpipe: 4 at most)
  MsaaShading shading = MsaaShading::EdgesPerSample;
  ResolveOrder order = ResolveOrder::TonemapFirst;
  MsaaShow show = MsaaShow::Image;
  MsaaLights lights = MsaaLights::Volumes;
  MsaaOutput output = MsaaOutput::Display;
  // An edge: some sample lies off sample 0's plane (or sample 0 off its plane) by more than
  // depth_threshold times sample 0's distance to the eye (a step of 1 cm at 1 m), or its
  // normal turns by more than normal_degrees, or its emissive colour differs (another
  // material: a window in its wall), or one sample is sky and another is not. The
  // plane, not the depth: a floor at a grazing angle changes depth by several per cent
  // across a pixel, yet all its samples lie in one plane.
  float depth_threshold = 0.01f;
  float normal_degrees = 30.f;
  bool mark_every_pixel = false;  // the cross-check: every pixel shaded per sample
  // Chapter 05's curves (hdr_math.glsl: 0 clamp, 1 Reinhard, 2 extended, 3 ACES) at a fixed
  // exposure. Clamp at exposure 1 is what chapter 03's sRGB8 output does to light above 1.
  int tonemap_operator = 0;
  float exposure = 1.f;  // MsaaOutput::Radiance: the exposure its weights assume (the eye's last)
  float white = 4.f;  // the extended Reinhard's white point
};
// [/settings]

// Exact counts of the last render() made without metrics, from GL_SAMPLES_PASSED (64-bit).
// (Not chapter 03's atomic counters: on llvmpipe, in a multisampled pass with early stencil
// tests, their atomics also ran for fragments the stencil had rejected.)
struct MsaaCounts {
  std::uint64_t pixels = 0;      // width x height
  std::uint64_t marked = 0;      // pixels the edge pass marked
  // pixels whose stencil is the edge bit alone once every light is drawn (the volumes kept
  // the mark and cleaned their own bits): `marked` when the two share the stencil rightly
  std::uint64_t marked_after_lights = 0;
  std::uint64_t per_pixel = 0;   // invocations of the per-pixel light pass
  std::uint64_t per_sample = 0;  // invocations of the per-sample light pass
  // MsaaLights::Volumes, summed over the local lights (per_pixel and per_sample above are
  // then the directional + ambient passes): the samples the per-pixel volume draws wrote
  // (an invocation writes the samples of its pixel inside the volume, 1 to N: samples, not
  // invocations), and the invocations of the per-sample volume draws (one sample each).
  std::uint64_t volume_pixel_samples = 0;
  std::uint64_t volume_per_sample = 0;
  bool counted = false;          // false after a render() with metrics: the counts are zero
  std::uint64_t shaded() const { return per_pixel + per_sample; }
  std::uint64_t volume_samples() const { return volume_pixel_samples + volume_per_sample; }
  double marked_fraction() const { return pixels ? double(marked) / double(pixels) : 0.0; }
};

class MsaaFrame {
 public:
  // Lit by `lights`, chapter 03's frame's (frame.volumes(): the lights with their cuts, as
  // use_lights() set them, their records and volumes already on the GPU): read, never copied.
  MsaaFrame(const SceneGpu& scene, ch03::LightVolumes& lights);
  void reload_shaders();
  void set_ambient(const glm::vec3& ambient) { ambient_ = ambient; }
  void set_background(const glm::vec3& background) { background_ = background; }
  // Chapter 05's glow: the emissive colours its G-buffer holds, as chapter 03's frame does.
  void set_emissive_scale(float scale) { geometry_.set_emissive_scale(scale); }
  // The stages of chapter 03's frame whose hooks the light passes include (chapter 06's sun:
  // its visibility per sample on the marked edges, per pixel elsewhere): their hook files and
  // defines, and frame.bind_hooks() before the light passes. nullptr: chapter 03's hooks.
  // The frame's prepare_stages() runs their before_lights; this frame draws no map itself.
  void use_stages(const ch03::DeferredFrame* frame) { stages_ = frame; }
  // What is drawn over the lit samples before the resolve (chapter 10's glass, in the whole
  // frame): called with this frame's G-buffer, its view (with the stages' hooks) and the
  // multisampled light target, bound, its depth the G-buffer's sample for sample. So what it
  // draws is resolved with the rest: its edges antialiased too. Empty: nothing.
  using OverSamples = std::function<void(const ch02::GBuffer& gbuffer, const ch03::SurfaceView& view,
                                         const ch03::FrameOutput& samples, PassMetrics* metrics)>;
  void draw_over_samples(OverSamples over) { over_ = std::move(over); }
  // Chapter 04's tubes, lit after the local lights as they are: each tube's capsule through
  // chapter 03's stencil in bits 0-6, per sample on the marked pixels and per pixel elsewhere
  // (msaa_tube.frag). nullptr: none. Their glass is the caller's, drawn over the samples.
  void set_tubes(const ch04::NeonTubes* tubes, const ch04::NeonDraw& how = {}) {
    tubes_ = tubes;
    tube_how_ = how;
  }

  // The frame into `output` (an sRGB8 target: the resolve writes linear display values; or a
  // float target, which keeps them unencoded). Each pass timed in `metrics`.
  void render(const FrameCamera& camera, const ch03::FrameOutput& output, const MsaaSettings& settings,
              PassMetrics* metrics = nullptr);

  // The last render()'s samples resolved again into `output` (step 5 alone), e.g. with another
  // exposure for the radiance resolve's weights.
  void resolve(const ch03::FrameOutput& output, const MsaaSettings& settings, PassMetrics* metrics = nullptr);

  const MsaaCounts& counts() const { return counts_; }
  // Where the rasteriser put each sample within its pixel (0..1) in the last render().
  const std::vector<glm::vec2>& sample_positions() const { return positions_; }
  const ch02::GBuffer& gbuffer() const { return *gbuffer_; }
  std::size_t allocated_bytes() const;  // G-buffer + radiance + its depth-stencil, all samples

 private:
  void resize(int width, int height, int samples);
  // The local lights as chapter 03's volumes, into the bound light target (step 4).
  void draw_volumes(const MsaaSettings& s, bool counting);
  void draw_tubes(const MsaaSettings& s);  // set_tubes()'s, the same way (step 4 too)
  void bind_light_target() const;
  // MsaaLights::FullScreen: the local lights with their cuts as msaa_light.glsl reads them.
  void pack_local_lights();

  const SceneGpu& scene_;
  ch02::GeometryPass geometry_;
  std::unique_ptr<ch02::GBuffer> gbuffer_;
  // N samples: RGBA16F light; a depth-stencil of the G-buffer's format, for the edge mask, the
  // volumes' masks and a copy of the G-buffer's depth (their depth tests)
  gl::Texture radiance_{GL_TEXTURE_2D}, stencil_{GL_TEXTURE_2D};
  gl::Framebuffer radiance_fbo_;
  gl::VertexArray empty_;
  gl::Buffer local_;  // MsaaLights::FullScreen's records, packed each frame that draws them
  int local_count_ = 0;
  struct Programs {
    ShaderProgram edges, per_pixel, per_sample, resolve, mark, centre_depth, resolve_radiance;
  };
  std::unique_ptr<Programs> programs_;
  int programs_samples_ = 0;
  std::vector<std::string> programs_hooks_;  // the hooks' defines the programs were built with
  const ch03::DeferredFrame* stages_ = nullptr;
  OverSamples over_;
  const ch04::NeonTubes* tubes_ = nullptr;
  ch04::NeonDraw tube_how_;
  ProgramCache tube_programs_;
  ch03::LightVolumes& volumes_;  // the frame's: its lights, meshes and records, its volume shader
  std::vector<std::pair<bool, gl::Query>> volume_queries_;  // counting: {per sample?, GL_SAMPLES_PASSED} per draw
  MsaaCounts counts_;
  std::vector<glm::vec2> positions_;
  glm::vec3 ambient_{0}, background_;
};

}  // namespace lp::ch10
