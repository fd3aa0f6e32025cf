// Chapter 06's convolution shadow maps on the GPU (llvmpipe in CI): the sun's visibility from
// the step's truncated Fourier series (csm_math.h, shadow_visibility.glsl [csm-glsl]) against
// the ray-traced hard truth on the atrium, by the number of terms.
#include <gtest/gtest.h>

#include <cstdio>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/06_shadows/shadow_stage.h"
#include "chapters/06_shadows/shadow_truth.h"
#include "common/paths.h"
#include "common/target.h"
#include "tests/unit/gl_environment.h"

using namespace lp;
using namespace lp::ch06;

namespace {
constexpr int kW = 320, kH = 180;
}  // namespace

// [csm-gl]
// More terms, nearer the hard truth: the mean |visibility - truth| over what the sun reaches
// falls with every doubling of the terms (the series' L2 distance from the step falls as
// 1 / terms, csm_math.h), and even the most terms leave the error above the hard map's on the
// same map (the ringing and the step's finite slope, which put light inside shadows near their
// casters). And the ringing shows: inside the truth's shadows, away from its edges, pixels the
// series reads more than half lit, at every count.
TEST(CsmGl, ErrorFallsWithTheTermsAndTheRingingStays) {
  Scene scene = load_scene(from_root("assets/atrium/atrium.gltf"));
  SceneGpu gpu(scene);
  RayScene rays(scene);
  ch03::DeferredFrame frame(gpu);
  ShadowStage stage(gpu, find_sun(scene));
  frame.volumes().set_lights(ch03::build_light_set(
      scene.lights, ch03::cut_threshold(1.f, ch03::peak_reflectance(scene)), frame.volumes().shapes()));
  frame.add_stage(stage);
  const FrameCamera cam = frame_camera(scene.camera("overview"), float(kW) / kH);
  const ImageF truth = cached_shadow_truth(scene, rays, cam, kW, kH, find_sun(scene).direction);
  auto visibility = [&](const ShadowSettings& s) {
    ColourTarget target(kW, kH, GL_RGBA32F);
    stage.set(s, ShadowPicture::Visibility);
    frame.render(cam, {target.framebuffer(), kW, kH});
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    return target.read();
  };
  const std::vector<bool> edges = hard_edge_pixels(truth, 2);
  const double hard = visibility_error(visibility({.method = ShadowMethod::Hard}), truth, 0).mean_abs;
  double last = 1e9;
  for (int terms : {1, 2, 4, 8}) {
    const ImageF v = visibility({.method = ShadowMethod::CsmFourier, .csm_terms = terms});
    const VisibilityError e = visibility_error(v, truth, 0);
    std::size_t dark = 0, leaking = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x)
        if (truth.at(x, y, 2) > 0.5f && truth.at(x, y, 0) < 0.5f && !edges[std::size_t(y) * kW + x])
          ++dark, leaking += v.at(x, y, 0) > 0.5f;
    std::printf("%d terms: mean |error| %.4f (hard map %.4f), wrong %.2f%%; %zu of %zu shadowed pixels read lit\n", terms,
                e.mean_abs, hard, 100 * e.wrong, leaking, dark);
    EXPECT_LT(e.mean_abs, last) << terms;
    EXPECT_GT(e.mean_abs, hard) << terms;
    ASSERT_GT(dark, std::size_t(1000));
    EXPECT_GT(leaking, std::size_t(0)) << terms;
    last = e.mean_abs;
  }
}
// [/csm-gl]
