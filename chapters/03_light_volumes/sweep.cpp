// Chapter 03's measurements, as CSV files for the book's figures:
//   03_lights.csv        frame time and light evaluations (fragments shaded) per strategy as
//                        lights grow, with chapter 01's forward pass and chapter 02's
//                        full-screen pass on the same frame; overshading (shaded / lit)
//   03_tessellation.csv  the volumes' triangles against overshading and time
//   03_cut.csv           where a light is cut against the error it leaves (vs uncut) and cost
// Timings are GPU time on a GPU and CPU time on llvmpipe (common/measure.h: warm-up until
// the times settle, then --frames frames); each CSV's first line says which, and every row
// names the renderer, the size and the frames measured. Fragment counts are exact, 64-bit and
// the same on every machine (they come from a separate frame with the atomic counters on, so
// the timed frames do not pay for them).
//
//   03_light_volumes_sweep [--out DIR] [--size WxH] [--frames N] [--max-lights N] [--view NAME]
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>

#include "chapters/01_forward/forward.h"
#include "chapters/01_forward/ground_truth.h"
#include "chapters/02_gbuffer/deferred.h"
#include "chapters/02_gbuffer/gbuffer.h"
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_counts.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/03_light_volumes/light_volumes.h"
#include "common/cli.h"
#include "common/context.h"
#include "common/error.h"
#include "common/measure.h"
#include "common/paths.h"
#include "common/sweep.h"
#include "common/target.h"

namespace {

using namespace lp;
using namespace lp::ch03;

struct Settings {
  std::string out = (source_root() / "book" / "figures").string();
  int width = 1920, height = 1080;
  bool size_given = false;
  int frames = 20;
  int max_lights = 4096;
  std::string view = "street_level";
};

// The passes of one frame, timed with the one measurement (common/measure.h), and the
// wall-clock time of a whole frame, finished with glFinish on both sides. On llvmpipe the
// passes are CPU times with glFinish around each (PassMetrics), so they add up to about the
// wall clock there.
Measurement measure_frames(int frames, const std::function<void(PassMetrics&)>& frame) {
  PassMetrics metrics;
  return measure(metrics, [&] { frame(metrics); }, {.frames = frames, .wall_clock = true});
}

class Sweep {
 public:
  Sweep(const Settings& s, const Scene& scene, const SceneGpu& gpu, bool software)
      : s_(s), scene_(scene), gpu_(gpu), software_(software), geometry_(gpu), gbuffer_(s.width, s.height),
        target_(s.width, s.height),
        camera_(frame_camera(scene.camera(s.view), float(s.width) / s.height)) {}

  // Counts from one frame with the counters on, then the timed frames with them off; each
  // frame is the chapter's own (deferred_frame.cpp), into the sweep's output image.
  struct Result {
    Measurement time;
    double local_ms = 0;  // the local lights' pass
    FragmentCounts counts;
    DrawStats stats;
  };
  Result run(DeferredFrame& frame, Strategy strategy) {
    frame.set_strategy(strategy);
    auto volume_frame = [&](PassMetrics& m) { frame.render(camera_, {target_.framebuffer(), s_.width, s_.height}, &m); };
    Result r;
    frame.volumes().set_counting(true);
    {
      PassMetrics metrics;  // one frame, no warm-up: only its counts are wanted
      measure(metrics, [&] { volume_frame(metrics); }, {.frames = 1, .skip_warmup = true});
    }
    r.counts = frame.volumes().counts();
    r.stats = frame.volumes().draw_stats();
    frame.volumes().set_counting(false);
    r.time = measure_frames(s_.frames, volume_frame);
    r.local_ms = r.time.pass("local lights: " + kStrategies[int(strategy)]).mean_ms;
    return r;
  }

