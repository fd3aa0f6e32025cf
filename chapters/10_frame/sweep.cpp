// Chapter 10's sweep: transparency as layers grow. The glass scene's panes replaced by a stack
// of N panes (N = 1 .. 64, three colours in turn, 10 cm apart, each shifted a little so the
// stack's edges show every count from 1 to N), drawn sorted and with WBOIT: the time of each
// method's passes (the one measurement, common/measure.h) and its error against the exact
// per-pixel order, in 8-bit steps over the pixels with glass. Writes
// book/figures/10_transparency_llvmpipe.csv (or 10_transparency.csv on a GPU), each row naming
// the renderer, size and frames.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/10_frame/transparency.h"
#include "common/context.h"
#include "common/error.h"
#include "common/measure.h"
#include "common/paths.h"
#include "common/sweep.h"
#include "common/target.h"

namespace {

using namespace lp;
using namespace lp::ch10;

struct Settings {
  std::string out = (source_root() / "book" / "figures").string();
  int width = 640, height = 360;
  int frames = 10;
  int max_layers = 64;
  std::string renderer;
};

// [stack]
// The glass scene with its panes replaced by `layers` panes one behind another.
Scene stacked(int layers) {
  Scene scene = load_scene(from_root("assets/glass/glass.gltf"));
  std::vector<Instance> panes;
  for (const char* name : {"pane_blue", "pane_amber", "pane_green"})
    for (const Instance& i : scene.instances)
      if (i.name == name) panes.push_back(i);
  std::erase_if(scene.instances, [](const Instance& i) { return i.name.rfind("pane_", 0) == 0 || i.name.rfind("cross_", 0) == 0; });
  for (int k = 0; k < layers; ++k) {
    Instance pane = panes[std::size_t(k) % panes.size()];
    pane.name = "stack_" + std::to_string(k);
    pane.model = glm::translate(glm::mat4(1), glm::vec3(0.02f * float(k), 0.9f, 1.f - 0.1f * float(k)));
    pane.model = pane.model * glm::mat4(glm::mat3(panes[0].model));  // the panes' rotation (facing the camera)
    scene.instances.push_back(pane);
  }
  return scene;
}
// [/stack]

struct Errors {
  double mean = 0, p99 = 0, max = 0;
  std::size_t pixels = 0;
};
Errors errors(const ImageRGBA8& a, const ExactComposite& exact) {
  std::vector<int> e;
  for (std::size_t i = 0; i < exact.layers.size(); ++i) {
    if (exact.layers[i] == 0) continue;
    int d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a.pixels[i * 4 + c]) - int(exact.image.pixels[i * 4 + c])));
    e.push_back(d);
  }
  Errors r;
  r.pixels = e.size();
  if (e.empty()) return r;
  std::sort(e.begin(), e.end());
  for (int v : e) r.mean += v;
  r.mean /= double(e.size());
  r.p99 = e[std::size_t(std::ceil(0.99 * double(e.size()))) - 1];
  r.max = e.back();
  return r;
}

void sweep(const Settings& s, std::ofstream& csv) {
  for (int layers = 1; layers <= s.max_layers; layers *= 2) {
    Scene scene = stacked(layers);
    SceneGpu gpu(scene);
    ch03::DeferredFrame frame(gpu);
    frame.volumes().set_lights(ch03::build_light_set(
        scene.lights, ch03::cut_threshold(1.f, ch03::peak_reflectance(scene)), frame.volumes().shapes()));
    TransparencyStage stage(frame, gpu);
    frame.add_stage(stage);
    OutputTarget target(s.width, s.height);
    const FrameCamera camera = frame_camera(scene.camera("front"), float(s.width) / s.height);
    const ch03::FrameOutput output{target.framebuffer(), s.width, s.height};
    stage.set({.method = Method::Off});
    frame.render(camera, output);
    const ExactComposite exact = stage.exact_composite(frame, std::size_t(layers) + 8);
    if (exact.overflow) throw Error("10_frame_sweep: the exact composite overflowed at " + std::to_string(layers) + " layers");
    const int deepest = *std::max_element(exact.layers.begin(), exact.layers.end());
    for (Method method : {Method::Sorted, Method::Wboit}) {
      // [measure]
      TransparencySettings t{.method = method, .order = method == Method::Wboit ? DrawOrder::AsListed : DrawOrder::BackToFront};
      stage.set(t);
      frame.render(camera, output);
      const Errors e = errors(target.read(), exact);
      PassMetrics metrics;
      const Measurement m = measure(metrics, [&] { frame.render(camera, output, &metrics); }, {.frames = s.frames});
      double ms = 0, min_ms = 0;
      std::uint64_t fragments = 0;
      for (const PassMeasurement& p : m.passes)
        if (p.name.rfind("transparency:", 0) == 0) ms += p.mean_ms, min_ms += p.min_ms, fragments += p.fragments;
      // [/measure]
      csv << layers << ',' << deepest << ',' << kMethods[int(method)] << ',' << ms << ',' << min_ms << ',' << fragments << ','
          << e.pixels << ',' << e.mean << ',' << e.p99 << ',' << e.max << ','
          << csv_measure_values(s.renderer, s.width, s.height, m.frames) << '\n';
      std::cout << "  " << layers << " layers, " << kMethods[int(method)] << ": " << ms << " ms, error mean " << e.mean
                << " p99 " << e.p99 << " max " << e.max << " steps" << std::endl;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  return run_sweep(argc, argv, "10_frame_sweep", [&](SweepArgs& args) {
    args.text("--out", s.out).size("--size", s.width, s.height).integer("--frames", s.frames).integer("--layers", s.max_layers);
  }, [&] {
    if (s.frames < 1) throw UsageError("--frames must be at least 1");
    if (s.max_layers < 1 || s.max_layers > 128) throw UsageError("--layers must be between 1 and 128");
    std::filesystem::create_directories(s.out);
    auto context = Context::create({.headless = true, .width = s.width, .height = s.height});
    s.renderer = context->renderer();
    const std::string timer = (context->is_software() ? "llvmpipe CPU time: " : "GPU time: ") + context->renderer();
    std::cout << timer << '\n';
    const std::string path = s.out + (context->is_software() ? "/10_transparency_llvmpipe.csv" : "/10_transparency.csv");
    std::ofstream csv(path);
    csv << "# " << timer << ", " << s.width << "x" << s.height << "; the glass scene's panes replaced by a stack of N\n"
        << "# ms: the method's passes (sorted: one; wboit: accumulate + composite), mean and fastest of " << s.frames
        << " frames; fragments: what they shaded and composited\n"
        << "# errors against the exact per-pixel order, in 8-bit steps, over the pixels with glass\n"
        << "layers,deepest,method,ms,min_ms,fragments,glass_pixels,error_mean,error_p99,error_max,"
        << csv_measure_columns() << "\n";
    sweep(s, csv);
    std::cout << "wrote " << path << '\n';
  });
}
