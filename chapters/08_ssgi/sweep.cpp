// Chapter 08's measurements: the indirect light's error against the ray-traced one-bounce truth
// (mean absolute, relative, and the fraction of the true energy captured; also against the
// screen-limited truth, what the screen can show) and the SSGI pass's time, as the samples and
// the pattern vary, and with a second bounce (against the two-bounce truth); then the limits: the
// camera panned away from the red wall until it leaves the screen; and the two fixes the program
// has for the screen's losses, with and without: the back-face layer and the guard band (their
// errors and their time, the SSGI pass's and the whole frame's). On the Cornell box (and the
// atrium unless --only cornell). Times are GPU time on a GPU and CPU time on llvmpipe
// (common/measure.h); every row names the renderer, the size and the frames measured. Also
// writes the pictures the book shows.
//
//   08_ssgi_sweep [--out DIR] [--size WxH] [--frames N] [--truth-samples N] [--only cornell|atrium|pan|fixes]
//   -> DIR/08_ssgi.csv, 08_ssgi_pan.csv and 08_ssgi_fixes.csv (..._llvmpipe.csv on llvmpipe), DIR/08_<scene>_*.png
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/08_ssgi/gi_frame.h"
#include "chapters/08_ssgi/gi_truth.h"
#include "common/context.h"
#include "common/error.h"
#include "common/measure.h"
#include "common/paths.h"
#include "common/raytrace.h"
#include "common/sweep.h"

