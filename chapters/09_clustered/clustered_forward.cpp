#include "chapters/09_clustered/clustered_forward.h"

#include "chapters/01_forward/material.h"
#include "chapters/02_gbuffer/layout.h"
#include "common/metrics.h"

namespace lp::ch09 {

// [forward-draw]
void draw_forward(const SceneGpu& gpu, const ch02::GBuffer& gbuffer, const FrameCamera& camera, ClusteredLights& lists,
                  const ShaderProgram& depth_program, const ShaderProgram& program, GLuint framebuffer, int w, int h,
                  bool counting, bool add, PassMetrics* metrics, const std::string& prepass_name,
                  const std::string& shade_name) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, w, h);
  gbuffer.begin_depth_convention();  // the G-buffer's test, LESS (or GREATER with reversed-Z)
  glClearDepth(gbuffer.sky_depth());
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_CULL_FACE);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_DEPTH_TEST);
  for (int prepass = 1; prepass >= 0; --prepass) {
    auto pass = timed(metrics, prepass ? prepass_name : shade_name);
    const ShaderProgram& p = prepass ? depth_program : program;
    if (prepass) {
      p.use();
    } else {
      lists.bind_for_forward(p, camera, counting);  // uses p; with counting, resets the counts
      glDepthFunc(GL_EQUAL);
    }
    p.set("u_view_projection", gbuffer.camera().view_projection());
    glDepthMask(prepass ? GL_TRUE : GL_FALSE);
    glColorMask(!prepass, !prepass, !prepass, !prepass);
    if (!prepass && add) {
      glEnable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE);
    }
    gpu.draw([&](const Instance& inst, const Material& m) { ch01::set_surface(p, gpu, inst, m); },
             SceneGpu::Primitives::Opaque);
  }
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glClearDepth(1.0);
  ch02::GBuffer::restore_default_depth_convention();
}
// [/forward-draw]


ClusteredForward::ClusteredForward(const ch03::DeferredFrame& frame, const SceneGpu& gpu, ClusterSettings settings)
    : frame_(frame), gpu_(gpu), lists_(frame.volumes(), settings) {
  set_settings(settings);
}

void ClusteredForward::set_settings(ClusterSettings s) {
  s.kind = CullKind::Clustered;
  s.all_cells = true;  // a forward fragment may lie in any cluster, not only in those the G-buffer fills
  lists_.set_settings(s);
}

void ClusteredForward::set_metrics(PassMetrics* metrics) { metrics_ = metrics; }

void ClusteredForward::reload_shaders() {
  programs_.clear();
  lists_.reload_shaders();
}

std::vector<std::string> ClusteredForward::pass_names() {
  const std::string p = "local lights: clustered-forward: ";
  return {p + "assign", p + "depth pre-pass", p + "shade"};
}

// [forward-pass]
void ClusteredForward::draw(const ch03::LightBuffer& light, const ch03::SurfaceView& view,
                            ch03::LightVolumes::Output output) {
  const int w = light.width(), h = light.height();
  // 1. The lists of every cluster (ClusteredLights' assignment; no depth bounds are needed),
  //    timed here as one pass (lists_ has no metrics of its own: scopes do not nest).
  {
    auto pass = timed(metrics_, pass_names()[0]);
    lists_.build_lists(w, h, view);
  }
  // 2. The target: the light buffer's L1 and L2, and a depth buffer of our own for the
  //    pre-pass (a forward renderer has no G-buffer depth to test against).
  if (w != width_ || h != height_ || light.diffuse() != colour_l1_ || light.specular() != colour_l2_) {
    depth_ = gl::make_texture_2d(ch02::depth_format(frame_.gbuffer().layout().depth), w, h);
    glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, light.diffuse(), 0);
    glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT1, light.specular(), 0);
    const GLenum format = ch02::depth_format(frame_.gbuffer().layout().depth);
    const bool has_stencil = format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8;
    glNamedFramebufferTexture(fbo_.id(), has_stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT, depth_.id(), 0);
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo_.id(), 2, buffers);
    width_ = w;
    height_ = h;
    colour_l1_ = light.diffuse();
    colour_l2_ = light.specular();
  }
  // 3. The scene again, forward, each fragment lit from its cluster, added to the global light.
  std::vector<std::string> defines = lists_.forward_defines(view, counting_);
  if (output == ch03::LightVolumes::Output::HeatShaded) defines.push_back("HEAT_SHADED 1");
  if (output == ch03::LightVolumes::Output::HeatLit) defines.push_back("HEAT_LIT 1");
  auto program = [&](bool depth_only) -> const ShaderProgram& {
    std::vector<ShaderStage> stages = {{GL_VERTEX_SHADER, "01_forward/shaders/forward.vert"}};
    if (!depth_only) stages.push_back({GL_FRAGMENT_SHADER, "09_clustered/shaders/clustered_forward.frag"});
    return programs_.get(stages, defines);  // the pre-pass: no fragment shader
  };
  const std::vector<std::string> names = pass_names();
  draw_forward(gpu_, frame_.gbuffer(), view.camera, lists_, program(true), program(false), fbo_.id(), w, h, counting_,
               true, metrics_, names[1], names[2]);
  // The materials' textures took units 0.. where the frame keeps the G-buffer for every later
  // pass (deferred_frame.cpp binds it once, at 0): put it back.
  frame_.gbuffer().bind_textures(0);
  light.bind();
}
// [/forward-pass]

}  // namespace lp::ch09
