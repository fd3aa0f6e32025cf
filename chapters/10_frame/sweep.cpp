// Chapter 10's sweep: transparency as layers grow. The glass scene's panes replaced by a stack
// of N panes (N = 1 .. 64, three colours in turn, 10 cm apart, each shifted a little so the
// stack's edges show every count from 1 to N), drawn sorted and with WBOIT: the time of each
// method's passes (the one measurement, common/measure.h) and its error against the exact
// per-pixel order, in 8-bit steps over the pixels with glass. Writes
// book/figures/10_transparency_llvmpipe.csv (or 10_transparency.csv on a GPU), each row naming
// the renderer, size and frames.
//
// Then MSAA with deferred shading (msaa.h), on the street: no MSAA, 4 samples lit per sample
// on the edges only, 4 samples lit per sample everywhere, and the edges with the wrong resolve
// order, each with the local lights as chapter 03's stencil volumes and as one full-screen loop
// (MsaaSettings::lights), each against a supersampled ground truth (the frame at 4x the width
// and height, one sample, each pixel's display value averaged over its 4x4 block): error in
// 8-bit steps, fragments shaded, volume samples lit, edges marked, and the time of the MSAA
// passes. Writes 10_msaa_llvmpipe.csv (or 10_msaa.csv), and on llvmpipe the book's pictures of
// the edges and of the resolve order (--msaa-size 160x90 keeps the loop's llvmpipe run short).
//
// Then the tubes (--part tubes): the shop street's whole frame, every stage on, with the tubes'
// light in chapter 09's clusters and as chapter 04's capsule volumes: the passes' times, the
// tubes' share (the volumes' pass, or nothing apart: the clusters' shading pass holds them) and
// the images' difference. Writes 10_tubes_llvmpipe.csv (or 10_tubes.csv).
//
// Then the whole frame with MSAA (--part whole-msaa): the shop street, every stage at its
// default, --msaa 1, 4 and 8 (--msaa-size): the frame's time, MSAA's passes, the sun's map, the glass, the
// pixels marked, the bytes and the stages run. Writes 10_whole_msaa_llvmpipe.csv (or
// 10_whole_msaa.csv).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/10_frame/msaa.h"
#include "chapters/10_frame/transparency.h"
#include "chapters/10_frame/whole_frame.h"
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
  std::string part = "all";                     // all, transparency, msaa, tubes, whole-msaa
  int msaa_width = 0, msaa_height = 0;          // 0: 1920x1080 on a GPU, 320x180 on llvmpipe (whole-msaa too)
  int tubes_width = 0, tubes_height = 0;        // the same
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


// [msaa-truth]
// The ground truth: the frame at `factor` times the width and height, one sample per pixel,
// its linear display values (after the tonemap) averaged over each factor x factor block.
// Its local lights are the full-screen loop's (summed in fp32, not rounded to half floats per
// light), the same truth for both ways the sweep brings them.
ImageRGBA8 supersampled(ch10::MsaaFrame& msaa, const FrameCamera& camera, int w, int h, int factor) {
  const int W = w * factor, H = h * factor;
  gl::Texture colour = gl::make_texture_2d(GL_RGBA32F, W, H);
  gl::Framebuffer fbo;
  glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, colour.id(), 0);
  msaa.render(camera, {fbo.id(), W, H}, {.samples = 1, .lights = ch10::MsaaLights::FullScreen});
  std::vector<float> big(std::size_t(W) * std::size_t(H) * 4);
  glGetTextureImage(colour.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(big.size() * sizeof(float)), big.data());
  ImageF mean = ImageF::blank(w, h, 3);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (int c = 0; c < 3; ++c)
        mean.at(x / factor, h - 1 - y / factor, c) += big[(std::size_t(y) * W + x) * 4 + c] / float(factor * factor);
  return to_srgb8(mean);
}
// [/msaa-truth]

