// Chapter 11's sweep: a camera path of the scene played with no AA and with TAA (and TAA with
// each of its parts switched off), each frame measured against its supersampled truth
// (measure.h: 16 frames on a 4x4 grid of jitter, without history, averaged): the error overall
// and on edges, ghosting (on pixels disoccluded in the last 4 frames) and flicker (change from
// the last frame where the truth changed less than an 8-bit step). Then the cost: each pass's
// time (the one measurement, common/measure.h) of the frame with and without TAA at the path's
// first view. Writes <out>/11_path_<scene>_<path>[_llvmpipe].csv and
// <out>/11_cost[_llvmpipe].csv; llvmpipe's times are CPU times and the file says so. `--ao`
// and `--gi` add chapter 07's AO and chapter 08's AO and indirect light along the path, per
// frame and accumulated (sweep_ao, sweep_gi), `--shadows` chapter 06's PCSS for the sun
// (sweep_shadows); `--no-path` leaves out the TAA variants. The
// error over the path's frames as a plot:
//   tools/plot.py --csv out/11_temporal/11_path_street_shop_walk_llvmpipe.csv --x frame
//                 --y edge_error --group method --title "Edge error along the walk" --out walk.svg
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "chapters/06_shadows/shadow_truth.h"
#include "chapters/11_temporal/camera_path.h"
#include "chapters/11_temporal/measure.h"
#include "chapters/11_temporal/temporal_frame.h"
#include "common/context.h"
#include "common/error.h"
#include "common/measure.h"
#include "common/paths.h"
#include "common/sweep.h"
#include "common/target.h"

