// Chapter 05's measurements and figures:
//  - the GPU log-average (every method) against the exact double-precision reduction of the
//    same float buffer, for power-of-two and odd sizes, with its cost;
//  - bloom cost against its resolution (and radius), and its error against a
//    full-resolution bloom;
//  - eye adaptation over frames (GPU against the C++ formula);
//  - the book's pictures: 8-bit against float, each operator, the adaptation strip, the
//    bloom stages, what the naive mip chain never sees.
// Timings are GPU time on a GPU and CPU time on llvmpipe (common/measure.h: warm-up until the
// times settle, then --frames frames); the CSV files say which, and every row of a rendered
// table names the renderer, the size and the frames measured.
//
//   05_hdr_sweep [--out DIR] [--frames N] [--sizes WxH,WxH,...] [--bloom-size WxH]
//                [--figure-size WxH] [--no-figures] [--no-sweeps]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>

#include "chapters/05_hdr/exposure_feedback.h"
#include "chapters/05_hdr/hdr_math.h"
#include "chapters/05_hdr/hdr_pipeline.h"
#include "chapters/05_hdr/radiance_source.h"
#include "chapters/05_hdr/reference.h"
#include "common/context.h"
#include "common/error.h"
#include "common/measure.h"
#include "common/paths.h"
#include "common/cli.h"
#include "common/sweep.h"
#include "common/target.h"

namespace {

using namespace lp;
using namespace lp::ch05;

struct Settings {
  std::string out = (source_root() / "book" / "figures").string();
  int frames = 20;
  std::vector<std::pair<int, int>> sizes = {{256, 256}, {1024, 1024}, {1280, 720}, {1920, 1080}, {1921, 1081}, {2560, 1440}, {3840, 2160}};
  int bloom_width = 1920, bloom_height = 1080;
  int figure_width = 640, figure_height = 360;
  bool no_figures = false;
  bool no_sweeps = false;  // figures and adaptation only
  std::string renderer;   // GL_RENDERER, for the CSV rows
};

// "640x360,1920x1080" -> sizes (the --sizes option).
std::vector<std::pair<int, int>> parse_sizes(const std::string& text) {
  std::vector<std::pair<int, int>> sizes;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) {
    int w = 0, h = 0;
    parse_size("--sizes", item, w, h);
    sizes.push_back({w, h});
  }
  return sizes;
}

// `work` as one measured pass (common/measure.h): on a GPU its GL_TIME_ELAPSED time, which
// covers compute dispatches; on llvmpipe the CPU clock with glFinish on both sides.
PassMeasurement measure_work(int frames, const std::function<void()>& work) {
  PassMetrics metrics;
  Measurement m = measure(metrics, [&] {
    auto p = metrics.pass("work");
    work();
  }, {.frames = frames});
  return m.pass("work");
}

// The chapter's radiance: chapter 03's deferred path, the volumes cut as on the program's
// first frame (for the stage's largest exposure: nothing the eye could see is cut).
struct SceneSource {
  Scene scene;
  DeferredRadiance source;
  explicit SceneSource(const std::string& path) : scene(load_scene(from_root(path))), source(scene) {
    source.set_cut_exposure(exposure_limit({.key = 0.18f, .adapt_floor = 0.f}, 1e-4f, 1.f));  // the fixed key: the largest
  }
  RadianceTarget render(const std::string& view, int w, int h, float sun, float glow, GLenum format = GL_RGBA16F) {
    source.set_scales(sun, glow);
    RadianceTarget t(w, h, format, false);
    source.render(frame_camera(scene.camera(view), float(w) / float(h)), t);
    return t;
  }
};

