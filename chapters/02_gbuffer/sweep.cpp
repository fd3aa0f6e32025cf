// Chapter 02's measurements, written as CSV for the book's tables and figures:
// - 02_normal_encodings.csv: each normal encoding's angular error over the whole sphere (CPU,
//   the C++ twin of the shaders), with nearest and best-of-four rounding, and its bound;
// - 02_layouts.csv: for each G-buffer layout, bytes per pixel against the error of the
//   deferred image against chapter 01's forward image (same scene, lights, camera), and the
//   decoded normals and positions against the float reference layout;
// - 02_position_error.csv: reconstructed-position error against distance from the camera for
//   each depth format (cameras from 3 m to 500 m, near 0.1 m, far 1000 m);
// - 02_lights.csv: forward against deferred time as lights grow (GPU time on a GPU, CPU time
//   on llvmpipe: the CSV's first line says which; common/measure.h measures).
// - 02_layout_times.csv: each layout's geometry and lighting passes timed (the atrium overview
//   at --light-size with 64 lights), for the layouts' time-against-error plot.
// Every row of the rendered tables names the renderer, the size and the frames measured.
//
//   02_gbuffer_sweep [--out DIR] [--size WxH] [--light-size WxH] [--frames N] [--max-lights N]
//                    [--only encodings|layouts|position|lights|layout-times]
//
// The book's plots from these files (book/figures/02_lights_llvmpipe.* is the llvmpipe run):
//   tools/plot.py --csv 02_lights.csv --x lights --y total_ms --group method --xlog --ylog
//     --title "Forward against deferred as lights grow" --ylabel "ms per frame" --out 02_lights.svg
//   tools/plot.py --csv 02_position_error.csv --x distance_m --y p99_rel --group layout --xlog --ylog
//     --title "Reconstructed position: 99th-percentile error / distance" --out 02_position_error.svg
//   tools/plot.py --csv 02_normal_encodings.csv --x bits_per_normal --y max_deg --group rounding
//     --filter encoding=octahedral --ylog --out 02_normal_encodings.svg
//   tools/plot.py --csv 02_layouts.csv --x bytes_per_pixel --y image_max --group layout
//     --filter view=forward/close_128 --xlog --out 02_layouts_bytes.svg
#include <algorithm>
#include <map>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/01_forward/forward.h"
#include "chapters/01_forward/ground_truth.h"
#include "chapters/02_gbuffer/deferred.h"
#include "chapters/02_gbuffer/depth.h"
#include "chapters/02_gbuffer/encoding.h"
#include "chapters/02_gbuffer/probe.h"
#include "common/context.h"
#include "common/error.h"
#include "common/measure.h"
#include "common/paths.h"
#include "common/sweep.h"
#include "common/target.h"

