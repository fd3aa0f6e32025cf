// Chapter 03: light volumes with stencil. Chapter 02 lit every pixel for every light; here
// each local light is drawn as a volume (an icosphere, or a cone for a spot) and lights only
// the pixels its volume covers, into a light buffer of diffuse and specular light that a
// last pass combines with the surface. The modes are the five culling strategies (all give
// the same image) and deferred lighting; `--show` draws the pictures of the book.
#include <chrono>
#include <iostream>
#include <memory>

#include <glm/gtc/matrix_transform.hpp>
#include <imgui.h>

#include "chapters/01_forward/ground_truth.h"
#include "chapters/02_gbuffer/gbuffer.h"
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_counts.h"
#include "chapters/03_light_volumes/light_prepass.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/03_light_volumes/light_volumes.h"
#include "common/app.h"
#include "common/target.h"

namespace {

using namespace lp;
using namespace lp::ch03;

enum Show { kResult, kDiffuse, kSpecular, kVolumes, kStencilMask, kHeatShaded, kHeatLit, kSplit };  // --show's order
constexpr float kHeatFullScale = 40.f;  // fragments per pixel shown white

std::vector<std::string> modes() {
  std::vector<std::string> m = {"stencil", "full-screen", "scissor", "front-faces", "back-faces", "stencil-bits"};
  m.push_back("light-prepass");
  m.push_back("light-prepass-chroma");
  return m;
}

std::vector<Shot> references() {
  std::vector<Shot> shots;
  for (const auto& s : kStrategies) shots.push_back({"street_level", s});  // all the same image
  // The hard cases: the eye inside a light, and volumes cut by a far plane pulled in to 30 m.
  for (const std::string s : {"stencil", "front-faces", "back-faces"}) {
    shots.push_back({"inside_light", s});
    shots.push_back({"street_level", s, {{"far", 30}}});
  }
  shots.push_back({"overview", "stencil"});
  shots.push_back({"street_level", "light-prepass"});
  shots.push_back({"street_level", "light-prepass-chroma"});
  // The heat maps count fragments per pixel: on another renderer a volume's edge may move.
  for (int show : {kDiffuse, kSpecular, kVolumes, kStencilMask})
    shots.push_back({"overview", "stencil", {{"show", show}}});
  for (int show : {kHeatShaded, kHeatLit}) shots.push_back({"overview", "stencil", {{"show", show}}, {}, kMovedEdgeAllowance});
  shots.push_back({"overview", "back-faces", {{"show", kHeatShaded}}, {}, kMovedEdgeAllowance});
  shots.push_back({"street_level", "stencil", {{"show", kHeatShaded}}, {}, kMovedEdgeAllowance});
  shots.push_back({"street_level", "stencil", {{"show", kSplit}}, {}, kMovedEdgeAllowance});  // the opening, the README's picture
  return shots;
}

const lp::Chapter kChapter{
    .cli = {.program = "03_light_volumes",
            .summary = "Light volumes: each light drawn as a sphere or cone into a light buffer; five ways to cull "
                       "its pixels, the stencil mask the tightest.",
            .default_scene = "assets/street/street.gltf",
            .modes = modes(),
            .knobs = {{"lights", "local lights (0: the scene's own; more adds lights like them)", 0, 0, 100000, true},
                      choice_knob("show", "result, the L1 diffuse or L2 specular light, the volumes, one light's stencil "
                                          "mask (--light), fragments shaded or lit per pixel, or the image's left half "
                                          "beside the fragments the volumes shaded",
                                  {"result", "diffuse", "specular", "volumes", "stencil-mask", "heat-shaded", "heat-lit", "split"}),
                      {"light", "the light whose stencil mask --show stencil-mask draws (light order)", 0, 0, 100000, true},
                      {"far", "far plane in metres (0: the camera's own); small values cut volumes", 0, 0, 10000, false},
                      {"exposure", "the exposure the light cut is relative to", 1, 0.01, 100, false},
                      {"cut", "cut each light where it is one sRGB step at black on the brightest material (off: at 1/256 of the source)", 1, 0, 1, true},
                      {"count", "count fragments shaded and lit (atomic counters, costs a little time)", 1, 0, 1, true}},
            // Down the street among its lamps' pools of light (the overview is mostly sky), the
            // image beside the fragments the lights' volumes shaded: each pool a volume's cover.
            .opening = {"--view", "street_level", "--show", "split"}},
    .references = references(),
    // [exercises]
    .exercises = {{.title = "the window that ends a light at its range",
                   .file = "range_window.glsl",
                   .define = "EXERCISE_RANGE_WINDOW",
                   .shots = {{"street_level", "stencil"}, {"overview", "stencil"}},
                   .look_at = "the rims of the lamps' pools of light: a light without its window ends in a hard circle where its volume is cut"},
                  {.title = "the basis that turns a spot's cone to its direction",
                   .file = "basis_around.glsl",
                   .define = "EXERCISE_BASIS_AROUND",
                   .shots = {{"street_level", "stencil"}, {"overview", "stencil", {{"show", 3}}}},  // 3: the volumes
                   .look_at = "the spots' pools of light and their cones (--show volumes): a cone turned wrong cuts its pool off"},
                  {.title = "unpacking a light volume's instance record",
                   .file = "unpack_lights.glsl",
                   .define = "EXERCISE_UNPACK_LIGHTS",
                   .shots = {{"street_level", "stencil"}, {"overview", "stencil"}},
                   .look_at = "the lamps' light and the spots' cones: position, colour, range and direction each show somewhere"}},
    // [/exercises]
};

bool is_prepass(const std::string& mode) { return mode == "light-prepass" || mode == "light-prepass-chroma"; }

FrameCamera with_far(FrameCamera camera, double far) {
  if (far > 0) {
    camera.zfar = static_cast<float>(far);
    camera.projection = glm::perspective(camera.yfov, camera.aspect, camera.znear, camera.zfar);
  }
  return camera;
}

FrameShow frame_show(int show) {
  switch (show) {
    case kDiffuse: return FrameShow::DiffuseLight;
    case kSpecular: return FrameShow::SpecularLight;
    case kHeatShaded: return FrameShow::HeatShaded;
    case kHeatLit: return FrameShow::HeatLit;
    default: return FrameShow::Image;
  }
}

}  // namespace