void log_average_sweep(const Settings& s, SceneSource& atrium, const std::string& timer) {
  std::ofstream csv(s.out + "/05_log_average.csv");
  csv << "# " << timer << "; delta 1e-4; rel_error = |exp(mean_log_gpu - mean_log_exact) - 1|; exact = double-precision CPU reduction of the same RGBA16F buffer\n"
      << "width,height,buffer,method,pixels,pixels_counted,lost_fraction,rel_error,ms,renderer,frames\n";
  LogAverage la;
  const float delta = 1e-4f;
  for (auto [w, h] : s.sizes) {
    std::cout << "log-average " << w << "x" << h << std::endl;
    RadianceTarget scene = atrium.render("aisle", w, h, 25.f, 1.f);
    gl::Texture ramp = upload_radiance(ramp_image(w, h));
    for (auto [name, texture] : {std::pair<std::string, GLuint>{"atrium", scene.texture()}, {"ramp", ramp.id()}}) {
      ExactLogAverage exact = exact_log_average(read_texture(texture, w, h), delta);
      for (int m = 0; m < 4; ++m) {
        auto method = static_cast<AverageMethod>(m);
        la.compute(texture, w, h, method, delta);
        LogAverageResult r = la.read();
        double error = std::abs(std::exp(double(r.mean_log) - exact.mean_log) - 1.0);
        PassMeasurement t = measure_work(s.frames, [&] { la.compute(texture, w, h, method, delta); });
        double ms = t.mean_ms;
        double pixels = double(w) * h;
        // (width and height are already columns here: the renderer and frames complete them)
        csv << w << ',' << h << ',' << name << ',' << kAverageMethodNames[m] << ',' << std::size_t(pixels) << ','
            << std::size_t(r.count) << ',' << 1.0 - r.count / pixels << ',' << error << ',' << ms << ','
            << csv_quoted(s.renderer) << ',' << t.frames << '\n';
        std::cout << "  " << name << ' ' << kAverageMethodNames[m] << ": error " << error << ", counted " << r.count << ", "
                  << ms << " ms" << std::endl;
      }
    }
  }
}

// The bloom term alone (what gets added), at full resolution, as floats.
ImageF bloom_term(HdrPipeline& hdr, GLuint radiance, int w, int h, HdrSettings s) {
  ColourTarget term(w, h, GL_RGBA32F, false);
  s.view = HdrSettings::View::Bloom;
  hdr.process(radiance, w, h, s, term.framebuffer());
  return term.read();
}

void bloom_sweep(const Settings& s, SceneSource& street, const std::string& timer) {
  const int w = s.bloom_width, h = s.bloom_height;
  std::cout << "bloom " << w << "x" << h << std::endl;
  RadianceTarget radiance = street.render("street_level", w, h, 1.f, 8.f);
  std::ofstream csv(s.out + "/05_bloom.csv");
  csv << "# " << timer << "; " << w << "x" << h << " street_level, glow 8; error of the bloom term against the level-0 (full-resolution) bloom of the same radius: "
         "rel_rms = rms(difference) / rms(full), max_abs in exposed units\n"
      << "radius,level,blur_width,blur_height,sigma_texels,taps,ms_bright,ms_blur,ms_total,rel_rms,max_abs,"
      << csv_measure_columns() << "\n";
  HdrPipeline hdr;
  for (float radius : {0.02f, 0.05f}) {
    ImageF full;
    for (int level = 0; level <= 5; ++level) {
      HdrSettings hs;
      hs.adaptation.tau = 0;
      hs.adaptation.adapt_floor = 0.f;  // the fixed key: the street at its brightest, the most above the threshold
      hs.bloom = BloomMode::AfterTonemap;
      hs.bloom_chain = {.level = level, .radius = radius, .threshold = 1.f, .limit = 64.f};
      ImageF term = bloom_term(hdr, radiance.texture(), w, h, hs);
      if (level == 0) full = term;
      double se = 0, sf = 0, max_abs = 0;
      for (std::size_t i = 0; i < term.data.size(); ++i) {
        if (i % 4 == 3) continue;
        double d = double(term.data[i]) - full.data[i];
        se += d * d;
        sf += double(full.data[i]) * full.data[i];
        max_abs = std::max(max_abs, std::abs(d));
      }
      const Bloom& b = hdr.bloom();
      BloomSettings chain = hs.bloom_chain;
      // The passes timed alone, each with the exposure the pipeline just computed.
      Bloom bloom;
      GLuint exposure = hdr.adaptation().state_buffer();
      double bright_ms = measure_work(s.frames, [&] { bloom.bright_pass(radiance.texture(), w, h, exposure, chain); }).mean_ms;
      double blur_ms = measure_work(s.frames, [&] { bloom.blur(chain); }).mean_ms;
      PassMeasurement total = measure_work(s.frames, [&] { bloom.bright_pass(radiance.texture(), w, h, exposure, chain); bloom.blur(chain); });
      double total_ms = total.mean_ms;
      double rel_rms = sf > 0 ? std::sqrt(se / sf) : 0.0;
      csv << radius << ',' << level << ',' << b.level_size().x << ',' << b.level_size().y << ',' << b.sigma_texels() << ','
          << b.taps() << ',' << bright_ms << ',' << blur_ms << ',' << total_ms << ',' << rel_rms << ',' << max_abs << ','
          << csv_measure_values(s.renderer, w, h, total.frames) << '\n';
      std::cout << "  radius " << radius << " level " << level << ": " << total_ms << " ms, rel rms " << rel_rms << std::endl;
    }
  }
}

