// The ray tracer against the rasteriser (llvmpipe in CI): both must see the same surface at
// every pixel, so a chapter can compare its screen-space estimate with the truth at the
// same points. Only silhouettes may differ, where a pixel centre lies within rounding of a
// triangle edge and the two take different sides.
#include <gtest/gtest.h>

#include <set>

#include "chapters/01_forward/ground_truth.h"
#include "common/context.h"
#include "common/paths.h"
#include "common/raytrace.h"

using namespace lp;

namespace {

constexpr int kW = 320, kH = 180;

class RayTraceGl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { context_ = Context::create({.headless = true, .width = kW, .height = kH}).release(); }
  static void TearDownTestSuite() { delete context_; }
  static Context* context_;
};
Context* RayTraceGl::context_ = nullptr;

struct Agreement {
  std::size_t pixels_with_geometry = 0, silhouette = 0, silhouette_mismatches = 0, interior_mismatches = 0;
};

// A pixel is on a silhouette when its 3x3 neighbourhood in the rasterised ids holds more
// than one id (an edge between instances, or between an instance and the sky).
bool on_silhouette(const std::vector<int>& ids, int x, int y) {
  const int centre = ids[std::size_t(y) * kW + x];
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      int nx = std::clamp(x + dx, 0, kW - 1), ny = std::clamp(y + dy, 0, kH - 1);
      if (ids[std::size_t(ny) * kW + nx] != centre) return true;
    }
  return false;
}

Agreement compare_view(const SceneGpu& gpu, const RayScene& rays, const Camera& camera) {
  FrameCamera fc = frame_camera(camera, float(kW) / kH);
  std::vector<int> raster = ch01::render_instance_ids(gpu, fc, kW, kH);  // instance + 1, top row first
  std::vector<std::optional<Hit>> hits = primary_hits(rays, fc, kW, kH);
  Agreement a;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      std::size_t i = std::size_t(y) * kW + x;
      int traced = hits[i] ? hits[i]->instance + 1 : 0;
      bool edge = on_silhouette(raster, x, y);
      a.pixels_with_geometry += raster[i] != 0;
      a.silhouette += edge;
      if (traced != raster[i]) ++(edge ? a.silhouette_mismatches : a.interior_mismatches);
    }
  return a;
}

}  // namespace

TEST_F(RayTraceGl, RayTracerAndRasteriserSeeTheSameInstanceAtEveryPixelOffSilhouettes) {
  for (const char* file : {"assets/cornell/cornell.gltf", "assets/atrium/atrium.gltf", "assets/street/street.gltf"}) {
    Scene scene = load_scene(from_root(file));
    SceneGpu gpu(scene);
    RayScene rays(scene);
    for (const Camera& camera : scene.cameras) {
      Agreement a = compare_view(gpu, rays, camera);
      std::string where = std::string(file) + " view " + camera.name;
      ASSERT_GT(a.pixels_with_geometry, std::size_t(kW) * kH / 20) << where << ": the view must see the scene";
      // Off silhouettes the pixel centre is at least a pixel from any edge between ids:
      // rounding cannot move an edge that far, so every such pixel must agree. (Rows
      // counted from the wrong end fail here by the ten thousand.)
      EXPECT_EQ(a.interior_mismatches, 0u) << where;
      // On silhouettes the two may take different sides of an edge through a pixel centre
      // (within rounding), or of a line where two surfaces meet at the same depth (the
      // Cornell box's corners: the depth test keeps the first drawn, the tracer either):
      // 1.8% there, under 0.5% in the atrium and the street. A pixel centre off by half a
      // pixel along one axis moves every edge across that axis by half a pixel, which flips
      // one pixel of its three-pixel band: about a sixth of the silhouette pixels (16-19%
      // measured). A twentieth keeps the ties and catches that.
      EXPECT_LE(a.silhouette_mismatches, a.silhouette / 20) << where;
      RecordProperty(std::string(file) + ":" + camera.name, std::to_string(a.silhouette_mismatches) + " of " +
                                                               std::to_string(a.silhouette) + " silhouette pixels differ");
      std::printf("%s: %zu of %zu silhouette pixels differ, %zu interior\n", where.c_str(), a.silhouette_mismatches,
                  a.silhouette, a.interior_mismatches);
    }
  }
}
