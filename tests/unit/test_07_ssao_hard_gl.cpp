// Chapter 07's hard cases against closed forms and bounds derived here, on the GPU (llvmpipe
// in CI): the inner corner of the Cornell box's floor and back wall against the closed-form
// AO of a 90-degree dihedral for rays of length R, a grazing view of a flat plane, samples
// off the screen's edge, a surface right in front of the camera (the screen-radius clamp),
// and the too-bright side of the depth-discontinuity halo.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/07_ssao/ao_corner.h"
#include "chapters/07_ssao/ao_frame.h"
#include "chapters/07_ssao/ao_truth.h"
#include "common/paths.h"
#include "common/raytrace.h"
#include "tests/unit/gl_environment.h"
#include "tests/unit/squares_scene.h"

using namespace lp;
using namespace lp::ch07;

namespace {

constexpr int kW = 320, kH = 180;
constexpr double kPi = 3.14159265358979;

struct Box {
  explicit Box(const std::string& file) : Box(load_scene(from_root(file))) {}
  explicit Box(Scene s) : scene(std::move(s)), gpu(scene), rays(scene), frame(gpu, kW, kH) {}
  Scene scene;
  SceneGpu gpu;
  RayScene rays;
  AoFrame frame;
};

Box& cornell() {
  static Box* b = new Box("assets/cornell/cornell.gltf");  // never destroyed: GL objects outlive no context
  return *b;
}

FrameCamera look(glm::vec3 eye, glm::vec3 target, float yfov = 0.6864f) {
  Camera c;
  c.world = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
  c.yfov = yfov;
  c.znear = 0.01f;
  c.zfar = 20.f;
  return frame_camera(c, float(kW) / kH);
}

}  // namespace

namespace {
// The closed form of the corner's AO, dihedral_ao (ao_corner.h [dihedral]), and the corner's
// view and pixels (ao_corner.h). The truth is held to the closed form below, so the formula is
// checked by the rays, not only used.
double corner_ao(double h) { return dihedral_ao(h); }
constexpr float kCornerR = kCornerRadius;
FrameCamera corner_camera() { return ch07::corner_camera(float(kW) / kH); }
std::vector<CornerPixel> corner_pixels() {
  Box& b = cornell();
  return ch07::corner_pixels(b.scene, b.rays, corner_camera(), kW, kH);
}

struct CornerError {
  double truth_signed[4] = {}, method_abs = 0, max_radius_px = 0;  // the truth's mean signed error per quarter of h; the method's mean |error|
  long pixels = 0;
};
// Over the pixels within R of the crease (h < 1), against corner_ao.
CornerError corner_error(const ImageF& ao, const ImageF& truth, const std::vector<CornerPixel>& pixels = corner_pixels()) {
  CornerError e;
  double n[4] = {};
  for (const auto& p : pixels) {
    if (p.h >= 1.0) continue;
    e.max_radius_px = std::max(e.max_radius_px, p.radius_px);
    const int bin = std::min(3, int(p.h * 4));
    e.truth_signed[bin] += truth.at(p.x, p.y, 0) - corner_ao(p.h), n[bin] += 1;
    e.method_abs += std::abs(ao.at(p.x, p.y, 0) - corner_ao(p.h));
    ++e.pixels;
  }
  for (int i = 0; i < 4; ++i) e.truth_signed[i] /= std::max(n[i], 1.0);
  e.method_abs /= double(std::max(e.pixels, 1L));
  return e;
}
}  // namespace

