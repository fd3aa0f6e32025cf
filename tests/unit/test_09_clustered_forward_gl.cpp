// Chapter 09's clustered forward on the GPU (llvmpipe in CI): the opaque street drawn forward,
// each fragment lit from its cluster's list (clustered_forward.glsl), against chapter 09's
// clustered deferred shading of the same frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "chapters/01_forward/material.h"
#include "chapters/02_gbuffer/layout.h"
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_counts.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/09_clustered/clustered_forward.h"
#include "chapters/09_clustered/clustered_lights.h"
#include "common/error.h"
#include "common/metrics.h"
#include "common/paths.h"
#include "common/target.h"
#include "tests/unit/gl_environment.h"

using namespace lp;
using namespace lp::ch09;

namespace {

std::vector<float> read_rgba(GLuint texture, int w, int h) {
  std::vector<float> v(std::size_t(w) * h * 4);
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(v.size() * 4), v.data());
  return v;
}

// The forward pass's target: L1 and L2 in RGBA32F (no rounding of the forward sums) and a
// depth-stencil of the G-buffer's format (D24S8 in the float layout).
struct ForwardTarget {
  ForwardTarget(int w, int h)
      : l1(gl::make_texture_2d(GL_RGBA32F, w, h)), l2(gl::make_texture_2d(GL_RGBA32F, w, h)),
        depth(gl::make_texture_2d(GL_DEPTH24_STENCIL8, w, h)) {
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, l1.id(), 0);
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT1, l2.id(), 0);
    glNamedFramebufferTexture(fbo.id(), GL_DEPTH_STENCIL_ATTACHMENT, depth.id(), 0);
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo.id(), 2, buffers);
  }
  gl::Framebuffer fbo;
  gl::Texture l1, l2, depth;
};

// The opaque scene drawn forward into the RGBA32F target (clustered_forward.h's draw_forward,
// the program's pass too), with the shading program itself as the pre-pass's: the colours
// cleared first, nothing added to them.
void draw_forward(const SceneGpu& gpu, const ch03::DeferredFrame& frame, ClusteredLights& pass,
                  const ShaderProgram& program, const ForwardTarget& target, bool counting) {
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(target.fbo.id(), GL_COLOR, 0, zero);
  glClearNamedFramebufferfv(target.fbo.id(), GL_COLOR, 1, zero);
  glDisable(GL_BLEND);
  ch09::draw_forward(gpu, frame.gbuffer(), frame.view().camera, pass, program, program, target.fbo.id(),
                     frame.light().width(), frame.light().height(), counting, false);
}

}  // namespace

