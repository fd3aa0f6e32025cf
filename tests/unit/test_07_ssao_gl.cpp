// Chapter 07's AO passes on the GPU (llvmpipe in CI) against the ray-traced truth and in the
// hard cases: an open flat plane (nothing occludes it), the sky and the blur beside it, the
// tutorial bug of a world-space kernel on a view-space position, bad settings. Bounds are
// stated where they are asserted; they hold on any conforming renderer.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/07_ssao/ao_frame.h"
#include "chapters/07_ssao/ao_truth.h"
#include "common/error.h"
#include "common/paths.h"
#include "common/raytrace.h"
#include "tests/unit/gl_environment.h"

using namespace lp;
using namespace lp::ch07;

namespace {

constexpr int kW = 320, kH = 180;

struct World {
  explicit World(const std::string& file) : scene(load_scene(from_root(file))), gpu(scene), frame(gpu, kW, kH) {}
  FrameCamera camera(const std::string& view) const { return frame_camera(scene.camera(view), float(kW) / kH); }
  Scene scene;
  SceneGpu gpu;
  AoFrame frame;
};

World& cornell() {
  // never destroyed: its GL objects must not outlive the test environment's context
  static World* w = new World("assets/cornell/cornell.gltf");
  return *w;
}

// The Cornell box's truth: 512 cosine-weighted rays of R = 0.5 per pixel (standard error per
// pixel <= 0.5 / sqrt(512) = 0.022; its contribution to a mean absolute error over 30 000
// pixels is at most its mean absolute deviation, 0.8 x 0.022 = 0.018, far below the bounds).
const ImageF& cornell_truth() {
  static ImageF t = cached_ray_traced_ao(cornell().scene, cornell().camera("front"), kW, kH,
                                         {.radius = 0.5f, .samples = 512});
  return t;
}

AoErrors against_truth(const AoSettings& s) {
  World& w = cornell();
  AoErrors e = ao_errors(w.frame.ao(w.camera("front"), s), cornell_truth());
  std::cout << kMethodNames[int(s.method)] << ": mean absolute error " << e.mean_abs << " over " << e.pixels << " pixels\n";
  return e;
}

}  // namespace

// [truth-bounds]
// Each method within its stated mean absolute error of the truth, R = 0.5 in a box of side 2.
// These are regression bounds, not derived ones: a screen-space method's bias against the truth
// has no closed form, so each is the llvmpipe measurement (in the comment) plus a quarter for
// what another renderer's rounding changes. What is derived is the truth's share: its noise
// adds at most 0.018 to a mean absolute error (above), so the bounds tell apart changes larger
// than that. A method that broke (AO 1 everywhere: 0.197 here, or noise left in) fails them.
TEST(SsaoTruth, ClassicWithinItsBoundOfRayTracedAo) {
  AoErrors e = against_truth({.method = AoMethod::Classic, .samples = 16, .radius = 0.5f});
  EXPECT_GT(e.pixels, 25000);
  EXPECT_LT(e.mean_abs, 0.10);  // measured 0.078
}
TEST(SsaoTruth, ClassicHalfResolutionWithinItsBound) {
  AoErrors e = against_truth({.method = AoMethod::Classic, .samples = 16, .radius = 0.5f, .scale = 2});
  EXPECT_LT(e.mean_abs, 0.11);  // measured 0.081
}
TEST(SsaoTruth, DiskWithinItsBoundOfRayTracedAo) {
  AoErrors e = against_truth({.method = AoMethod::Disk, .samples = 32, .radius = 0.5f});
  EXPECT_LT(e.mean_abs, 0.072);  // measured 0.0575 (0.102 with the source's fixed spiral and no slab)
}
TEST(SsaoTruth, GtaoWithinItsBoundOfRayTracedAo) {
  AoErrors e = against_truth({.method = AoMethod::Gtao, .samples = 32, .radius = 0.5f});
  EXPECT_LT(e.mean_abs, 0.059);  // measured 0.047 (0.062 with no slab behind the surfaces)
}
// The disk's bands (book 07, 'Bands, and the turned spiral'): the source's fixed spiral puts
// every pixel's samples on the same offsets, so each edge a sample crosses steps A along a whole
// line of pixels. Turned per pixel by the noise tile and blurred, the 16 spirals of the tile
// interleave. Measured: the source's fixed spiral 0.0702; the fixed spiral blurred 0.0605 (the
// blur alone does most of it); turned and blurred 0.0575. Asserted: turned and blurred at least
// 10 % below the source's (a blur that stopped blurring the disk fails it; another renderer's
// rounding does not), and below the fixed spiral blurred (5 % measured; a turn that stopped
// turning gives exactly the fixed spiral blurred, and fails it).
TEST(SsaoTruth, DiskTurnedAndBlurredIsCloserThanTheFixedSpiral) {
  const AoErrors turned = against_truth({.method = AoMethod::Disk, .samples = 32, .radius = 0.5f});
  const AoErrors fixed =
      against_truth({.method = AoMethod::Disk, .samples = 32, .radius = 0.5f, .noise = false, .blur = false});
  AoSettings blurred{.method = AoMethod::Disk, .samples = 32, .radius = 0.5f, .noise = false};
  const AoErrors fixed_blurred = against_truth(blurred);
  EXPECT_LT(turned.mean_abs, 0.9 * fixed.mean_abs);
  EXPECT_LT(turned.mean_abs, fixed_blurred.mean_abs);
}
TEST(SsaoTruth, NoAoIsFarFromTheTruth) {
  // the yardstick the bounds are read against: A = 1 everywhere
  AoErrors e = against_truth({.method = AoMethod::Off});
  EXPECT_GT(e.mean_abs, 0.15);
}
// [/truth-bounds]