// A picture for the book: `image` cropped around (cx, cy) and enlarged `zoom` times.
ImageRGBA8 zoomed(const ImageRGBA8& image, int cx, int cy, int w, int h, int zoom) {
  ImageRGBA8 out = ImageRGBA8::blank(w * zoom, h * zoom);
  const int x0 = std::clamp(cx - w / 2, 0, image.width - w), y0 = std::clamp(cy - h / 2, 0, image.height - h);
  for (int y = 0; y < h * zoom; ++y)
    for (int x = 0; x < w * zoom; ++x)
      std::copy_n(image.at(x0 + x / zoom, y0 + y / zoom), 4, out.at(x, y));
  return out;
}

ImageRGBA8 side_by_side(const std::vector<ImageRGBA8>& images, int gap) {
  int w = -gap;
  for (const auto& i : images) w += i.width + gap;
  ImageRGBA8 out = ImageRGBA8::blank(w, images[0].height);
  for (auto& p : out.pixels) p = 255;
  int x0 = 0;
  for (const auto& i : images) {
    for (int y = 0; y < i.height; ++y)
      for (int x = 0; x < i.width; ++x) std::copy_n(i.at(x, y), 4, out.at(x0 + x, y));
    x0 += i.width + gap;
  }
  return out;
}

void sweep_msaa(const Settings& s, bool software) {
  const int w = s.msaa_width ? s.msaa_width : software ? 320 : 1920;
  const int h = s.msaa_height ? s.msaa_height : software ? 180 : 1080;
  const std::string path = s.out + (software ? "/10_msaa_llvmpipe.csv" : "/10_msaa.csv");
  std::ofstream csv(path);
  csv << "# " << (software ? "llvmpipe CPU time: " : "GPU time: ") << s.renderer << ", " << w << "x" << h
      << "; the street (street_level); ms: the MSAA frame's passes, mean and fastest of " << s.frames << " frames\n"
      << "# error: against the frame at 4x the width and height (16 samples per pixel, display values box-filtered), "
         "in 8-bit steps over all pixels\n"
      << "# shaded: fragment shader invocations of the full-screen light passes (exact, GL_SAMPLES_PASSED); marked: edge "
         "pixels\n"
      << "# lights: the local lights as chapter 03's stencil volumes or a full-screen loop (every light per invocation); "
         "volume_pixel_samples / volume_per_sample: the samples the volumes' per-pixel draws wrote and their per-sample "
         "invocations, over all lights (exact, GL_SAMPLES_PASSED)\n"
      << "mode,lights,samples,marked,marked_percent,shaded,shaded_per_pixel,volume_pixel_samples,volume_per_sample,ms,"
         "min_ms,error_mean,error_p99,error_max,psnr_db,"
      << csv_measure_columns() << "\n";
  Scene scene = load_scene(from_root("assets/street/street.gltf"));
  SceneGpu gpu(scene);
  ch03::DeferredFrame frame(gpu);
  ch03::use_lights(frame, scene, scene.lights, false);
  ch10::MsaaFrame msaa(gpu, frame.volumes());
  const FrameCamera camera = frame_camera(scene.camera("street_level"), float(w) / h);
  const ImageRGBA8 truth = supersampled(msaa, camera, w, h, 4);
  OutputTarget target(w, h);
  const ch03::FrameOutput output{target.framebuffer(), w, h};
  struct Mode {
    const char* name;
    ch10::MsaaSettings settings;
  };
  const std::vector<Mode> modes = {
      {"no_msaa", {.samples = 1}},
      {"edges_per_sample", {.samples = 4}},
      {"per_sample_everywhere", {.samples = 4, .shading = ch10::MsaaShading::PerSampleEverywhere}},
      {"edges_resolve_first", {.samples = 4, .order = ch10::ResolveOrder::ResolveFirst}}};
  std::map<std::string, ImageRGBA8> images;  // the volumes' (the default)
  for (const ch10::MsaaLights lights : {ch10::MsaaLights::Volumes, ch10::MsaaLights::FullScreen})
    for (Mode mode : modes) {
      mode.settings.lights = lights;
      const char* lights_name = lights == ch10::MsaaLights::Volumes ? "volumes" : "full_screen";
      msaa.render(camera, output, mode.settings);  // counts (no metrics), then the image
      const ch10::MsaaCounts n = msaa.counts();
      const ImageRGBA8 image = target.read();
      if (lights == ch10::MsaaLights::Volumes) images[mode.name] = image;
      const CompareResult e = compare(image, truth);
      PassMetrics metrics;
      const Measurement m = measure(metrics, [&] { msaa.render(camera, output, mode.settings, &metrics); }, {.frames = s.frames});
      double ms = 0, min_ms = 0;
      for (const PassMeasurement& p : m.passes)
        if (p.name.rfind("msaa:", 0) == 0) ms += p.mean_ms, min_ms += p.min_ms;
      csv << mode.name << ',' << lights_name << ',' << mode.settings.samples << ',' << n.marked << ','
          << 100.0 * n.marked_fraction() << ',' << n.shaded() << ',' << double(n.shaded()) / double(n.pixels) << ','
          << n.volume_pixel_samples << ',' << n.volume_per_sample << ',' << ms << ',' << min_ms << ',' << e.mean_error
          << ',' << e.p99_error << ',' << e.max_error << ',' << e.psnr_db << ','
          << csv_measure_values(s.renderer, w, h, m.frames) << '\n';
      std::cout << "  msaa " << mode.name << " (" << lights_name << "): " << n.marked << " marked, " << n.shaded()
                << " shaded, " << n.volume_samples() << " volume samples, " << ms << " ms, error mean " << e.mean_error
                << " p99 " << e.p99_error << std::endl;
    }
  std::cout << "wrote " << path << '\n';
  if (!software) return;
  // The pictures (llvmpipe's, committed with the book): the edges, and the resolve orders
  // where they differ most, enlarged next to the ground truth.
  msaa.render(camera, output, {.samples = 4, .show = ch10::MsaaShow::Edges});
  save_png(s.out + "/10_msaa_edges.png", target.read());
  const ImageRGBA8& right = images["edges_per_sample"];
  const ImageRGBA8& wrong = images["edges_resolve_first"];
  int best = -1, bx = 0, by = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      int d = 0;
      for (int c = 0; c < 3; ++c) d += std::abs(int(right.at(x, y)[c]) - int(wrong.at(x, y)[c]));
      if (d > best) best = d, bx = x, by = y;
    }
  save_png(s.out + "/10_msaa_order.png",
           side_by_side({zoomed(images["no_msaa"], bx, by, 24, 16, 8), zoomed(right, bx, by, 24, 16, 8),
                         zoomed(wrong, bx, by, 24, 16, 8), zoomed(truth, bx, by, 24, 16, 8)}, 8));
  std::cout << "wrote 10_msaa_edges.png, 10_msaa_order.png (around pixel " << bx << ", " << by << ")\n";
}