// [corner]
// The inner corner against its closed form. First the truth: the ray tracer (512 rays a pixel)
// agrees with corner_ao in every quarter of h to 0.005 (its standard error per pixel is at most
// 0.022, so over the 800+ pixels of a quarter its mean is good to 0.002; the rest is room for
// the pixels' positions, which the closed form takes from the rays' hits). Then each method's
// mean |A - corner_ao| over the pixels within R of the crease, bounded as the truth bounds are
// (SsaoTruth): regression bounds, the llvmpipe measurement plus a quarter for another renderer's
// rounding (the truth's check above is derived).
// Measured: classic 0.018, disk 0.044 (most of it at the crease, where the wall is seen edge-on:
// the book's inner-corner failure; 0.058 with the source's fixed spiral and no slab), GTAO
// 0.022. Broken, each fails (measured before the slabs and the disk's turned spiral): the
// classic kernel a sphere instead of a hemisphere (0.40), R projected with the horizontal focal
// length (disk 0.107, GTAO 0.096), GTAO's slices weighted uniformly instead of by the cosine (0.050). The view
// keeps R under the screen-radius clamp: nearer than 1.4 m (R = 0.25) the clamp shortens the
// disk's and GTAO's reach, and the same corner from 0.6 m gave them 0.115 and 0.098.
TEST(SsaoHardCases, InnerCornerMatchesItsClosedForm) {
  Box& b = cornell();
  const FrameCamera cam = corner_camera();
  const ImageF truth = cached_ray_traced_ao(b.scene, cam, kW, kH, {.radius = kCornerR, .samples = 512});
  const CornerError t = corner_error(truth, truth);
  std::printf("truth - closed form by quarter of h: %+.4f %+.4f %+.4f %+.4f over %ld pixels\n", t.truth_signed[0],
              t.truth_signed[1], t.truth_signed[2], t.truth_signed[3], t.pixels);
  ASSERT_GT(t.pixels, 2500);
  std::printf("R is at most %.1f pixels on the screen there\n", t.max_radius_px);
  ASSERT_LT(t.max_radius_px, AoSettings{}.max_screen_radius * kH);  // the clamp does not shorten R
  for (double e : t.truth_signed) EXPECT_LT(std::abs(e), 0.005);
  struct Case {
    AoSettings s;
    double bound;
  };
  for (const Case& c : {Case{{.method = AoMethod::Classic, .samples = 16, .radius = kCornerR}, 0.022},
                        Case{{.method = AoMethod::Disk, .samples = 32, .radius = kCornerR}, 0.055},
                        Case{{.method = AoMethod::Gtao, .samples = 32, .radius = kCornerR}, 0.0275}}) {
    const CornerError e = corner_error(b.frame.ao(cam, c.s), truth);
    std::printf("%s: mean |A - closed form| within R of the crease %.4f\n", kMethodNames[int(c.s.method)].c_str(),
                e.method_abs);
    EXPECT_LT(e.method_abs, c.bound) << kMethodNames[int(c.s.method)];
  }
}
// [/corner]

// [corner-along-z]
// The same closed form at a crease along the other horizontal axis: the floor meeting the
// right wall (x = 1), for z in [-0.7, -0.3] (more than R from the back wall, the short box and
// the tall box), seen from (0.2, 1.2, 0.5), 1.75 m away (R under the screen-radius clamp, as
// above). The first crease runs along x: a kernel turned about the world's x axis instead of
// the normal (a hemisphere tilted towards +x) keeps its points' heights over that crease's
// other face, and the first corner cannot see it. Same truth check and methods; the bounds as
// the first corner's are made (regression bounds): the llvmpipe measurement plus a quarter. Measured: classic
// 0.040, disk 0.056, GTAO 0.052 (all about twice the first corner's: the right wall is seen at
// a slant here, not face on); the classic hemisphere tilted towards world +x, 0.067.
TEST(SsaoHardCases, InnerCornerAlongTheOtherAxisMatchesItsClosedForm) {
  Box& b = cornell();
  const FrameCamera cam = look({0.2f, 1.2f, 0.5f}, {1.f, 0.f, -0.5f});
  std::vector<CornerPixel> pixels;
  const auto hits = primary_hits(b.rays, cam, kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const auto& h = hits[std::size_t(y) * kW + x];
      if (!h || h->position.z < -0.7f || h->position.z > -0.3f) continue;
      const std::string& name = b.scene.instances[std::size_t(h->instance)].name;
      const double z = -(cam.view * glm::vec4(h->position, 1.f)).z;
      const double radius_px = kCornerR * cam.projection[1][1] * 0.5 * kH / z;
      if (name == "floor") pixels.push_back({x, y, (1.0 - h->position.x) / kCornerR, radius_px});
      else if (name == "right_wall") pixels.push_back({x, y, h->position.y / kCornerR, radius_px});
    }
  const ImageF truth = cached_ray_traced_ao(b.scene, cam, kW, kH, {.radius = kCornerR, .samples = 512});
  const CornerError t = corner_error(truth, truth, pixels);
  std::printf("truth - closed form by quarter of h: %+.4f %+.4f %+.4f %+.4f over %ld pixels\n", t.truth_signed[0],
              t.truth_signed[1], t.truth_signed[2], t.truth_signed[3], t.pixels);
  ASSERT_GT(t.pixels, 2000);  // 500 a quarter of h: the truth's mean good to 0.001 in each
  std::printf("R is at most %.1f pixels on the screen there\n", t.max_radius_px);
  ASSERT_LT(t.max_radius_px, AoSettings{}.max_screen_radius * kH);
  for (double e : t.truth_signed) EXPECT_LT(std::abs(e), 0.005);
  struct Case {
    AoSettings s;
    double bound;
  };
  for (const Case& c : {Case{{.method = AoMethod::Classic, .samples = 16, .radius = kCornerR}, 0.050},
                        Case{{.method = AoMethod::Disk, .samples = 32, .radius = kCornerR}, 0.070},
                        Case{{.method = AoMethod::Gtao, .samples = 32, .radius = kCornerR}, 0.065}}) {
    const CornerError e = corner_error(b.frame.ao(cam, c.s), truth, pixels);
    std::printf("%s: mean |A - closed form| within R of the crease %.4f\n", kMethodNames[int(c.s.method)].c_str(),
                e.method_abs);
    EXPECT_LT(e.method_abs, c.bound) << kMethodNames[int(c.s.method)];
  }
}
// [/corner-along-z]

