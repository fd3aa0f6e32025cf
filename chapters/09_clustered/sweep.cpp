// Chapter 09's measurement: time per frame against the number of lights, 1 ... 100 000, on
// the street at 1920x1080, for chapter 03's stencil volumes, the five deferred ways of this
// chapter and clustered forward, each split into its passes (depth bounds, assign, the
// forward depth pre-pass, shade), with the lists' memory and the exact evaluated-per-lit ratio. On llvmpipe (no --size) it runs a small size and
// fewer lights so that it ends in minutes; on a GPU, the full sweep.
//   09_clustered_sweep [--out DIR] [--size WxH] [--frames N] [--max-lights N] [--stencil-max N]
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_counts.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/09_clustered/clustered_forward.h"
#include "chapters/09_clustered/clustered_lights.h"
#include "common/context.h"
#include "common/measure.h"
#include "common/paths.h"
#include "common/sweep.h"
#include "common/target.h"

namespace {
using namespace lp;

struct Settings {
  std::string out = (source_root() / "book" / "figures").string();
  int width = 1920, height = 1080;
  bool size_given = false;
  int frames = 20;
  int max_lights = 100000;
  int stencil_max = 100000;  // the stencil volumes cost a draw per light: where to stop them
  std::string view = "street_level";
};
}  // namespace

