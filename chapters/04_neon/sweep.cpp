// Chapter 04's measurements: every method's error against the ground truth (diffuse and
// specular apart) and its cost, on the neon scene's views; then N point lights as N grows.
// Writes CSV files and the images the book shows; timings are GPU time on a GPU and CPU time
// on llvmpipe (common/measure.h: warm-up until the times settle, then --frames frames), the
// CSV says which, and every row names the renderer, the size and the frames measured.
//
//   04_neon_sweep [--out DIR] [--size WxH] [--frames N] [--reference-samples N]
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>

#include "chapters/01_forward/ground_truth.h"
#include "chapters/04_neon/neon_forward.h"
#include "chapters/04_neon/neon_scene.h"
#include "common/context.h"
#include "common/error.h"
#include "common/measure.h"
#include "common/paths.h"
#include "common/sweep.h"
#include "common/target.h"

namespace {

using namespace lp;
using namespace lp::ch04;

struct Settings {
  std::string out = (source_root() / "book" / "figures").string();
  int width = 640, height = 360;  // llvmpipe; a GPU measures at 1920x1080 unless --size says otherwise
  bool size_given = false;
  int frames = 10;
  int reference_samples = 2048;
  std::string renderer;  // GL_RENDERER, for the CSV rows
};

// A method as the sweep names it: the renderer's method and its sample count.
struct Variant {
  std::string name;
  NeonDraw draw;
};

class Sweep {
 public:
  Sweep(const Settings& s, const Scene& scene, const SceneGpu& gpu)
      : s_(s), scene_(scene), forward_(gpu), srgb_(s.width, s.height), linear_(s.width, s.height, GL_RGBA32F) {
    tubes_.upload(neon_lights(scene));
    lights_.upload(scene.lights);
  }

  ImageRGBA8 render8(const FrameCamera& camera, NeonDraw how) {
    srgb_.bind();
    clear();
    forward_.draw(camera, how, lights_, tubes_);
    return srgb_.read();
  }
  ImageF render_linear(const FrameCamera& camera, NeonDraw how) {
    linear_.bind();
    clear();
    forward_.draw(camera, how, lights_, tubes_);
    glEnable(GL_FRAMEBUFFER_SRGB);
    return linear_.read();
  }
  // The whole forward pass, measured (common/measure.h): mean and fastest of s_.frames frames.
  PassMeasurement time(const FrameCamera& camera, NeonDraw how) {
    srgb_.bind();
    Measurement m = measure(metrics_, [&] {
      clear();
      auto pass = metrics_.pass("frame");
      forward_.draw(camera, how, lights_, tubes_);
    }, {.frames = s_.frames});
    return m.pass("frame");
  }

 private:
  void clear() {
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  }
  const Settings& s_;
  const Scene& scene_;
  NeonForward forward_;
  NeonTubes tubes_;
  ch01::LightBuffer lights_;
  OutputTarget srgb_;
  ColourTarget linear_;  // the linear light before 8-bit quantisation and clipping
  PassMetrics metrics_;
};

// [relative-error]
// Per pixel: |method - truth| / max(truth, 1/256), on the mean of the RGB light. Where the
// truth is below one 8-bit step the error counts in steps, so a dark pixel cannot make a
// huge relative error of an invisible one.
struct Errors {
  double mean_steps = 0, p99_steps = 0, mean_rel = 0, p99_rel = 0;
};
Errors errors(const ImageRGBA8& img, const ImageRGBA8& truth8, const ImageF& lin, const ImageF& truth_lin) {
  std::vector<std::uint8_t> mask(std::size_t(lin.width) * lin.height, 0);
  std::vector<float> rel;
  for (int y = 0; y < lin.height; ++y)
    for (int x = 0; x < lin.width; ++x) {
      float m = 0, t = 0;
      for (int c = 0; c < 3; ++c) m += lin.at(x, y, c) / 3.f, t += truth_lin.at(x, y, c) / 3.f;
      if (m <= 0 && t <= 0) continue;  // no light from the tubes here in either image
      mask[std::size_t(y) * lin.width + x] = 1;
      rel.push_back(std::isfinite(m) ? std::abs(m - t) / std::max(t, 1.f / 256.f) : 1e30f);
    }
  Errors e;
  FloatErrorStats steps = compare_float(ch01::srgb_steps(img), ch01::srgb_steps(truth8), mask);
  e.mean_steps = steps.mean_abs;
  e.p99_steps = steps.p99;
  if (rel.empty()) return e;
  std::sort(rel.begin(), rel.end());
  for (float r : rel) e.mean_rel += r / static_cast<double>(rel.size());
  e.p99_rel = rel[std::min(rel.size() - 1, static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(rel.size()))) - 1)];
  return e;
}
// [/relative-error]

