// Chapter 01's measurements: per-vertex and per-pixel error against the ground truth as the
// sphere's tessellation grows (with their cost), and forward-shading time as lights grow.
// Writes CSV files and the figures the book shows; timings are GPU time on a GPU and CPU
// time on llvmpipe (common/measure.h: warm-up until the times settle, then --frames frames),
// and every row names the renderer, the size and the frames measured.
//
//   01_forward_sweep [--out DIR] [--size WxH] [--light-size WxH] [--frames N] [--max-lights N]
#include <fstream>
#include <iostream>
#include <functional>
#include <string>

#include "chapters/01_forward/forward.h"
#include "chapters/01_forward/ground_truth.h"
#include "common/context.h"
#include "common/error.h"
#include "common/measure.h"
#include "common/paths.h"
#include "common/sweep.h"
#include "common/target.h"

namespace {

using namespace lp;
using namespace lp::ch01;

struct Settings {
  std::string out = (source_root() / "book" / "figures").string();
  int width = 640, height = 360;  // llvmpipe; a GPU measures at 1280x720 unless --size says otherwise
  bool size_given = false;
  int light_width = 1920, light_height = 1080;
  int frames = 20;
  int max_lights = 1024;
};

// The measured frame: clear, then `draw` as the pass "frame".
PassMeasurement measure_frame(PassMetrics& metrics, int frames, const std::function<void()>& draw) {
  Measurement m = measure(metrics, [&] {
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    auto pass = metrics.pass("frame");
    draw();
  }, {.frames = frames});
  return m.pass("frame");
}

void tessellation_sweep(const Settings& s, const Scene& scene, const SceneGpu& gpu, const std::string& timer,
                        const std::string& renderer) {
  ForwardRenderer forward(gpu);
  LightBuffer lights;
  lights.upload(scene.lights);
  OutputTarget target(s.width, s.height);
  PassMetrics metrics;
  std::ofstream csv(s.out + "/01_tessellation.csv");
  csv << "# " << timer << ", " << s.width << "x" << s.height << ", error in 8-bit sRGB steps over sphere pixels\n"
      << "segments,triangles,mode,mean_error,p99_error,max_error,ms,fragments," << csv_measure_columns() << "\n";
  for (int segments : {8, 16, 32, 64, 128}) {
    const Camera& camera = scene.camera("close_" + std::to_string(segments));
    GroundTruth truth = render_ground_truth(scene, camera, s.width, s.height, scene.lights);
    FrameCamera fc = frame_camera(camera, float(s.width) / s.height);
    std::vector<std::uint8_t> mask = sphere_mask(scene, truth, render_instance_ids(gpu, fc, s.width, s.height));
    int triangles = segments * (segments / 2) * 2;
    for (const std::string mode : {"per-vertex", "unnormalized", "per-pixel"}) {
      target.bind();
      glClearColor(lp::ch01::kBackground.r, lp::ch01::kBackground.g, lp::ch01::kBackground.b, 1.f);
      auto stats = measure_frame(metrics, s.frames, [&] { forward.draw(fc, forward_mode(mode), lights); });
      ImageRGBA8 image = target.read();
      FloatErrorStats e = sphere_error(image, truth, mask);
      csv << segments << ',' << triangles << ',' << mode << ',' << e.mean_abs << ',' << e.p99 << ',' << e.max << ','
          << stats.mean_ms << ',' << stats.fragments << ',' << csv_measure_values(renderer, s.width, s.height, stats.frames) << '\n';
      std::cout << "close_" << segments << ' ' << mode << ": mean " << e.mean_abs << " p99 " << e.p99 << " max " << e.max
                << " steps, " << stats.mean_ms << " ms\n";
      if (segments == 16) {
        save_png(s.out + "/01_close16_" + mode + ".png", image);
        std::vector<float> err = pixel_errors(srgb_steps(image), srgb_steps(to_srgb8(truth.radiance)));
        for (size_t i = 0; i < err.size(); ++i) if (!mask[i]) err[i] = 0;
        save_png(s.out + "/01_close16_" + mode + "_error.png", error_heatmap(err, s.width, s.height, 16.f));
      }
    }
    if (segments == 16) save_png(s.out + "/01_close16_ground-truth.png", to_srgb8(truth.radiance));
  }
}

void light_sweep(const Settings& s, const Scene& scene, const SceneGpu& gpu, const std::string& timer,
                 const std::string& renderer, bool software) {
  ForwardRenderer forward(gpu);
  OutputTarget target(s.light_width, s.light_height);
  PassMetrics metrics;
  FrameCamera fc = frame_camera(scene.camera("overview"), float(s.light_width) / s.light_height);
  std::ofstream csv(s.out + "/01_lights.csv");
  csv << "# " << timer << ", " << s.light_width << "x" << s.light_height << ", view overview\n"
      << "lights,mode,ms,fragments," << csv_measure_columns() << "\n";
  for (int n = 1; n <= s.max_lights; n *= 2) {
    LightBuffer lights;
    lights.upload(lights_for_count(scene, n));
    target.bind();
    auto one = measure_frame(metrics, s.frames, [&] { forward.draw(fc, ForwardMode::PerPixel, lights); });
    const std::string columns = csv_measure_values(renderer, s.light_width, s.light_height, one.frames);
    csv << n << ",single-pass," << one.mean_ms << ',' << one.fragments << ',' << columns << '\n';
    std::cout << n << " lights: single pass " << one.mean_ms << " ms";
    if (!software || n <= 64) {  // one pass per light: too slow to sweep far on a CPU
      auto multi = measure_frame(metrics, s.frames, [&] {
        forward.draw_base(fc, lights);
        forward.draw_additive_lights(fc, lights);
      });
      csv << n << ",multi-pass," << multi.mean_ms << ',' << multi.fragments << ','
          << csv_measure_values(renderer, s.light_width, s.light_height, multi.frames) << '\n';
      std::cout << ", multi-pass " << multi.mean_ms << " ms";
    }
    std::cout << std::endl;
  }
}

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  return run_sweep(argc, argv, "01_forward_sweep", [&](SweepArgs& args) {
    args.text("--out", s.out).size("--size", s.width, s.height, &s.size_given).size("--light-size", s.light_width, s.light_height)
        .integer("--frames", s.frames).integer("--max-lights", s.max_lights);
  }, [&] {
    std::filesystem::create_directories(s.out);
    auto context = Context::create({.headless = true, .width = s.width, .height = s.height});
    if (!context->is_software() && !s.size_given) {  // the book's GPU figures: more pixels per draw
      s.width = 1280;
      s.height = 720;
    }
    Scene scene = load_scene(from_root("assets/forward/forward.gltf"));
    SceneGpu gpu(scene);
    std::string timer = (context->is_software() ? "llvmpipe CPU time: " : "GPU time: ") + context->renderer();
    std::cout << timer << '\n';
    tessellation_sweep(s, scene, gpu, timer, context->renderer());
    light_sweep(s, scene, gpu, timer, context->renderer(), context->is_software());
    std::cout << "wrote " << s.out << "/01_tessellation.csv and 01_lights.csv\n";
  });
}