namespace {

using namespace lp;
using namespace lp::ch11;

struct Settings {
  std::string out = (source_root() / "out" / "11_temporal").string();
  std::string scene = "assets/street_shop/street_shop.gltf";
  std::string path = "walk";
  int width = 160, height = 90;
  int first = 0, count = -1;  // the path's frames measured; -1: to its end
  int frames = 10;            // the cost's measured frames
  std::string methods;        // a ';'-separated list of variant names; empty: all
  std::string dump;           // non-empty: each measured frame and its truth as PNGs under this prefix
  bool no_cost = false;       // the path only
  bool no_path = false;       // not the TAA path (with --ao or --gi: those alone)
  std::string truth_dir;      // non-empty: the truths kept there as PFM between runs
  bool ao = false;            // also chapter 07's AO along the path, per frame and accumulated
  int ao_width = 0, ao_height = 0;  // its size (0: --size)
  bool gi = false;            // also chapter 08's AO and indirect light along the path, per frame and accumulated
  bool shadows = false;       // also chapter 06's PCSS for the sun along the path, per frame and accumulated
  int shadows_width = 0, shadows_height = 0;  // --shadows' error measured at this size (0: --size)
  int gi_width = 0, gi_height = 0;  // its size (0: --size)
};

bool chosen(const Settings& s, const std::string& name) {
  if (s.methods.empty()) return true;
  std::size_t start = 0;
  while (start <= s.methods.size()) {
    const std::size_t end = std::min(s.methods.find(';', start), s.methods.size());
    if (s.methods.substr(start, end - start) == name) return true;
    start = end + 1;
  }
  return false;
}

// [variants]
struct Variant {
  std::string name;
  TemporalSettings settings;
};
std::vector<Variant> variants() {
  TemporalSettings base;
  base.whole.hdr.adaptation.tau = 0.f;  // the truth's frames are each a new shot: the eye adapts at once in both
  std::vector<Variant> v;
  v.push_back({"no AA", base});
  v.back().settings.taa.enabled = false;
  v.push_back({"TAA", base});
  v.push_back({"TAA, no disocclusion test", base});
  v.back().settings.taa.reject_disocclusion = false;
  v.push_back({"TAA, relative depth test", base});  // no slack for the surface's slope (step 6)
  v.back().settings.taa.depth_slope = 0.f;
  v.push_back({"TAA, no clip", base});
  v.back().settings.taa.clip = HistoryClip::Off;
  v.push_back({"TAA, RGB clamp", base});
  v.back().settings.taa.clip = HistoryClip::ClampRgb;
  v.push_back({"TAA, bilinear history", base});
  v.back().settings.taa.filter = HistoryFilter::Bilinear;
  v.push_back({"TAA, linear blend", base});
  v.back().settings.taa.tonemapped = false;
  v.push_back({"TAA, pixel as sampled", base});
  v.back().settings.taa.unjitter = false;
  v.push_back({"TAA, extremes' box", base});
  v.back().settings.taa.gamma = 0.f;
  v.push_back({"TAA, this frame's box alone", base});  // no remembered box (thin geometry, hard cases)
  v.back().settings.taa.box_memory = 0;
  v.push_back({"TAA, one weight", base});
  v.back().settings.taa.alpha_moving = base.taa.alpha;
  v.push_back({"this frame rebuilt, no history", base});  // what the history adds, over the rebuilt pixel
  v.back().settings.taa.alpha = v.back().settings.taa.alpha_moving = 1.f;
  // The eye adapted on the path's first frame and held there: flicker without chapter 05's
  // exposure following each frame (the truths, each a new shot, adapt as before).
  v.push_back({"no AA, exposure held", v[0].settings});
  v.back().settings.whole.hdr.adaptation.tau = 1e9f;
  v.push_back({"TAA, exposure held", base});
  v.back().settings.whole.hdr.adaptation.tau = 1e9f;
  return v;
}
// [/variants]

void sweep_path(const Settings& s, const SceneGpu& gpu, const std::string& renderer, bool software) {
  const CameraPath& path = path_named(s.scene, s.path);
  const std::string stem = std::filesystem::path(s.scene).stem().string();
  const std::string file = s.out + "/11_path_" + stem + "_" + s.path + (software ? "_llvmpipe" : "") + ".csv";
  std::ofstream csv(file);
  csv << "# " << renderer << ", " << s.width << "x" << s.height << ", path " << s.path << " of " << stem << " at " << path.fps
      << " fps; errors: mean |image - truth| of sRGB values in [0, 1] (an 8-bit step is 0.0039)\n"
      << "# truth: 16 frames on a 4x4 grid of jitter, no history, averaged in linear light\n"
      << "method,frame,cut,error,edge_error,edge_pixels,ghost_error,ghost_pixels,flicker,still_pixels," << csv_measure_columns()
      << "\n";
  const std::string conv_file = s.out + "/11_convergence_" + stem + "_" + s.path + (software ? "_llvmpipe" : "") + ".csv";
  std::ofstream conv(conv_file);
  conv << "# " << renderer << ", " << s.width << "x" << s.height << ", path " << s.path << " of " << stem
       << "; error on the pixels disoccluded exactly k frames ago, pooled over the path's frames (0: this frame)\n"
       << "method,frames_since,error,pixels\n";
  std::vector<ImageF> truths;  // one truth per frame, for every variant
  for (const Variant& v : variants()) {
    if (!chosen(s, v.name)) continue;
    std::string dump;
    if (!s.dump.empty()) {
      dump = s.dump + v.name + "_";
      for (char& c : dump) if (c == ' ' || c == ',') c = '_';
    }
    const std::vector<PathFrame> frames = measure_path(
        gpu, path, v.settings, {.width = s.width, .height = s.height, .first = s.first, .count = s.count, .dump_prefix = dump,
                   .truths = &truths, .truth_dir = s.truth_dir});
    double edge = 0;
    for (const PathFrame& f : frames) {
      csv << csv_quoted(v.name) << ',' << f.frame << ',' << int(f.cut) << ',' << f.error << ',' << f.edge_error << ','
          << f.edge_pixels << ',' << f.ghost_error << ',' << f.ghost_pixels << ',' << f.flicker << ',' << f.still_pixels << ','
          << csv_measure_values(renderer, s.width, s.height, 1) << '\n';
      edge += f.edge_error;
    }
    // Pooled: each frame's mean weighed by its pixel count.
    for (std::size_t k = 0; !frames.empty() && k < frames[0].since_error.size(); ++k) {
      double sum = 0;
      std::size_t n = 0;
      for (const PathFrame& f : frames) {
        sum += f.since_error[k] * double(f.since_pixels[k]);
        n += f.since_pixels[k];
      }
      conv << csv_quoted(v.name) << ',' << k << ',' << (n ? sum / double(n) : 0.0) << ',' << n << '\n';
    }
    std::cout << v.name << ": mean edge error " << (frames.empty() ? 0.0 : edge / double(frames.size())) << " over "
              << frames.size() << " frames\n";
  }
  std::cout << "wrote " << file << " and " << conv_file << '\n';
}

// The errors of a path's frames pooled by frames since a disocclusion (the frames' since_error
// and since_pixels), one CSV row per k for `name`.
template <class PathFrames>
void write_convergence(std::ostream& conv, const char* name, const PathFrames& frames) {
  for (std::size_t k = 0; !frames.empty() && k < frames[0].since_error.size(); ++k) {
    double e = 0;
    std::size_t n = 0;
    for (const auto& f : frames) {
      e += f.since_error[k] * double(f.since_pixels[k]);
      n += f.since_pixels[k];
    }
    conv << csv_quoted(name) << ',' << k << ',' << (n ? e / double(n) : 0.0) << ',' << n << '\n';
  }
}

// The whole frame with `t` (no TAA) played along the path at --size, each pass's time as a CSV
// row for `name`.
void write_path_cost(std::ostream& cost, const char* name, const Settings& s, const SceneGpu& gpu, const CameraPath& path,
                     const TemporalSettings& t, const std::string& renderer) {
  TemporalFrame frame(gpu);
  OutputTarget target(s.width, s.height);
  PassMetrics metrics;
  int i = 0;
  const Measurement measured = measure(metrics, [&] {
    const int k = i++ % path.frames();
    frame.render(frame_camera(path.camera(gpu.scene(), k), float(s.width) / float(s.height)),
                 {target.framebuffer(), s.width, s.height}, t, 1.f / path.fps, path.cut_at(k), &metrics);
  }, {.frames = s.frames});
  for (const PassMeasurement& p : measured.passes)
    cost << csv_quoted(name) << ',' << csv_quoted(p.name) << ',' << p.mean_ms << ',' << p.min_ms << ','
         << csv_measure_values(renderer, s.width, s.height, measured.frames) << '\n';
}

// [ao-sweep]
// Chapter 07's classic AO along the path against its ray-traced truth: 4 points a frame alone,
// the same 4 points a frame accumulated (temporal_ao.h: a part of a 32-point kernel a frame),
// and 32 points a frame alone. Writes 11_ao_<scene>_<path>[_llvmpipe].csv (per frame) and
// 11_ao_convergence_<scene>_<path>[_llvmpipe].csv (error against frames since a disocclusion).
void sweep_ao(const Settings& s, const SceneGpu& gpu, const std::string& renderer, bool software) {
  const CameraPath& path = path_named(s.scene, s.path);
  const int w = s.ao_width > 0 ? s.ao_width : s.width, h = s.ao_height > 0 ? s.ao_height : s.height;
  const std::string stem = std::filesystem::path(s.scene).stem().string(), tail = stem + "_" + s.path + (software ? "_llvmpipe" : "") + ".csv";
  std::ofstream csv(s.out + "/11_ao_" + tail), conv(s.out + "/11_ao_convergence_" + tail);
  csv << "# " << renderer << ", " << w << "x" << h << ", path " << s.path << " of " << stem
      << "; chapter 07's classic AO (R 0.5, blurred) against its ray-traced truth (256 rays a pixel): mean |A - truth|\n"
      << "method,frame,error," << csv_measure_columns() << '\n';
  conv << "# " << renderer << ", " << w << "x" << h << ", path " << s.path << " of " << stem
       << "; AO error on the pixels disoccluded exactly k frames ago, pooled over the path's frames\n"
       << "method,frames_since,error,pixels\n";
  ch07::AoSettings four;
  four.samples = 4;
  ch07::AoSettings many = four;
  many.samples = 32;
  TemporalAoSettings on, off;
  off.enabled = false;
  const struct {
    const char* name;
    ch07::AoSettings ao;
    TemporalAoSettings temporal;
  } methods[] = {{"4 points a frame", four, off}, {"4 points accumulated", four, on}, {"32 points a frame", many, off}};
  for (const auto& m : methods) {
    const std::vector<AoPathFrame> frames =
        measure_ao_path(gpu, path, m.ao, m.temporal, {.width = w, .height = h, .first = s.first, .count = s.count});
    double sum = 0;
    for (const AoPathFrame& f : frames) {
      csv << csv_quoted(m.name) << ',' << f.frame << ',' << f.error << ',' << csv_measure_values(renderer, w, h, 1) << '\n';
      sum += f.error;
    }
    write_convergence(conv, m.name, frames);
    std::cout << m.name << ": mean AO error " << (frames.empty() ? 0.0 : sum / double(frames.size())) << " over "
              << frames.size() << " frames\n";
  }
  std::cout << "wrote " << s.out << "/11_ao_" << tail << " and " << s.out << "/11_ao_convergence_" << tail << '\n';
}
// [/ao-sweep]

// [gi-sweep]
// Chapter 08's pass along the path against the ray-traced truths: 4 samples a frame alone, the
// same 4 accumulated (temporal_gi.h: a part of a 32-point pattern a frame, turned), and 32 a
// frame alone. Writes 11_gi_<scene>_<path>[_llvmpipe].csv (per frame: the indirect light
// against the screen-limited truth and the full one, the AO against chapter 07's),
// 11_gi_convergence_... (the indirect light's error against frames since a disocclusion) and
// 11_gi_cost_... (each pass's time in the whole frame at --size, along the path).
void sweep_gi(const Settings& s, const SceneGpu& gpu, const std::string& renderer, bool software) {
  const CameraPath& path = path_named(s.scene, s.path);
  const int w = s.gi_width > 0 ? s.gi_width : s.width, h = s.gi_height > 0 ? s.gi_height : s.height;
  const std::string stem = std::filesystem::path(s.scene).stem().string(), tail = stem + "_" + s.path + (software ? "_llvmpipe" : "") + ".csv";
  std::ofstream csv(s.out + "/11_gi_" + tail), conv(s.out + "/11_gi_convergence_" + tail), cost(s.out + "/11_gi_cost_" + tail);
  csv << "# " << renderer << ", " << w << "x" << h << ", path " << s.path << " of " << stem
      << "; chapter 08's pass (randomised, blurred) against the ray-traced truths (256 rays a pixel): mean |L1_ind - truth| "
         "(screen-limited and full), mean |A - truth| (chapter 07's)\n"
      << "method,frame,error_screen,error_full,ao_error," << csv_measure_columns() << '\n';
  conv << "# " << renderer << ", " << w << "x" << h << ", path " << s.path << " of " << stem
       << "; indirect light's error (screen-limited truth) on the pixels disoccluded exactly k frames ago, pooled over the path's frames\n"
       << "method,frames_since,error,pixels\n";
  cost << "# " << (software ? "llvmpipe CPU time (glFinish around each pass): " : "GPU time: ") << renderer << ", " << s.width
       << "x" << s.height << ", the whole frame along path " << s.path << "; each pass's mean and fastest ms\n"
       << "method,pass,ms,min_ms," << csv_measure_columns() << '\n';
  ch08::GiSettings four;
  four.samples = 4;
  ch08::GiSettings many;
  TemporalGiSettings on, off;
  on.enabled = true;
  const struct {
    const char* name;
    ch08::GiSettings gi;
    TemporalGiSettings temporal;
  } methods[] = {{"4 samples a frame", four, off}, {"4 samples accumulated", four, on}, {"32 samples a frame", many, off}};
  for (const auto& m : methods) {
    const GiPathOptions o{.width = w, .height = h, .first = s.first, .count = s.count};
    GiPathOptions full = o;
    full.screen_limited = false;
    full.ao_truth = true;
    const std::vector<GiPathFrame> screen = measure_gi_path(gpu, path, m.gi, m.temporal, o);
    const std::vector<GiPathFrame> frames = measure_gi_path(gpu, path, m.gi, m.temporal, full);
    double sum = 0;
    for (std::size_t k = 0; k < frames.size(); ++k) {
      csv << csv_quoted(m.name) << ',' << frames[k].frame << ',' << screen[k].error << ',' << frames[k].error << ','
          << frames[k].ao_error << ',' << csv_measure_values(renderer, w, h, 1) << '\n';
      sum += screen[k].error;
    }
    write_convergence(conv, m.name, screen);
    if (!s.dump.empty() && !frames.empty()) {
      // The last frame's AO (its occlusion 1 - A times 4, as grey from white) beside its indirect
      // light (times 16, clamped), for the book.
      const ImageF& g = frames.back().gi;
      ImageF picture = ImageF::blank(2 * w, h, 3);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < 3; ++c) {
            picture.at(x, y, c) = std::max(0.f, 1.f - 4.f * (1.f - g.at(x, y, 3)));
            picture.at(w + x, y, c) = std::min(1.f, 16.f * g.at(x, y, c));
          }
      std::string name = m.name;
      std::replace(name.begin(), name.end(), ' ', '_');
      save_png(s.dump + "gi_" + name + ".png", to_srgb8(picture));
      std::cout << "wrote " << s.dump << "gi_" << name << ".png\n";
    }
    std::cout << m.name << ": mean indirect error (screen-limited truth) " << (screen.empty() ? 0.0 : sum / double(screen.size()))
              << " over " << screen.size() << " frames\n";
    // The cost: the whole frame (no TAA) with this pass, along the path.
    TemporalSettings t;
    t.taa.enabled = false;
    t.whole.gi = m.gi;
    t.gi = m.temporal;
    t.gi.samples = m.gi.samples;
    write_path_cost(cost, m.name, s, gpu, path, t, renderer);
  }
  std::cout << "wrote " << s.out << "/11_gi_" << tail << ", " << s.out << "/11_gi_convergence_" << tail << " and " << s.out
            << "/11_gi_cost_" << tail << '\n';
}
// [/gi-sweep]