namespace {

using namespace lp;
using namespace lp::ch02;

constexpr double kDegrees = 57.29577951308232;

struct Settings {
  std::string out = (source_root() / "book" / "figures").string();
  int width = 640, height = 360;
  int light_width = 1920, light_height = 1080;
  int frames = 10;
  int max_lights = 1024;
  std::string only;
};

// ---- normal encodings over the sphere (CPU) ------------------------------------------------

// Directions over the whole sphere: a dense Fibonacci spiral plus the hard places, the poles,
// the equator (where the octahedron folds), the fold's corners and the diagonals.
std::vector<glm::vec3> sphere_directions(int count) {
  std::vector<glm::vec3> d;
  const double golden = 3.883222077450933;  // pi (3 - sqrt 5)
  for (int i = 0; i < count; ++i) {
    double z = 1.0 - 2.0 * (i + 0.5) / count, r = std::sqrt(1.0 - z * z);
    d.emplace_back(float(r * std::cos(golden * i)), float(r * std::sin(golden * i)), float(z));
  }
  for (int i = 0; i < 3600; ++i) {
    double a = i * 6.283185307179586 / 3600;
    d.emplace_back(float(std::cos(a)), float(std::sin(a)), 0.f);                          // equator: the fold
    d.push_back(glm::normalize(glm::vec3(std::cos(a), std::sin(a), -1e-3f)));             // just below it
    d.push_back(glm::normalize(glm::vec3(std::cos(a) * 1e-3, std::sin(a) * 1e-3, -1.0)));  // around the lower pole
  }
  for (float z : {-1.f, 1.f}) d.emplace_back(0.f, 0.f, z);
  for (float x : {-1.f, 1.f})
    for (float y : {-1.f, 1.f})
      for (float z : {-1.f, 0.f, 1.f}) d.push_back(glm::normalize(glm::vec3(x, y, z)));
  return d;
}

struct AngleStats {
  double mean = 0, max = 0;
};

AngleStats encoding_error(const std::vector<glm::vec3>& dirs, const std::function<glm::vec3(glm::vec3)>& round_trip) {
  AngleStats s;
  for (const auto& n : dirs) {
    glm::dvec3 a(n), b(round_trip(n));
    double angle = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
    s.mean += angle;
    s.max = std::max(s.max, angle);
  }
  s.mean /= double(dirs.size());
  return s;
}

void encoding_sweep(const Settings& s) {
  std::ofstream csv(s.out + "/02_normal_encodings.csv");
  csv << "# CPU (the C++ twin), degrees\n"
      << "# angular error over 1e6 spiral directions plus the poles, the equator and the folded corners\n"
      << "encoding,bits_per_normal,rounding,mean_deg,max_deg,bound_deg\n";
  auto dirs = sphere_directions(1000000);
  for (int bits : {8, 10, 16}) {
    for (bool best : {false, true}) {
      AngleStats e = encoding_error(dirs, [&](glm::vec3 n) { return decode_octahedral(encode_octahedral(n, bits, best), bits); });
      csv << "octahedral," << 2 * bits << ',' << (best ? "best-of-four" : "nearest") << ',' << e.mean * kDegrees << ','
          << e.max * kDegrees << ',' << octahedral_error_bound(bits) * kDegrees << '\n';
      std::cout << "octahedral " << bits << "+" << bits << (best ? " best-of-four" : " nearest") << ": mean "
                << e.mean * kDegrees << " max " << e.max * kDegrees << " deg\n";
    }
  }
  for (int bits : {8, 10}) {
    AngleStats e = encoding_error(dirs, [&](glm::vec3 n) { return decode_xyz(encode_xyz(n, bits), bits); });
    csv << "xyz," << 3 * bits << ",nearest," << e.mean * kDegrees << ',' << e.max * kDegrees << ','
        << xyz_error_bound(bits) * kDegrees << '\n';
    std::cout << "xyz " << bits << "x3: mean " << e.mean * kDegrees << " max " << e.max * kDegrees << " deg\n";
  }
}

// ---- layouts against forward ----------------------------------------------------------------

struct Renderer {
  const Scene& scene;
  const SceneGpu& gpu;
  ch01::ForwardRenderer forward{gpu};
  GeometryPass geometry{gpu};
  DeferredLighting lighting;
  SurfaceProbe probe;
  ch01::LightBuffer lights;

  Renderer(const Scene& s, const SceneGpu& g) : scene(s), gpu(g) { lights.upload(s.lights); }