// [grazing]
// A grazing view of an open plane (tests/data/minimal.gltf, 2 x 2 m, seen from 8 cm above it,
// 5 cm beyond its near edge, looking 2.2 degrees down: the view rays meet it at 2 to 22 degrees). Nothing occludes it, so A = 1. What
// could darken it is the depth buffer's pixel grid: a kernel point h above the plane is read at
// its pixel's centre, up to half a pixel (theta / 2, theta = yfov / H = 0.0038 rad) away along
// the plane, where the plane's depth is nearer by up to d theta / 2 / sin(a) at distance d and
// angle a, while the point is h / sin(a) in front of the plane behind it: it is never counted
// hidden while h > d theta / 2. Every kernel point is at least kMinCosine kMinLength R =
// 0.0075 m above the plane (R = 0.5), d theta / 2 <= 0.0044 m at the plane's far edge (2.3 m):
// no point is falsely hidden, and the bound is the open plane's, 0.995 (one point in 200 lost
// to D24 rounding). GTAO and the disk see the plane's own pixels at most bias x R above the
// tangent plane (the bias drops them) and edge-on (cosine 0).
TEST(SsaoHardCases, GrazingViewOfAPlaneHasNoFalseOcclusion) {
  Box w("tests/data/minimal.gltf");
  const FrameCamera cam = look({0.f, 0.08f, 1.05f}, {0.f, 0.0f, -1.0f});
  long floor = 0;
  for (float v : cached_ray_traced_ao(w.scene, cam, kW, kH, {.radius = 0.5f, .samples = 16}).data) floor += v >= 0.f;
  ASSERT_GT(floor, kW * kH / 20);  // the plane is in view
  for (AoSettings s : {AoSettings{.method = AoMethod::Classic, .samples = 32, .radius = 0.5f},
                       AoSettings{.method = AoMethod::Disk, .samples = 64, .radius = 0.5f},
                       AoSettings{.method = AoMethod::Gtao, .samples = 32, .radius = 0.5f}}) {
    const ImageF ao = w.frame.ao(cam, s);
    float lowest = 1.f;
    for (float v : ao.data) lowest = std::min(lowest, v);
    std::printf("%s: lowest A on the grazing plane %.4f\n", kMethodNames[int(s.method)].c_str(), lowest);
    EXPECT_GE(lowest, 0.995f) << kMethodNames[int(s.method)];
  }
}
// [/grazing]