int main(int argc, char** argv) {
  Settings s;
  return run_sweep(argc, argv, "09_clustered_sweep", [&](SweepArgs& args) {
    args.text("--out", s.out).size("--size", s.width, s.height, &s.size_given).integer("--frames", s.frames)
        .integer("--max-lights", s.max_lights).integer("--stencil-max", s.stencil_max).text("--view", s.view);
  }, [&] {
    std::filesystem::create_directories(s.out);
    auto context = Context::create({.headless = true, .width = s.width, .height = s.height});
    const bool software = context->is_software();
    if (software && !s.size_given) {  // a CPU: small, few lights, few frames
      s.width = 320;
      s.height = 180;
      s.frames = std::min(s.frames, 3);
      s.max_lights = std::min(s.max_lights, 1000);  // 10 000 take 25 s a frame here
      s.stencil_max = std::min(s.stencil_max, 1000);
    }
    Scene scene = load_scene(from_root("assets/street/street.gltf"));
    SceneGpu gpu(scene);
    ch03::DeferredFrame frame(gpu);
    OutputTarget target(s.width, s.height);
    const FrameCamera camera = frame_camera(scene.camera(s.view), float(s.width) / float(s.height));
    const std::string timer = (software ? "llvmpipe CPU time: " : "GPU time: ") + context->renderer();
    // On a GPU 09_lights.csv (the lead names it after the GPU: 09_lights_h200.csv), on llvmpipe 09_lights_llvmpipe.csv.
    const std::string file = s.out + (software ? "/09_lights_llvmpipe.csv" : "/09_lights.csv");
    std::ofstream csv(file);
    csv << "# " << timer << ", " << s.width << "x" << s.height << ", street, view " << s.view << "\n"
        << "lights,method,total_ms,local_ms,depth_bounds_ms,assign_ms,prepass_ms,shade_ms,list_bytes,list_entries,regrown,"
        << "cells_over,evaluated,lit,evaluated_per_lit," << csv_measure_columns() << "\n";
    const float threshold = ch03::cut_threshold(1.f, ch03::peak_reflectance(scene));
    for (int n : {1, 10, 100, 1000, 10000, 100000}) {
      if (n > s.max_lights) break;
      frame.volumes().set_lights(ch03::build_light_set(ch03::lights_for_count(scene, n), threshold, frame.volumes().shapes()));
      auto draw = [&](PassMetrics& m) { frame.render(camera, {target.framebuffer(), s.width, s.height}, &m); };
      std::vector<std::string> methods = {"stencil"};
      for (const auto& m : ch09::kClusterModes) methods.push_back(m);
      methods.push_back("clustered-forward");  // the scene drawn again, lit from every cluster's list
      for (const std::string& method : methods) {
        if (method == "stencil" && n > s.stencil_max) continue;
        const bool forward = method == "clustered-forward";
        ch09::ClusteredForward forward_pass(frame, gpu);
        ch09::ClusteredLights deferred_pass(frame.volumes(), ch09::settings_for_mode(
                                                method == "stencil" || forward ? "clustered" : method));
        ch09::ClusteredLights& pass = forward ? forward_pass.lists() : deferred_pass;
        frame.set_local_lights(method == "stencil" ? nullptr : forward ? static_cast<ch03::LocalLightPass*>(&forward_pass) : &pass);
        frame.set_strategy(ch03::Strategy::Stencil);
        // Lists that fit first (they grow a frame after they overflow; a full cell is shaded
        // from every light meanwhile), then one counted frame for the exact counts, then the
        // timed frames without counting.
        if (method != "stencil")
          for (int k = 0; k < 4; ++k) {
            frame.render(camera, {target.framebuffer(), s.width, s.height}, nullptr);
            if (pass.wait_stats().cells_over == 0) break;
          }
        std::uint64_t evaluated = 0, lit = 0;
        frame.volumes().set_counting(method == "stencil");
        pass.set_counting(method != "stencil" && !forward);
        forward_pass.set_counting(forward);
        {
          PassMetrics m;
          measure(m, [&] { draw(m); }, {.frames = 1, .skip_warmup = true});
        }
        if (method == "stencil") {
          const ch03::FragmentCounts c = frame.volumes().counts();
          evaluated = c.shaded;
          lit = c.lit;
        } else {
          const ch09::EvalCounts c = pass.counts();
          evaluated = c.evaluated;
          lit = c.lit;
        }
        frame.volumes().set_counting(false);
        pass.set_counting(false);
        forward_pass.set_counting(false);
        PassMetrics metrics;
        // The stencil volumes at 10 000 lights and more take most of a second a frame or more:
        // a few frames, one-frame warm-up blocks (a pass that long
        // needs no clock ramp), so that the sweep stays within minutes.
        MeasureOptions options{.frames = s.frames};
        if (method == "stencil" && n >= 10000) {
          options.frames = std::min(s.frames, 3);
          options.warmup = {.block_frames = 1, .block_seconds = 0, .min_seconds = 0, .tolerance = 0.03, .max_seconds = 1};
        }
        const Measurement t = measure(metrics, [&] { draw(metrics); }, options);
        double parts[4] = {0, 0, 0, 0}, local = 0;  // depth bounds, assign, pre-pass, shade
        if (method == "stencil") {
          local = t.pass("local lights: stencil").mean_ms;
        } else if (forward) {
          const auto names = ch09::ClusteredForward::pass_names();  // assign, depth pre-pass, shade
          for (int k = 0; k < 3; ++k) local += parts[k + 1] = t.pass(names[k]).mean_ms;
        } else {
          const auto names = ch09::ClusteredLights::pass_names(method);
          for (int k = 0; k < 3; ++k) local += parts[k == 2 ? 3 : k] = t.pass(names[k]).mean_ms;
        }
        const bool ours = method != "stencil";
        const ch09::ClusterStats& st = ours ? pass.wait_stats() : pass.stats();
        csv << n << ',' << method << ',' << t.total_ms() << ',' << local << ',' << parts[0] << ',' << parts[1] << ','
            << parts[2] << ',' << parts[3] << ',' << (ours ? st.bytes : 0) << ',' << (ours ? st.indices : 0) << ',' << (ours ? st.regrown : 0)
            << ',' << (ours ? st.cells_over : 0) << ',' << evaluated << ',' << lit << ','
            << (lit ? double(evaluated) / double(lit) : 0.0) << ',' << csv_measure_values(context->renderer(), s.width, s.height, t.frames)
            << std::endl;  // a row at a time: a long GPU run cut short keeps what it measured
        std::cout << n << " lights, " << method << ": " << t.total_ms() << " ms (local lights " << local << "), evaluated "
                  << evaluated << ", lit " << lit << (ours && st.cells_over ? ", CELLS OVER " + std::to_string(st.cells_over) : "")
                  << std::endl;
        frame.set_local_lights(nullptr);
      }
    }
    std::cout << "wrote " << file << '\n';
  });
}