  ImageRGBA8 forward_image(const FrameCamera& camera, OutputTarget& target) {
    target.bind();
    glClearColor(ch01::kBackground.r, ch01::kBackground.g, ch01::kBackground.b, 1.f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    forward.draw(camera, ch01::ForwardMode::PerPixel, lights);
    return target.read();
  }

  ImageRGBA8 deferred_image(const FrameCamera& camera, GBuffer& gbuffer, OutputTarget& target) {
    geometry.draw(gbuffer, camera);
    target.bind();
    lighting.draw(gbuffer, lights, scene.ambient, ch01::kBackground);
    return target.read();
  }
};

struct SurfaceError {
  AngleStats normal;
  double position_p99 = 0, position_max = 0;  // |error| / distance from the camera
  std::size_t pixels = 0;
};

SurfaceError surface_error(const SurfaceImages& a, const SurfaceImages& reference, const glm::vec3& eye) {
  SurfaceError e;
  std::vector<double> rel;
  const int w = a.position.width, h = a.position.height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (a.sky(x, y) || reference.sky(x, y)) continue;
      glm::dvec3 n(a.normal.at(x, y, 0), a.normal.at(x, y, 1), a.normal.at(x, y, 2));
      glm::dvec3 m(reference.normal.at(x, y, 0), reference.normal.at(x, y, 1), reference.normal.at(x, y, 2));
      double angle = std::atan2(glm::length(glm::cross(n, m)), glm::dot(n, m));
      e.normal.mean += angle;
      e.normal.max = std::max(e.normal.max, angle);
      glm::dvec3 p(a.position.at(x, y, 0), a.position.at(x, y, 1), a.position.at(x, y, 2));
      glm::dvec3 q(reference.position.at(x, y, 0), reference.position.at(x, y, 1), reference.position.at(x, y, 2));
      rel.push_back(glm::length(p - q) / glm::length(q - glm::dvec3(eye)));
      ++e.pixels;
    }
  if (e.pixels) {
    e.normal.mean /= double(e.pixels);
    std::sort(rel.begin(), rel.end());
    e.position_p99 = rel[std::min(rel.size() - 1, std::size_t(std::ceil(0.99 * rel.size())) - 1)];
    e.position_max = rel.back();
  }
  return e;
}

void layout_sweep(const Settings& s, const std::string& scene_file, const std::vector<std::string>& views, std::ofstream& csv,
                  const std::string& renderer) {
  Scene scene = load_scene(from_root(scene_file));
  SceneGpu gpu(scene);
  Renderer r(scene, gpu);
  OutputTarget target(s.width, s.height);
  for (const auto& view : views) {
    FrameCamera camera = frame_camera(scene.camera(view), float(s.width) / s.height);
    ImageRGBA8 forward = r.forward_image(camera, target);
    for (const auto& layout : layouts()) {
      GBuffer reference(s.width, s.height, float_reference_for(layout));
      r.geometry.draw(reference, camera);
      SurfaceImages truth = r.probe.read(reference);
      GBuffer gbuffer(s.width, s.height, layout);
      ImageRGBA8 deferred = r.deferred_image(camera, gbuffer, target);
      SurfaceError se = surface_error(r.probe.read(gbuffer), truth, camera.position);
      CompareResult c = compare(deferred, forward, {.threshold = 1, .max_failing_fraction = 0});
      csv << layout.name << ',' << gbuffer.bytes_per_pixel() << ',' << scene.path.stem().string() << '/' << view << ','
          << c.mean_error << ',' << c.p99_error << ',' << c.max_error << ',' << c.failing_fraction << ','
          << se.normal.mean * kDegrees << ',' << se.normal.max * kDegrees << ',' << se.position_p99 << ','
          << se.position_max << ',' << csv_measure_values(renderer, s.width, s.height, 1) << '\n';
      std::cout << view << ' ' << layout.name << " (" << gbuffer.bytes_per_pixel() << " B): image " << c.summary()
                << "\n    normal mean " << se.normal.mean * kDegrees << " max " << se.normal.max * kDegrees
                << " deg, position p99 " << se.position_p99 << " max " << se.position_max << std::endl;
      std::string stem = s.out + "/02_" + scene.path.stem().string() + "_" + view + "_" + layout.name;
      bool figure = view == "aisle" || view == "close_128";  // the heat maps the book shows
      if (figure && (layout.name == "ours" || layout.name == "source" || layout.name == "oct8"))
        save_png(stem + "_diff.png", diff_heatmap(deferred, forward, 1, 8));
    }
  }
}

// ---- position error against distance --------------------------------------------------------

// A camera `distance` metres from the scene's centre, looking at it, framing it.
Camera camera_at_distance(const Scene& scene, float distance) {
  glm::vec3 centre = (scene.bounds_min + scene.bounds_max) * 0.5f;
  float radius = glm::length(scene.bounds_max - scene.bounds_min) * 0.5f;
  glm::vec3 eye = centre + distance * glm::normalize(glm::vec3(0.35f, 0.45f, 1.f));
  Camera c;
  c.name = "distance_" + std::to_string(int(distance));
  c.world = glm::inverse(glm::lookAt(eye, centre, glm::vec3(0, 1, 0)));
  c.yfov = std::clamp(2.f * std::atan(0.8f * radius / distance), 0.01f, 1.2f);
  c.znear = 0.1f;
  c.zfar = 1000.f;
  return c;
}

void position_sweep(const Settings& s, const std::string& renderer) {
  Scene scene = load_scene(from_root("assets/atrium/atrium.gltf"));
  SceneGpu gpu(scene);
  GeometryPass geometry(gpu);
  SurfaceProbe probe;
  std::ofstream csv(s.out + "/02_position_error.csv");
  csv << "# " << renderer << ", " << s.width << "x" << s.height << ", near 0.1 m, far 1000 m\n"
      << "# |reconstructed - float reference| against distance from the camera, the atrium seen from 3..500 m\n"
      << "layout,depth,distance_m,pixels,mean_abs_m,p99_abs_m,max_abs_m,mean_rel,p99_rel,max_rel," << csv_measure_columns() << "\n";
  // Layouts that differ from ours only in where depth comes from.
  std::vector<std::string> names = {"ours", "d32f", "reversed-z", "source"};
  const std::vector<double> bin_edges = {2, 4, 8, 16, 32, 64, 128, 256, 512, 1024};
  for (const auto& name : names) {
    const Layout& layout = layout_named(name);
    std::vector<std::vector<double>> abs_err(bin_edges.size()), rel_err(bin_edges.size());
    for (float distance : {3.f, 6.f, 12.f, 25.f, 50.f, 100.f, 200.f, 400.f, 500.f}) {
      FrameCamera camera = frame_camera(camera_at_distance(scene, distance), float(s.width) / s.height);
      GBuffer reference(s.width, s.height, float_reference_for(layout)), gbuffer(s.width, s.height, layout);
      geometry.draw(reference, camera);
      SurfaceImages truth = probe.read(reference);
      geometry.draw(gbuffer, camera);
      SurfaceImages got = probe.read(gbuffer);
      for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
          if (got.sky(x, y) || truth.sky(x, y)) continue;
          glm::dvec3 p(got.position.at(x, y, 0), got.position.at(x, y, 1), got.position.at(x, y, 2));
          glm::dvec3 q(truth.position.at(x, y, 0), truth.position.at(x, y, 1), truth.position.at(x, y, 2));
          double d = glm::length(q - glm::dvec3(camera.position)), err = glm::length(p - q);
          size_t bin = std::upper_bound(bin_edges.begin(), bin_edges.end(), d) - bin_edges.begin();
          if (bin == 0 || bin >= bin_edges.size()) continue;
          abs_err[bin].push_back(err);
          rel_err[bin].push_back(err / d);
        }
    }
    for (size_t b = 1; b < bin_edges.size(); ++b) {
      auto& a = abs_err[b];
      auto& r = rel_err[b];
      if (a.size() < 100) continue;
      std::sort(a.begin(), a.end());
      std::sort(r.begin(), r.end());
      auto mean = [](const std::vector<double>& v) { double t = 0; for (double x : v) t += x; return t / double(v.size()); };
      auto p99 = [](const std::vector<double>& v) { return v[std::size_t(std::ceil(0.99 * v.size())) - 1]; };
      double centre = std::sqrt(bin_edges[b - 1] * bin_edges[b]);
      csv << name << ',' << depth_format_name(layout.depth) << (layout.depth_target ? " + R32F copy" : "") << ',' << centre
          << ',' << a.size() << ',' << mean(a) << ',' << p99(a) << ',' << a.back() << ',' << mean(r) << ',' << p99(r) << ','
          << r.back() << ',' << csv_measure_values(renderer, s.width, s.height, 1) << '\n';
      std::cout << name << " at ~" << centre << " m: p99 " << p99(a) << " m (relative " << p99(r) << ")\n";
    }
  }
}