// The classic test's bias: a kernel point counts as hidden only when the stored surface lies at
// least bias x R in front of it, so a larger bias can only drop hidden points, never add one.
// Two consequences that hold exactly (the same kernel, noise and blur weights, which depend on
// depth and normals only; float sums and products of non-negative weights are monotone): on the
// open plane, nothing in front of any point, A stays 1 (the open plane's 0.995) even with a
// bias of a quarter of R; and in the Cornell box's corner, A with bias 0.25 is at least A with
// the default bias, which is at least A without bias, pixel by pixel. A bias of the wrong sign
// hides every point up to bias x R above a surface: the plane darkens and the order reverses.
TEST(SsaoHardCases, ClassicBiasOnlyEverDropsOccluders) {
  Box w("tests/data/minimal.gltf");
  const FrameCamera above = look({0.f, 1.2f, 0.6f}, {0.f, 0.f, 0.f});
  AoSettings s{.method = AoMethod::Classic, .samples = 32, .radius = 0.5f};
  s.bias = 0.25f;
  const ImageF plane = w.frame.ao(above, s);
  float lowest = 1.f;
  for (float v : plane.data) lowest = std::min(lowest, v);
  std::printf("classic, bias 0.25 R: lowest A on the open plane %.4f\n", lowest);
  EXPECT_GE(lowest, 0.995f);

  Box& b = cornell();
  const FrameCamera cam = corner_camera();
  std::vector<ImageF> ao;
  for (float bias : {0.f, AoSettings{}.bias, 0.25f}) {
    AoSettings c{.method = AoMethod::Classic, .samples = 16, .radius = kCornerR};
    c.bias = bias;
    ao.push_back(b.frame.ao(cam, c));
  }
  long lower = 0, raised = 0;
  for (std::size_t i = 0; i < ao[0].data.size(); ++i) {
    lower += ao[1].data[i] < ao[0].data[i] || ao[2].data[i] < ao[1].data[i];
    raised += ao[2].data[i] > ao[0].data[i];
  }
  std::printf("corner: %ld pixels brighter with bias 0.25 R than with none, %ld darker with more bias\n", raised, lower);
  EXPECT_EQ(lower, 0);
  EXPECT_GT(raised, 100);  // the bias does something in the crease
}

// [screen-edge]
// Samples off the screen's edge. Every method counts them as open (classic: the point counts
// as not hidden; the disk and GTAO skip the sample, so the horizon or the occlusion sum stays as
// it was): nothing is known there, and unknown is taken as open, never as hidden. So at the
// edge A can only rise, and by at most the occlusion of the samples that fell off, which for a
// pixel in the edge column is at most the half of them on the outer side. The corner's crease
// is seen twice: in the middle of the corner view and, with the camera turned 30 degrees to the
// right, at the left edge (the crease runs across the image, so the off-screen half of each
// edge pixel's samples holds as much of the wall as the other half). For the crease pixels of
// the edge columns (x < 6), against the same points in the middle view (their nearest pixel):
// the mean of A_edge - A_middle is >= -0.02 (no darkening; 0.02: the two pixels differ by up to
// half a pixel in h, and the blur's 4x4 tile meets them at different phases) and <= half the
// middle's mean occlusion + 0.02.
TEST(SsaoHardCases, SamplesOffTheScreenEdgeCountAsOpen) {
  Box& b = cornell();
  const FrameCamera middle = corner_camera();
  const glm::vec3 eye = kCornerEye;
  const glm::vec3 ahead = glm::vec3(0.48f, 0.0f, -1.0f) - eye;
  const glm::vec3 turned = glm::vec3(glm::rotate(glm::mat4(1), glm::radians(-30.f), glm::vec3(0, 1, 0)) * glm::vec4(ahead, 0));
  const FrameCamera edge = look(eye, eye + turned);
  const auto hits = primary_hits(b.rays, edge, kW, kH);
  for (AoSettings s : {AoSettings{.method = AoMethod::Classic, .samples = 16, .radius = kCornerR},
                       AoSettings{.method = AoMethod::Disk, .samples = 32, .radius = kCornerR},
                       AoSettings{.method = AoMethod::Gtao, .samples = 32, .radius = kCornerR}}) {
    const ImageF at_edge = b.frame.ao(edge, s), in_middle = b.frame.ao(middle, s);
    double diff = 0, occlusion = 0;
    long n = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < 6; ++x) {
        const auto& h = hits[std::size_t(y) * kW + x];
        if (!h) continue;
        const std::string& name = b.scene.instances[std::size_t(h->instance)].name;
        const double dist = name == "floor" ? h->position.z + 1.0 : name == "back_wall" ? h->position.y : 1e9;
        if (dist >= kCornerR) continue;  // the crease's pixels only
        const glm::vec4 c = middle.projection * middle.view * glm::vec4(h->position, 1.f);
        const int mx = int((c.x / c.w * 0.5f + 0.5f) * kW), my = int((0.5f - 0.5f * c.y / c.w) * kH);
        if (mx < 20 || mx >= kW - 20 || my < 20 || my >= kH - 20) continue;  // well inside the middle view
        diff += at_edge.at(x, y, 0) - in_middle.at(mx, my, 0);
        occlusion += 1.0 - in_middle.at(mx, my, 0);
        ++n;
      }
    diff /= double(std::max(n, 1L)), occlusion /= double(std::max(n, 1L));
    std::printf("%s: at the edge A - A in the middle %+.4f (middle's occlusion %.3f) over %ld pixels\n",
                kMethodNames[int(s.method)].c_str(), diff, occlusion, n);
    EXPECT_GT(n, 100);
    EXPECT_GE(diff, -0.02) << kMethodNames[int(s.method)];
    EXPECT_LE(diff, 0.5 * occlusion + 0.02) << kMethodNames[int(s.method)];
  }
}
// [/screen-edge]