  void lights(const std::string& timer, const std::string& renderer) {
    std::ofstream csv(s_.out + "/03_lights.csv");
    csv << "# " << timer << ", " << s_.width << "x" << s_.height << ", street, view " << s_.view << "\n"
        << "lights,method,total_ms,lighting_ms,wall_ms,light_evaluations,fragments_lit,overshading,draw_calls,"
        << csv_measure_columns() << "\n";
    DeferredFrame frame(gpu_);
    LightVolumes& volumes = frame.volumes();
    ch01::ForwardRenderer forward(gpu_);
    ch02::DeferredLighting deferred;
    // Brute force on a CPU: the full-screen ways cost pixels x lights; stop them early there.
    const int brute_force_cap = software_ ? 256 : 1 << 30;
    for (int n : {1, 16, 256, 1024, 4096}) {
      if (n > s_.max_lights) break;
      std::vector<Light> lights = lights_for_count(scene_, n);
      volumes.set_lights(build_light_set(lights, cut_threshold(1.f, peak_reflectance(scene_)), volumes.shapes()));
      ch01::LightBuffer all;
      all.upload(lights);
      std::uint64_t lit = 0;
      for (std::size_t k = 0; k < kStrategies.size(); ++k) {
        Strategy strategy = static_cast<Strategy>(k);
        if (strategy == Strategy::FullScreen && n > brute_force_cap) continue;
        Result r = run(frame, strategy);
        // The counters are 64 bits: the full-screen pass at 4096 lights and 1080p shades
        // more than 2^32 fragments. It shades every pixel for every light by construction: a
        // cross-check of the counters where they cross 2^32.
        const std::uint64_t every_pixel = std::uint64_t(volumes.lights().local_count()) * s_.width * s_.height;
        if (strategy == Strategy::FullScreen && r.counts.shaded != every_pixel)
          std::cerr << "warning: the full-screen pass counted " << r.counts.shaded << " fragments, not " << every_pixel << '\n';
        lit = r.counts.lit;
        const double local_ms = r.local_ms;
        csv << n << ',' << kStrategies[k] << ',' << r.time.total_ms() << ',' << local_ms << ',' << r.time.wall_ms << ',' << r.counts.shaded
            << ',' << r.counts.lit << ',' << r.counts.overshading() << ',' << r.stats.draw_calls << ','
            << csv_measure_values(renderer, s_.width, s_.height, r.time.frames) << '\n';
        std::cout << n << " lights, " << kStrategies[k] << ": " << r.time.total_ms() << " ms (local lights "
                  << local_ms << ", wall clock " << r.time.wall_ms << "), shaded " << r.counts.shaded << ", lit " << r.counts.lit
                  << ", overshading " << r.counts.overshading() << std::endl;
      }
      if (n > brute_force_cap) continue;
      // Chapter 01: every object once, every light per fragment (the fragments include overdraw).
      Measurement f = measure_frames(s_.frames, [&](PassMetrics& m) {
        target_.bind();
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        auto p = m.pass("forward");
        forward.draw(camera_, ch01::ForwardMode::PerPixel, all);
      });
      std::uint64_t evaluations = f.pass("forward").fragments * std::uint64_t(all.count());
      csv << n << ",forward (ch. 01)," << f.total_ms() << ',' << f.pass("forward").mean_ms << ',' << f.wall_ms << ',' << evaluations << ','
          << lit << ',' << double(evaluations) / double(lit) << ",1," << csv_measure_values(renderer, s_.width, s_.height, f.frames)
          << '\n';
      // Chapter 02: the G-buffer, then every light for every pixel in one full-screen pass.
      Measurement d = measure_frames(s_.frames, [&](PassMetrics& m) {
        {
          auto p = m.pass("geometry");
          geometry_.draw(gbuffer_, camera_);
        }
        target_.bind();
        auto p = m.pass("lighting");
        deferred.draw(gbuffer_, all, scene_.ambient, ch01::kBackground, ch02::LightSelection::All);
      });
      evaluations = std::uint64_t(s_.width) * s_.height * std::uint64_t(all.count());
      csv << n << ",full-screen pass (ch. 02)," << d.total_ms() << ',' << d.pass("lighting").mean_ms << ',' << d.wall_ms << ','
          << evaluations << ',' << lit << ',' << double(evaluations) / double(lit) << ",1,"
          << csv_measure_values(renderer, s_.width, s_.height, d.frames) << '\n';
      std::cout << n << " lights: forward " << f.total_ms() << " ms (wall " << f.wall_ms << "), chapter 02 " << d.total_ms()
                << " ms (wall " << d.wall_ms << ")" << std::endl;
    }
  }

  void tessellation(const std::string& timer, const std::string& renderer) {
    std::ofstream csv(s_.out + "/03_tessellation.csv");
    const int n = std::min(1024, s_.max_lights);
    csv << "# " << timer << ", " << s_.width << "x" << s_.height << ", street, view " << s_.view << ", " << n
        << " lights, stencil strategy\n"
        << "subdivisions,triangles,circumradius,total_ms,lighting_ms,wall_ms,fragments_shaded,fragments_lit,overshading,"
        << csv_measure_columns() << "\n";
    std::vector<Light> lights = lights_for_count(scene_, n);
    for (int subdivisions : {0, 1, 2, 3}) {
      DeferredFrame frame(gpu_, ch02::our_layout(), subdivisions);
      LightVolumes& volumes = frame.volumes();
      volumes.set_lights(build_light_set(lights, cut_threshold(1.f, peak_reflectance(scene_)), volumes.shapes()));
      Result r = run(frame, Strategy::Stencil);
      csv << subdivisions << ',' << volumes.shapes().sphere.triangle_count() << ',' << icosphere_circumradius(subdivisions) << ','
          << r.time.total_ms() << ',' << r.local_ms << ',' << r.time.wall_ms << ',' << r.counts.shaded << ','
          << r.counts.lit << ',' << r.counts.overshading() << ',' << csv_measure_values(renderer, s_.width, s_.height, r.time.frames)
          << '\n';
      std::cout << "icosphere " << subdivisions << ": overshading " << r.counts.overshading() << ", local lights "
                << r.local_ms << " ms" << std::endl;
    }
  }