void adaptation_sweep(const Settings& s, SceneSource& atrium, const std::string& timer) {
  const int w = s.figure_width, h = s.figure_height;
  RadianceTarget radiance = atrium.render("aisle", w, h, 25.f, 1.f);
  HdrPipeline hdr;
  HdrSettings hs;
  hs.adaptation = {.key = 0.18f, .tau = 0.5f, .dt = 1.f / 60.f};
  hdr.reset_adaptation(30.f);
  OutputTarget target(w, h);
  std::ofstream csv(s.out + "/05_adaptation.csv");
  csv << "# " << timer << "; atrium aisle, sun 25; eye adapted to 30x the scene's log-average at frame 0; tau 0.5 s, 60 frames/s; "
         "adapted_cpu = the C++ formula (hdr_math.h) from the same first value\n"
      << "frame,time_s,target,adapted_gpu,adapted_cpu,exposure," << csv_measure_columns() << "\n";
  std::vector<ImageRGBA8> strip;
  float cpu = 0;
  for (int frame = 0; frame <= 150; ++frame) {
    hdr.process(radiance.texture(), w, h, hs, target.framebuffer());
    ExposureState e = hdr.adaptation().read();
    cpu = frame == 0 ? e.adapted : adapt(cpu, e.target, hs.adaptation.dt, hs.adaptation.tau);
    csv << frame << ',' << frame / 60.0 << ',' << e.target << ',' << e.adapted << ',' << cpu << ',' << e.exposure << ','
        << csv_measure_values(s.renderer, w, h, 1) << '\n';
    if (!s.no_figures && (frame == 0 || frame == 15 || frame == 30 || frame == 60 || frame == 90 || frame == 150)) strip.push_back(target.read());
  }
  if (s.no_figures) return;
  // One strip, the frames side by side at half size.
  int sw = w / 2, sh = h / 2, gap = 4;
  ImageRGBA8 out = ImageRGBA8::blank(int(strip.size()) * (sw + gap) - gap, sh);
  std::fill(out.pixels.begin(), out.pixels.end(), std::uint8_t(255));  // white gaps
  for (std::size_t k = 0; k < strip.size(); ++k)
    for (int y = 0; y < sh; ++y)
      for (int x = 0; x < sw; ++x)
        for (int c = 0; c < 4; ++c) {
          int sum = 0;
          for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) sum += strip[k].at(2 * x + dx, 2 * y + dy)[c];
          out.at(int(k) * (sw + gap) + x, y)[c] = std::uint8_t((sum + 2) / 4);
        }
  save_png(s.out + "/05_adaptation_strip.png", out);
}

void operator_curves(const Settings& s) {
  std::ofstream csv(s.out + "/05_operators.csv");
  csv << "# display value against exposed value x; reinhard-extended with white = 4\nx,clamp,reinhard,reinhard-extended,aces\n";
  for (int i = -300; i <= 200; ++i) {
    float x = std::pow(10.f, i / 100.f);
    csv << x << ',' << tonemap_clamp(x) << ',' << tonemap_reinhard(x) << ',' << tonemap_reinhard_extended(x, 4.f) << ','
        << tonemap_aces(x) << '\n';
  }
}