// [near-camera]
// A surface right in front of the camera: the crease of the floor and the back wall seen from
// 4 cm away (near plane 1 cm), R = 0.25. R projects to R / z of the focal length, over 1 000
// pixels here; the disk and GTAO clamp it to max_screen_radius x H (45 pixels) and read
// `samples` depths whatever it is, so their cost per pixel cannot grow as the camera nears a
// wall (a loop count, not something to time on shared cores). The clamp's price: they see
// occluders only within the clamped reach, so near the camera they are too bright (measured
// +0.41 and +0.43), never too dark. The classic kernel is in world space and reaches 25 cm,
// behind the camera and off the screen, where its points count as open (+0.48). Every method:
// A finite and in [0, 1], and its mean over the view no darker than the truth's by more than
// 0.02 (the truth's mean is good to 0.001; 0.02 as the screen-edge test's). Counting the
// classic kernel's points behind the camera (w <= 0) as hidden fails it (-0.13). And the other
// way: the disk and GTAO may be too bright, but not AO gone. What they can see is the crease's
// closed form (dihedral_ao, ao_corner.h) with their reach clamped to 45 pixels at each pixel's
// depth, R' = min(R, 45 z / (f H / 2)): its mean occlusion over the view (printed) is derived.
// Each must keep at least half of it (a regression bound: measured 85 % for the disk, 68 % for
// GTAO; AO gone keeps none). The classic is AO gone here by design: its world-space kernel lies
// off the screen or behind the camera, where points count as open (SamplesOffTheScreenEdge...).
TEST(SsaoHardCases, SurfaceRightInFrontOfTheCameraIsNotDarkened) {
  Box& b = cornell();
  const FrameCamera cam = look({0.5f, 0.03f, -0.97f}, {0.5f, 0.0f, -1.0f});
  const ImageF truth = cached_ray_traced_ao(b.scene, cam, kW, kH, {.radius = kCornerR, .samples = 512});
  // The crease's closed form with the reach the screen-radius clamp leaves: R' = min(R, 45
  // pixels at the pixel's depth), A = dihedral_ao(x / R') (ao_corner.h).
  const auto hits = primary_hits(b.rays, cam, kW, kH);
  std::vector<double> clamped(std::size_t(kW) * kH, -1.0);
  const double clamp_px = AoSettings{}.max_screen_radius * kH;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const auto& h = hits[std::size_t(y) * kW + x];
      if (!h) continue;
      const std::string& name = b.scene.instances[std::size_t(h->instance)].name;
      const double z = -(cam.view * glm::vec4(h->position, 1.f)).z;
      const double reach = std::min(double(kCornerR), clamp_px / (cam.projection[1][1] * 0.5 * kH / z));
      if (name == "floor") clamped[std::size_t(y) * kW + x] = corner_ao(std::abs(h->position.z + 1.0) / reach);
      else if (name == "back_wall") clamped[std::size_t(y) * kW + x] = corner_ao(h->position.y / reach);
    }
  double clamped_occlusion = 0;
  long clamped_n = 0;
  for (double c : clamped)
    if (c >= 0) clamped_occlusion += 1 - c, ++clamped_n;
  clamped_occlusion /= double(std::max(clamped_n, 1L));
  std::printf("the crease's closed form within the clamped reach: mean occlusion %.4f over %ld pixels\n", clamped_occlusion,
              clamped_n);
  ASSERT_GT(clamped_n, kW * kH / 2);
  for (AoSettings s : {AoSettings{.method = AoMethod::Classic, .samples = 32, .radius = kCornerR},
                       AoSettings{.method = AoMethod::Disk, .samples = 64, .radius = kCornerR},
                       AoSettings{.method = AoMethod::Gtao, .samples = 32, .radius = kCornerR}}) {
    const ImageF ao = b.frame.ao(cam, s);
    long bad = 0, n = 0;
    double diff = 0, mean_truth = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const float v = ao.at(x, y, 0), t = truth.at(x, y, 0);
        bad += !std::isfinite(v) || v < 0.f || v > 1.f;
        if (t < 0.f) continue;
        diff += v - t, mean_truth += t, ++n;
      }
    diff /= double(std::max(n, 1L)), mean_truth /= double(std::max(n, 1L));
    std::printf("%s: 4 cm from the crease, mean A - truth %+.4f (truth %.3f) over %ld pixels\n",
                kMethodNames[int(s.method)].c_str(), diff, mean_truth, n);
    double occlusion = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x)
        if (clamped[std::size_t(y) * kW + x] >= 0) occlusion += 1 - ao.at(x, y, 0);
    occlusion /= double(clamped_n);
    std::printf("%s: mean occlusion %.4f, %.0f %% of the clamped reach's\n", kMethodNames[int(s.method)].c_str(), occlusion,
                100 * occlusion / clamped_occlusion);
    if (s.method != AoMethod::Classic) { EXPECT_GT(occlusion, 0.5 * clamped_occlusion) << kMethodNames[int(s.method)] << ": AO gone"; }
    EXPECT_GT(n, kW * kH / 2);
    EXPECT_EQ(bad, 0);
    EXPECT_GE(diff, -0.02) << kMethodNames[int(s.method)];
  }
}
// [/near-camera]