struct Truth {
  ImageRGBA8 image8[3];  // per Term
  ImageF linear[3];
};

Truth render_truth(Sweep& sweep, const FrameCamera& camera, int samples) {
  Truth t;
  for (Term term : {Term::All, Term::Diffuse, Term::Specular}) {
    NeonDraw how{.method = Method::GroundTruth, .samples = samples, .term = term};
    t.image8[int(term)] = sweep.render8(camera, how);
    t.linear[int(term)] = sweep.render_linear(camera, how);
  }
  return t;
}

void write_row(std::ofstream& csv, const Settings& s, const std::string& prefix, const std::string& term, const Errors& e,
               const PassMeasurement& time) {
  csv << prefix << ',' << term << ',' << e.mean_steps << ',' << e.p99_steps << ',' << 100 * e.mean_rel << ','
      << 100 * e.p99_rel << ',' << time.mean_ms << ',' << time.min_ms << ','
      << csv_measure_values(s.renderer, s.width, s.height, time.frames) << '\n';
}

void methods_sweep(const Settings& s, const Scene& scene, Sweep& sweep, const std::string& timer) {
  std::ofstream csv(s.out + "/04_methods.csv");
  csv << "# " << timer << ", " << s.width << "x" << s.height << ", truth " << s.reference_samples << " samples per tube\n"
      << "# steps: 8-bit sRGB; rel: |m - t| / max(t, 1/256) in %; ms: the whole forward pass, mean and fastest of "
      << s.frames << " frames\n"
      << "view,method,term,mean_steps,p99_steps,mean_rel_pct,p99_rel_pct,ms,min_ms," << csv_measure_columns() << "\n";
  const std::vector<Variant> variants = {
      {"ground-truth-256", {.method = Method::GroundTruth, .samples = 256}},
      {"source", {.method = Method::Source}},
      {"improved", {.method = Method::Improved}},
      {"points-8", {.method = Method::Points, .samples = 8}},
      {"points-32", {.method = Method::Points, .samples = 32}},
      {"representative-point", {.method = Method::RepresentativePoint}},
      {"analytic-diffuse", {.method = Method::AnalyticDiffuse}},
  };
  for (const std::string view : {"overview", "grazing", "close"}) {
    FrameCamera camera = frame_camera(scene.camera(view), float(s.width) / s.height);
    Truth truth = render_truth(sweep, camera, s.reference_samples);
    if (view != "close") save_png(s.out + "/04_" + view + "_truth.png", truth.image8[0]);
    for (const auto& v : variants) {
      PassMeasurement time = sweep.time(camera, v.draw);
      std::cout << view << ' ' << v.name << ": " << time.mean_ms << " ms (fastest " << time.min_ms << ")";
      for (Term term : {Term::Diffuse, Term::Specular}) {
        if (v.draw.method == Method::AnalyticDiffuse && term == Term::Specular) continue;  // it has none
        NeonDraw how = v.draw;
        how.term = term;
        Errors e = errors(sweep.render8(camera, how), truth.image8[int(term)], sweep.render_linear(camera, how),
                          truth.linear[int(term)]);
        write_row(csv, s, view + ',' + v.name, term == Term::Diffuse ? "diffuse" : "specular", e, time);
        std::cout << (term == Term::Diffuse ? " | diffuse" : " | specular") << " mean " << e.mean_steps << " p99 "
                  << e.p99_steps << " steps, rel mean " << 100 * e.mean_rel << "% p99 " << 100 * e.p99_rel << "%";
      }
      std::cout << std::endl;
      // The book's pictures: every method on the overview, the hard case on the grazing view.
      bool figure = view == "overview" ? v.name != "points-32" && v.name != "analytic-diffuse" && v.name != "ground-truth-256"
                                       : view == "grazing" && (v.name == "source" || v.name == "improved");
      if (figure) {
        ImageRGBA8 image = sweep.render8(camera, v.draw);
        save_png(s.out + "/04_" + view + "_" + v.name + ".png", image);
        std::vector<float> err = pixel_errors(ch01::srgb_steps(image), ch01::srgb_steps(truth.image8[0]));
        save_png(s.out + "/04_" + view + "_" + v.name + "_error.png", error_heatmap(err, s.width, s.height, 16.f));
      }
    }
  }
}