void figures(const Settings& s, SceneSource& street, SceneSource& atrium) {
  const int w = s.figure_width, h = s.figure_height;
  OutputTarget target(w, h);
  HdrPipeline hdr;
  auto shoot = [&](GLuint radiance, HdrSettings hs, const std::string& name) {
    hs.adaptation.tau = 0;
    hdr.process(radiance, w, h, hs, target.framebuffer());
    save_png(s.out + "/" + name + ".png", target.read());
    std::cout << "  " << name << ".png" << std::endl;
  };
  std::cout << "figures " << w << "x" << h << std::endl;
  std::ofstream clip(s.out + "/05_clipping.csv");
  clip << "# " << w << "x" << h << "; what an RGBA8 light accumulation loses: pixels with a channel above 1 (clipped), "
          "and the float buffer's luminance percentiles\n"
       << "scene,view,sun,glow,pixels_above_1,fraction_above_1,max_luminance,p1_luminance,p50_luminance,p99_luminance,log_average,"
       << csv_measure_columns() << "\n";
  for (auto& [scene, name, view, sun, glow] :
       {std::tuple{&street, "street", "street_level", 1.f, 8.f}, std::tuple{&atrium, "atrium", "aisle", 25.f, 1.f}}) {
    RadianceTarget hdr16 = scene->render(view, w, h, sun, glow), ldr8 = scene->render(view, w, h, sun, glow, GL_RGBA8);
    {
      ImageF radiance = hdr16.read();
      std::vector<float> lum;
      std::size_t above = 0;
      for (int i = 0; i < w * h; ++i) {
        glm::vec3 c(radiance.data[4 * i], radiance.data[4 * i + 1], radiance.data[4 * i + 2]);
        above += std::max({c.r, c.g, c.b}) > 1.f;
        lum.push_back(luminance(sanitize(c).rgb));
      }
      std::sort(lum.begin(), lum.end());
      auto pct = [&](double p) { return lum[std::min(lum.size() - 1, std::size_t(p * lum.size()))]; };
      clip << name << ',' << view << ',' << sun << ',' << glow << ',' << above << ',' << double(above) / (w * h) << ','
           << lum.back() << ',' << pct(0.01) << ',' << pct(0.5) << ',' << pct(0.99) << ','
           << exact_log_average(radiance, 1e-4f).luminance << ',' << csv_measure_values(s.renderer, w, h, 1) << '\n';
    }
    HdrSettings hs;
    hs.adaptation.adapt_floor = 0.f;  // the operators side by side at the fixed key (the floor: the references)
    shoot(ldr8.texture(), hs, std::string("05_") + name + "_8bit");
    for (int op = 0; op < 4; ++op) {
      hs.tonemap.op = static_cast<Operator>(op);
      shoot(hdr16.texture(), hs, std::string("05_") + name + "_" + kOperatorNames[op]);
    }
    if (std::string(name) == "street") {
      hs.tonemap.op = Operator::Aces;
      hs.adaptation.key = 0.045f;
      shoot(hdr16.texture(), hs, "05_street_aces_key0.045");
      hs.adaptation.key = 0.18f;
      hs.bloom = BloomMode::AfterTonemap;
      shoot(hdr16.texture(), hs, "05_bloom_after");
      hs.view = HdrSettings::View::BrightPass;
      shoot(hdr16.texture(), hs, "05_bloom_bright");
      hs.view = HdrSettings::View::Bloom;
      shoot(hdr16.texture(), hs, "05_bloom_blurred");
      hs.view = HdrSettings::View::Final;
      hs.bloom = BloomMode::BeforeTonemap;
      shoot(hdr16.texture(), hs, "05_bloom_before");
    } else {
      // What the naive mip chain averages of a 1920x1080 frame: the lower-left 1024x1024
      // (scaled to this figure). The rest is dimmed.
      hs.tonemap.op = Operator::Reinhard;
      hdr.process(hdr16.texture(), w, h, hs, target.framebuffer());
      ImageRGBA8 img = target.read();
      int kw = int(std::lround(w * 1024.0 / 1920.0)), kh = int(std::lround(h * 1024.0 / 1080.0));
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          if (x >= kw || y < h - kh)
            for (int c = 0; c < 3; ++c) img.at(x, y)[c] = std::uint8_t(img.at(x, y)[c] / 4 + (c == 0 ? 150 : 0));
      save_png(s.out + "/05_naive_chain_coverage.png", img);
      std::cout << "  05_naive_chain_coverage.png" << std::endl;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  std::string sizes;
  return run_sweep(argc, argv, "05_hdr_sweep", [&](SweepArgs& args) {
    args.text("--out", s.out).integer("--frames", s.frames).text("--sizes", sizes)
        .size("--bloom-size", s.bloom_width, s.bloom_height).size("--figure-size", s.figure_width, s.figure_height)
        .flag("--no-figures", s.no_figures).flag("--no-sweeps", s.no_sweeps);
  }, [&] {
    if (!sizes.empty()) s.sizes = parse_sizes(sizes);
    std::filesystem::create_directories(s.out);
    auto context = Context::create({.headless = true, .width = 64, .height = 64});
    s.renderer = context->renderer();
    std::string timer = (context->is_software() ? "llvmpipe CPU wall-clock time (glFinish around the work): " : "GPU time (GL_TIME_ELAPSED): ") + context->renderer();
    std::cout << timer << std::endl;
    SceneSource street("assets/street/street.gltf"), atrium("assets/atrium/atrium.gltf");
    operator_curves(s);
    if (!s.no_figures) figures(s, street, atrium);
    adaptation_sweep(s, atrium, timer);
    if (!s.no_sweeps) {
      log_average_sweep(s, atrium, timer);
      bloom_sweep(s, street, timer);
    }
    std::cout << "wrote " << s.out << "/05_*.csv" << std::endl;
  });
}