// [halo-bright]
// The depth discontinuity's other side: too BRIGHT. The back wall beside the tall box (the
// pixels of the halo test in test_07_ssao_gl.cpp: wall within 6 pixels of box pixels more than
// R nearer). The box stands 0.9 m in front of the wall at its front face, but its back is 0.23
// to 0.3 m from the wall, within R: the truth there (mean 0.59) is darker than the same wall with
// the box taken away (0.73, ray traced as well). A method that drops an occluder because its
// visible face is more than R in front loses that occlusion. The bound mirrors the dark halo's:
// the mean signed error there may not exceed +0.10 (about the methods' mean absolute error
// over the whole image). The classic algorithm holds it (measured +0.004: its range check fades
// such occluders, R / dz, instead of dropping them); with the range check a hard cut (|dz| > R:
// dropped) it fails. The disk and GTAO drop every surface more than R away in 3D, and with
// nothing behind the depth buffer's surfaces (thickness 0: the source's disk, XeGTAO's
// horizons) they fail it, +0.30 (the source's fixed spiral +0.31) and +0.20: the test asserts
// that too, so it can tell. With each sample a slab (ssao.comp [thickness], the thickness chosen on another view) they hold it:
// measured disk +0.046, GTAO -0.088 (a horizon fills everything below it, the gap between the
// box's back and the wall too: too dark, within the dark halo's bound, -0.10).
double bright_halo_error(Box& b, const FrameCamera& cam, const std::vector<std::pair<int, int>>& halo,
                         double mean_truth, const AoSettings& s) {
  const ImageF ao = b.frame.ao(cam, s);
  double mean = 0;
  for (auto [x, y] : halo) mean += ao.at(x, y, 0);
  return mean / double(halo.size()) - mean_truth;
}
TEST(SsaoHardCases, DepthDiscontinuityIsNotTooBright) {
  Box& b = cornell();
  const FrameCamera cam = frame_camera(b.scene.camera("front"), float(kW) / kH);
  Scene without = b.scene;
  std::vector<Instance> kept;
  for (const Instance& i : without.instances)
    if (i.name.rfind("tall_box", 0) != 0) kept.push_back(i);
  without.instances = kept;
  const ImageF open = cached_ray_traced_ao(without, cam, kW, kH, {.radius = 0.5f, .samples = 512});
  const ImageF truth = cached_ray_traced_ao(b.scene, cam, kW, kH, {.radius = 0.5f, .samples = 512});
  const auto hits = primary_hits(b.rays, cam, kW, kH);
  auto is = [&](int x, int y, const std::string& prefix) {
    const auto& h = hits[std::size_t(y) * kW + x];
    return h && b.scene.instances[std::size_t(h->instance)].name.rfind(prefix, 0) == 0;
  };
  std::vector<std::pair<int, int>> halo;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (!is(x, y, "back_wall")) continue;
      const float t = hits[std::size_t(y) * kW + x]->t;
      for (int dx = -6; dx <= 6; ++dx) {
        const int nx = x + dx;
        if (nx >= 0 && nx < kW && is(nx, y, "tall_box") && hits[std::size_t(y) * kW + nx]->t < t - 0.5f) {
          halo.push_back({x, y});
          break;
        }
      }
    }
  ASSERT_GT(halo.size(), 100u);
  double mean_open = 0, mean_truth = 0;
  for (auto [x, y] : halo) mean_open += open.at(x, y, 0), mean_truth += truth.at(x, y, 0);
  mean_open /= double(halo.size()), mean_truth /= double(halo.size());
  std::printf("halo pixels %zu: truth %.3f, without the box %.3f\n", halo.size(), mean_truth, mean_open);
  EXPECT_LT(mean_truth, mean_open - 0.05);  // the box's hidden back does occlude the wall there
  for (AoSettings s : {AoSettings{.method = AoMethod::Classic, .samples = 16, .radius = 0.5f},
                       AoSettings{.method = AoMethod::Disk, .samples = 32, .radius = 0.5f},
                       AoSettings{.method = AoMethod::Gtao, .samples = 32, .radius = 0.5f}}) {
    const std::string name = kMethodNames[int(s.method)];
    const double e = bright_halo_error(b, cam, halo, mean_truth, s);
    std::printf("%s: mean A - truth beside the box %+.3f\n", name.c_str(), e);
    EXPECT_LT(e, 0.10) << name;
    if (s.method == AoMethod::Classic) continue;
    s.thickness = 0.f;
    const double flat = bright_halo_error(b, cam, halo, mean_truth, s);
    std::printf("%s, nothing behind the surfaces (thickness 0): %+.3f\n", name.c_str(), flat);
    EXPECT_GT(flat, 0.10) << name << ": the test no longer tells a slab from none";
  }
}
// [/halo-bright]

