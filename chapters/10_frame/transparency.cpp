#include "chapters/10_frame/transparency.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "chapters/01_forward/material.h"
#include "chapters/02_gbuffer/layout.h"
#include "common/error.h"

namespace lp::ch10 {

Method method_named(const std::string& name) {
  for (std::size_t i = 0; i < kMethods.size(); ++i)
    if (kMethods[i] == name) return static_cast<Method>(i);
  throw Error("unknown transparency method '" + name + "' (off, sorted or wboit)");
}

std::vector<BlendedDraw> blended_draws(const Scene& scene) {
  std::vector<BlendedDraw> draws;
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    const auto& primitives = scene.meshes[inst.mesh].primitives;
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      if (!scene.materials[primitives[p].material].blend) continue;
      glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
      for (std::uint32_t k = 0; k < primitives[p].index_count; ++k) {
        const glm::vec3 w = glm::vec3(inst.model * glm::vec4(scene.vertices[scene.indices[primitives[p].first_index + k]].position, 1.f));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
      }
      draws.push_back({i, p, primitives[p].index_count ? 0.5f * (lo + hi) : glm::vec3(inst.model[3])});
    }
  }
  return draws;
}

// [sort]
std::vector<BlendedDraw> ordered(std::vector<BlendedDraw> draws, const glm::mat4& view, DrawOrder order,
                                 std::uint32_t seed) {
  auto depth = [&](const BlendedDraw& d) { return -(view * glm::vec4(d.centre, 1.f)).z; };  // metres ahead
  if (order == DrawOrder::BackToFront)
    std::stable_sort(draws.begin(), draws.end(), [&](const auto& a, const auto& b) { return depth(a) > depth(b); });
  if (order == DrawOrder::FrontToBack)
    std::stable_sort(draws.begin(), draws.end(), [&](const auto& a, const auto& b) { return depth(a) < depth(b); });
  if (order == DrawOrder::Shuffled) std::shuffle(draws.begin(), draws.end(), std::mt19937(seed));
  return draws;
}
// [/sort]

float wboit_weight(float z, float alpha) {
  const float a = z / 5.f, b = z / 200.f;
  return alpha * std::clamp(10.f / (1e-5f + a * a + b * b * b * b * b * b), 1e-2f, 3e3f);
}

namespace {
std::vector<ShaderStage> surface_stages() {
  return {{GL_VERTEX_SHADER, "01_forward/shaders/forward.vert"}, {GL_FRAGMENT_SHADER, "10_frame/shaders/transparent.frag"}};
}
// Storage bindings beside chapter 09's lists (0, 1, 4; 2 and 5 its assignment's) and the
// fragment counters: the directional lights, the captured fragments and their counter.
constexpr GLuint kDirectionalBinding = 3, kCaptureBinding = 6, kCounterBinding = 7;
struct CapturedFragment {  // std430 twin of `Fragment` in transparent.frag
  std::uint32_t pixel, rank;
  float depth, pad;
  glm::vec4 colour;  // premultiplied linear colour, alpha
};
static_assert(sizeof(CapturedFragment) == 32);
}  // namespace