void sweep_cost(const Settings& s, const SceneGpu& gpu, const std::string& renderer, bool software) {
  const CameraPath& path = path_named(s.scene, s.path);
  const std::string file = s.out + "/11_cost" + std::string(software ? "_llvmpipe" : "") + ".csv";
  std::ofstream csv(file);
  csv << "# " << (software ? "llvmpipe CPU time (glFinish around each pass): " : "GPU time: ") << renderer << ", " << s.width
      << "x" << s.height << "; each pass's mean and fastest ms\n"
      << "method,pass,ms,min_ms," << csv_measure_columns() << '\n';
  OutputTarget target(s.width, s.height);
  for (const Variant& v : variants()) {
    if ((v.name != "no AA" && v.name != "TAA") || !chosen(s, v.name)) continue;
    TemporalFrame frame(gpu);
    PassMetrics metrics;
    int i = 0;
    const Measurement m = measure(metrics, [&] {
      const int k = i++ % path.frames();
      frame.render(frame_camera(path.camera(gpu.scene(), k), float(s.width) / float(s.height)),
                   {target.framebuffer(), s.width, s.height}, v.settings, 1.f / path.fps, path.cut_at(k), &metrics);
    }, {.frames = s.frames});
    for (const PassMeasurement& p : m.passes)
      csv << csv_quoted(v.name) << ',' << csv_quoted(p.name) << ',' << p.mean_ms << ',' << p.min_ms << ','
          << csv_measure_values(renderer, s.width, s.height, m.frames) << '\n';
  }
  std::cout << "wrote " << file << '\n';
}

