// Chapter 06's measurements: every shadow method x setting on the atrium's views, its cost
// (the depth pass, the pre-filter, and the global pass that does the lookups; common/measure.h:
// warm-up until the times settle, then --frames frames) and its error against the ray-traced
// hard and soft truths (shadow_truth.h), and over the penumbra and in full shadow
// (shadow_metrics.h). Writes book/figures/06_shadows.csv on a GPU,
// 06_shadows_llvmpipe.csv on llvmpipe (CPU times); every row names the renderer, the size
// and the frames measured.
//
//   06_shadows_sweep [--out DIR] [--size WxH] [--frames N] [--truth-samples N]
//                    [--only main|pcf|moments|volumes|pcss|cascades|msm|points|atlas]
//   -> DIR/06_shadows.csv, and 06_shadows_moments.csv: VSM and ESM with the filtered map in
//      RG32F and in RG16F (..._llvmpipe.csv on llvmpipe); --only pcf: the main CSV's PCF rows
//      alone (the grid and the Poisson disk) into 06_shadows_pcf.csv; 06_shadows_pcss.csv:
//      PCSS against the fixed PCF kernels on three views, and at three sun sizes (each against
//      the soft truth of its own sun); 06_shadows_cascades.csv: cascaded maps on the street
//      (chapter 03's street, its moon alone), error by cascade count and map size, and shimmer
//      as the camera steps, with and without snapping; 06_shadows_msm.csv: moment shadow maps
//      against VSM and ESM on the atrium's views: light leaking, error, cost and bytes;
//      06_shadows_points.csv: the atrium's point lights from cube maps, hard and PCF, by the
//      number that cast and the face size; 06_shadows_atlas.csv: marked spot lights in the
//      atlas, hard and PCF, by the number of tiles and the atlas size (each row's seconds
//      printed: --size 1920x1080 --only points, then --only atlas, are what the book's Pareto
//      plots of them read, as 06_shadows_points_1080p_h200.csv and 06_shadows_atlas_1080p_h200.csv)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/06_shadows/shadow_metrics.h"
#include "chapters/06_shadows/shadow_stage.h"
#include "chapters/06_shadows/shadow_truth.h"
#include "common/context.h"
#include "common/error.h"
#include "common/measure.h"
#include "common/paths.h"
#include "common/sweep.h"
#include "common/target.h"