void points_sweep(const Settings& s, const Scene& scene, Sweep& sweep, const std::string& timer) {
  std::ofstream csv(s.out + "/04_points.csv");
  csv << "# " << timer << ", " << s.width << "x" << s.height << ", overview, truth " << s.reference_samples
      << " samples per tube\n"
      << "# steps: 8-bit sRGB; rel: |m - t| / max(t, 1/256) in %; ms: the whole forward pass, mean and fastest of "
      << s.frames << " frames\n"
      << "n,series,term,mean_steps,p99_steps,mean_rel_pct,p99_rel_pct,ms,min_ms," << csv_measure_columns() << "\n";
  FrameCamera camera = frame_camera(scene.camera("overview"), float(s.width) / s.height);
  Truth truth = render_truth(sweep, camera, s.reference_samples);
  auto row = [&](int n, const std::string& series, NeonDraw how) {
    PassMeasurement time = sweep.time(camera, how);
    for (Term term : {Term::Diffuse, Term::Specular}) {
      how.term = term;
      Errors e = errors(sweep.render8(camera, how), truth.image8[int(term)], sweep.render_linear(camera, how),
                        truth.linear[int(term)]);
      write_row(csv, s, std::to_string(n) + ',' + series, term == Term::Diffuse ? "diffuse" : "specular", e, time);
    }
    std::cout << series << ' ' << n << ": " << time.mean_ms << " ms (fastest " << time.min_ms << ")" << std::endl;
  };
  for (int n = 1; n <= 256; n *= 2) {
    row(n, "points", {.method = Method::Points, .samples = n});
    row(n, "ground truth (clipped midpoint)", {.method = Method::GroundTruth, .samples = n});
    row(n, "improved (fixed cost)", {.method = Method::Improved});
  }
}

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  return run_sweep(argc, argv, "04_neon_sweep", [&](SweepArgs& args) {
    args.text("--out", s.out).size("--size", s.width, s.height, &s.size_given).integer("--frames", s.frames)
        .integer("--reference-samples", s.reference_samples);
  }, [&] {
    std::filesystem::create_directories(s.out);
    auto context = Context::create({.headless = true, .width = s.width, .height = s.height});
    s.renderer = context->renderer();
    if (!context->is_software() && !s.size_given) {  // the book's GPU figures are at 1080p
      s.width = 1920;
      s.height = 1080;
    }
    Scene scene = load_scene(from_root("assets/neon/neon.gltf"));
    SceneGpu gpu(scene);
    std::string timer = (context->is_software() ? "llvmpipe CPU time: " : "GPU time: ") + context->renderer();
    std::cout << timer << '\n';
    Sweep sweep(s, scene, gpu);
    methods_sweep(s, scene, sweep, timer);
    points_sweep(s, scene, sweep, timer);
    std::cout << "wrote " << s.out << "/04_methods.csv and 04_points.csv\n";
  });
}