// [shadows-sweep]
// Chapter 06's PCSS for the sun along the path against its ray-traced soft visibility (64 rays a
// pixel): a 4-tap disk a frame alone, 4 taps of the 32-tap disk accumulated (temporal_shadows.h:
// a part a frame, turned), and the 32 a frame alone. Writes 11_shadows_<scene>_<path>[_llvmpipe].csv
// (per frame: mean |V - truth| where the sun reaches), 11_shadows_convergence_... (against frames
// since a disocclusion) and 11_shadows_cost_... (each pass's time in the whole frame at --size,
// along the path); with --dump, the last frame's visibility of each beside the truth.
void sweep_shadows(const Settings& s, const SceneGpu& gpu, const std::string& renderer, bool software) {
  const CameraPath& path = path_named(s.scene, s.path);
  const int w = s.shadows_width > 0 ? s.shadows_width : s.width, h = s.shadows_height > 0 ? s.shadows_height : s.height;
  const std::string stem = std::filesystem::path(s.scene).stem().string(), tail = stem + "_" + s.path + (software ? "_llvmpipe" : "") + ".csv";
  std::ofstream csv(s.out + "/11_shadows_" + tail), conv(s.out + "/11_shadows_convergence_" + tail),
      cost(s.out + "/11_shadows_cost_" + tail);
  csv << "# " << renderer << ", " << w << "x" << h << ", path " << s.path << " of " << stem
      << "; chapter 06's PCSS for the sun against its ray-traced soft visibility (64 rays a pixel): mean |V - truth| where "
         "the sun reaches\n"
      << "method,frame,error," << csv_measure_columns() << '\n';
  conv << "# " << renderer << ", " << w << "x" << h << ", path " << s.path << " of " << stem
       << "; the visibility's error on the pixels disoccluded exactly k frames ago, pooled over the path's frames\n"
       << "method,frames_since,error,pixels\n";
  cost << "# " << (software ? "llvmpipe CPU time (glFinish around each pass): " : "GPU time: ") << renderer << ", " << s.width
       << "x" << s.height << ", the whole frame with PCSS along path " << s.path << "; each pass's mean and fastest ms\n"
       << "method,pass,ms,min_ms," << csv_measure_columns() << '\n';
  const ch06::ShadowSettings many{.method = ch06::ShadowMethod::Pcss};
  ch06::ShadowSettings four = many;
  four.poisson_taps = 4;
  TemporalShadowSettings on, off;
  off.enabled = false;
  const struct {
    const char* name;
    ch06::ShadowSettings shadows;
    TemporalShadowSettings temporal;
  } methods[] = {{"4 taps a frame", four, off}, {"4 taps accumulated", many, on}, {"32 taps a frame", many, off}};
  std::vector<ImageF> last;
  for (const auto& m : methods) {
    const std::vector<ShadowPathFrame> frames =
        measure_shadow_path(gpu, path, m.shadows, m.temporal, {.width = w, .height = h, .first = s.first, .count = s.count});
    double sum = 0;
    for (const ShadowPathFrame& f : frames) {
      csv << csv_quoted(m.name) << ',' << f.frame << ',' << f.error << ',' << csv_measure_values(renderer, w, h, 1) << '\n';
      sum += f.error;
    }
    write_convergence(conv, m.name, frames);
    if (!frames.empty()) last.push_back(frames.back().visibility);
    std::cout << m.name << ": mean visibility error " << (frames.empty() ? 0.0 : sum / double(frames.size())) << " over "
              << frames.size() << " frames\n";
    if (s.no_cost) continue;
    // The cost: the whole frame (no TAA) with this PCSS, along the path.
    TemporalSettings t;
    t.taa.enabled = false;
    t.pcss = true;
    t.pcss_taps = m.shadows.poisson_taps;
    t.shadows = m.temporal;
    write_path_cost(cost, m.name, s, gpu, path, t, renderer);
  }
  if (!s.dump.empty() && last.size() == 3) {
    // The last frame's visibility of each method beside the truth, as grey, labelled.
    const int end = s.count < 0 ? path.frames() : std::min(path.frames(), s.first + s.count);
    const FrameCamera camera = frame_camera(path.camera(gpu.scene(), end - 1), float(w) / float(h));
    const RayScene rays(gpu.scene());
    const ImageF truth = ch06::cached_shadow_truth(gpu.scene(), rays, camera, w, h,
                                                   gpu.scene().lights[std::size_t(ch06::shadowed_sun(gpu.scene()))].direction);
    ImageF picture = ImageF::blank(4 * w, h, 3);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) {
          for (int k = 0; k < 3; ++k) picture.at(k * w + x, y, c) = last[std::size_t(k)].at(x, y, 0);
          picture.at(3 * w + x, y, c) = truth.at(x, y, 2) > 0.5f ? truth.at(x, y, 1) : 1.f;
        }
    ImageRGBA8 out = to_srgb8(picture);
    const char* labels[] = {"4 taps", "4 accumulated", "32 taps", "ray-traced"};
    for (int k = 0; k < 4; ++k) draw_label(out, k * w + 4, 4, labels[k]);
    save_png(s.dump + "shadows_" + s.path + ".png", out);
    std::cout << "wrote " << s.dump << "shadows_" << s.path << ".png\n";
  }
  std::cout << "wrote " << s.out << "/11_shadows_" << tail << ", " << s.out << "/11_shadows_convergence_" << tail << " and "
            << s.out << "/11_shadows_cost_" << tail << '\n';
}
// [/shadows-sweep]

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  return run_sweep(argc, argv, "11_temporal_sweep", [&](SweepArgs& args) {
    args.text("--out", s.out).text("--scene", s.scene).text("--path", s.path).size("--size", s.width, s.height)
        .integer("--first", s.first).integer("--count", s.count).integer("--frames", s.frames)
        .text("--methods", s.methods).text("--dump", s.dump).flag("--no-cost", s.no_cost)
        .text("--truth-dir", s.truth_dir).flag("--ao", s.ao).size("--ao-size", s.ao_width, s.ao_height)
        .flag("--gi", s.gi).size("--gi-size", s.gi_width, s.gi_height).flag("--no-path", s.no_path)
        .flag("--shadows", s.shadows).size("--shadows-size", s.shadows_width, s.shadows_height);
  }, [&] {
    if (s.frames < 1) throw UsageError("--frames must be at least 1");
    if (s.first < 0 || s.first > 100000) throw UsageError("--first must be between 0 and 100000");
    if (s.count < -1 || s.count > 100000) throw UsageError("--count must be -1 (to the end) or between 0 and 100000");
    // Every name in --methods must be a variant: a typo would otherwise measure nothing, silently.
    for (std::size_t start = 0; !s.methods.empty() && start <= s.methods.size();) {
      const std::size_t end = std::min(s.methods.find(';', start), s.methods.size());
      const std::string name = s.methods.substr(start, end - start);
      bool known = false;
      std::string names;
      for (const Variant& v : variants()) {
        known = known || v.name == name;
        names += (names.empty() ? "" : "; ") + v.name;
      }
      if (!known) throw UsageError("--methods: no variant named '" + name + "' (the variants: " + names + ")");
      start = end + 1;
    }
    std::filesystem::create_directories(s.out);
    if (!s.truth_dir.empty()) std::filesystem::create_directories(s.truth_dir);
    auto context = Context::create({.headless = true, .width = s.width, .height = s.height});
    const Scene scene = load_scene(from_root(s.scene));
    path_named(s.scene, s.path);  // an unknown path says so before anything is drawn
    const SceneGpu gpu(scene);
    if (!s.no_path) sweep_path(s, gpu, context->renderer(), context->is_software());
    if (s.gi) sweep_gi(s, gpu, context->renderer(), context->is_software());
    if (s.ao) sweep_ao(s, gpu, context->renderer(), context->is_software());
    if (s.shadows) sweep_shadows(s, gpu, context->renderer(), context->is_software());
    if (!s.no_cost) sweep_cost(s, gpu, context->renderer(), context->is_software());
  });
}