TEST(ClusteredForwardGl, ForwardEqualsClusteredDeferredOnTheStreet) {
  // The float G-buffer: what the deferred pass reads is exactly what the forward fragment has
  // (world position, normal, specular colour and exponent in RGBA32F), so the two differ only
  // by rounding, and the bound below can be derived.
  Scene scene = load_scene(from_root("assets/street/street.gltf"));
  SceneGpu gpu(scene);
  ch03::DeferredFrame frame(gpu, ch02::float_layout());
  frame.volumes().set_lights(ch03::build_light_set(ch03::lights_for_count(scene, 2000),
                                                   ch03::cut_threshold(1.f, ch03::peak_reflectance(scene)),
                                                   frame.volumes().shapes()));
  const int w = 128, h = 72;
  const FrameCamera cam = frame_camera(scene.camera("street_level"), float(w) / float(h));
  ClusterSettings settings;
  settings.all_cells = true;  // every cluster gets its list: forward fragments may be anywhere
  ClusteredLights pass(frame.volumes(), settings);
  frame.set_local_lights(&pass);
  OutputTarget output(w, h);
  frame.render(cam, {output.framebuffer(), w, h});
  // The deferred local lights alone: the light buffer cleared, chapter 09's pass again.
  frame.light().clear();
  pass.set_counting(true);
  pass.draw(frame.light(), frame.view(), ch03::LightVolumes::Output::Light);
  const EvalCounts deferred = pass.counts();
  const std::vector<float> d1 = read_rgba(frame.light().diffuse(), w, h), d2 = read_rgba(frame.light().specular(), w, h);
  // All cells were assigned, not only the occupied ones.
  const std::vector<std::uint32_t> counts = pass.cell_counts();
  ASSERT_EQ(counts.size(), std::size_t(16 * 9 * 24));

  ForwardTarget target(w, h);
  const std::vector<ShaderStage> stages = {{GL_VERTEX_SHADER, "01_forward/shaders/forward.vert"},
                                           {GL_FRAGMENT_SHADER, "09_clustered/shaders/clustered_forward.frag"}};
  ShaderProgram forward(stages, pass.forward_defines(frame.view(), true));
  draw_forward(gpu, frame, pass, forward, target, true);
  const EvalCounts ours = pass.counts();
  const std::vector<float> f1 = read_rgba(target.l1.id(), w, h), f2 = read_rgba(target.l2.id(), w, h);
  // Lights evaluated per pixel, from the same pass with HEAT_SHADED.
  std::vector<std::string> heat_defines = pass.forward_defines(frame.view());
  heat_defines.push_back("HEAT_SHADED 1");
  ShaderProgram heat(stages, heat_defines);
  draw_forward(gpu, frame, pass, heat, target, false);
  const std::vector<float> k = read_rgba(target.l1.id(), w, h);
  frame.set_local_lights(nullptr);
  ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));

  // The same fragments, the same clusters, the same lists: the counts are equal exactly.
  EXPECT_GT(deferred.lit, 10000u);
  EXPECT_EQ(ours.evaluated, deferred.evaluated);
  EXPECT_EQ(ours.lit, deferred.lit);
  // And the forward pass lit the pixels the deferred one did (not a black image).
  std::size_t both = 0, deferred_lit = 0;
  for (std::size_t i = 0; i < d1.size(); i += 4)
    if (d1[i] + d1[i + 1] + d1[i + 2] > 0) {
      ++deferred_lit;
      if (f1[i] + f1[i + 1] + f1[i + 2] > 0) ++both;
    }
  EXPECT_GT(deferred_lit, std::size_t(w * h / 4));
  EXPECT_EQ(both, deferred_lit);

  // [forward-tolerance]
  // Both sum the same lights in the same order in float with the same local_light(). The
  // surfaces differ only in the normal: deferred renormalises the stored unit normal once
  // more, moving it by a few float ulps, so each of the k terms may differ by a relative
  // 2^-20 at most (generous for a few 2^-24). The deferred sum is then stored once in
  // RGBA16F; OpenGL leaves the rounding of that conversion to the implementation (on
  // llvmpipe a pixel whose forward sum is 1.093606 holds 1.092773, a step below; the nearest
  // half is 1.09375), so it may move the value by one half-float step: relative 2^-10 in the
  // normal range, 2^-24 absolute among the subnormals. The forward sum is stored in RGBA32F.
  // Per channel, with k the lights evaluated at the pixel:
  //   |forward - deferred| <= 2^-10 max + (k + 1) 2^-20 max + 2^-24.
  std::size_t failing = 0, compared = 0;
  std::string first;
  for (std::size_t i = 0; i < f1.size(); ++i) {
    if (i % 4 == 3) continue;
    for (int t = 0; t < 2; ++t) {
      const double a = (t == 0 ? f1 : f2)[i], b = (t == 0 ? d1 : d2)[i];
      const double m = std::max(std::fabs(a), std::fabs(b));
      const double bound = std::ldexp(m, -10) + (double(k[i - i % 4]) + 1.0) * std::ldexp(m, -20) + std::ldexp(1.0, -24);
      ++compared;
      if (std::fabs(a - b) > bound && failing++ == 0)
        first = "pixel " + std::to_string(i / 4) + (t == 0 ? " L1 " : " L2 ") + std::to_string(a) + " vs " +
                std::to_string(b) + " (" + std::to_string(k[i - i % 4]) + " lights)";
    }
  }
  // [/forward-tolerance]
  EXPECT_EQ(failing, 0u) << "of " << compared << "; first: " << first;

}

TEST(ClusteredForwardGl, ForwardNeedsTheListsOfEveryCluster) {
  Scene scene = load_scene(from_root("assets/street/street.gltf"));
  SceneGpu gpu(scene);
  ch03::DeferredFrame frame(gpu);
  ClusteredLights pass(frame.volumes());  // all_cells off: only occupied clusters have lists
  frame.set_local_lights(&pass);
  OutputTarget output(32, 18);
  frame.render(frame_camera(scene.camera("street_level"), 32.f / 18.f), {output.framebuffer(), 32, 18});
  frame.set_local_lights(nullptr);
  const std::vector<ShaderStage> stages = {{GL_VERTEX_SHADER, "01_forward/shaders/forward.vert"},
                                           {GL_FRAGMENT_SHADER, "09_clustered/shaders/clustered_forward.frag"}};
  ShaderProgram forward(stages, pass.forward_defines(frame.view()));
  try {
    pass.bind_for_forward(forward, frame.view().camera);
    FAIL() << "bind_for_forward accepted lists of the occupied clusters only";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("all_cells off"), std::string::npos) << e.what();
  }
}