// [tubes-sweep]
void sweep_tubes(const Settings& s, bool software) {
  const int w = s.tubes_width ? s.tubes_width : software ? 320 : 1920;
  const int h = s.tubes_height ? s.tubes_height : software ? 180 : 1080;
  const std::string path = s.out + (software ? "/10_tubes_llvmpipe.csv" : "/10_tubes.csv");
  std::ofstream csv(path);
  csv << "# " << (software ? "llvmpipe CPU time: " : "GPU time: ") << s.renderer << ", " << w << "x" << h
      << "; the shop street's whole frame, every stage on, local lights in chapter 09's clusters\n"
      << "# tubes: their light in the clusters' shading pass, or chapter 04's capsule volumes; ms: mean of " << s.frames
      << " frames; neon_ms: the volumes' pass (0 in the clusters: their shading pass holds the tubes); "
         "local_ms: the clusters' passes; steps_max / steps_mean: the output against the volumes', 8-bit steps\n"
      << "# pixels_over_8: pixels more than 8 steps apart; worst_x, worst_y: the pixel steps_max is of (from the top left)\n"
      << "view,tubes,neon_ms,local_ms,lights_and_tubes_ms,total_ms,steps_max,steps_mean,pixels_over_8,worst_x,worst_y,"
      << csv_measure_columns() << "\n";
  const Scene scene = load_scene(from_root("assets/street_shop/street_shop.gltf"));
  WholeFrame whole(scene);
  OutputTarget target(w, h);
  const ch03::FrameOutput output{target.framebuffer(), w, h};
  for (const char* view : {"shops", "shop_window"}) {
    const FrameCamera camera = frame_camera(scene.camera(view), float(w) / float(h));
    ImageRGBA8 volumes_image;
    for (const TubeLight tubes : {TubeLight::Volumes, TubeLight::Clusters}) {
      WholeFrameSettings settings;
      settings.tubes = tubes;
      whole.render(camera, output, settings, 1.f / 60.f, true);  // the eye adapted: the same exposure in both
      const ImageRGBA8 image = target.read();
      if (tubes == TubeLight::Volumes) volumes_image = image;
      const CompareResult e = compare(image, volumes_image);
      // Where the two differ most, for finding out why (the pixels and their values; the heat map
      // beside the CSV when some differ by more than 8 steps).
      int worst = 0, worst_x = -1, worst_y = -1, over = 0;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          int d = 0;
          for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(image.at(x, y)[c]) - int(volumes_image.at(x, y)[c])));
          over += d > 8;
          if (d > worst) worst = d, worst_x = x, worst_y = y;
          if (d > 8 && over <= 8)
            std::cout << "  tubes " << view << ": pixel " << x << "," << y << " clusters " << int(image.at(x, y)[0]) << ' '
                      << int(image.at(x, y)[1]) << ' ' << int(image.at(x, y)[2]) << ", volumes " << int(volumes_image.at(x, y)[0])
                      << ' ' << int(volumes_image.at(x, y)[1]) << ' ' << int(volumes_image.at(x, y)[2]) << '\n';
        }
      if (over > 0) save_png(s.out + "/10_tubes_diff_" + view + ".png", diff_heatmap(image, volumes_image, 8));
      PassMetrics metrics;
      const Measurement m = measure(metrics, [&] { whole.render(camera, output, settings, 1.f / 60.f, true, &metrics); },
                                    {.frames = s.frames});
      double neon = 0, local = 0;
      for (const PassMeasurement& p : m.passes) {
        if (p.name.rfind("neon:", 0) == 0) neon += p.mean_ms;
        if (p.name.rfind("local lights:", 0) == 0) local += p.mean_ms;
      }
      const char* name = tubes == TubeLight::Volumes ? "volumes" : "clusters";
      csv << view << ',' << name << ',' << neon << ',' << local << ',' << neon + local << ',' << m.total_ms() << ','
          << e.max_error << ',' << e.mean_error << ',' << over << ',' << worst_x << ',' << worst_y << ','
          << csv_measure_values(s.renderer, w, h, m.frames) << '\n';
      std::cout << "  tubes " << view << " " << name << ": neon " << neon << " ms, local lights " << local << " ms, frame "
                << m.total_ms() << " ms; against the volumes max " << e.max_error << " steps" << std::endl;
    }
  }
  std::cout << "wrote " << path << '\n';
}
// [/tubes-sweep]