// [two-radii]
// The source's two radii at 1:5 (classic): the kernel again at R / 5, A the product of the two
// visibilities. In the corner its closed form follows from corner_ao: corner_ao(h) x
// corner_ao(5 h), the narrow set's h being x / (R / 5). Three claims, over the corner view's
// pixels: (1) within R / 5 of the crease (h < 0.2) it is darker than the wide radius alone, by
// at least half of what the closed forms predict there (their mean of corner_ao(h) (1 -
// corner_ao(5 h)), printed); (2) beyond 2 R / 5 (h >= 0.4: no narrow point reaches the wall,
// and the blur's 4 pixels do not reach back to h = 0.2) it is the wide radius's A, to 0.002 in
// the mean: not exactly, because the narrow kernel's lowest points (kMinCosine kMinLength R / 5
// = 0.75 mm up) lie below half a pixel's depth step on the floor 1.8 m away (the grazing test's
// d theta / 2 = 3.4 mm), so a few of them are hidden by the floor itself (the largest
// difference, printed, is 0.005); (3) its mean |A - closed form| within R is at most its
// measurement (0.0228) plus a quarter, 0.0285, a regression bound as the corner test's. Averaging the two
// sets instead of multiplying fails (2).
TEST(SsaoHardCases, TwoRadiiDarkenContactAndNothingElse) {
  Box& b = cornell();
  const FrameCamera cam = corner_camera();
  const AoSettings wide{.method = AoMethod::Classic, .samples = 16, .radius = kCornerR};
  AoSettings two = wide;
  two.two_radii = true;
  const ImageF a_wide = b.frame.ao(cam, wide), a_two = b.frame.ao(cam, two);
  double contact = 0, predicted = 0, beyond = 0, beyond_max = 0, error = 0;
  long n_contact = 0, n_beyond = 0, n = 0;
  for (const auto& p : corner_pixels()) {
    const double w = a_wide.at(p.x, p.y, 0), t = a_two.at(p.x, p.y, 0);
    const double closed = corner_ao(p.h) * corner_ao(5.0 * p.h);
    if (p.h < 0.2) contact += w - t, predicted += corner_ao(p.h) - closed, ++n_contact;
    if (p.h >= 0.4) beyond += std::abs(w - t), beyond_max = std::max(beyond_max, std::abs(w - t)), ++n_beyond;
    if (p.h < 1.0) error += std::abs(t - closed), ++n;
  }
  contact /= double(std::max(n_contact, 1L)), predicted /= double(std::max(n_contact, 1L));
  beyond /= double(std::max(n_beyond, 1L)), error /= double(std::max(n, 1L));
  std::printf("two radii: darker by %.4f within R / 5 (closed forms: %.4f, %ld pixels); beyond 2 R / 5 %.5f apart "
              "in the mean, %.5f at most (%ld pixels); mean |A - closed form| %.4f\n",
              contact, predicted, n_contact, beyond, beyond_max, n_beyond, error);
  ASSERT_GT(n_contact, 200);
  ASSERT_GT(n_beyond, 1000);
  EXPECT_GT(contact, 0.5 * predicted);
  EXPECT_LT(beyond, 0.002);
  EXPECT_LT(error, 0.0285);
}
// [/two-radii]