int main(int argc, char** argv) {
  return lp::run_chapter(argc, argv, kChapter, [](lp::App& app) {
    DeferredFrame frame(app.scene_gpu());
    LightVolumes& volumes = frame.volumes();
    LightPrePass prepass(app.scene_gpu());
    std::unique_ptr<LightBuffer> prepass_light;
    std::unique_ptr<OutputTarget> heat;  // --show split: the heat map's half
    std::vector<double> lights_key;
    const glm::vec3 background = ch01::kBackground, ambient = app.scene().ambient;

    while (app.next_frame()) {
      const lp::Frame& f = app.frame();
      const FrameOutput output{f.target, f.width, f.height};
      const auto start = std::chrono::steady_clock::now();
      if (f.reload_shaders) {
        frame.reload_shaders();
        prepass.reload_shaders();
      }
      std::vector<double> key = {f.knob("lights"), f.knob("exposure"), f.knob("cut")};
      if (key != lights_key) {
        lights_key = key;
        // [choose-threshold]
        // Ours: one sRGB step at black, for the brightest highlight the scene's materials
        // can make. The sources': 1/256 of the light, whatever reflects it.
        const float exposure = float(f.knob("exposure"));
        const float threshold = f.knob_int("cut") ? cut_threshold(exposure, peak_reflectance(app.scene()))
                                                  : cut_threshold(exposure, 1.f, kLinearEightBitStep);
        // [/choose-threshold]
        LightSet set = build_light_set(lights_for_count(app.scene(), f.knob_int("lights")), threshold, volumes.shapes());
        for (const auto& w : set.warnings) std::cerr << "warning: " << w << '\n';
        volumes.set_lights(std::move(set));
      }
      volumes.set_counting(f.knob_int("count") != 0);
      const FrameCamera camera = with_far(f.camera, f.knob("far"));
      const int show = f.knob_int("show");

      if (!is_prepass(f.mode)) {
        // [frame]
        // Chapter 03's frame (deferred_frame.cpp): the G-buffer, ambient and directional
        // light for every pixel, each local light in its volume, culled by the strategy the
        // mode names, and the composite; or one of the light buffer's pictures instead.
        frame.set_strategy(strategy_named(f.mode));
        frame.render(camera, output, &app.metrics(), {.show = frame_show(show), .heat_full_scale = kHeatFullScale});
        // The pictures over the image: every volume, or one light's stencil mask.
        if (show == kVolumes || show == kStencilMask) {
          frame.copy_depth_to_output();
          if (show == kVolumes) volumes.draw_wireframe(frame.view());
          else volumes.draw_stencil_mask(frame.view(), f.knob_int("light"));
        }
        // [/frame]
        // The split: the heat map of fragments shaded rendered too, its right half over the image's.
        if (show == kSplit) {
          if (!heat || heat->width() != f.width || heat->height() != f.height)
            heat = std::make_unique<OutputTarget>(f.width, f.height);
          frame.render(camera, {heat->framebuffer(), f.width, f.height}, nullptr,
                       {.show = FrameShow::HeatShaded, .heat_full_scale = kHeatFullScale});
          glDisable(GL_FRAMEBUFFER_SRGB);  // a copy of the bytes
          glBlitNamedFramebuffer(heat->framebuffer(), f.target, f.width / 2, 0, f.width, f.height, f.width / 2, 0,
                                 f.width, f.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
          glEnable(GL_FRAMEBUFFER_SRGB);
        }
        if (show == kHeatShaded || show == kHeatLit || show == kSplit) {  // the heat map's key, in the picture
          ImageRGBA8 img = read_framebuffer(f.target, f.width, f.height);
          const int from = show == kSplit ? f.width / 2 : 0;
          if (show == kSplit) {
            draw_label(img, 2, 2, "image");
            draw_label(img, from + 2, 2, "volumes: fragments shaded");
          }
          draw_heat_key(img, {.full_scale = kHeatFullScale,
                              .what = show == kSplit     ? "fragments per pixel"  // half the width: the caption says shaded
                                     : show == kHeatLit ? "fragments lit per pixel"
                                                        : "fragments shaded per pixel",
                              .stops = kHeatRamp}, from);
          put_picture(img, f.target);
        }
        app.metrics().set_allocation("G-buffer (chapter 02) + light buffer L1 + L2 RGBA16F + depth-stencil",
                                     frame.allocated_bytes());
      } else {
        if (!prepass_light || prepass_light->width() != f.width || prepass_light->height() != f.height)
          prepass_light = std::make_unique<LightBuffer>(f.width, f.height, LightPrePass::kDepthFormat, LightBuffer::Kind::PrePass);
        // Deferred lighting (light_prepass.cpp): geometry twice, the lights in between.
        prepass.render(volumes, *prepass_light, camera, output, ambient, background,
                       f.mode == "light-prepass" ? PrePassSpecular::White : PrePassSpecular::Chroma, &app.metrics());
      }
      FragmentCounts counts = volumes.counting() ? volumes.counts() : FragmentCounts{};
      if (volumes.counting()) {
        // The local-light pass's own counts beside its GL_SAMPLES_PASSED (which also counts
        // the stencil-marking draws' fragments): --bench reports them apart.
        const std::string local = is_prepass(f.mode) ? "local lights: stencil" : "local lights: " + f.mode;
        app.metrics().count(local, "shaded", counts.shaded);
        app.metrics().count(local, "lit", counts.lit);
        app.metrics().count(local, "marking", counts.marking);
      }
      if (std::ostream& out = app.report()) {
        glFinish();
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        out << volumes.lights().local_count() << " local lights, " << f.mode << ": frame took " << ms
            << " ms (wall clock, " << app.context().renderer() << ")";
        if (volumes.counting())
          out << "; fragments shaded " << counts.shaded << ", lit " << counts.lit << ", overshading "
              << counts.overshading();
        const DrawStats& s = volumes.draw_stats();
        out << "; " << s.draw_calls << " draw calls, " << s.lights_skipped << " lights skipped, "
            << s.lights_camera_inside << " with the eye inside\n";
      }
      app.panel([&] {
        const LightSet& set = volumes.lights();
        ImGui::Text("%zu points, %zu spot cones, %zu wide spots, %zu directional", set.points.size(), set.cones.size(),
                    set.wide_spots.size(), set.directional.size());
        if (volumes.counting())
          ImGui::Text("fragments shaded %llu, lit %llu: overshading %.2f", (unsigned long long)counts.shaded,
                      (unsigned long long)counts.lit, counts.overshading());
        const DrawStats& s = volumes.draw_stats();
        ImGui::Text("%d draw calls, %d lights skipped, %d with the eye inside", s.draw_calls, s.lights_skipped,
                    s.lights_camera_inside);
      });
    }
  });
}
