// Chapter 08's pass on the GPU (llvmpipe in CI) against the ray-traced one-bounce truth: the
// Cornell box's colour bleeding, the patterns, the second bounce, and the hard cases. Bounds are
// stated where they are asserted; they hold on any conforming renderer.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/08_ssgi/gi_frame.h"
#include "chapters/08_ssgi/gi_truth.h"
#include "common/error.h"
#include "common/paths.h"
#include "common/raytrace.h"
#include "tests/unit/gl_environment.h"

using namespace lp;
using namespace lp::ch08;

namespace {

constexpr int kW = 160, kH = 90;

struct World {
  explicit World(const std::string& file) : scene(load_scene(from_root(file))), gpu(scene), frame(gpu, kW, kH) {}
  FrameCamera camera(const std::string& view) const { return frame_camera(scene.camera(view), float(kW) / kH); }
  // The instance each pixel sees (its name), from the ray tracer's primary hits (the raster's pixels).
  std::vector<std::string> names(const FrameCamera& cam) const {
    RayScene rays(scene);
    std::vector<std::string> n;
    for (const auto& h : primary_hits(rays, cam, kW, kH)) n.push_back(h ? scene.instances[std::size_t(h->instance)].name : "");
    return n;
  }
  Scene scene;
  SceneGpu gpu;
  GiFrame frame;
};

World& cornell() {
  // never destroyed: its GL objects must not outlive the test environment's context
  static World* w = new World("assets/cornell/cornell.gltf");
  return *w;
}

// The truth at 160x90: 1024 cosine-weighted rays per pixel.
ImageF truth(World& w, const FrameCamera& cam, GiTruthSettings s = {.samples = 1024}) {
  return cached_ray_traced_indirect(w.scene, w.frame.lights(), cam, kW, kH, s);
}

// Mean of channel c over the pixels that see `name` and lie in columns [x0, x1).
double region_mean(const ImageF& img, const std::vector<std::string>& names, const std::string& name, int c, int x0 = 0,
                   int x1 = kW) {
  double sum = 0;
  long n = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = x0; x < x1; ++x)
      if (names[std::size_t(y) * kW + x] == name) {
        sum += img.at(x, y, c);
        ++n;
      }
  return n ? sum / double(n) : std::nan("");
}

}  // namespace

TEST(SsgiCornell, Explore) {
  World& w = cornell();
  const FrameCamera cam = w.camera("front");
  const auto names = w.names(cam);
  const ImageF t = truth(w, cam), screen = truth(w, cam, {.samples = 1024, .screen_limited = true});
  for (Pattern p : {Pattern::Regular, Pattern::Spiral, Pattern::Randomised})
    for (int samples : {16, 32, 64, 128}) {
      ImageF gi = w.frame.indirect(cam, GiMode::Ssgi, {.samples = samples, .pattern = p});
      GiErrors e = gi_errors(gi, t), es = gi_errors(gi, screen);
      std::cout << kPatternNames[int(p)] << " " << samples << ": mean abs " << e.mean_abs << " rel " << e.relative
                << " captured " << e.captured << " | vs screen-limited " << es.mean_abs << " rel " << es.relative
                << " captured " << es.captured << "\n";
    }
  GiErrors sl = gi_errors(screen, t);
  std::cout << "screen-limited truth captures " << sl.captured << "\n";
  ImageF gi = w.frame.indirect(cam, GiMode::Ssgi, {.samples = 64});
  {
    const ImageF t2 = truth(w, cam, {.samples = 1024, .bounces = 2});
    ImageF g2 = w.frame.indirect(cam, GiMode::Ssgi, {.samples = 64, .bounces = 2});
    GiErrors a = gi_errors(t2, t), b = gi_errors(g2, gi), c = gi_errors(g2, t2);
    std::cout << "2 bounce truth / 1 bounce " << a.captured << " ssgi2/ssgi1 " << b.captured << " ssgi2 vs t2 " << c.relative << " " << c.captured << "\n";
    ImageF t512 = truth(w, cam, {.samples = 1024, .seed = 99});
    GiErrors n = gi_errors(t512, t);
    std::cout << "truth noise mean abs " << n.mean_abs << " rel " << n.relative << "\n";
  }
  for (const char* region : {"floor", "tall_box_nx", "tall_box_pz", "short_box_pz", "short_box_px", "back_wall", "ceiling"})
    for (auto [x0, x1] : {std::pair{0, kW / 2}, std::pair{kW / 2, kW}})
      std::cout << region << " [" << x0 << "," << x1 << "): truth " << region_mean(t, names, region, 0, x0, x1) << " "
                << region_mean(t, names, region, 1, x0, x1) << " screen " << region_mean(screen, names, region, 0, x0, x1)
                << " " << region_mean(screen, names, region, 1, x0, x1) << " ssgi " << region_mean(gi, names, region, 0, x0, x1)
                << " " << region_mean(gi, names, region, 1, x0, x1) << "\n";
}