  // The light cut: the sources' 1/256 of the light against ours, on the street as it is and
  // with every range removed (the inverse square alone, where the cut decides everything).
  void cut(const std::string& timer, const std::string& renderer) {
    std::ofstream csv(s_.out + "/03_cut.csv");
    csv << "# " << timer << ", " << s_.width << "x" << s_.height << ", street (312 lights), view " << s_.view
        << "; error: 8-bit sRGB steps against chapter 02's uncut full-screen shading\n"
        << "lights,rule,threshold,mean_radius,lighting_ms,wall_ms,fragments_shaded,max_error,p99_error,mean_error,"
        << csv_measure_columns() << "\n";
    DeferredFrame frame(gpu_);
    LightVolumes& volumes = frame.volumes();
    ch02::DeferredLighting deferred;
    for (bool ranged : {true, false}) {
      std::vector<Light> lights = scene_.lights;
      if (!ranged)
        for (auto& l : lights) l.range = 0;
      ch01::LightBuffer all;
      all.upload(lights);
      geometry_.draw(gbuffer_, camera_);
      target_.bind();
      deferred.draw(gbuffer_, all, scene_.ambient, ch01::kBackground, ch02::LightSelection::All);
      const ImageRGBA8 truth = target_.read();
      const float peak = peak_reflectance(scene_);
      struct Rule {
        std::string name;
        float threshold;
      };
      for (const Rule& rule : {Rule{"sources: 1/256", cut_threshold(1.f, 1.f, kLinearEightBitStep)},
                               Rule{"sRGB step", cut_threshold(1.f, 1.f, kSrgbFirstStep)},
                               Rule{"sRGB step / peak reflectance", cut_threshold(1.f, peak, kSrgbFirstStep)}}) {
        LightSet set = build_light_set(lights, rule.threshold, volumes.shapes());
        double radius = 0;
        for (const auto& p : set.points) radius += p.position_radius.w;
        radius /= std::max<std::size_t>(1, set.points.size());
        volumes.set_lights(std::move(set));
        Result r = run(frame, Strategy::Stencil);
        CompareResult e = compare(target_.read(), truth, {.threshold = 1, .max_failing_fraction = 1.0});
        csv << (ranged ? "with ranges" : "no ranges") << ',' << rule.name << ',' << rule.threshold << ',' << radius << ','
            << r.local_ms << ',' << r.time.wall_ms << ',' << r.counts.shaded << ',' << e.max_error << ','
            << e.p99_error << ',' << e.mean_error << ',' << csv_measure_values(renderer, s_.width, s_.height, r.time.frames) << '\n';
        std::cout << (ranged ? "with ranges, " : "no ranges, ") << rule.name << ": mean radius " << radius << " m, max error "
                  << e.max_error << " steps, shaded " << r.counts.shaded << std::endl;
      }
    }
  }

 private:
  const Settings& s_;
  const Scene& scene_;
  const SceneGpu& gpu_;
  bool software_;
  ch02::GeometryPass geometry_;
  ch02::GBuffer gbuffer_;  // chapter 02's full-screen pass, the yardstick
  OutputTarget target_;
  FrameCamera camera_;
};

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  return run_sweep(argc, argv, "03_light_volumes_sweep", [&](SweepArgs& args) {
    args.text("--out", s.out).size("--size", s.width, s.height, &s.size_given).integer("--frames", s.frames)
        .integer("--max-lights", s.max_lights).text("--view", s.view);
  }, [&] {
    std::filesystem::create_directories(s.out);
    auto context = Context::create({.headless = true, .width = s.width, .height = s.height});
    const bool software = context->is_software();
    if (software && !s.size_given) {  // a CPU renders 1920x1080 x 4096 lights far too slowly
      s.width = 480;
      s.height = 270;
      s.frames = std::min(s.frames, 5);
    }
    Scene scene = load_scene(from_root("assets/street/street.gltf"));
    SceneGpu gpu(scene);
    std::string timer = (software ? "llvmpipe CPU time: " : "GPU time: ") + context->renderer();
    std::cout << timer << ", " << s.width << "x" << s.height << '\n';
    Sweep sweep(s, scene, gpu, software);
    sweep.lights(timer, context->renderer());
    sweep.tessellation(timer, context->renderer());
    sweep.cut(timer, context->renderer());
    std::cout << "wrote " << s.out << "/03_lights.csv, 03_tessellation.csv and 03_cut.csv\n";
  });
}