// An open flat plane (tests/data/minimal.gltf, a 2x2 rectangle seen from above at 27 degrees
// and the sky around it): no surface occludes it, so A = 1 at every pixel (GTAO through its
// normalisation by the open slice, and the bias that keeps depth rounding from raising horizons), including those
// next to the sky after the blur (the sky is never averaged in) and the sky itself. The bound
// 0.995 allows one kernel point in 200 lost to depth rounding; none is lost on llvmpipe.
TEST(SsaoHardCases, OpenPlaneAndSkyStayUnoccluded) {
  World w("tests/data/minimal.gltf");
  const FrameCamera cam = w.camera("view");
  for (AoSettings s : {AoSettings{.method = AoMethod::Classic, .samples = 32, .radius = 0.5f},
                       AoSettings{.method = AoMethod::Classic, .samples = 32, .radius = 0.5f, .scale = 4},
                       AoSettings{.method = AoMethod::Disk, .samples = 64, .radius = 0.5f},
                       AoSettings{.method = AoMethod::Gtao, .samples = 32, .radius = 0.5f}}) {
    ImageF ao = w.frame.ao(cam, s);
    float lowest = 1.f;
    for (float v : ao.data) lowest = std::min(lowest, v);
    EXPECT_GE(lowest, 0.995f) << kMethodNames[int(s.method)] << " scale " << s.scale;
  }
}

// [tutorial-bug]
// The bug of many tutorials: the kernel turned into world space and added to a view-space
// position. Rolling the camera 180 degrees about its view axis turns the image upside down
// exactly (pixel (x, y) becomes (W-1-x, H-1-y)); the AO of a surface must not change. Noise
// and blur off (the noise tile is fixed to the screen). The right kernel changes by rounding
// only (bound 0.01 mean, measured below 0.001); the bug's changes by far more (bound > 0.03).
double roll_difference(bool bug) {
  World& w = cornell();
  FrameCamera cam = w.camera("front"), rolled = cam;
  rolled.view = glm::rotate(glm::mat4(1), glm::pi<float>(), glm::vec3(0, 0, 1)) * cam.view;
  AoSettings s{.method = AoMethod::Classic, .samples = 16, .radius = 0.5f, .noise = false, .blur = false,
               .tutorial_bug = bug};
  ImageF a = w.frame.ao(cam, s), b = w.frame.ao(rolled, s);
  double sum = 0;
  long n = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      float t = cornell_truth().at(x, y, 0);
      if (t < 0.f) continue;  // geometry only
      sum += std::abs(a.at(x, y, 0) - b.at(kW - 1 - x, kH - 1 - y, 0));
      ++n;
    }
  return sum / double(n);
}
TEST(SsaoHardCases, AoDoesNotChangeWhenTheCameraRollsAndTheTutorialBugDoes) {
  const double right = roll_difference(false), bug = roll_difference(true);
  std::cout << "mean change when the camera rolls: " << right << ", with the bug " << bug << '\n';
  EXPECT_LT(right, 0.01);
  EXPECT_GT(bug, 0.03);
}
// [/tutorial-bug]