namespace {

using namespace lp;
using namespace lp::ch08;

struct Settings {
  std::string out = (source_root() / "book" / "figures").string();
  int width = 320, height = 180;
  int frames = 10;
  int truth_samples = 1024;  // the pan's truths use a quarter: it reads means over thousands of pixels
  std::string only;
  std::string renderer;
};

struct Variant {
  std::string name;
  GiSettings gi;
};

// [variants]
std::vector<Variant> variants() {
  std::vector<Variant> v;
  for (int n : {8, 16, 32, 64, 128}) {
    v.push_back({"regular", {.samples = n, .pattern = Pattern::Regular}});
    v.push_back({"spiral", {.samples = n, .pattern = Pattern::Spiral}});
    v.push_back({"randomised-no-blur", {.samples = n, .pattern = Pattern::Randomised, .blur = false}});
    v.push_back({"randomised", {.samples = n, .pattern = Pattern::Randomised}});
    v.push_back({"randomised-2-bounces", {.samples = n, .pattern = Pattern::Randomised, .bounces = 2}});
    // beyond the source: the same samples' budget along slices with a visibility bitmask
    v.push_back({"randomised-bitmask", {.samples = n, .pattern = Pattern::Randomised, .gather = Gather::Bitmask}});
  }
  return v;
}
// [/variants]

std::string csv_name(const Settings& s, const std::string& stem) {
  return s.out + "/" + stem + (s.renderer.find("llvmpipe") != std::string::npos ? "_llvmpipe.csv" : ".csv");
}

void sweep_scene(const Settings& s, std::ofstream& csv, const std::string& file, const std::string& view) {
  Scene scene = load_scene(from_root(file));
  SceneGpu gpu(scene);
  GiFrame frame(gpu, s.width, s.height);
  const FrameCamera camera = frame_camera(scene.camera(view), float(s.width) / s.height);
  const std::string stem = std::filesystem::path(file).stem().string();
  std::cout << stem << " " << view << ": the truths, " << s.truth_samples << " rays per pixel ..." << std::endl;
  const ImageF truth1 = cached_ray_traced_indirect(scene, frame.lights(), camera, s.width, s.height, {.samples = s.truth_samples});
  const ImageF truth2 =
      cached_ray_traced_indirect(scene, frame.lights(), camera, s.width, s.height, {.samples = s.truth_samples, .bounces = 2});
  const ImageF screen = cached_ray_traced_indirect(scene, frame.lights(), camera, s.width, s.height,
                                                   {.samples = s.truth_samples, .screen_limited = true});
  const ImageF noise = cached_ray_traced_indirect(scene, frame.lights(), camera, s.width, s.height,
                                                  {.samples = s.truth_samples, .seed = 99});
  const GiErrors truth_noise = gi_errors(noise, truth1), screen_share = gi_errors(screen, truth1);
  const GiErrors second = gi_errors(truth2, truth1);
  // rows for the truths themselves: their noise, what the screen shows, what a second bounce adds
  auto truth_row = [&](const std::string& name, const GiErrors& e) {
    csv << stem << ',' << view << ',' << name << ",0,0,0,0," << e.mean_abs << ',' << e.relative << ',' << e.captured
        << ",0,0," << e.pixels << ',' << csv_measure_values(s.renderer, s.width, s.height, 0) << '\n';
  };
  truth_row("truth-other-seed", truth_noise);
  truth_row("truth-screen-limited", screen_share);
  truth_row("truth-2-bounces", second);
  // the book's pictures: the truths, and the lit strip: direct only, + SSAO, + SSGI
  frame.stage().set_picture(truth1);
  save_png(s.out + "/08_" + stem + "_truth.png", frame.image(camera, GiMode::Ssgi, {}, GiShow::Picture, 1.f, 4.f));
  save_png(s.out + "/08_" + stem + "_direct.png", frame.image(camera, GiMode::Off, {}));
  save_png(s.out + "/08_" + stem + "_ssao.png", frame.image(camera, GiMode::Ssao, {}));
  save_png(s.out + "/08_" + stem + "_ssgi.png", frame.image(camera, GiMode::Ssgi, {}));
  for (const Variant& v : variants()) {
    const ImageF gi = frame.indirect(camera, GiMode::Ssgi, v.gi);
    const GiErrors e = gi_errors(gi, v.gi.bounces == 2 ? truth2 : truth1);
    const GiErrors es = gi_errors(gi, screen);
    const PassMeasurement t = frame.time(camera, GiMode::Ssgi, v.gi, s.frames);
    csv << stem << ',' << view << ',' << v.name << ',' << Ssgi::used_samples(v.gi.pattern, v.gi.samples) << ','
        << v.gi.bounces << ',' << t.mean_ms << ',' << t.min_ms << ',' << e.mean_abs << ',' << e.relative << ','
        << e.captured << ',' << es.relative << ',' << es.captured << ',' << e.pixels << ','
        << csv_measure_values(s.renderer, s.width, s.height, t.frames) << '\n';
    std::cout << "  " << v.name << " " << v.gi.samples << ": " << t.mean_ms << " ms, relative " << e.relative
              << ", captured " << e.captured << " (of the screen's: " << es.captured << ")" << std::endl;
    if (v.gi.samples == 16 && v.gi.bounces == 1) {
      const std::string name = s.out + "/08_" + stem + "_" + v.name + "_16";
      save_png(name + ".png", frame.image(camera, GiMode::Ssgi, v.gi, GiShow::Indirect, 1.f, 4.f));
      frame.stage().set_picture(gi_error_map(gi, truth1), 0.2f);
      save_png(name + "_error.png", frame.image(camera, GiMode::Ssgi, v.gi, GiShow::Heat));
    }
  }
}

// [fixes]
// The source's fixes for what the screen misses, each with and without, on the Cornell box and
// the atrium: the back-face layer (the disk gather reads the nearest back faces too; its G-buffer
// and lights are timed inside the SSGI pass), and the guard band (the frame drawn wider by a
// fraction of the height on every side; it costs the whole frame, not only the pass: frame_ms).
// Errors against the one-bounce truth over the screen's pixels.
void fixes(const Settings& s, const std::string& timer) {
  std::ofstream csv(csv_name(s, "08_ssgi_fixes"));
  csv << "# " << timer << ", " << s.width << "x" << s.height << ", truth " << s.truth_samples
      << " rays per pixel; gi_ms: the SSGI pass (with the back-face layer's G-buffer and lights when on), frame_ms: "
      << "every pass of the frame, means of " << s.frames << " frames; guard: pixels on every side\n"
      << "scene,view,fix,samples,guard,gi_ms,frame_ms,mean_abs,relative,captured,pixels," << csv_measure_columns() << "\n";
  for (auto [file, view] : {std::pair{"assets/cornell/cornell.gltf", "front"}, std::pair{"assets/atrium/atrium.gltf", "overview"}}) {
    const std::string stem = std::filesystem::path(file).stem().string();
    if (!s.only.empty() && s.only != "fixes" && s.only != stem) continue;
    Scene scene = load_scene(from_root(file));
    SceneGpu gpu(scene);
    GiFrame frame(gpu, s.width, s.height);
    const FrameCamera camera = frame_camera(scene.camera(view), float(s.width) / s.height);
    const ImageF truth = cached_ray_traced_indirect(scene, frame.lights(), camera, s.width, s.height, {.samples = s.truth_samples});
    auto row = [&](GiFrame& f, const std::string& fix, const GiSettings& gi) {
      const GiErrors e = gi_errors(f.indirect(camera, GiMode::Ssgi, gi), truth);
      const Measurement m = f.measure_frame(camera, GiMode::Ssgi, gi, s.frames);
      const PassMeasurement& t = m.pass(GiFrame::pass_name(GiMode::Ssgi, gi));
      csv << stem << ',' << view << ',' << fix << ',' << gi.samples << ',' << f.guard_band().pixels << ',' << t.mean_ms << ','
          << m.total_ms() << ',' << e.mean_abs << ',' << e.relative << ',' << e.captured << ',' << e.pixels << ','
          << csv_measure_values(s.renderer, s.width, s.height, t.frames) << '\n';
      std::cout << "  " << stem << " " << fix << " " << gi.samples << ": " << t.mean_ms << " ms (frame " << m.total_ms()
                << "), relative " << e.relative << ", captured " << e.captured << std::endl;
    };
    for (int n : {16, 32, 64, 128}) {
      GiSettings gi{.samples = n, .pattern = Pattern::Randomised};
      row(frame, "none", gi);
      gi.back_faces = true;
      row(frame, "back-faces", gi);
    }
    for (float fraction : {0.1f, 0.25f}) {
      GiFrame guarded(gpu, s.width, s.height, guard_band_pixels(fraction, s.height));
      row(guarded, "guard-band", {.samples = 32, .pattern = Pattern::Randomised});
    }
    // the book's pictures: the back-face layer's light, and the indirect light with it
    const GiSettings with{.samples = 32, .pattern = Pattern::Randomised, .back_faces = true};
    save_png(s.out + "/08_" + stem + "_back_faces.png", frame.image(camera, GiMode::Ssgi, with, GiShow::BackFaces));
  }
}
// [/fixes]

// [pan]
// The off-screen limit: a camera 1.9 m above the Cornell box's floor looks straight down and
// moves to the right (+x), from x = -0.6 to 0.5: the red wall (x = -1, seen from above at a
// slant) leaves the image at about x = 0.2, while the floor between x = -0.6 and -0.1 stays in
// it. At each offset, the red light those floor pixels receive (red - green / 0.93 of L1_ind) in
// the truth, in the screen-limited truth and in the pass; the red wall's pixels; and the frame's
// energy captured. (A camera that turns away from the wall, or moves at eye height, takes the
// floor beside the wall off the screen with it.) And the cheaper of the source's fixes measured: a
// guard band (guard_band.h, the program's --guard-band 0.1), the whole frame rendered 10 % of the
// height wider on every side with the same focal length (so its inner pixels are the screen's
// pixels), the pass run on it, the screen's part kept: what it recovers, and its time.
void pan(const Settings& s, const std::string& timer) {
  Scene scene = load_scene(from_root("assets/cornell/cornell.gltf"));
  SceneGpu gpu(scene);
  GiFrame frame(gpu, s.width, s.height);
  RayScene rays(scene);
  const FrameCamera start = frame_camera(scene.camera("front"), float(s.width) / s.height);
  std::ofstream csv(csv_name(s, "08_ssgi_pan"));
  csv << "# " << timer << ", " << s.width << "x" << s.height << ", truth " << std::max(1, s.truth_samples / 4)
      << " rays per pixel; the camera 1.9 m above the floor looking down at x = `offset`; red_*: red - green / 0.93 of L1_ind over the floor "
      << "between x = -0.6 and -0.1; captured: the pass's energy over the truth's\n"
      << "offset,red_wall_pixels,floor_pixels,red_truth,red_screen,red_pass,red_guard,captured,captured_screen,"
      << "captured_guard,gi_ms,guard_gi_ms,"
      << csv_measure_columns() << "\n";
  const GiSettings gi_settings{.samples = 32};
  GiFrame guard(gpu, s.width, s.height, guard_band_pixels(0.1, s.height));  // the program's --guard-band 0.1
  for (float offset : {-0.6f, -0.4f, -0.2f, 0.f, 0.1f, 0.2f, 0.3f, 0.4f, 0.5f}) {
    FrameCamera cam = start;
    cam.position = glm::vec3(offset, 1.9f, 0.2f);
    cam.view = glm::lookAt(cam.position, glm::vec3(offset, 0.f, 0.2f), glm::vec3(0, 0, -1));
    const auto hits = primary_hits(rays, cam, s.width, s.height);
    const int samples = std::max(1, s.truth_samples / 4);
    const ImageF truth = cached_ray_traced_indirect(scene, frame.lights(), cam, s.width, s.height, {.samples = samples});
    const ImageF screen = cached_ray_traced_indirect(scene, frame.lights(), cam, s.width, s.height,
                                                     {.samples = samples, .screen_limited = true});
    const ImageF gi = frame.indirect(cam, GiMode::Ssgi, gi_settings);
    const ImageF guarded = guard.indirect(cam, GiMode::Ssgi, gi_settings);
    double red[4] = {0, 0, 0, 0};
    long floor = 0, wall = 0;
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        const auto& h = hits[std::size_t(y) * s.width + x];
        if (!h) continue;
        const std::string& name = scene.instances[std::size_t(h->instance)].name;
        wall += name == "left_wall";
        if (name != "floor" || h->position.x < -0.6f || h->position.x > -0.1f) continue;
        ++floor;
        int k = 0;
        for (const ImageF* img : {&truth, &screen, static_cast<const ImageF*>(&gi), static_cast<const ImageF*>(&guarded)}) red[k++] += img->at(x, y, 0) - img->at(x, y, 1) / 0.93f;
      }
    const PassMeasurement t = frame.time(cam, GiMode::Ssgi, gi_settings, s.frames);
    const PassMeasurement tg = guard.time(cam, GiMode::Ssgi, gi_settings, s.frames);
    csv << offset << ',' << wall << ',' << floor;
    for (double r : red) csv << ',' << (floor ? r / double(floor) : 0.0);
    csv << ',' << gi_errors(gi, truth).captured << ',' << gi_errors(screen, truth).captured << ','
        << gi_errors(guarded, truth).captured << ',' << t.mean_ms << ',' << tg.mean_ms << ','
        << csv_measure_values(s.renderer, s.width, s.height, t.frames) << '\n';
    std::cout << "  pan " << offset << " m: red wall " << wall << " pixels, floor red: truth "
              << (floor ? red[0] / floor : 0) << ", pass " << (floor ? red[2] / floor : 0) << ", with the guard band "
              << (floor ? red[3] / floor : 0) << std::endl;
  }
}
// [/pan]

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  return run_sweep(argc, argv, "08_ssgi_sweep", [&](SweepArgs& args) {
    args.text("--out", s.out).size("--size", s.width, s.height).integer("--frames", s.frames)
        .integer("--truth-samples", s.truth_samples).text("--only", s.only);
  }, [&] {
    if (s.truth_samples < 1) throw UsageError("--truth-samples must be at least 1");
    if (!s.only.empty() && s.only != "cornell" && s.only != "atrium" && s.only != "pan" && s.only != "fixes")
      throw UsageError("--only must be cornell, atrium, pan or fixes (got '" + s.only + "')");
    std::filesystem::create_directories(s.out);
    auto context = Context::create({.headless = true, .width = s.width, .height = s.height});
    s.renderer = context->renderer();
    const std::string timer = (context->is_software() ? "llvmpipe CPU time: " : "GPU time: ") + context->renderer();
    std::cout << timer << '\n';
    if (s.only != "pan" && s.only != "fixes") {
      const std::string path = csv_name(s, "08_ssgi");
      std::ofstream csv(path);
      csv << "# " << timer << ", " << s.width << "x" << s.height << ", truth " << s.truth_samples
          << " cosine-weighted rays per pixel (the truth-other-seed row: two truths' difference)\n"
          << "# gi_ms: the SSGI pass (AO + indirect, its blur, a second pass), mean and fastest of " << s.frames
          << " frames; errors of L1_ind over the pixels that see geometry, against the truth of as many bounces; "
          << "*_screen: against the one-bounce screen-limited truth\n"
          << "scene,view,variant,samples,bounces,gi_ms,gi_min_ms,mean_abs,relative,captured,relative_screen,"
          << "captured_screen,pixels," << csv_measure_columns() << "\n";
      if (s.only.empty() || s.only == "cornell") sweep_scene(s, csv, "assets/cornell/cornell.gltf", "front");
      if (s.only.empty() || s.only == "atrium") sweep_scene(s, csv, "assets/atrium/atrium.gltf", "overview");
      std::cout << "wrote " << path << '\n';
    }
    if (s.only.empty() || s.only == "pan") pan(s, timer);
    if (s.only != "pan") fixes(s, timer);
  });
}