TransparencyStage::TransparencyStage(const ch03::DeferredFrame& frame, const SceneGpu& scene)
    : scene_(scene), draws_(blended_draws(scene.scene())), frame_(frame),
      composite_({{GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"},
                  {GL_FRAGMENT_SHADER, "10_frame/shaders/wboit_composite.frag"}}) {}

void TransparencyStage::reload_shaders() {
  programs_.clear();
  composite_samples_.reset();
  if (own_lists_) own_lists_->reload_shaders();
  composite_.reload();
}

// The frame's lists, or the stage's own (made when first needed).
void TransparencyStage::use_frame_lists(ch09::ClusteredLights* lists) {
  if (lists && (lists->settings().kind != ch09::CullKind::Clustered || !lists->settings().all_cells))
    throw Error("chapter 10: the glass can share the frame's clusters only with all_cells on (" + lists->name() + ")");
  frame_lists_ = lists;
}

ch09::ClusteredLights& TransparencyStage::lists() {
  if (frame_lists_) return *frame_lists_;
  if (!own_lists_)
    own_lists_ = std::make_unique<ch09::ClusteredLights>(
        frame_.volumes(), ch09::ClusterSettings{.kind = ch09::CullKind::Clustered, .all_cells = true});
  return *own_lists_;
}

// [glass-lights]
// The glass's lights are the frame's: its directional lights for the global part (the
// buffer chapter 03's global pass reads, bound in draw_surfaces), and chapter 09's lists of
// every cluster for the local lights (a pane may lie in a cluster no opaque surface
// occupies): the frame's own when its local lights are clusters, already built for this
// frame's camera; else the stage's, built here for it.
void TransparencyStage::build_lights(const GlassTarget& target, PassMetrics* metrics) {
  if (frame_lists_) return;  // the frame's draw() built them
  auto pass = timed(metrics, "transparency: light lists (chapter 09, every cluster)");
  lists().build_lists(target.image.width, target.image.height, target.view);
}

const ShaderProgram& TransparencyStage::program(Output output, const GlassTarget& target) {
  std::vector<std::string> defines = lists().forward_defines(target.view);
  defines.push_back(output == kOver ? "GLASS_OVER 1" : output == kWboit ? "GLASS_WBOIT 1" : "GLASS_CAPTURE 1");
  return programs_.get(surface_stages(), defines);
}
// [/glass-lights]

std::size_t TransparencyStage::allocated_bytes() const {
  return std::size_t(width_) * std::size_t(height_) * std::size_t(samples_) *
         (gl::bytes_per_texel(GL_RGBA16F) + gl::bytes_per_texel(GL_R16F) + gl::bytes_per_texel(depth_format_));
}

// WBOIT's targets, and a depth buffer of the G-buffer's format to test against its depth; as
// many samples as the G-buffer has.
void TransparencyStage::resize(const GlassTarget& target) {
  const int w = target.image.width, h = target.image.height, samples = target.gbuffer.samples();
  const GLenum depth = ch02::depth_format(target.gbuffer.layout().depth);
  if (w == width_ && h == height_ && depth == depth_format_ && samples == samples_) return;
  width_ = w, height_ = h, depth_format_ = depth, samples_ = samples;
  accum_ = gl::make_render_texture(GL_RGBA16F, w, h, samples);
  reveal_ = gl::make_render_texture(GL_R16F, w, h, samples);
  depth_ = gl::make_render_texture(depth, w, h, samples);
  fbo_ = gl::Framebuffer();
  glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, accum_.id(), 0);
  glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT1, reveal_.id(), 0);
  const bool stencil = depth == GL_DEPTH24_STENCIL8 || depth == GL_DEPTH32F_STENCIL8;
  glNamedFramebufferTexture(fbo_.id(), stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT, depth_.id(), 0);
  const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(fbo_.id(), 2, buffers);
  if (glCheckNamedFramebufferStatus(fbo_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("chapter 10: the WBOIT framebuffer is incomplete");
}

// Every blended surface in `draws`' order: chapter 01's vertex shader and material, the
// G-buffer's camera and depth convention (reversed-Z layouts included), the depth test on and
// depth writes off, back faces culled.
void TransparencyStage::draw_surfaces(const ch03::DeferredFrame& frame, const GlassTarget& target, Output output,
                                      const std::vector<BlendedDraw>& draws, bool ranks) {
  const FrameCamera& camera = target.gbuffer.camera();
  const ShaderProgram& program = this->program(output, target);
  lists().bind_for_forward(program, target.view.camera);  // uses the program, sets the grid's uniforms
  program.set("u_view_projection", camera.view_projection());
  program.set("u_eye", frame.camera().position);
  program.set("u_ambient", scene_.scene().ambient);
  program.set("u_light_count", int(frame.volumes().lights().directional.size()));
  program.set("u_size", glm::vec2(width_, height_));
  if (output == kCapture) program.set("u_capacity", capacity_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDirectionalBinding, frame.volumes().directional_buffer());
  frame.bind_hooks();  // the stages' passes since the lights (chapter 08's) may have taken their units
  target.gbuffer.bind_textures(0);  // what the hooks read of it (the frame's is bound already; MSAA's is not)
  target.gbuffer.begin_depth_convention();
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glEnable(GL_CULL_FACE);
  glDisable(GL_STENCIL_TEST);
  // The rank of each draw in the back-to-front order, for the exact composite's bookkeeping.
  std::vector<BlendedDraw> back_to_front;
  if (ranks) back_to_front = ordered(draws_, frame.camera().view, DrawOrder::BackToFront);
  for (const BlendedDraw& d : draws) {
    const Scene& s = scene_.scene();
    const Instance& inst = s.instances[d.instance];
    const Material& m = s.materials[s.meshes[inst.mesh].primitives[d.primitive].material];
    ch01::set_surface(program, scene_, inst, m);
    program.set("u_emissive", m.emissive * frame.emissive_scale());  // chapter 05's glow on set_surface's
    if (ranks) {
      auto same = [&](const BlendedDraw& o) { return o.instance == d.instance && o.primitive == d.primitive; };
      program.set("u_rank", int(std::find_if(back_to_front.begin(), back_to_front.end(), same) - back_to_front.begin()));
    }
    scene_.draw_primitive(d.instance, d.primitive);
  }
  glDepthMask(GL_TRUE);
  ch02::GBuffer::restore_default_depth_convention();
  // The materials' textures took units 0.. where the frame keeps the G-buffer: put it back.
  target.gbuffer.bind_textures(0);
}

// [after-composite]
// [glass-hook]
void TransparencyStage::after_composite(ch03::DeferredFrame& frame, PassMetrics* metrics) {
  if (settings_.method == Method::Off || draws_.empty()) return;
  if (settings_.method == Method::Sorted) frame.copy_depth_to_output();  // sorted tests against the output's depth
  draw_over(frame, frame_target(frame), metrics);
}
// [/glass-hook]

void TransparencyStage::draw_over(const ch03::DeferredFrame& frame, const GlassTarget& target, PassMetrics* metrics) {
  if (settings_.method == Method::Off || draws_.empty()) return;
  resize(target);
  build_lights(target, metrics);
  if (settings_.method == Method::Sorted) draw_sorted(frame, target, metrics);
  else draw_wboit(frame, target, metrics);
}

// Sorted: each surface blended over the image in the target itself ("over", premultiplied).
void TransparencyStage::draw_sorted(const ch03::DeferredFrame& frame, const GlassTarget& target, PassMetrics* metrics) {
  target.image.bind();
  auto pass = timed(metrics, "transparency: sorted, back to front");
  const auto draws = ordered(draws_, frame.camera().view, settings_.order, settings_.shuffle_seed);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // C = c alpha (the shader's) + (1 - alpha) C
  draw_surfaces(frame, target, kOver, draws, false);
  glDisable(GL_BLEND);
}

// WBOIT: the sum of w * (alpha c, alpha) into RGBA16F and the product of (1 - alpha) into
// R16F, in any order; then their average over the image where any glass is.
void TransparencyStage::draw_wboit(const ch03::DeferredFrame& frame, const GlassTarget& target, PassMetrics* metrics) {
  {
    auto pass = timed(metrics, "transparency: WBOIT accumulate");
    const int w = width_, h = height_;
    glBlitNamedFramebuffer(target.gbuffer.framebuffer(), fbo_.id(), 0, 0, w, h, 0, 0, w, h, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 0, 0, 0};
    glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 1, one);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, w, h);
    glEnable(GL_BLEND);
    glBlendFunci(0, GL_ONE, GL_ONE);                  // accumulation: a sum
    glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);  // revealage: a product of (1 - alpha)
    draw_surfaces(frame, target, kWboit, ordered(draws_, frame.camera().view, settings_.order, settings_.shuffle_seed), false);
    glBlendFunc(GL_ONE, GL_ZERO);
    glDisable(GL_BLEND);
  }
  auto pass = timed(metrics, "transparency: WBOIT composite");
  target.image.bind();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  const bool picture = settings_.show != TransparencyShow::Image;
  if (!picture) {
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // average (1 - revealage) + image revealage
  }
  // A multisampled target: the composite runs per sample, each over its own sample's image.
  if (samples_ > 1 && !composite_samples_)
    composite_samples_ = std::make_unique<ShaderProgram>(
        std::vector<ShaderStage>{{GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"},
                                 {GL_FRAGMENT_SHADER, "10_frame/shaders/wboit_composite.frag"}},
        std::vector<std::string>{"WBOIT_SAMPLES 1"});
  const ShaderProgram& composite = samples_ > 1 ? *composite_samples_ : composite_;
  composite.use();
  composite.set("u_show", int(settings_.show));
  glBindTextureUnit(0, accum_.id());
  glBindTextureUnit(1, reveal_.id());
  glBindVertexArray(empty_vao_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisable(GL_BLEND);
}
// [/after-composite]

// [exact]
ExactComposite TransparencyStage::exact_composite(const ch03::DeferredFrame& frame, std::size_t max_per_pixel) {
  const GlassTarget target = frame_target(frame);
  resize(target);
  build_lights(target, nullptr);
  const int w = width_, h = height_;
  const std::size_t pixels = std::size_t(w) * std::size_t(h);
  if (max_per_pixel == 0 || max_per_pixel > 256) throw Error("exact_composite: 1 to 256 fragments per pixel");
  const std::size_t capacity = pixels * max_per_pixel;
  if (capacity * sizeof(CapturedFragment) > (std::size_t(1) << 30)) throw Error("exact_composite: capture over 1 GiB");
  ExactComposite out;
  // The opaque image the frame left.
  out.image.width = w, out.image.height = h;
  out.image.pixels.resize(pixels * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, frame.output().framebuffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, out.image.pixels.data());
  // Every fragment in front of the opaque surface, in no order, appended to a list.
  gl::Buffer list = gl::make_buffer(nullptr, capacity * sizeof(CapturedFragment), GL_MAP_READ_BIT);
  const std::uint32_t zero = 0;
  gl::Buffer counter = gl::make_buffer(&zero, sizeof zero, GL_MAP_READ_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCaptureBinding, list.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCounterBinding, counter.id());
  glBlitNamedFramebuffer(frame.gbuffer().framebuffer(), fbo_.id(), 0, 0, w, h, 0, 0, w, h, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
  glViewport(0, 0, w, h);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  capacity_ = int(std::min<std::size_t>(capacity, std::numeric_limits<int>::max()));
  draw_surfaces(frame, target, kCapture, draws_, true);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::uint32_t count = 0;
  glGetNamedBufferSubData(counter.id(), 0, sizeof count, &count);
  out.overflow = count > capacity;
  out.fragments = std::min<std::size_t>(count, capacity);
  std::vector<CapturedFragment> fragments(out.fragments);
  glGetNamedBufferSubData(list.id(), 0, GLsizeiptr(fragments.size() * sizeof(CapturedFragment)), fragments.data());
  // Per pixel: sorted by depth (ties in draw order), composited back to front in double.
  std::stable_sort(fragments.begin(), fragments.end(), [](const auto& a, const auto& b) {
    return a.pixel != b.pixel ? a.pixel < b.pixel : a.depth < b.depth;  // view depth: nearest first
  });
  out.layers.assign(pixels, 0);
  out.surface_order_right.assign(pixels, 1);
  for (std::size_t i = 0; i < fragments.size();) {
    std::size_t end = i;
    while (end < fragments.size() && fragments[end].pixel == fragments[i].pixel) ++end;
    const std::uint32_t px = fragments[i].pixel % w, py = fragments[i].pixel / w;  // GL rows: bottom first
    const std::size_t row = std::size_t(h - 1 - py) * w + px;
    std::uint8_t* rgba = &out.image.pixels[(std::size_t(py) * w + px) * 4];
    double c[3];
    for (int k = 0; k < 3; ++k) c[k] = srgb_to_linear(rgba[k] / 255.f);
    for (std::size_t j = end; j-- > i;) {  // farthest first
      const CapturedFragment& f = fragments[j];
      // What blending into the 8-bit output does with each layer in the right order, without
      // rounding: a fixed-point target clamps the shader's colour and what it holds to [0, 1].
      for (int k = 0; k < 3; ++k)
        c[k] = std::clamp(std::clamp(double(f.colour[k]), 0.0, 1.0) + (1.0 - double(f.colour.a)) * c[k], 0.0, 1.0);
      if (j + 1 < end && fragments[j + 1].rank > f.rank) out.surface_order_right[row] = 0;  // drawn after a nearer one
    }
    for (int k = 0; k < 3; ++k)
      rgba[k] = std::uint8_t(std::lround(std::clamp(double(linear_to_srgb(float(c[k]))), 0.0, 1.0) * 255.0));
    out.layers[row] = int(end - i);
    i = end;
  }
  flip_vertically(out.image);
  return out;
}
// [/exact]

}  // namespace lp::ch10