// [whole-msaa-sweep]
// --part whole-msaa: the shop street's whole frame with every stage at its default, at 1, 4 and
// 8 samples (those the renderer makes): the frame's time, MSAA's passes, the sun's map, the glass, the
// pixels marked, the bytes held, and which stages ran (plan(): with MSAA some are not run yet).
void sweep_whole_msaa(const Settings& s, bool software) {
  const int w = s.msaa_width ? s.msaa_width : software ? 320 : 1920;
  const int h = s.msaa_height ? s.msaa_height : software ? 180 : 1080;
  const std::string path = s.out + (software ? "/10_whole_msaa_llvmpipe.csv" : "/10_whole_msaa.csv");
  std::ofstream csv(path);
  csv << "# " << (software ? "llvmpipe CPU time: " : "GPU time: ") << s.renderer << ", " << w << "x" << h
      << "; the shop street's whole frame (view shops), every stage at its default, --msaa 1, 4, 8\n"
      << "# ms: mean of " << s.frames << " frames; msaa_ms: the passes named msaa: (G-buffer, edges, light, resolve); "
         "shadow_ms: the sun's map; glass_ms: the passes named transparency: (with MSAA into the samples); "
         "marked: pixels lit per sample; stages_run: of the plan's lines; not_run: '+'-separated\n"
      << "msaa,total_ms,msaa_ms,shadow_ms,glass_ms,marked,marked_fraction,allocated_mb,stages_run,not_run," << csv_measure_columns()
      << "\n";
  const Scene scene = load_scene(from_root("assets/street_shop/street_shop.gltf"));
  WholeFrame whole(scene);
  OutputTarget target(w, h);
  const ch03::FrameOutput output{target.framebuffer(), w, h};
  const FrameCamera camera = frame_camera(scene.camera("shops"), float(w) / float(h));
  GLint max_samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  for (const int samples : {1, 4, 8}) {
    if (samples > max_samples) {
      std::cout << "  whole frame --msaa " << samples << ": this renderer makes at most " << max_samples << ", left out\n";
      continue;
    }
    WholeFrameSettings settings;
    settings.msaa = samples;
    whole.render(camera, output, settings, 1.f / 60.f, true);  // counts (no metrics); the eye adapted
    const std::uint64_t marked = whole.msaa() ? whole.msaa()->counts().marked : 0;
    int runs = 0;
    std::string not_run;
    for (const PlannedStage& st : whole.plan(settings)) {
      runs += st.runs;
      if (!st.runs) not_run += (not_run.empty() ? "" : "+") + st.stage.substr(0, st.stage.find(" ("));
    }
    std::replace(not_run.begin(), not_run.end(), ',', ';');
    PassMetrics metrics;
    const Measurement m = measure(metrics, [&] { whole.render(camera, output, settings, 1.f / 60.f, false, &metrics); },
                                  {.frames = s.frames});
    double msaa_ms = 0, shadow_ms = 0, glass_ms = 0;
    for (const PassMeasurement& p : m.passes) {
      if (p.name.rfind("msaa:", 0) == 0) msaa_ms += p.mean_ms;
      if (p.name.rfind("transparency:", 0) == 0) glass_ms += p.mean_ms;
      if (p.name.rfind("shadow map:", 0) == 0) shadow_ms += p.mean_ms;
    }
    const double fraction = double(marked) / (double(w) * double(h));
    csv << samples << ',' << m.total_ms() << ',' << msaa_ms << ',' << shadow_ms << ',' << glass_ms << ',' << marked << ',' << fraction << ','
        << double(whole.allocated_bytes()) / (1024.0 * 1024.0) << ',' << runs << ',' << not_run << ','
        << csv_measure_values(s.renderer, w, h, m.frames) << '\n';
    std::cout << "  whole frame --msaa " << samples << ": " << m.total_ms() << " ms (msaa passes " << msaa_ms
              << " ms, sun's map " << shadow_ms << " ms, glass " << glass_ms << " ms), " << marked << " pixels marked, " << runs << " stages run"
              << std::endl;
  }
  std::cout << "wrote " << path << '\n';
}
// [/whole-msaa-sweep]

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  return run_sweep(argc, argv, "10_frame_sweep", [&](SweepArgs& args) {
    args.text("--out", s.out).size("--size", s.width, s.height).integer("--frames", s.frames).integer("--layers", s.max_layers)
        .text("--part", s.part).size("--msaa-size", s.msaa_width, s.msaa_height).size("--tubes-size", s.tubes_width, s.tubes_height);
  }, [&] {
    if (s.frames < 1) throw UsageError("--frames must be at least 1");
    if (s.max_layers < 1 || s.max_layers > 128) throw UsageError("--layers must be between 1 and 128");
    if (s.part != "all" && s.part != "transparency" && s.part != "msaa" && s.part != "tubes" && s.part != "whole-msaa")
      throw UsageError("--part must be all, transparency, msaa, tubes or whole-msaa (got '" + s.part + "')");
    std::filesystem::create_directories(s.out);
    auto context = Context::create({.headless = true, .width = s.width, .height = s.height});
    s.renderer = context->renderer();
    const std::string timer = (context->is_software() ? "llvmpipe CPU time: " : "GPU time: ") + context->renderer();
    std::cout << timer << '\n';
    if (s.part == "all" || s.part == "transparency") {
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
    }
    if (s.part == "all" || s.part == "msaa") sweep_msaa(s, context->is_software());
    if (s.part == "all" || s.part == "tubes") sweep_tubes(s, context->is_software());
    if (s.part == "all" || s.part == "whole-msaa") sweep_whole_msaa(s, context->is_software());
  });
}
