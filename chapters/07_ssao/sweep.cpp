// Chapter 07's measurements: each AO method's error against the ray-traced truth (mean
// absolute and mean squared, over the pixels that see geometry) and the AO pass's time, as the
// samples, the noise and blur, the kernel and the resolution vary; on the Cornell box and the
// atrium. Times are GPU time on a GPU and CPU time on llvmpipe (common/measure.h); every row
// names the renderer, the size and the frames measured. Also writes the pictures the book
// shows (each method, the truth, and the error heat maps).
//
//   07_ssao_sweep [--out DIR] [--size WxH] [--frames N] [--truth-samples N] [--only cornell|atrium|wall|corner]
//                 [--method NAME]
//   -> DIR/07_ssao.csv, 07_ssao_wall.csv and 07_ssao_corner.csv (..._llvmpipe.csv on llvmpipe),
//      DIR/07_<scene>_*.png
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "chapters/07_ssao/ao_corner.h"
#include "chapters/07_ssao/ao_frame.h"
#include "chapters/07_ssao/ao_truth.h"
#include "common/context.h"
#include "common/error.h"
#include "common/measure.h"
#include "common/paths.h"
#include "common/raytrace.h"

#include <glm/gtc/matrix_transform.hpp>
#include "common/sweep.h"

namespace {

using namespace lp;
using namespace lp::ch07;

struct Settings {
  std::string out = (source_root() / "book" / "figures").string();
  int width = 320, height = 180;
  int frames = 10;
  int truth_samples = 512;
  std::string only;  // --only cornell|atrium|wall|corner: one part
  std::string method;  // --method NAME: the variants of that name only
  std::string renderer;
};

struct Variant {
  std::string name;
  AoSettings ao;
};

// [variants]
std::vector<Variant> variants(float radius) {
  std::vector<Variant> v;
  for (int n : {8, 16, 32, 64}) {
    v.push_back({"classic", {.method = AoMethod::Classic, .samples = n, .radius = radius}});
    v.push_back({"classic-no-blur", {.method = AoMethod::Classic, .samples = n, .radius = radius, .blur = false}});
    v.push_back({"classic-no-noise", {.method = AoMethod::Classic, .samples = n, .radius = radius, .noise = false, .blur = false}});
    v.push_back({"classic-random-kernel", {.method = AoMethod::Classic, .samples = n, .radius = radius, .energy_minimised = false}});
    v.push_back({"classic-half", {.method = AoMethod::Classic, .samples = n, .radius = radius, .scale = 2}});
    v.push_back({"classic-quarter", {.method = AoMethod::Classic, .samples = n, .radius = radius, .scale = 4}});
  }
  for (int n : {8, 16, 32, 64, 128}) {
    v.push_back({"gtao", {.method = AoMethod::Gtao, .samples = n, .radius = radius}});
    v.push_back({"gtao-no-blur", {.method = AoMethod::Gtao, .samples = n, .radius = radius, .blur = false}});
    v.push_back({"disk", {.method = AoMethod::Disk, .samples = n, .radius = radius}});
    v.push_back({"disk-bunnell", {.method = AoMethod::Disk, .samples = n, .radius = radius, .bunnell_term = true}});
  }
  return v;
}
// [/variants]

ImageRGBA8 grey(const ImageF& ao) {
  ImageRGBA8 img = ImageRGBA8::blank(ao.width, ao.height);
  for (int y = 0; y < ao.height; ++y)
    for (int x = 0; x < ao.width; ++x) {
      float a = ao.at(x, y, 0);
      auto v = std::uint8_t(a < 0.f ? 0 : std::lround(std::min(a, 1.f) * 255.f));
      std::uint8_t* p = &img.pixels[(std::size_t(y) * ao.width + x) * 4];
      p[0] = p[1] = p[2] = v;
      p[3] = 255;
    }
  return img;
}

void sweep_scene(const Settings& s, std::ofstream& csv, const std::string& file, const std::string& view, float radius) {
  Scene scene = load_scene(from_root(file));
  SceneGpu gpu(scene);
  AoFrame frame(gpu, s.width, s.height);
  const FrameCamera camera = frame_camera(scene.camera(view), float(s.width) / s.height);
  const std::string stem = std::filesystem::path(file).stem().string();
  std::cout << stem << " " << view << ": the truth, " << s.truth_samples << " rays per pixel ..." << std::endl;
  const ImageF truth = cached_ray_traced_ao(scene, camera, s.width, s.height, {.radius = radius, .samples = s.truth_samples});
  save_png(s.out + "/07_" + stem + "_truth.png", grey(truth));
  for (const Variant& v : variants(radius)) {
    if (!s.method.empty() && v.name != s.method) continue;
    const ImageF ao = frame.ao(camera, v.ao);
    const AoErrors e = ao_errors(ao, truth);
    const PassMeasurement t = frame.time(camera, v.ao, s.frames);
    csv << stem << ',' << view << ',' << v.name << ',' << v.ao.samples << ',' << radius << ',' << v.ao.scale << ','
        << t.mean_ms << ',' << t.min_ms << ',' << e.mean_abs << ',' << e.mean_sq << ',' << e.mean_signed << ','
        << e.pixels << ',' << csv_measure_values(s.renderer, s.width, s.height, t.frames) << '\n';
    std::cout << "  " << v.name << " " << v.ao.samples << ": " << t.mean_ms << " ms, mean abs " << e.mean_abs
              << ", mean sq " << e.mean_sq << ", signed " << e.mean_signed << std::endl;
    // the book's pictures: the default classic and disk settings
    if ((v.name == "classic" || v.name == "classic-no-noise" || v.name == "classic-no-blur") && v.ao.samples == 16 ||
        (v.name == "disk" && v.ao.samples == 32) || (v.name == "gtao" && v.ao.samples == 32)) {
      const std::string name = s.out + "/07_" + stem + "_" + v.name + "_" + std::to_string(v.ao.samples);
      save_png(name + ".png", grey(ao));
      save_png(name + "_error.png", error_heatmap(ao_error_map(ao, truth), s.width, s.height, 0.5f));
    }
  }
}

// [wall-approach]
// The source's complaint: the classic algorithm's frame time grows as the camera nears a wall
// (its kernel covers more of the screen, its reads scatter over more memory). The camera of
// the Cornell box's view moves along its view direction toward the back wall, from where it
// stands to 5 % of that distance; each method's AO pass is timed at each distance. The disk
// and GTAO clamp their screen radius (a quarter of the image height); the classic kernel does not.
void wall_approach(const Settings& s, const std::string& timer) {
  Scene scene = load_scene(from_root("assets/cornell/cornell.gltf"));
  SceneGpu gpu(scene);
  AoFrame frame(gpu, s.width, s.height);
  const FrameCamera start = frame_camera(scene.camera("front"), float(s.width) / s.height);
  const glm::mat4 inverse = glm::inverse(start.view);
  const glm::vec3 forward = -glm::normalize(glm::vec3(inverse[2]));
  RayScene rays(scene);
  const auto hit = rays.intersect(start.position, forward, 0.f, 1e4f);
  if (!hit) throw Error("wall approach: the view's centre sees no wall");
  const std::string path = s.out + (s.renderer.find("llvmpipe") != std::string::npos ? "/07_ssao_wall_llvmpipe.csv"
                                                                                         : "/07_ssao_wall.csv");
  std::ofstream csv(path);
  csv << "# " << timer << ", " << s.width << "x" << s.height << "; the camera moves toward the back wall along its "
      << "view; ao_ms: the AO pass, mean and fastest of " << s.frames << " frames\n"
      << "distance,distance_fraction,method,samples,ao_ms,ao_min_ms," << csv_measure_columns() << "\n";
  const std::vector<Variant> methods = {{"classic", {.method = AoMethod::Classic, .samples = 16, .radius = 0.5f}},
                                        {"disk", {.method = AoMethod::Disk, .samples = 32, .radius = 0.5f}},
                                        {"gtao", {.method = AoMethod::Gtao, .samples = 32, .radius = 0.5f}}};
  for (float fraction : {1.f, 0.7f, 0.5f, 0.3f, 0.2f, 0.1f, 0.05f}) {
    FrameCamera cam = start;
    const float move = hit->t * (1.f - fraction);
    cam.position = start.position + forward * move;
    cam.view = start.view * glm::translate(glm::mat4(1), -forward * move);
    for (const Variant& v : methods) {
      const PassMeasurement t = frame.time(cam, v.ao, s.frames);
      csv << hit->t * fraction << ',' << fraction << ',' << v.name << ',' << v.ao.samples << ',' << t.mean_ms << ','
          << t.min_ms << ',' << csv_measure_values(s.renderer, s.width, s.height, t.frames) << '\n';
      std::cout << "  wall at " << hit->t * fraction << ": " << v.name << " " << t.mean_ms << " ms" << std::endl;
    }
  }
  std::cout << "wrote " << path << '\n';
}
// [/wall-approach]

// [corner-rows]
// The inner corner (ao_corner.h): each method's mean |A - closed form| over the pixels within R
// of the crease, its mean signed error within R / 5 of it (where the disk fails), and its AO
// pass's time; the classic algorithm with one radius and with the source's two (1:5), whose
// closed form is dihedral_ao(h) dihedral_ao(5 h) and whose second kernel doubles the reads.
void corner_rows(const Settings& s, const std::string& timer) {
  Scene scene = load_scene(from_root("assets/cornell/cornell.gltf"));
  SceneGpu gpu(scene);
  AoFrame frame(gpu, s.width, s.height);
  RayScene rays(scene);
  const FrameCamera cam = corner_camera(float(s.width) / s.height);
  const auto pixels = corner_pixels(scene, rays, cam, s.width, s.height);
  const std::string path = s.out + (s.renderer.find("llvmpipe") != std::string::npos ? "/07_ssao_corner_llvmpipe.csv"
                                                                                         : "/07_ssao_corner.csv");
  std::ofstream csv(path);
  csv << "# " << timer << ", " << s.width << "x" << s.height << "; the Cornell box's floor meeting its back wall, R = "
      << kCornerRadius << "; mean_abs: mean |A - closed form| within R of the crease; crease_signed: mean A - closed "
      << "form within R / 5; ao_ms: the AO pass, mean and fastest of " << s.frames << " frames\n"
      << "method,samples,two_radii,ao_ms,ao_min_ms,mean_abs,crease_signed,pixels," << csv_measure_columns() << "\n";
  AoSettings two{.method = AoMethod::Classic, .samples = 16, .radius = kCornerRadius};
  two.two_radii = true;
  const std::vector<Variant> methods = {{"classic", {.method = AoMethod::Classic, .samples = 16, .radius = kCornerRadius}},
                                        {"classic", two},
                                        {"disk", {.method = AoMethod::Disk, .samples = 32, .radius = kCornerRadius}},
                                        {"gtao", {.method = AoMethod::Gtao, .samples = 32, .radius = kCornerRadius}}};
  for (const Variant& v : methods) {
    const ImageF ao = frame.ao(cam, v.ao);
    double mean_abs = 0, crease = 0;
    long n = 0, n_crease = 0;
    for (const CornerPixel& p : pixels) {
      if (p.h >= 1.0) continue;
      const double closed = dihedral_ao(p.h) * (v.ao.two_radii ? dihedral_ao(5.0 * p.h) : 1.0);
      const double e = ao.at(p.x, p.y, 0) - closed;
      mean_abs += std::abs(e), ++n;
      if (p.h < 0.2) crease += e, ++n_crease;
    }
    mean_abs /= double(std::max(n, 1L)), crease /= double(std::max(n_crease, 1L));
    const PassMeasurement t = frame.time(cam, v.ao, s.frames);
    csv << v.name << ',' << v.ao.samples << ',' << (v.ao.two_radii ? 1 : 0) << ',' << t.mean_ms << ',' << t.min_ms << ','
        << mean_abs << ',' << crease << ',' << n << ',' << csv_measure_values(s.renderer, s.width, s.height, t.frames)
        << '\n';
    std::cout << "  corner: " << v.name << (v.ao.two_radii ? " (two radii)" : "") << " " << t.mean_ms
              << " ms, mean abs " << mean_abs << ", crease signed " << crease << std::endl;
  }
  std::cout << "wrote " << path << '\n';
}
// [/corner-rows]

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  return run_sweep(argc, argv, "07_ssao_sweep", [&](SweepArgs& args) {
    args.text("--out", s.out).size("--size", s.width, s.height).integer("--frames", s.frames)
        .integer("--truth-samples", s.truth_samples).text("--only", s.only).text("--method", s.method);
  }, [&] {
    if (s.truth_samples < 1) throw UsageError("--truth-samples must be at least 1");
    if (!s.only.empty() && s.only != "cornell" && s.only != "atrium" && s.only != "wall" && s.only != "corner")
      throw UsageError("--only must be cornell, atrium, wall or corner, not '" + s.only + "'");
    std::filesystem::create_directories(s.out);
    auto context = Context::create({.headless = true, .width = s.width, .height = s.height});
    s.renderer = context->renderer();
    const std::string timer = (context->is_software() ? "llvmpipe CPU time: " : "GPU time: ") + context->renderer();
    std::cout << timer << '\n';
    if (s.only.empty() || s.only == "cornell" || s.only == "atrium") {
      const std::string path = s.out + (context->is_software() ? "/07_ssao_llvmpipe.csv" : "/07_ssao.csv");
      std::ofstream csv(path);
      csv << "# " << timer << ", " << s.width << "x" << s.height << ", truth " << s.truth_samples
          << " cosine-weighted rays per pixel (standard error <= " << 0.5 / std::sqrt(double(s.truth_samples)) << ")\n"
          << "# ao_ms: the AO pass (and its blur), mean and fastest of " << s.frames
          << " frames; errors of A over the pixels that see geometry\n"
          << "scene,view,method,samples,radius,scale,ao_ms,ao_min_ms,mean_abs,mean_sq,mean_signed,pixels,"
          << csv_measure_columns() << "\n";
      if (s.only.empty() || s.only == "cornell") sweep_scene(s, csv, "assets/cornell/cornell.gltf", "front", 0.5f);
      if (s.only.empty() || s.only == "atrium") sweep_scene(s, csv, "assets/atrium/atrium.gltf", "overview", 1.0f);
      std::cout << "wrote " << path << '\n';
    }
    if (s.only.empty() || s.only == "wall") wall_approach(s, timer);
    if (s.only.empty() || s.only == "corner") corner_rows(s, timer);
  });
}