namespace {

using namespace lp;
using namespace lp::ch06;

struct Settings {
  std::string out = (source_root() / "book" / "figures").string();
  int width = 640, height = 360;
  int frames = 10;
  int truth_samples = 64;
  std::string only;  // main | pcf | moments: one CSV (pcf: the main one's PCF rows, in a file of their own)
};

struct Variant {
  std::string setting;  // what the row varies, as the book names it
  ShadowSettings shadow;
};

std::vector<Variant> variants() {
  std::vector<Variant> v;
  for (int n : {256, 512, 1024, 2048}) v.push_back({"map " + std::to_string(n), {.method = ShadowMethod::Hard, .map_size = n}});
  for (int k : {3, 5, 7}) v.push_back({"kernel " + std::to_string(k), {.method = ShadowMethod::Pcf, .kernel = k}});
  v.push_back({"map 2048 kernel 5", {.method = ShadowMethod::Pcf, .map_size = 2048, .kernel = 5}});
  // the rotated Poisson disk over the same footprints, with fewer taps than the grid's k^2
  for (auto [taps, k] : {std::pair{8, 3}, std::pair{16, 5}, std::pair{32, 7}})
    v.push_back({"poisson " + std::to_string(taps) + " kernel " + std::to_string(k),
                 {.method = ShadowMethod::Pcf, .kernel = k, .poisson_taps = taps}});
  for (int k : {1, 3, 5}) v.push_back({"kernel " + std::to_string(k), {.method = ShadowMethod::PcfHardware, .kernel = k}});
  for (int k : {3, 5, 7}) v.push_back({"kernel " + std::to_string(k), {.method = ShadowMethod::Vsm, .kernel = k}});
  for (float p : {0.f, 0.4f, 0.6f}) v.push_back({"pmin " + std::to_string(p).substr(0, 3), {.method = ShadowMethod::Vsm, .p_min = p}});
  v.push_back({"map 2048 kernel 5", {.method = ShadowMethod::Vsm, .map_size = 2048, .kernel = 5}});
  for (int k : {3, 5, 7}) v.push_back({"kernel " + std::to_string(k), {.method = ShadowMethod::Esm, .kernel = k}});
  for (float c : {40.f, 300.f, 1000.f}) v.push_back({"c " + std::to_string(int(c)), {.method = ShadowMethod::Esm, .c = c}});
  v.push_back({"map 2048 kernel 5", {.method = ShadowMethod::Esm, .map_size = 2048, .kernel = 5}});
  // PCSS for the soft truth's sun: the taps of its search and of its filter
  for (int taps : {16, 32, 64}) v.push_back({"taps " + std::to_string(taps), {.method = ShadowMethod::Pcss, .poisson_taps = taps}});
  v.push_back({"map 2048 taps 32", {.method = ShadowMethod::Pcss, .map_size = 2048, .poisson_taps = 32}});
  // convolution shadow maps: the step's Fourier series by its terms (two channels each)
  for (int t : {2, 4, 8}) v.push_back({"terms " + std::to_string(t), {.method = ShadowMethod::CsmFourier, .csm_terms = t}});
  return v;
}

// A visibility channel as a picture: grey (white lit), blue where the sun does not reach.
ImageRGBA8 visibility_picture(const ImageF& v, int channel, const ImageF& truth) {
  ImageRGBA8 out = ImageRGBA8::blank(v.width, v.height);
  for (int y = 0; y < v.height; ++y)
    for (int x = 0; x < v.width; ++x) {
      std::uint8_t* p = out.at(x, y);
      const float g = std::clamp(v.at(x, y, channel), 0.f, 1.f);
      const bool outside = truth.at(x, y, 2) < 0.5f;
      p[0] = outside ? 89 : std::uint8_t(g * 255.f + 0.5f);  // show_visibility.frag's blue in sRGB
      p[1] = outside ? 108 : p[0];
      p[2] = outside ? 170 : p[0];
      p[3] = 255;
    }
  return out;
}
// |v - truth| over the mask, 1 = full scale.
ImageRGBA8 error_picture(const ImageF& v, const ImageF& truth, int channel) {
  std::vector<float> e(std::size_t(v.width) * std::size_t(v.height), 0.f);
  for (int y = 0; y < v.height; ++y)
    for (int x = 0; x < v.width; ++x)
      if (truth.at(x, y, 2) > 0.5f) e[std::size_t(y) * v.width + x] = std::abs(v.at(x, y, 0) - truth.at(x, y, channel));
  return error_heatmap(e, v.width, v.height, 1.f);
}

double pass_ms(const Measurement& m, const std::string& name) {
  const PassMeasurement* p = m.find(name);
  return p ? p->mean_ms : 0.0;
}

// The shimmer path: steps of 2 mm across the view (to the camera's right and a little up).
constexpr int kSteps = 8;
constexpr float kStep = 0.002f;

// [cascade-rows]
// Cascaded maps on the street (street_level looks 120 m down it), its moon alone: the 312 local
// lights are left out, the shadows measured are the moon's. Error against the truths and cost by
// cascade count and map size; then shimmer: the camera steps `kSteps` times by `kStep` metres
// (across the view: to its right and a little up), and each step's flips (shadow_truth.h [shimmer]) are counted for
// the hard method and for the truth, with the boxes snapped to whole texels and not.
void cascade_rows(const Settings& s, const std::string& renderer, bool software) {
  Scene scene = load_scene(from_root("assets/street/street.gltf"));
  std::erase_if(scene.lights, [](const Light& l) { return l.type != LightType::Directional; });
  SceneGpu gpu(scene);
  RayScene rays(scene);
  const Light& sun = find_sun(scene);
  ch03::DeferredFrame frame(gpu);
  ch03::use_lights(frame, scene, scene.lights, true);
  ShadowStage stage(gpu, sun);
  frame.add_stage(stage);
  OutputTarget image(s.width, s.height);
  ColourTarget visibility(s.width, s.height, GL_RGBA32F);
  const std::string file = s.out + (software ? "/06_shadows_cascades_llvmpipe.csv" : "/06_shadows_cascades.csv");
  std::ofstream csv(file);
  csv << "# " << (software ? "llvmpipe CPU time: " : "GPU time: ") << renderer << ", " << s.width << "x" << s.height
      << ", the street's moon alone; soft truth: sun disk " << TruthSettings{}.angular_radius << " rad, "
      << s.truth_samples << " rays per pixel; shimmer: flips per step over the pixels counted, " << kSteps
      << " steps of " << kStep * 1000 << " mm\n"
      << "view,kind,method,cascades,map,lambda,snap,bytes,near_texel_cm,depth_ms,global_ms,frame_ms,hard_wrong_pct,"
         "soft_mean,method_flips,truth_flips,flip_pixels,"
      << csv_measure_columns() << "\n";
  const std::string view = "street_level";
  const Camera base = scene.camera(view);
  const FrameCamera camera = frame_camera(base, float(s.width) / s.height);
  const ImageF truth = cached_shadow_truth(scene, rays, camera, s.width, s.height, sun.direction, {.samples = s.truth_samples});
  auto row = [&](const std::string& kind, const ShadowSettings& x, double hard_wrong, double soft_mean, const Flips& flips,
                 const Measurement* m) {
    csv << view << ',' << kind << ',' << kMethodNames[int(x.method)] << ',' << x.cascades << ',' << x.map_size << ','
        << x.cascade_lambda << ',' << x.cascade_snap << ',' << stage.allocated_bytes() << ','
        << stage.frustum().texel_world(x.map_size) * 100 << ',' << (m ? pass_ms(*m, "shadow map: depth from the sun") : 0)
        << ',' << (m ? pass_ms(*m, "global: ambient + directional (chapter 03)") : 0) << ',' << (m ? m->total_ms() : 0)
        << ',' << hard_wrong << ',' << soft_mean << ',' << flips.method << ',' << flips.truth << ',' << flips.pixels << ','
        << csv_measure_values(renderer, s.width, s.height, m ? m->frames : 0) << "\n";
  };
  // Error and cost.
  for (ShadowMethod method : {ShadowMethod::Hard, ShadowMethod::Pcf})
    for (int cascades : {1, 2, 3, 4})
      for (int map : {512, 1024, 2048}) {
        const ShadowSettings x{.method = method, .map_size = map, .cascades = cascades};
        stage.set(x, ShadowPicture::Visibility);
        frame.render(camera, {visibility.framebuffer(), s.width, s.height});
        const ImageF vis = visibility.read();
        const VisibilityError hard = visibility_error(vis, truth, 0), soft = visibility_error(vis, truth, 1);
        if (map == 1024 && method == ShadowMethod::Hard && (cascades == 1 || cascades == 4)) {
          const std::string name = s.out + "/06_street_" + std::to_string(cascades) + "_cascades";
          save_png(name + "_visibility.png", visibility_picture(vis, 0, truth));
          save_png(name + "_error.png", error_picture(vis, truth, 0));
          if (cascades == 4) {
            stage.set(x, ShadowPicture::Cascades);
            frame.render(camera, {image.framebuffer(), s.width, s.height});
            save_png(name + "_tinted.png", image.read());
            save_png(s.out + "/06_street_truth_hard.png", visibility_picture(truth, 0, truth));
          }
        }
        stage.set(x);
        PassMetrics metrics;
        const Measurement m = measure(metrics, [&] { frame.render(camera, {image.framebuffer(), s.width, s.height}, &metrics); },
                                      {.frames = s.frames});
        row("error", x, 100 * hard.wrong, soft.mean_abs, {}, &m);
        std::cout << "street " << kMethodNames[int(method)] << " cascades " << cascades << " map " << map << ": hard wrong "
                  << 100 * hard.wrong << "%, soft mean " << soft.mean_abs << ", frame " << m.total_ms() << " ms" << std::endl;
      }
  // Shimmer: the same camera path for every setting, its truths traced once.
  std::vector<FrameCamera> path;
  std::vector<ImageF> truths;
  for (int i = 0; i <= kSteps; ++i) {
    Camera c = base;
    const glm::vec3 across = glm::normalize(glm::vec3(base.world[0]) + 0.3f * glm::vec3(base.world[1]));
    c.world = glm::translate(glm::mat4(1), float(i) * kStep * across) * c.world;
    path.push_back(frame_camera(c, float(s.width) / s.height));
    truths.push_back(shadow_truth(scene, rays, path.back(), s.width, s.height, sun.direction, {.samples = 1}));
  }
  for (int cascades : {1, 4})
    for (int map : {1024, 2048})
      for (bool snap : {true, false}) {
        if (cascades == 1 && !snap) continue;  // one map has no snapping to switch
        const ShadowSettings x{.method = ShadowMethod::Hard, .map_size = map, .cascades = cascades, .cascade_snap = snap};
        Flips total;
        ImageF previous;
        for (int i = 0; i <= kSteps; ++i) {
          stage.set(x, ShadowPicture::Visibility);
          frame.render(path[std::size_t(i)], {visibility.framebuffer(), s.width, s.height});
          ImageF v = visibility.read();
          if (i > 0) {
            const Flips f = visibility_flips(previous, v, truths[std::size_t(i) - 1], truths[std::size_t(i)]);
            total.method += f.method, total.truth += f.truth, total.pixels += f.pixels;
          }
          previous = std::move(v);
        }
        row("shimmer", x, 0, 0, total, nullptr);
        std::cout << "street shimmer cascades " << cascades << " map " << map << (snap ? " snapped" : " unsnapped") << ": "
                  << total.method << " flips against the truth's " << total.truth << " over " << total.pixels
                  << " pixel-steps" << std::endl;
      }
  std::cout << "wrote " << file << '\n';
}
// [/cascade-rows]

double local_ms(const Measurement& m) {  // chapter 03's local-light pass, whatever its strategy
  double ms = 0;
  for (const PassMeasurement& p : m.passes)
    if (p.name.rfind("local lights", 0) == 0) ms += p.mean_ms;
  return ms;
}

// [local-rows]
// Point lights' cube maps and the spots' atlas on the atrium's overview: for each setting the
// lights that cast (the scene's first `count` point lights marked, or `count` of the GL test's
// four spots added and marked), each light's visibility alone against one ray per pixel toward
// it (spot_shadow_truth), over the pixels it reaches, no band: the wrong pixels and the mean
// |error| summed over the lights' pixels; the depth pass that draws the maps, chapter 03's local
// pass that looks them up, the frame, and the bytes.
void local_rows(const Settings& s, const std::string& renderer, bool software, bool spots) {
  const std::string stem = spots ? "/06_shadows_atlas" : "/06_shadows_points";
  const std::string file = s.out + stem + (software ? "_llvmpipe.csv" : ".csv");
  std::ofstream csv(file);
  csv << "# " << (software ? "llvmpipe CPU time: " : "GPU time: ") << renderer << ", " << s.width << "x" << s.height
      << ", atrium overview; " << (spots ? "spot lights in the atlas (--map texels a side)" : "point lights' cube maps")
      << "; error: each light's visibility against its ray-traced hard shadows over the pixels it reaches\n"
      << "# made by: 06_shadows_sweep --size " << s.width << "x" << s.height << " --frames " << s.frames << " --only "
      << (spots ? "atlas" : "points") << "\n"
      << "view,kind,method,lights,size,tile,bytes,maps_ms,local_ms,frame_ms,reached,hard_wrong_pct,hard_mean,"
      << csv_measure_columns() << "\n";
  // The GL test SpotAtlasGl's four spots: 3 m up in the aisle, aimed past the columns.
  auto spot = [](const std::string& name, glm::vec3 at, glm::vec3 to, float cone) {
    Light l;
    l.name = name, l.type = LightType::Spot, l.intensity = 40.f, l.position = at, l.direction = glm::normalize(to);
    l.outer_cone = cone, l.inner_cone = 0.8f * cone, l.casts_shadows = true;
    return l;
  };
  const std::vector<Light> four = {
      spot("spot_a", {1, 3, 1.5f}, {3.5f, -3, 0}, 0.8f), spot("spot_b", {-1, 3, 0.5f}, {-3.5f, -3, 1.5f}, 0.7f),
      spot("spot_c", {0.5f, 2.5f, 5}, {3, -3, -2}, 0.8f), spot("spot_d", {-1.5f, 3.5f, 7}, {-2.5f, -3, -1}, 0.9f)};
  const std::vector<int> counts = spots ? std::vector<int>{1, 2, 4} : std::vector<int>{1, 2, 4, 8};
  const std::vector<int> sizes = spots ? std::vector<int>{1024, 2048, 4096} : std::vector<int>{256, 512, 1024, 2048};
  const auto started = std::chrono::steady_clock::now();
  auto seconds_since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  for (int count : counts) {
    Scene scene = load_scene(from_root("assets/atrium/atrium.gltf"));
    int marked = 0;
    if (spots) scene.lights.insert(scene.lights.end(), four.begin(), four.begin() + count);
    else
      for (Light& l : scene.lights)
        if (l.type == LightType::Point && marked < count) l.casts_shadows = true, ++marked;
    SceneGpu gpu(scene);
    RayScene rays(scene);
    ch03::DeferredFrame frame(gpu);
    frame.volumes().set_lights(ch03::build_light_set(
        scene.lights, ch03::cut_threshold(1.f, ch03::peak_reflectance(scene)), frame.volumes().shapes()));
    ShadowStage stage(gpu, find_sun(scene));
    frame.add_stage(stage);
    OutputTarget image(s.width, s.height);
    ColourTarget visibility(s.width, s.height, GL_RGBA32F);
    const FrameCamera camera = frame_camera(scene.camera("overview"), float(s.width) / s.height);
    const std::vector<int> lights = spots ? shadowed_spot_lights(scene) : shadowed_point_lights(scene);
    if (int(lights.size()) != count) throw Error("06_shadows_sweep: " + std::to_string(lights.size()) + " lights cast, not " +
                                                 std::to_string(count));
    std::vector<ImageF> truths;
    for (int i : lights) truths.push_back(spot_shadow_truth(rays, camera, s.width, s.height, scene.lights[std::size_t(i)]));
    for (ShadowMethod method : {ShadowMethod::Hard, ShadowMethod::Pcf})
      for (int size : sizes) {
        ShadowSettings x{.method = method};
        if (spots) x.map_size = size;
        else x.cube_size = size;
        double wrong = 0, error = 0;
        std::size_t reached = 0;
        const auto row_started = std::chrono::steady_clock::now();
        for (int k = 0; k < count; ++k) {
          if (spots) x.spot_shown = k;
          else x.point_shown = k;
          stage.set(x, spots ? ShadowPicture::SpotVisibility : ShadowPicture::PointVisibility);
          frame.render(camera, {visibility.framebuffer(), s.width, s.height});
          const VisibilityError e = visibility_error(visibility.read(), truths[std::size_t(k)], 0);
          wrong += e.wrong * double(e.pixels), error += e.mean_abs * double(e.pixels), reached += e.pixels;
        }
        stage.set(x);
        PassMetrics metrics;
        // The warm-up capped at 2 s (settling takes well under one on a GPU): 50 rows, so the
        // two CSVs at 1920x1080 stay within a few minutes on the H200 whatever happens.
        const Measurement m = measure(metrics, [&] { frame.render(camera, {image.framebuffer(), s.width, s.height}, &metrics); },
                                      {.warmup = {.max_seconds = 2.0}, .frames = s.frames});
        const double maps = pass_ms(m, spots ? "shadow map: the spot lights' atlas" : "shadow map: cube maps of the point lights");
        const int tile = spots ? stage.spot_tile(0).size : size;
        const double n = std::max<double>(double(reached), 1.0);
        csv << "overview," << (spots ? "atlas" : "cube") << ',' << kMethodNames[int(method)] << ',' << count << ',' << size
            << ',' << tile << ',' << stage.allocated_bytes() << ',' << maps << ',' << local_ms(m) << ',' << m.total_ms()
            << ',' << reached << ',' << 100 * wrong / n << ',' << error / n << ','
            << csv_measure_values(renderer, s.width, s.height, m.frames) << "\n";
        std::cout << (spots ? "atlas " : "cube maps ") << kMethodNames[int(method)] << ", " << count << " lights, " << size
                  << ": maps " << maps << " ms, local " << local_ms(m) << " ms, wrong " << 100 * wrong / n << "% of "
                  << reached << " (" << seconds_since(row_started) << " s)" << std::endl;
      }
  }
  std::cout << "wrote " << file << " in " << seconds_since(started) << " s\n";
}
// [/local-rows]

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  return run_sweep(argc, argv, "06_shadows_sweep", [&](SweepArgs& args) {
    args.text("--out", s.out).size("--size", s.width, s.height).integer("--frames", s.frames)
        .integer("--truth-samples", s.truth_samples).text("--only", s.only);
  }, [&] {
    if (!s.only.empty() && s.only != "main" && s.only != "pcf" && s.only != "moments" && s.only != "volumes" &&
        s.only != "pcss" && s.only != "cascades" && s.only != "msm" && s.only != "points" && s.only != "atlas")
      throw UsageError("--only must be main, pcf, moments, volumes, pcss, cascades, msm, points or atlas, not '" + s.only +
                       "'");
    std::filesystem::create_directories(s.out);
    auto context = Context::create({.headless = true, .width = s.width, .height = s.height});
    const std::string renderer = context->renderer();
    Scene scene = load_scene(from_root("assets/atrium/atrium.gltf"));
    SceneGpu gpu(scene);
    RayScene rays(scene);
    const Light& sun = find_sun(scene);
    ch03::DeferredFrame frame(gpu);
    frame.volumes().set_lights(ch03::build_light_set(
        scene.lights, ch03::cut_threshold(1.f, ch03::peak_reflectance(scene)), frame.volumes().shapes()));
    ShadowStage stage(gpu, sun);
    frame.add_stage(stage);
    OutputTarget image(s.width, s.height);
    ColourTarget visibility(s.width, s.height, GL_RGBA32F);
    const bool software = context->is_software();
    if (s.only.empty() || s.only == "main" || s.only == "pcf") {
    const bool pcf_only = s.only == "pcf";
    const std::string stem = pcf_only ? "/06_shadows_pcf" : "/06_shadows";
    const std::string file = s.out + stem + (software ? "_llvmpipe.csv" : ".csv");
    std::ofstream csv(file);
    csv << "# " << (software ? "llvmpipe CPU time: " : "GPU time: ") << renderer << ", " << s.width << "x" << s.height
        << ", atrium; soft truth: sun disk " << TruthSettings{}.angular_radius << " rad, " << s.truth_samples
        << " rays per pixel\n"
        << "# ms: mean over the measured frames; hard_*, soft_*: error over the pixels the sun reaches (shadow_truth.h)\n"
        << "# penumbra_*: mean |error| over the reference's penumbra (strictly between 0 and 1) and " << kPenumbraBand
        << " pixels around it (shadow_metrics.h); penumbra_soft against the soft truth, penumbra_box against the hard truth "
           "box-filtered over PCF 3x3's footprint on the 1024^2 map; leak: of full_shadow pixels (soft truth 0), those lit > "
        << kLeakThreshold << "\n"
        << "# made by: 06_shadows_sweep --size " << s.width << "x" << s.height << " --frames " << s.frames
        << " --truth-samples " << s.truth_samples << (s.only.empty() ? std::string() : " --only " + s.only) << "\n"
        << "view,method,setting,map,kernel,pmin,c,bytes,depth_ms,filter_ms,global_ms,frame_ms,hard_mean,hard_wrong_pct,"
           "soft_mean,soft_p99,penumbra_soft,penumbra_box,penumbra_box_signed,full_shadow,leak,"
        << csv_measure_columns() << "\n";
    for (const std::string view : {"overview", "corner"}) {
      const FrameCamera camera = frame_camera(scene.camera(view), float(s.width) / s.height);
      const ImageF truth = cached_shadow_truth(scene, rays, camera, s.width, s.height, sun.direction,
                                               {.samples = s.truth_samples});
      if (!pcf_only && view == "overview") {
        save_png(s.out + "/06_overview_truth_hard.png", visibility_picture(truth, 0, truth));
        save_png(s.out + "/06_overview_truth_soft.png", visibility_picture(truth, 1, truth));
      }
      // The filtered hard truth of the default kernel (3x3 on the 1024^2 map): one reference for
      // every row, in the frustum the stage fits to this view (the same for every setting).
      stage.set(ShadowSettings{}, ShadowPicture::Visibility);
      frame.render(camera, {visibility.framebuffer(), s.width, s.height});
      const ImageF box = cached_filtered_hard_truth(scene, rays, camera, s.width, s.height,
                                                    kernel_footprint(stage.frustum(), ShadowSettings{}.map_size,
                                                                     ShadowSettings{}.kernel));
      for (const Variant& v : variants()) {
        if (pcf_only && v.shadow.method != ShadowMethod::Pcf) continue;
        stage.set(v.shadow, ShadowPicture::Visibility);
        frame.render(camera, {visibility.framebuffer(), s.width, s.height});
        const ImageF vis = visibility.read();
        const VisibilityError hard = visibility_error(vis, truth, 0), soft = visibility_error(vis, truth, 1);
        const std::vector<bool> outside = outside_method_mask(vis);
        const PenumbraError pen_soft = penumbra_error(vis, truth, 1, &outside), pen_box = penumbra_error(vis, box, 0, &outside);
        const LightLeak leak = light_leak(vis, truth, &outside);
        // The book's pictures: each method at its defaults, on the overview.
        const std::string name = kMethodNames[int(v.shadow.method)];
        if (!pcf_only && view == "overview" && (v.setting == "kernel 3" || v.setting == "map 1024" || v.setting == "taps 32")) {
          save_png(s.out + "/06_overview_" + name + "_visibility.png", visibility_picture(vis, 0, truth));
          const int against = v.shadow.method == ShadowMethod::Hard ? 0 : 1;
          save_png(s.out + "/06_overview_" + name + "_error.png", error_picture(vis, truth, against));
        }
        stage.set(v.shadow);
        PassMetrics metrics;
        const Measurement m = measure(metrics, [&] { frame.render(camera, {image.framebuffer(), s.width, s.height}, &metrics); },
                                      {.frames = s.frames});
        const ShadowSettings& x = v.shadow;
        csv << view << ',' << kMethodNames[int(x.method)] << ',' << v.setting << ',' << x.map_size << ',' << x.kernel << ','
            << x.p_min << ',' << x.c << ',' << stage.allocated_bytes() << ','
            << pass_ms(m, "shadow map: depth from the sun") << ',' << pass_ms(m, "shadow map: pre-filter") << ','
            << pass_ms(m, "global: ambient + directional (chapter 03)") << ',' << m.total_ms() << ',' << hard.mean_abs << ','
            << 100 * hard.wrong << ',' << soft.mean_abs << ',' << soft.p99 << ',' << pen_soft.mean_abs << ','
            << pen_box.mean_abs << ',' << pen_box.mean_signed << ',' << leak.full_shadow << ',' << leak.leaking << ','
            << csv_measure_values(renderer, s.width, s.height, m.frames) << "\n";
        std::cout << view << ' ' << kMethodNames[int(x.method)] << ' ' << v.setting << ": frame " << m.total_ms()
                  << " ms, hard wrong " << 100 * hard.wrong << "%, soft mean " << soft.mean_abs << ", penumbra "
                  << pen_soft.mean_abs << " (soft) " << pen_box.mean_abs << " (box), leak " << leak.leaking << " of "
                  << leak.full_shadow << std::endl;
      }
    }
    std::cout << "wrote " << file << '\n';
    }
    // [moments-rows]
    // VSM and ESM with the filtered map in RG32F and RG16F: bytes, cost and error against the
    // soft truth, at the default map and kernel and at 2048 with a 5-texel filter.
    if (s.only.empty() || s.only == "moments") {
      const std::string file = s.out + (software ? "/06_shadows_moments_llvmpipe.csv" : "/06_shadows_moments.csv");
      std::ofstream csv(file);
      csv << "# " << (software ? "llvmpipe CPU time: " : "GPU time: ") << renderer << ", " << s.width << "x" << s.height
          << ", atrium overview; soft truth: sun disk " << TruthSettings{}.angular_radius << " rad, " << s.truth_samples
          << " rays per pixel; bits: of each value of the filtered map (RG32F or RG16F)\n"
          << "view,method,bits,map,kernel,bytes,depth_ms,filter_ms,global_ms,frame_ms,soft_mean,soft_p99,"
          << csv_measure_columns() << "\n";
      const FrameCamera camera = frame_camera(scene.camera("overview"), float(s.width) / s.height);
      const ImageF truth = cached_shadow_truth(scene, rays, camera, s.width, s.height, sun.direction,
                                               {.samples = s.truth_samples});
      for (ShadowMethod method : {ShadowMethod::Vsm, ShadowMethod::Esm})
        for (int bits : {32, 16})
          for (auto [map, kernel] : {std::pair{1024, 3}, std::pair{2048, 5}}) {
            const ShadowSettings x{.method = method, .map_size = map, .kernel = kernel, .moment_bits = bits};
            stage.set(x, ShadowPicture::Visibility);
            frame.render(camera, {visibility.framebuffer(), s.width, s.height});
            const VisibilityError soft = visibility_error(visibility.read(), truth, 1);
            stage.set(x);
            PassMetrics metrics;
            const Measurement m = measure(
                metrics, [&] { frame.render(camera, {image.framebuffer(), s.width, s.height}, &metrics); }, {.frames = s.frames});
            csv << "overview," << kMethodNames[int(method)] << ',' << bits << ',' << map << ',' << kernel << ','
                << stage.allocated_bytes() << ',' << pass_ms(m, "shadow map: depth from the sun") << ','
                << pass_ms(m, "shadow map: pre-filter") << ',' << pass_ms(m, "global: ambient + directional (chapter 03)")
                << ',' << m.total_ms() << ',' << soft.mean_abs << ',' << soft.p99 << ','
                << csv_measure_values(renderer, s.width, s.height, m.frames) << "\n";
            std::cout << "overview " << kMethodNames[int(method)] << " " << bits << "-bit map " << map << " kernel " << kernel
                      << ": frame " << m.total_ms() << " ms, soft mean " << soft.mean_abs << std::endl;
          }
      std::cout << "wrote " << file << '\n';
    }
    // [/moments-rows]
    // [volumes-rows]
    // Shadow volumes against the hard 1024^2 map as the casters grow: the atrium's instances
    // 1, 2 and 4 times (each copy raised 0.5 m more), on the overview: the volumes' triangles,
    // the fragments they rasterise (counted exactly, GL_SAMPLES_PASSED), each pass's time, and
    // the wrong pixels against the hard truth of that scene.
    if (s.only.empty() || s.only == "volumes") {
      const std::string file = s.out + (software ? "/06_shadows_volumes_llvmpipe.csv" : "/06_shadows_volumes.csv");
      std::ofstream csv(file);
      csv << "# " << (software ? "llvmpipe CPU time: " : "GPU time: ") << renderer << ", " << s.width << "x" << s.height
          << ", atrium overview with its instances copied; fragments: rasterised by the shadow volumes\n"
          << "view,method,copies,scene_triangles,cap_triangles,side_quads,fragments,cpu_ms,stencil_ms,fill_ms,depth_ms,"
             "frame_ms,hard_wrong_pct,"
          << csv_measure_columns() << "\n";
      for (int copies : {1, 2, 4}) {
        Scene grown = scene;
        const std::size_t n = scene.instances.size();
        for (int c = 1; c < copies; ++c)
          for (std::size_t i = 0; i < n; ++i) {
            Instance copy = scene.instances[i];
            copy.model = glm::translate(glm::mat4(1), glm::vec3(0, 0.5f * float(c), 0)) * copy.model;
            grown.instances.push_back(copy);
          }
        SceneGpu grown_gpu(grown);
        RayScene grown_rays(grown);
        ch03::DeferredFrame grown_frame(grown_gpu);
        grown_frame.volumes().set_lights(ch03::build_light_set(
            grown.lights, ch03::cut_threshold(1.f, ch03::peak_reflectance(grown)), grown_frame.volumes().shapes()));
        ShadowStage grown_stage(grown_gpu, sun);
        grown_frame.add_stage(grown_stage);
        const FrameCamera camera = frame_camera(grown.camera("overview"), float(s.width) / s.height);
        const ImageF truth = shadow_truth(grown, grown_rays, camera, s.width, s.height, sun.direction, {.samples = 1});
        for (ShadowMethod method : {ShadowMethod::Volumes, ShadowMethod::Hard}) {
          const ShadowSettings x{.method = method, .map_size = 1024, .count_volume_fragments = true};
          grown_stage.set(x, ShadowPicture::Visibility);
          grown_frame.render(camera, {visibility.framebuffer(), s.width, s.height});
          const VisibilityError hard = visibility_error(visibility.read(), truth, 0);
          const VolumeStats stats = grown_stage.volume_stats();
          grown_stage.set({.method = method, .map_size = 1024});
          PassMetrics metrics;
          const Measurement m = measure(metrics, [&] {
            grown_frame.render(camera, {image.framebuffer(), s.width, s.height}, &metrics);
          }, {.frames = s.frames});
          const bool volumes = method == ShadowMethod::Volumes;
          csv << "overview," << kMethodNames[int(method)] << ',' << copies << ',' << grown_gpu.triangle_count() << ','
              << (volumes ? stats.cap_triangles : 0) << ',' << (volumes ? stats.side_quads : 0) << ','
              << (volumes ? stats.fragments : 0) << ','
              << pass_ms(m, "shadow volumes: silhouettes and extrusion (CPU)") << ','
              << pass_ms(m, "shadow volumes: z-fail stencil count") << ','
              << pass_ms(m, "shadow volumes: visibility from the stencil") << ','
              << pass_ms(m, "shadow map: depth from the sun") << ',' << m.total_ms() << ',' << 100 * hard.wrong << ','
              << csv_measure_values(renderer, s.width, s.height, m.frames) << "\n";
          std::cout << "overview " << kMethodNames[int(method)] << " x" << copies << ": frame " << m.total_ms()
                    << " ms, " << stats.fragments << " volume fragments, hard wrong " << 100 * hard.wrong << "%"
                    << std::endl;
        }
      }
      std::cout << "wrote " << file << '\n';
    }
    // [/volumes-rows]
    // [pcss-rows]
    // PCSS against every fixed PCF kernel, on the views of the GL test PcssBeatsEveryFixed...:
    // the depth pass and the global pass that does the lookups (PCSS has no pre-filter), the
    // frame, and the error against the soft truth; then PCSS and PCF 3x3 at three sun sizes,
    // each against the soft truth of that sun (--sun-size: one knob for both).
    if (s.only.empty() || s.only == "pcss") {
      const std::string file = s.out + (software ? "/06_shadows_pcss_llvmpipe.csv" : "/06_shadows_pcss.csv");
      std::ofstream csv(file);
      csv << "# " << (software ? "llvmpipe CPU time: " : "GPU time: ") << renderer << ", " << s.width << "x" << s.height
          << ", atrium; soft truth: the sun as a disk of sun_size rad, " << s.truth_samples << " rays per pixel\n"
          << "view,method,setting,map,kernel,taps,sun_size,bytes,depth_ms,global_ms,frame_ms,soft_mean,soft_p99,"
             "hard_wrong_pct,"
          << csv_measure_columns() << "\n";
      struct Row { std::string setting; ShadowSettings shadow; };
      std::vector<Row> rows;
      for (int k : {1, 3, 5, 7}) rows.push_back({"kernel " + std::to_string(k), {.method = ShadowMethod::Pcf, .kernel = k}});
      for (auto [taps, k] : {std::pair{16, 5}, std::pair{32, 7}})
        rows.push_back({"poisson " + std::to_string(taps) + " kernel " + std::to_string(k),
                        {.method = ShadowMethod::Pcf, .kernel = k, .poisson_taps = taps}});
      for (int taps : {16, 32, 64}) rows.push_back({"taps " + std::to_string(taps), {.method = ShadowMethod::Pcss, .poisson_taps = taps}});
      for (float size : {0.01f, 0.04f}) {
        const std::string label = "sun " + std::to_string(size).substr(0, 4);
        rows.push_back({label + " kernel 3", {.method = ShadowMethod::Pcf, .kernel = 3, .sun_angular_radius = size}});
        rows.push_back({label + " taps 32", {.method = ShadowMethod::Pcss, .poisson_taps = 32, .sun_angular_radius = size}});
      }
      // The filter's radius as grey, white = 12 cm (the arches' penumbra radius: 5.7 m x tan 0.02 rad is 11 cm).
      auto radius_picture = [](const ImageF& r, const ImageF& truth) {
        ImageF scaled = r;
        for (float& v : scaled.data) v = std::min(v / 0.12f, 1.f);
        return visibility_picture(scaled, 0, truth);
      };
      for (const std::string view : {"overview", "aisle", "corner"}) {
        const FrameCamera camera = frame_camera(scene.camera(view), float(s.width) / s.height);
        for (const Row& r : rows) {
          const ShadowSettings& x = r.shadow;
          const ImageF truth = cached_shadow_truth(scene, rays, camera, s.width, s.height, sun.direction,
                                                   {.angular_radius = x.sun_angular_radius, .samples = s.truth_samples});
          stage.set(x, ShadowPicture::Visibility);
          frame.render(camera, {visibility.framebuffer(), s.width, s.height});
          const ImageF vis = visibility.read();
          const VisibilityError hard = visibility_error(vis, truth, 0), soft = visibility_error(vis, truth, 1);
          const bool pictured = view != "corner" && x.sun_angular_radius == kSunAngularRadius &&
                                (r.setting == "taps 32" || r.setting == "kernel 3");
          if (pictured) {
            const std::string name = "/06_" + view + "_" + kMethodNames[int(x.method)];
            save_png(s.out + name + "_visibility.png", visibility_picture(vis, 0, truth));
            save_png(s.out + name + "_error.png", error_picture(vis, truth, 1));
            if (view != "overview" && x.method == ShadowMethod::Pcf)
              save_png(s.out + "/06_" + view + "_truth_soft.png", visibility_picture(truth, 1, truth));
            if (x.method == ShadowMethod::Pcss) {
              stage.set(x, ShadowPicture::Penumbra);
              frame.render(camera, {visibility.framebuffer(), s.width, s.height});
              save_png(s.out + name + "_penumbra.png", radius_picture(visibility.read(), truth));
            }
          }
          stage.set(x);
          PassMetrics metrics;
          const Measurement m = measure(metrics, [&] { frame.render(camera, {image.framebuffer(), s.width, s.height}, &metrics); },
                                        {.frames = s.frames});
          csv << view << ',' << kMethodNames[int(x.method)] << ',' << r.setting << ',' << x.map_size << ',' << x.kernel << ','
              << (x.method == ShadowMethod::Pcss && x.poisson_taps == 0 ? kPcssDefaultTaps : x.poisson_taps) << ','
              << x.sun_angular_radius << ',' << stage.allocated_bytes() << ','
              << pass_ms(m, "shadow map: depth from the sun") << ','
              << pass_ms(m, "global: ambient + directional (chapter 03)") << ',' << m.total_ms() << ',' << soft.mean_abs << ','
              << soft.p99 << ',' << 100 * hard.wrong << ',' << csv_measure_values(renderer, s.width, s.height, m.frames) << "\n";
          std::cout << view << ' ' << kMethodNames[int(x.method)] << ' ' << r.setting << ": frame " << m.total_ms()
                    << " ms, global " << pass_ms(m, "global: ambient + directional (chapter 03)") << " ms, soft mean "
                    << soft.mean_abs << std::endl;
        }
      }
      std::cout << "wrote " << file << '\n';
    }
    // [/pcss-rows]
    if (s.only.empty() || s.only == "cascades") cascade_rows(s, renderer, software);
    // [msm-rows]
    // Moment shadow maps against VSM (with and without P_min) and ESM: light leaking (pixels the
    // soft truth has in full shadow lit by more than 0.1: all of them, and those where PCF 3x3 is
    // dark, where only the moments can bring light), the error against the soft truth, the
    // pre-filter's and the lookups' cost, and the bytes.
    if (s.only.empty() || s.only == "msm") {
      const std::string file = s.out + (software ? "/06_shadows_msm_llvmpipe.csv" : "/06_shadows_msm.csv");
      std::ofstream csv(file);
      csv << "# " << (software ? "llvmpipe CPU time: " : "GPU time: ") << renderer << ", " << s.width << "x" << s.height
          << ", atrium; soft truth: sun disk " << TruthSettings{}.angular_radius << " rad, " << s.truth_samples
          << " rays per pixel; leak: pixels in full shadow (soft truth 0) lit > 0.1\n"
          << "view,method,setting,bits,bytes,filter_ms,global_ms,frame_ms,full_shadow,leak,leak_pct,pcf_dark,leak_pcf_dark,"
             "soft_mean,soft_p99,"
          << csv_measure_columns() << "\n";
      struct Row { std::string setting; ShadowSettings shadow; };
      const std::vector<Row> rows = {
          {"pmin 0", {.method = ShadowMethod::Vsm, .p_min = 0.f}},
          {"pmin 0.2", {.method = ShadowMethod::Vsm}},
          {"c 80", {.method = ShadowMethod::Esm}},
          {"32-bit", {.method = ShadowMethod::Msm}},
          {"16-bit", {.method = ShadowMethod::Msm, .moment_bits = 16}},
          {"vsm 16-bit", {.method = ShadowMethod::Vsm, .p_min = 0.f, .moment_bits = 16}},
      };
      for (const std::string view : {"overview", "aisle", "corner"}) {
        const FrameCamera camera = frame_camera(scene.camera(view), float(s.width) / s.height);
        const ImageF truth = cached_shadow_truth(scene, rays, camera, s.width, s.height, sun.direction,
                                                 {.samples = s.truth_samples});
        stage.set({.method = ShadowMethod::Pcf, .kernel = 3}, ShadowPicture::Visibility);
        frame.render(camera, {visibility.framebuffer(), s.width, s.height});
        const ImageF pcf = visibility.read();
        for (const Row& r : rows) {
          const ShadowSettings& x = r.shadow;
          stage.set(x, ShadowPicture::Visibility);
          frame.render(camera, {visibility.framebuffer(), s.width, s.height});
          const ImageF vis = visibility.read();
          // shadow_metrics.h's light_leak, the rasteriser's sky of this method and of PCF left out;
          // then again only where PCF 3x3 is dark.
          std::vector<bool> exclude = outside_method_mask(vis);
          const std::vector<bool> pcf_outside = outside_method_mask(pcf);
          for (std::size_t i = 0; i < exclude.size(); ++i) exclude[i] = exclude[i] || pcf_outside[i];
          const LightLeak all = light_leak(vis, truth, &exclude);
          for (std::size_t i = 0; i < exclude.size(); ++i)
            exclude[i] = exclude[i] || pcf.data[i * std::size_t(pcf.channels)] != 0.f;
          const LightLeak where_pcf_dark = light_leak(vis, truth, &exclude);
          const std::size_t dark = all.full_shadow, leak = all.leaking;
          const std::size_t pcf_dark = where_pcf_dark.full_shadow, leak_pcf_dark = where_pcf_dark.leaking;
          const VisibilityError soft = visibility_error(vis, truth, 1);
          if (view == "overview" && (r.setting == "32-bit" || r.setting == "pmin 0")) {
            const std::string name = s.out + "/06_overview_" + kMethodNames[int(x.method)] + "_leak";
            save_png(name + "_visibility.png", visibility_picture(vis, 0, truth));
            save_png(name + "_error.png", error_picture(vis, truth, 1));
          }
          stage.set(x);
          PassMetrics metrics;
          const Measurement m = measure(metrics, [&] { frame.render(camera, {image.framebuffer(), s.width, s.height}, &metrics); },
                                        {.frames = s.frames});
          csv << view << ',' << kMethodNames[int(x.method)] << ',' << r.setting << ',' << x.moment_bits << ','
              << stage.allocated_bytes() << ',' << pass_ms(m, "shadow map: pre-filter") << ','
              << pass_ms(m, "global: ambient + directional (chapter 03)") << ',' << m.total_ms() << ',' << dark << ','
              << leak << ',' << (dark ? 100.0 * double(leak) / double(dark) : 0.0) << ',' << pcf_dark << ','
              << leak_pcf_dark << ',' << soft.mean_abs << ',' << soft.p99 << ','
              << csv_measure_values(renderer, s.width, s.height, m.frames) << "\n";
          std::cout << view << ' ' << kMethodNames[int(x.method)] << ' ' << r.setting << ": leak " << leak << " of " << dark
                    << " (" << leak_pcf_dark << " of " << pcf_dark << " where pcf is dark), soft mean " << soft.mean_abs
                    << ", frame " << m.total_ms() << " ms" << std::endl;
        }
      }
      std::cout << "wrote " << file << '\n';
    }
    // [/msm-rows]
    if (s.only.empty() || s.only == "points") local_rows(s, renderer, software, false);
    if (s.only.empty() || s.only == "atlas") local_rows(s, renderer, software, true);
  });
}