// ---- time as lights grow ---------------------------------------------------------------------

void light_sweep(const Settings& s, const std::string& timer, const std::string& renderer, bool software) {
  Scene scene = load_scene(from_root("assets/atrium/atrium.gltf"));
  SceneGpu gpu(scene);
  Renderer r(scene, gpu);
  OutputTarget target(s.light_width, s.light_height);
  GBuffer gbuffer(s.light_width, s.light_height, our_layout());
  FrameCamera camera = frame_camera(scene.camera("overview"), float(s.light_width) / s.light_height);
  std::ofstream csv(s.out + "/02_lights.csv");
  csv << "# " << (software ? "llvmpipe CPU wall time (glFinish per pass): " + timer.substr(timer.find(':') + 2) : timer)
      << ", " << s.light_width << "x" << s.light_height << "\n# atrium overview, G-buffer '" << our_layout().name
      << "', mean of " << s.frames << " frames after warm-up\n"
      << "lights,method,total_ms,geometry_ms,lighting_ms,fragments_shaded," << csv_measure_columns() << "\n";
  // [time-passes]
  // Each pass in a PassMetrics scope; measure() warms up until the times settle, then
  // measures s.frames frames and reads every one back (common/measure.h). On a GPU the
  // scopes are GL_TIME_ELAPSED queries; llvmpipe defers rasterising until something needs
  // the pixels, so there PassMetrics closes each pass with glFinish and reads the CPU clock.
  PassMetrics metrics;
  const MeasureOptions frames{.frames = s.frames};
  auto forward = [&] {
    return measure(metrics, [&] {
      target.bind();
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      auto p = metrics.pass("forward");
      r.forward.draw(camera, ch01::ForwardMode::PerPixel, r.lights);
    }, frames);
  };
  auto deferred = [&] {
    return measure(metrics, [&] {
      {
        auto p = metrics.pass("geometry");
        r.geometry.draw(gbuffer, camera);
      }
      target.bind();
      auto p = metrics.pass("lighting");
      r.lighting.draw(gbuffer, r.lights, scene.ambient, ch01::kBackground);
    }, frames);
  };
  // [/time-passes]
  for (int n = 1; n <= s.max_lights; n *= 2) {
    r.lights.upload(ch01::lights_for_count(scene, n));
    const Measurement fm = forward();
    const PassMeasurement& f = fm.pass("forward");
    csv << n << ",forward," << f.mean_ms << ",0," << f.mean_ms << ',' << f.fragments << ','
        << csv_measure_values(renderer, s.light_width, s.light_height, fm.frames) << '\n';
    std::cout << n << " lights: forward " << f.mean_ms << " ms (" << f.fragments << " fragments)";
    const Measurement dm = deferred();
    const PassMeasurement &g = dm.pass("geometry"), &l = dm.pass("lighting");
    csv << n << ",deferred," << g.mean_ms + l.mean_ms << ',' << g.mean_ms << ',' << l.mean_ms << ',' << l.fragments << ','
        << csv_measure_values(renderer, s.light_width, s.light_height, dm.frames) << '\n';
    std::cout << ", deferred " << g.mean_ms + l.mean_ms << " ms (geometry " << g.mean_ms << ", lighting " << l.mean_ms << ", "
              << l.fragments << " fragments)" << std::endl;
    if (software && n >= 256) break;  // a CPU renderer takes minutes beyond this
  }
}

