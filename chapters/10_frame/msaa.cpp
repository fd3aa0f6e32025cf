#include "chapters/10_frame/msaa.h"

#include <cmath>
#include <cstddef>
#include <vector>

#include "chapters/01_forward/ground_truth.h"
#include "common/error.h"

namespace lp::ch10 {

namespace glsl {
using glm::vec4;
using ch01::GpuLight;
#include "chapters/10_frame/shaders/msaa_local_light.h"  // struct LocalLight, shared with GLSL
}  // namespace glsl

namespace {

constexpr GLuint kDirectionalBinding = 0, kLocalBinding = 1;

using LocalLight = glsl::LocalLight;
static_assert(sizeof(LocalLight) == 80 && offsetof(LocalLight, cut) == 64, "std430: a GpuLight and a vec4");

// Where each sample lies within its pixel (0..1), as the rasteriser places them.
std::vector<glm::vec2> query_sample_positions(GLuint framebuffer, int samples) {
  std::vector<glm::vec2> p(std::size_t(samples), glm::vec2(0.5f));
  if (samples == 1) return p;
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  for (int i = 0; i < samples; ++i) glGetMultisamplefv(GL_SAMPLE_POSITION, GLuint(i), &p[std::size_t(i)].x);
  return p;
}

// Fragments the frame's passes run: a full-screen triangle, no depth test, no culling.
void fullscreen(const gl::VertexArray& empty) {
  glBindVertexArray(empty.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace

MsaaFrame::MsaaFrame(const SceneGpu& scene, ch03::LightVolumes& lights)
    : scene_(scene), geometry_(scene), local_(gl::make_buffer(nullptr, sizeof(LocalLight))), volumes_(lights),
      ambient_(scene.scene().ambient), background_(ch01::kBackground) {}

void MsaaFrame::reload_shaders() {
  geometry_.reload_shaders();
  tube_programs_.clear();
  programs_.reset();  // the volumes' programs are the frame's: its reload_shaders() makes them again
}

// The full-screen loop reads every local light with its cut in one buffer, in chapter 03's
// light order (points, cones, wide spots); the volumes read the frame's records as they are.
void MsaaFrame::pack_local_lights() {
  const ch03::LightSet& lights = volumes_.lights();
  std::vector<LocalLight> local;
  local.reserve(lights.local_count());
  for (const auto& p : lights.points) local.push_back({ch03::unpack(p), glm::vec4(p.position_radius.w, 0, 0, 0)});
  for (const auto& s : lights.cones) local.push_back({ch03::unpack(s), glm::vec4(s.position_radius.w, 0, 0, 0)});
  for (const auto& s : lights.wide_spots) local.push_back({ch03::unpack(s), glm::vec4(s.position_radius.w, 0, 0, 0)});
  local_count_ = int(local.size());
  if (local.empty()) local.resize(1);  // a buffer of no bytes cannot be bound
  local_ = gl::make_buffer(local.data(), local.size() * sizeof(LocalLight));
}

void MsaaFrame::resize(int width, int height, int samples) {
  if (width <= 0 || height <= 0)
    throw Error("the MSAA frame needs at least one pixel (asked for " + std::to_string(width) + "x" +
                std::to_string(height) + ")");
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  if (samples != 1 && samples != 2 && samples != 4 && samples != 8)
    throw Error("MSAA: " + std::to_string(samples) + " samples per pixel: use 1, 2, 4 or 8");
  if (samples > max_samples)
    throw Error("MSAA: " + std::to_string(samples) + " samples per pixel, but this renderer has at most " +
                std::to_string(max_samples));
  if (gbuffer_ && gbuffer_->width() == width && gbuffer_->height() == height && gbuffer_->samples() == samples) return;
  gbuffer_ = std::make_unique<ch02::GBuffer>(width, height, ch02::our_layout(), samples);
  radiance_ = gl::make_render_texture(GL_RGBA16F, width, height, samples);
  stencil_ = gl::make_render_texture(ch02::depth_format(gbuffer_->layout().depth), width, height, samples);  // blit: same format
  radiance_fbo_ = gl::Framebuffer();
  glNamedFramebufferTexture(radiance_fbo_.id(), GL_COLOR_ATTACHMENT0, radiance_.id(), 0);
  glNamedFramebufferTexture(radiance_fbo_.id(), GL_DEPTH_STENCIL_ATTACHMENT, stencil_.id(), 0);
  if (glCheckNamedFramebufferStatus(radiance_fbo_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("the MSAA light target (" + std::to_string(samples) + " samples) is incomplete on this driver");
  GLint made = 1;  // a renderer may make more samples than asked for: the shaders read exactly N
  if (samples > 1) glGetTextureLevelParameteriv(radiance_.id(), 0, GL_TEXTURE_SAMPLES, &made);
  if (made != samples)
    throw Error("MSAA: asked for " + std::to_string(samples) + " samples per pixel, this renderer made " +
                std::to_string(made) + "; use " + std::to_string(made));
  if (programs_samples_ != samples) programs_.reset();
}

// The G-buffer on units 0.., the light target bound, no depth test, culling or blending.
void MsaaFrame::bind_light_target() const {
  gbuffer_->bind_textures(0);
  glBindFramebuffer(GL_FRAMEBUFFER, radiance_fbo_.id());
  glViewport(0, 0, gbuffer_->width(), gbuffer_->height());
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
}

std::size_t MsaaFrame::allocated_bytes() const {
  if (!gbuffer_) return 0;
  const std::size_t samples = std::size_t(gbuffer_->samples());
  const std::size_t pixels = std::size_t(gbuffer_->width()) * std::size_t(gbuffer_->height());
  const std::size_t depth_stencil = gl::bytes_per_texel(ch02::depth_format(gbuffer_->layout().depth));
  return (gbuffer_->bytes_per_pixel() + 8 + depth_stencil) * pixels * samples;  // + RGBA16F light + depth-stencil
}

void MsaaFrame::render(const FrameCamera& camera, const ch03::FrameOutput& output, const MsaaSettings& s,
                       PassMetrics* metrics) {
  resize(output.width, output.height, s.samples);
  const std::vector<std::string> hooks = (stages_ ? stages_->stage_hooks() : ch03::ShaderHooks{}).glsl_defines();
  if (hooks != programs_hooks_) programs_.reset();
  if (!programs_) {
    std::vector<std::string> d = gbuffer_->shader_defines(0);
    for (const std::string& x : hooks) d.push_back(x);
    d.push_back("MSAA_SAMPLES " + std::to_string(s.samples));
    const ShaderStage vs{GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"};
    auto per_sample = d;
    per_sample.push_back("PER_SAMPLE 1");
    programs_ = std::make_unique<Programs>(Programs{
        ShaderProgram({vs, {GL_FRAGMENT_SHADER, "10_frame/shaders/msaa_edges.frag"}}, d),
        ShaderProgram({vs, {GL_FRAGMENT_SHADER, "10_frame/shaders/msaa_shade.frag"}}, d),
        ShaderProgram({vs, {GL_FRAGMENT_SHADER, "10_frame/shaders/msaa_shade.frag"}}, per_sample),
        ShaderProgram({vs, {GL_FRAGMENT_SHADER, "10_frame/shaders/msaa_resolve.frag"}}, d),
        ShaderProgram({vs, {GL_FRAGMENT_SHADER, "10_frame/shaders/msaa_mark.frag"}}, d),
        ShaderProgram({vs, {GL_FRAGMENT_SHADER, "10_frame/shaders/msaa_centre_depth.frag"}}, d),
        ShaderProgram({vs, {GL_FRAGMENT_SHADER, "10_frame/shaders/msaa_resolve_radiance.frag"}}, d)});
    programs_samples_ = s.samples;
    programs_hooks_ = hooks;
  }
  Programs& p = *programs_;
  positions_ = query_sample_positions(radiance_fbo_.id(), s.samples);
  const std::vector<glm::vec2>& positions = positions_;
  // Exact counts (no metrics: their occlusion queries and ours cannot both be active).
  const bool counting = metrics == nullptr;
  std::uint64_t samples_passed[4] = {0, 0, 0, 0};  // edges, per pixel, per sample, marked after the lights
  auto counted = [&](int which, auto&& draw) {
    if (!counting) return draw();
    gl::Query q(GL_SAMPLES_PASSED);
    glBeginQuery(GL_SAMPLES_PASSED, q.id());
    draw();
    glEndQuery(GL_SAMPLES_PASSED);
    samples_passed[which] = query_result_u64(q.id());
  };

  // 1. The surfaces: chapter 02's geometry pass into N samples per pixel.
  {
    auto pass = timed(metrics, "msaa: G-buffer (chapter 02, " + std::to_string(s.samples) + " samples)");
    geometry_.draw(*gbuffer_, camera);
  }
  bind_light_target();
  glDisable(GL_FRAMEBUFFER_SRGB);
  glEnable(GL_STENCIL_TEST);
  glStencilMask(0xFF);
  const GLint zero = 0;
  glClearNamedFramebufferiv(radiance_fbo_.id(), GL_STENCIL, 0, &zero);
  const bool volumes = s.lights == MsaaLights::Volumes;
  glDisable(GL_SCISSOR_TEST);
  glDepthMask(GL_TRUE);
  if (volumes)  // the volumes' depth tests: a copy of the G-buffer's depth, every sample
    glBlitNamedFramebuffer(gbuffer_->framebuffer(), radiance_fbo_.id(), 0, 0, output.width, output.height, 0, 0,
                           output.width, output.height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);

  // 2. The edges: bit 7 of the stencil where the pixel's samples differ.
  const bool everywhere = s.shading == MsaaShading::PerSampleEverywhere;
  if (!everywhere) {
    auto pass = timed(metrics, "msaa: mark edges");
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glStencilMask(kEdgeBit);  // this pass writes bit 7 and only bit 7
    glStencilFunc(GL_ALWAYS, kEdgeBit, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    p.edges.use();
    p.edges.set("u_depth_threshold", s.depth_threshold);
    p.edges.set("u_cos_normal", std::cos(glm::radians(s.normal_degrees)));
    p.edges.set("u_mark_all", int(s.mark_every_pixel));
    glProgramUniform2fv(p.edges.id(), glGetUniformLocation(p.edges.id(), "u_sample_positions"), s.samples,
                        &positions[0].x);
    counted(0, [&] { fullscreen(empty_); });
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }
  if (volumes && !everywhere && s.samples > 1) {  // the volumes' depth on unmarked pixels: their centre's
    auto pass = timed(metrics, "msaa: centre depth for the volumes");
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glStencilFunc(GL_EQUAL, 0, kEdgeBit);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    p.centre_depth.use();
    fullscreen(empty_);
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }

  // 3. The light: once per pixel where the edge bit is 0, once per sample where it is 1
  //    (per sample everywhere: the stencil is not looked at). Every light, or with volumes
  //    only the directional lights and the ambient (one light each, every pixel).
  glStencilMask(0xFF);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  if (stages_) stages_->bind_hooks();  // what the stages' hooks read (the sun's map), on their units
  if (!volumes) pack_local_lights();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDirectionalBinding, volumes_.directional_buffer());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLocalBinding, local_.id());  // with volumes: one record, never read
  for (ShaderProgram* program : {&p.per_pixel, &p.per_sample}) {
    program->set("u_directional_count", int(volumes_.lights().directional.size()));
    program->set("u_local_count", volumes ? 0 : local_count_);
    program->set("u_ambient", ambient_);
    program->set("u_background", background_);
  }
  if (!everywhere) {
    auto pass = timed(metrics, "msaa: light per pixel (stencil 0)");
    glStencilFunc(GL_EQUAL, 0, kEdgeBit);
    p.per_pixel.use();
    counted(1, [&] { fullscreen(empty_); });
  }
  {
    auto pass = timed(metrics, everywhere ? "msaa: light per sample everywhere" : "msaa: light per sample (stencil 1)");
    if (everywhere) glDisable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, kEdgeBit, kEdgeBit);
    p.per_sample.use();
    counted(2, [&] { fullscreen(empty_); });
  }
  // 4. With volumes: the local lights, each one chapter 03's stencil volume at both rates.
  if (volumes) {
    auto pass = timed(metrics, "msaa: local lights (chapter 03's volumes)");
    draw_volumes(s, counting);
    glBindFramebuffer(GL_FRAMEBUFFER, radiance_fbo_.id());
    glDisable(GL_DEPTH_TEST);
  }
  if (tubes_ && tubes_->count() > 0) {
    auto pass = timed(metrics, "msaa: neon tubes (chapter 04's capsules)");
    if (!volumes)  // the capsules' depth tests: the G-buffer's (the loop drew no volumes)
      glBlitNamedFramebuffer(gbuffer_->framebuffer(), radiance_fbo_.id(), 0, 0, output.width, output.height, 0, 0,
                             output.width, output.height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    draw_tubes(s);
    glBindFramebuffer(GL_FRAMEBUFFER, radiance_fbo_.id());
    glDisable(GL_DEPTH_TEST);
  }
  // [over-samples]
  // 4b. Over the lit samples, before the resolve: the glass of the whole frame. Its depth test
  //     reads the G-buffer's depth again, sample for sample (the volumes' pass left the centre's
  //     on unmarked pixels); its fragments are shaded once per pixel and blended into the
  //     samples they cover, so its edges and the opaque edges in front of it are resolved too.
  if (over_) {
    glBlitNamedFramebuffer(gbuffer_->framebuffer(), radiance_fbo_.id(), 0, 0, output.width, output.height, 0, 0,
                           output.width, output.height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    ch03::SurfaceView view = ch03::surface_view(*gbuffer_);
    if (stages_) view.hooks = stages_->stage_hooks();
    glDisable(GL_STENCIL_TEST);
    over_(*gbuffer_, view, {radiance_fbo_.id(), output.width, output.height}, metrics);
    bind_light_target();  // and the state the passes below expect, whatever it left
  }
  // [/over-samples]
  // What the lights left in the stencil, counted: the samples whose stencil is exactly the
  // edge bit (marked, and no volume count left behind); the picture draws them red.
  if (!everywhere && (counting || s.show == MsaaShow::Edges)) {
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, kEdgeBit, 0xFF);
    if (s.show != MsaaShow::Edges) glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    p.mark.use();
    counted(3, [&] { fullscreen(empty_); });
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }
  glDisable(GL_STENCIL_TEST);

  // 5. The resolve into the output.
  resolve(output, s, metrics);
  glEnable(GL_DEPTH_TEST);

  // [counts]
  // A fragment of a full-screen pass covers every sample of its pixel, and the edge stencil
  // is the same for all of them: the per-pixel passes pass N samples per fragment, the
  // per-sample pass one per invocation (early fragment tests: passed = shaded).
  const auto n = std::uint64_t(s.samples);
  counts_ = {.pixels = std::uint64_t(output.width) * std::uint64_t(output.height),
             .marked = samples_passed[0] / n, .per_pixel = samples_passed[1] / n, .per_sample = samples_passed[2],
             .counted = counting};
  // [/counts]
  counts_.marked_after_lights = samples_passed[3] / n;
  for (const auto& [per_sample, query] : volume_queries_)  // read once the frame is drawn: no stall per light
    (per_sample ? counts_.volume_per_sample : counts_.volume_pixel_samples) += query_result_u64(query.id());
}

void MsaaFrame::resolve(const ch03::FrameOutput& output, const MsaaSettings& s, PassMetrics* metrics) {
  if (!programs_ || !gbuffer_ || gbuffer_->samples() != s.samples)
    throw Error("MSAA: resolve() of " + std::to_string(s.samples) + " samples before a render() that drew them");
  Programs& p = *programs_;
  output.bind();
  glBindTextureUnit(0, radiance_.id());
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  if (s.output == MsaaOutput::Radiance) {  // for chapter 05's HDR chain: radiance, the curve's weights
    auto pass = timed(metrics, "msaa: float resolve (tonemap-resolve-inverse)");
    p.resolve_radiance.use();
    p.resolve_radiance.set("u_exposure", s.exposure);
    p.resolve_radiance.set("u_resolve_first", int(s.order == ResolveOrder::ResolveFirst));
    fullscreen(empty_);
  } else {  // display values: tonemap each sample, then average (or the wrong order)
    auto pass = timed(metrics, "msaa: tonemap + resolve");
    p.resolve.use();
    p.resolve.set("u_operator", s.tonemap_operator);
    p.resolve.set("u_exposure", s.exposure);
    p.resolve.set("u_white", s.white);
    p.resolve.set("u_resolve_first", int(s.order == ResolveOrder::ResolveFirst));
    fullscreen(empty_);
  }
  glEnable(GL_DEPTH_TEST);
}

void MsaaFrame::draw_volumes(const MsaaSettings& s, bool counting) {
  ch03::SurfaceView view = ch03::surface_view(*gbuffer_);
  view.defines.push_back("MSAA_SAMPLES " + std::to_string(s.samples));
  if (stages_) view.hooks = stages_->stage_hooks();
  const ShaderProgram& mark = volumes_.volume_program("03_light_volumes/shaders/stencil.frag", view);
  const ShaderProgram& per_pixel = volumes_.volume_program("10_frame/shaders/msaa_volume.frag", view);
  const ShaderProgram& per_sample = volumes_.volume_program("10_frame/shaders/msaa_volume.frag", view, {"PER_SAMPLE 1"});
  const int count = int(volumes_.lights().local_count());
  volume_queries_.clear();
  auto draw = [&](const ShaderProgram& program, int i) {
    if (!counting) return volumes_.draw_volume(program, i);
    volume_queries_.emplace_back(&program == &per_sample, gl::Query(GL_SAMPLES_PASSED));
    glBeginQuery(GL_SAMPLES_PASSED, volume_queries_.back().second.id());
    volumes_.draw_volume(program, i);
    glEndQuery(GL_SAMPLES_PASSED);
  };
  const bool everywhere = s.shading == MsaaShading::PerSampleEverywhere;
  // [msaa-volumes]
  // Chapter 03's stencil strategy, its masks in bits 0-6: per light, the mask (both faces
  // count where the surface lies inside: bits 0-6 become 1, bit 7 is never written), then the
  // light through it. That pass's state tests "bits 0-6 not 0" and zeroes bits 0-6 only;
  // here the edge bit picks the rate, and the order does the rest. First the per-sample
  // shader where the stencil is above 0x80 (edge bit set, inside): it zeroes those samples'
  // count. Then the per-pixel shader where a count is left: inside and not marked.
  ch03::draw_stencil_volumes(view, count, [&](int i, ch03::VolumePass pass) {
    if (pass == ch03::VolumePass::Mark) return volumes_.draw_volume(mark, i);
    if (everywhere) glStencilFunc(GL_NOTEQUAL, 0, kVolumeBits);  // no edge mark: all samples inside
    else glStencilFunc(GL_LESS, kEdgeBit, 0xFF);                 // 0x80 < stencil: marked and inside
    draw(per_sample, i);
    if (everywhere) return;  // every sample inside is done
    glStencilFunc(GL_NOTEQUAL, 0, kVolumeBits);  // a count left: inside, not marked
    draw(per_pixel, i);
  }, kVolumeBits);
  // [/msaa-volumes]
}

// [msaa-tubes]
// The tubes as the local lights above: per tube, its capsule's mask in bits 0-6, then its light,
// per sample where the edge bit is set, per pixel where a count is left.
void MsaaFrame::draw_tubes(const MsaaSettings& s) {
  ch03::SurfaceView view = ch03::surface_view(*gbuffer_);
  std::vector<std::string> d = view.defines;
  if (stages_) view.hooks = stages_->stage_hooks();
  for (const std::string& x : view.hooks.glsl_defines()) d.push_back(x);
  d.push_back("MSAA_SAMPLES " + std::to_string(s.samples));
  const ShaderStage vs{GL_VERTEX_SHADER, "04_neon/shaders/capsule.vert"};
  const ShaderProgram& mark = tube_programs_.get({vs, {GL_FRAGMENT_SHADER, "03_light_volumes/shaders/stencil.frag"}}, d);
  const ShaderProgram& per_pixel = tube_programs_.get({vs, {GL_FRAGMENT_SHADER, "10_frame/shaders/msaa_tube.frag"}}, d);
  d.push_back("PER_SAMPLE 1");
  const ShaderProgram& per_sample = tube_programs_.get({vs, {GL_FRAGMENT_SHADER, "10_frame/shaders/msaa_tube.frag"}}, d);
  for (const ShaderProgram* p : {&mark, &per_pixel, &per_sample}) {
    p->set("u_view_projection", view.camera.view_projection());
    p->set("u_glass", 0);  // the light's volume, not the glass
    p->set("u_method", static_cast<int>(tube_how_.method));
    p->set("u_samples", tube_how_.samples);
  }
  const bool everywhere = s.shading == MsaaShading::PerSampleEverywhere;
  ch03::draw_stencil_volumes(view, tubes_->count(), [&](int i, ch03::VolumePass pass) {
    const ShaderProgram& light = pass == ch03::VolumePass::Mark ? mark : per_sample;
    if (pass != ch03::VolumePass::Mark && everywhere) glStencilFunc(GL_NOTEQUAL, 0, kVolumeBits);  // all samples inside
    else if (pass != ch03::VolumePass::Mark) glStencilFunc(GL_LESS, kEdgeBit, 0xFF);             // marked and inside
    light.use();
    tubes_->draw_capsule(i);
    if (pass == ch03::VolumePass::Mark || everywhere) return;
    glStencilFunc(GL_NOTEQUAL, 0, kVolumeBits);  // a count left: inside, not marked
    per_pixel.use();
    tubes_->draw_capsule(i);
  }, kVolumeBits);
}
// [/msaa-tubes]

}  // namespace lp::ch10