// [halo]
// A depth discontinuity: the back wall of the box seen beside the tall box, which stands in
// front of it. Pixels of the wall within 6 pixels of a box pixel whose surface is more than R
// nearer (the rasteriser's pixels, found by the ray tracer's primary hits): the depth buffer
// puts the box in front of every kernel point there, and without the range check the wall
// would darken in a halo. The mean signed error there (negative: too dark) is bounded by the
// -0.10 (about the methods' mean absolute error over the whole image): a halo is an error beyond
// the ordinary. Measured on llvmpipe: classic +0.004, disk +0.046, GTAO -0.088 (its slabs'
// horizons fill the gap behind the box too; with no slab, ssao.comp [thickness], the disk and
// GTAO were too bright, +0.31 and +0.20: the opposite failure, which
// DepthDiscontinuityIsNotTooBright bounds); classic with its range check removed, -0.25.
double halo_signed_error(const AoSettings& s, long* count) {
  World& w = cornell();
  const FrameCamera cam = w.camera("front");
  static const auto hits = [&] {
    RayScene rays(w.scene);
    return primary_hits(rays, cam, kW, kH);
  }();
  auto is = [&](int x, int y, const std::string& prefix) {
    const auto& h = hits[std::size_t(y) * kW + x];
    return h && w.scene.instances[std::size_t(h->instance)].name.rfind(prefix, 0) == 0;
  };
  ImageF ao = w.frame.ao(cam, s);
  double sum = 0;
  *count = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (!is(x, y, "back_wall")) continue;
      const float t = hits[std::size_t(y) * kW + x]->t;
      bool near_edge = false;
      for (int dx = -6; dx <= 6 && !near_edge; ++dx) {
        int nx = x + dx;
        if (nx < 0 || nx >= kW || !is(nx, y, "tall_box")) continue;
        near_edge = hits[std::size_t(y) * kW + nx]->t < t - s.radius;
      }
      if (!near_edge) continue;
      sum += ao.at(x, y, 0) - cornell_truth().at(x, y, 0);
      ++*count;
    }
  return sum / double(std::max(*count, 1L));
}
TEST(SsaoHardCases, DepthDiscontinuityHaloIsBounded) {
  for (AoSettings s : {AoSettings{.method = AoMethod::Classic, .samples = 16, .radius = 0.5f},
                       AoSettings{.method = AoMethod::Disk, .samples = 32, .radius = 0.5f},
                       AoSettings{.method = AoMethod::Gtao, .samples = 32, .radius = 0.5f}}) {
    long count = 0;
    const double e = halo_signed_error(s, &count);
    std::cout << kMethodNames[int(s.method)] << ": mean signed error beside the tall box " << e << " over " << count
              << " pixels\n";
    EXPECT_GT(count, 100);
    EXPECT_GT(e, -0.10);
  }
}
// [/halo]

TEST(SsaoBadInput, SamplesAndRadiusAreChecked) {
  World& w = cornell();
  EXPECT_THROW(w.frame.ao(w.camera("front"), {.samples = 0}), Error);
  EXPECT_THROW(w.frame.ao(w.camera("front"), {.samples = kMaxSamples + 1}), Error);
  EXPECT_THROW(w.frame.ao(w.camera("front"), {.radius = -1.f}), Error);
  EXPECT_THROW(w.frame.ao(w.camera("front"), {.scale = 3}), Error);
}