// Every layout's two passes, timed: what its bytes cost. 64 lights, the middle of 02_lights.csv,
// where the lighting pass reads the G-buffer once per pixel and shades 64 lights.
void layout_time_sweep(const Settings& s, const std::string& timer, const std::string& renderer) {
  Scene scene = load_scene(from_root("assets/atrium/atrium.gltf"));
  SceneGpu gpu(scene);
  Renderer r(scene, gpu);
  OutputTarget target(s.light_width, s.light_height);
  FrameCamera camera = frame_camera(scene.camera("overview"), float(s.light_width) / s.light_height);
  constexpr int kLights = 64;
  r.lights.upload(ch01::lights_for_count(scene, kLights));
  std::ofstream csv(s.out + "/02_layout_times.csv");
  csv << "# " << timer << ", " << s.light_width << "x" << s.light_height << ", atrium overview, " << kLights << " lights\n"
      << "layout,bytes_per_pixel,geometry_ms,lighting_ms,total_ms," << csv_measure_columns() << "\n";
  PassMetrics metrics;
  for (const auto& layout : layouts()) {
    GBuffer gbuffer(s.light_width, s.light_height, layout);
    const Measurement m = measure(metrics, [&] {
      {
        auto p = metrics.pass("geometry");
        r.geometry.draw(gbuffer, camera);
      }
      target.bind();
      auto p = metrics.pass("lighting");
      r.lighting.draw(gbuffer, r.lights, scene.ambient, ch01::kBackground);
    }, {.frames = s.frames});
    const double g = m.pass("geometry").mean_ms, l = m.pass("lighting").mean_ms;
    csv << layout.name << ',' << gbuffer.bytes_per_pixel() << ',' << g << ',' << l << ',' << g + l << ','
        << csv_measure_values(renderer, s.light_width, s.light_height, m.frames) << '\n';
    std::cout << layout.name << " (" << gbuffer.bytes_per_pixel() << " B): geometry " << g << " ms, lighting " << l << " ms"
              << std::endl;
  }
}

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  return run_sweep(argc, argv, "02_gbuffer_sweep", [&](SweepArgs& args) {
    args.text("--out", s.out).size("--size", s.width, s.height).size("--light-size", s.light_width, s.light_height)
        .integer("--frames", s.frames).integer("--max-lights", s.max_lights).text("--only", s.only);
  }, [&] {
    std::filesystem::create_directories(s.out);
    auto context = Context::create({.headless = true, .width = s.width, .height = s.height});
    std::string timer = (context->is_software() ? "llvmpipe CPU time: " : "GPU time: ") + context->renderer();
    std::cout << timer << '\n';
    if (s.only.empty() || s.only == "encodings") encoding_sweep(s);
    if (s.only.empty() || s.only == "layouts") {
      std::ofstream csv(s.out + "/02_layouts.csv");
      csv << "# " << context->renderer() << ", " << s.width << "x" << s.height << ", against chapter 01's forward image\n"
          << "# image error in 8-bit sRGB steps (largest channel difference per pixel); normal and position against "
             "the float layout\n"
          << "layout,bytes_per_pixel,view,image_mean,image_p99,image_max,fraction_over_1,normal_mean_deg,normal_max_deg,"
             "position_rel_p99,position_rel_max," << csv_measure_columns() << "\n";
      layout_sweep(s, "assets/atrium/atrium.gltf", {"overview", "aisle", "corner"}, csv, context->renderer());
      layout_sweep(s, "assets/forward/forward.gltf", {"overview", "close_128", "grazing"}, csv, context->renderer());
      layout_sweep(s, "assets/street/street.gltf", {"street_level"}, csv, context->renderer());
    }
    if (s.only.empty() || s.only == "position") position_sweep(s, context->renderer());
    if (s.only.empty() || s.only == "lights") light_sweep(s, timer, context->renderer(), context->is_software());
    if (s.only.empty() || s.only == "layout-times") layout_time_sweep(s, timer, context->renderer());
    std::cout << "wrote the CSV files in " << s.out << '\n';
  });
}