// Each disk sample stands for an equal share of the disk, pi R^2 / N, at the receiver's depth
// zr; the surface it lands on lies at the emitter's depth ze, where the same share of the screen
// covers (ze / zr)^2 as much area. The Cornell views cannot see that factor: what lies within R
// of a receiver there is at nearly its depth. Here (tests/unit/squares_scene.h) every occluder
// is a roof 0.4 above the floor, seen through a hole from 1 m above the floor: ze / zr = 0.6,
// and the factor is 0.36. With it the disk's sum is a quadrature of the truth's integral (the
// form factor of the roof within R), less two losses that only lower it: the term's
// saturation, area / (pi d^2 + area) against area / (pi d^2), at most share x 0.36 / (0.77 x pi
// x 0.4^2) = 2.3 % (d >= 0.4, the slant's cosine >= 0.77), and the part of R's sphere the
// screen disk misses (at the roof it has a radius of R ze / zr = 0.3 m about the receiver's
// view ray, and the sphere's section one of sqrt(R^2 - 0.4^2) = 0.3 m about the receiver: they
// coincide at the hole's centre only). So the mean occlusion over the floor's pixels is at most the truth's
// plus the quadrature's error, and at least the truth's less those losses and that error; the
// truth's own standard error over the ~2 700 pixels is 0.0004. The bounds, 0.8 and 1.15 of the
// truth, give the quadrature of 32 turned samples at rounded pixels 15 %, an allowance, not a
// derivation (measured: 0.94 of the truth on llvmpipe). Without the factor the sum is 1 / 0.36 =
// 2.8 times as large.
TEST(SsaoHardCases, RoofSeenThroughAHoleOccludesAsMuchAsItsTruth) {
  const test::RoofHole r;
  Box b(test::roof_hole_scene(r));
  const FrameCamera cam = test::roof_hole_camera(r, float(kW) / kH);
  const AoSettings s{.method = AoMethod::Disk, .samples = 32, .radius = 0.5f, .blur = false, .max_screen_radius = 0.5f,
                     .thickness = 0.f};
  const double radius_px = s.radius * cam.projection[1][1] * 0.5 * kH / r.eye;
  ASSERT_LT(radius_px, s.max_screen_radius * kH);  // the clamp does not shorten R on the floor
  ASSERT_LT(r.roof, s.radius);                     // the roof is within R of the floor below it
  const ImageF truth = cached_ray_traced_ao(b.scene, cam, kW, kH, {.radius = s.radius, .samples = 512});
  const ImageF ao = b.frame.ao(cam, s);
  const auto hits = primary_hits(b.rays, cam, kW, kH);
  double method = 0, want = 0;
  long pixels = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const auto& h = hits[std::size_t(y) * kW + x];
      if (!h || b.scene.instances[std::size_t(h->instance)].name != "floor") continue;
      method += 1.0 - ao.at(x, y, 0), want += 1.0 - truth.at(x, y, 0), ++pixels;
    }
  method /= double(std::max(pixels, 1L)), want /= double(std::max(pixels, 1L));
  std::printf("floor through the hole: mean occlusion %.4f, truth %.4f (%.3f of it) over %ld pixels\n", method, want,
              method / want, pixels);
  ASSERT_GT(pixels, 2000);
  ASSERT_GT(want, 0.1);
  EXPECT_GT(method, 0.8 * want);
  EXPECT_LT(method, 1.15 * want);
}
