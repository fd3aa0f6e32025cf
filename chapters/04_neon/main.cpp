// Chapter 04: the neon (line) light. By default each tube is a light volume: its capsule is
// drawn over chapter 02's G-buffer through chapter 03's stencil mask, and the pixels inside
// call neon_light() with the method the mode names (the ground truth, the thesis's
// approximation "source", our improvement of it, N point lights, Karis's representative
// point, or the exact diffuse alone) into chapter 03's light buffer, where the scene's other
// lights arrive through chapter 03's own volumes. `--forward 1` lights every fragment with
// every tube in one forward pass instead: the same image, the yardstick of the tests.
#include <array>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>

#include <imgui.h>

#include "chapters/01_forward/ground_truth.h"
#include "chapters/01_forward/light_buffer.h"
#include "chapters/02_gbuffer/gbuffer.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/03_light_volumes/light_volumes.h"
#include "chapters/04_neon/neon_forward.h"
#include "chapters/04_neon/neon_scene.h"
#include "chapters/04_neon/neon_stage.h"
#include "common/app.h"
#include "common/error.h"
#include "common/image.h"
#include "common/target.h"

namespace {

using namespace lp;
using namespace lp::ch04;

enum Show { kResult, kVolumes, kMasks, kWaste };  // --show's order

// The program's modes: the chapter's result first (the default), then what it is measured against.
const std::vector<std::string> kModes = {"improved", "ground-truth", "source", "points", "representative-point",
                                         "analytic-diffuse"};

const CliSpec kCli{
    .program = "04_neon",
    .summary = "Neon (line) lights as capsule light volumes over the G-buffer: the thesis's approximation, our "
               "improvement and the common alternatives against numerical integration along the tube.",
    .default_scene = "assets/neon/neon.gltf",
    .modes = kModes,
    .knobs = {{"samples", "ground-truth: samples along each tube", 256, 1, 65536, true},
              {"points", "points: point lights per tube", 8, 1, 4096, true},
              choice_knob("term", "the whole image, or the neon diffuse or specular alone", {"all", "diffuse", "specular"}),
              {"forward", "draw the tubes in one forward pass (off: capsule volumes over the G-buffer, chapters 02, 03)", 0, 0, 1, true},
              choice_knob("show", "the result; the capsules as wireframes; and each tube's stencil mask tinted; what the "
                                  "capsules shade: green lit, red not lit, blue kept dark by barn doors (deferred only)",
                          {"result", "capsules", "masks", "waste"}),
              {"count", "count fragments shaded and lit by the tubes (atomic counters, costs a little time)", 1, 0, 1,
               true}}};

// [references]
// The reference images, per scene (a Shot names a view, not a scene): `--check` renders the
// neon room's, `--check --scene assets/street_neon/street_neon.gltf` the night street's
// (kChapter below).
std::vector<Shot> room_shots() {
  std::vector<Shot> shots = {{"overview", "improved"}, {"overview", "ground-truth"}, {"overview", "source"},
                             {"overview", "points"}, {"overview", "representative-point"},
                             {"overview", "analytic-diffuse"}, {"grazing", "improved"}, {"grazing", "source"},
                             {"grazing", "representative-point"}, {"close", "improved"},
                             {"close", "points", {{"points", 32}}}};
  // The forward pass: the same images.
  shots.push_back({"overview", "improved", {{"forward", 1}}});
  shots.push_back({"grazing", "source", {{"forward", 1}}});
  return shots;
}
// The street: its signs from the road, from the pavement inside the pink sign's capsule, and
// along the street, both ways; the capsules and their stencil masks seen from above.
std::vector<Shot> street_shots() {
  return {{"neon_signs", "improved"},
          {"neon_signs", "improved", {{"forward", 1}}},
          {"inside_sign", "improved"},
          {"inside_sign", "improved", {{"forward", 1}}},
          {"street_level", "improved"},
          {"above_signs", "improved", {{"show", kMasks}}}};
}
// [/references]

// [exercises]
// The exercises (chapters/04_neon/exercises/), in the neon room as the references.
std::vector<Exercise> exercises() {
  return {{.title = "the tube as point lights",
           .file = "neon_points.glsl",
           .define = "EXERCISE_NEON_POINTS",
           .shots = {{"overview", "points"}, {"close", "points", {{"points", 32}}}},
           .look_at = "the light on the floor and walls near the tubes, and the highlights (--mode points)"},
          {.title = "the exact diffuse light of a line",
           .file = "analytic_diffuse.glsl",
           .define = "EXERCISE_ANALYTIC_DIFFUSE",
           .shots = {{"overview", "analytic-diffuse"}, {"grazing", "improved", {{"term", 1}}}},  // 1: diffuse alone
           .look_at = "the diffuse light (--term diffuse): its fall-off from the tubes, and surfaces that see a tube only in part"},
          {.title = "the point of the tube nearest a point",
           .file = "closest_on_segment.glsl",
           .define = "EXERCISE_CLOSEST_ON_SEGMENT",
           .shots = {{"overview", "improved"}, {"overview", "source"}},
           .look_at = "where the tubes' light ends (the capsule volumes' mask) and the source's method (--mode source)"}};
}
// [/exercises]

const Chapter kChapter{.cli = kCli,
                       .references = room_shots(),
                       .scene_references = {{"assets/street_neon/street_neon.gltf", street_shots()}},
                       .exercises = exercises()};

// --show waste's key: each capsule adds its colour (neon_volume.frag's SHOW_WASTE, through the
// sRGB target), so a pixel under several capsules shows their sum.
void draw_waste_key(ImageRGBA8& picture) {
  const auto srgb = srgb_colour;
  draw_legend(picture, {{srgb(0.f, 0.2f, 0.f), "a capsule whose tube lights the pixel"},
                        {srgb(0.7f, 0.f, 0.f), "a capsule that shades it for nothing"},
                        {srgb(0.f, 0.1f, 0.7f), "a capsule whose barn doors keep it dark"},
                        {std::nullopt, "overlapping capsules add their colours"}});
}

NeonPicture picture_for(int show) {
  return show == kVolumes ? NeonPicture::Capsules
       : show == kMasks   ? NeonPicture::Masks
       : show == kWaste   ? NeonPicture::Waste
                          : NeonPicture::None;
}

}  // namespace

int main(int argc, char** argv) {
  return run_chapter(argc, argv, kChapter, [](App& app) {
    NeonTubes tubes;
    tubes.upload(neon_lights(app.scene()));
    NeonForward forward(app.scene_gpu());
    ch01::LightBuffer lights;  // the forward pass: every light of the scene
    lights.upload(app.scene().lights);
    // The deferred path: chapter 03's frame, its lights cut as chapter 03 cuts them, and
    // the tubes as a stage of it.
    ch03::DeferredFrame frame(app.scene_gpu());
    ch03::use_lights(frame, app.scene(), app.scene().lights);
    NeonStage stage(app.scene_gpu(), tubes);
    frame.add_stage(stage);
    NeonVolumes& neon = stage.volumes();
    const glm::vec3 background = ch01::kBackground;

    while (app.next_frame()) {
      const Frame& f = app.frame();
      const auto start = std::chrono::steady_clock::now();
      if (f.reload_shaders) {
        forward.reload_shaders();
        frame.reload_shaders();
        stage.reload_shaders();
      }
      NeonDraw how{.method = method_from_name(f.mode),
                   .samples = f.knob_int(f.mode == "points" ? "points" : "samples"),
                   .term = static_cast<Term>(f.knob_int("term"))};
      const bool deferred = f.knob_int("forward") == 0;
      neon.set_counting(deferred && f.knob_int("count") != 0);

      // [frame]
      if (deferred) {
        // Chapter 03's frame with the tubes as a stage: G-buffer, chapter 03's lights, each
        // tube's capsule through the stencil, the composite, the glass.
        stage.set(how, picture_for(f.knob_int("show")));
        frame.render(f.camera, {f.target, f.width, f.height}, &app.metrics(),
                     {.scene_lights = stage.wants_scene_lights()});
      } else {
        // The yardstick: every light and every tube for every fragment, in one forward pass.
        glClearColor(background.r, background.g, background.b, 1.f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        auto pass = app.metrics().pass("forward: lights and neon tubes");
        forward.draw(f.camera, how, lights, tubes);
      }
      // [/frame]
      if (deferred && f.knob_int("show") == kWaste) {
        ImageRGBA8 picture = read_framebuffer(f.target, f.width, f.height);
        draw_waste_key(picture);
        put_picture(picture, f.target);
      }
      if (deferred) app.metrics().set_allocation("G-buffer (chapter 02) + light buffer (chapter 03)", frame.allocated_bytes());

      const NeonCounts& c = neon.counts();
      if (neon.counting()) {
        // The neon pass's own counts beside its GL_SAMPLES_PASSED (which also counts the
        // stencil-marking draws' fragments): --bench reports them apart.
        app.metrics().count("neon: capsule volumes, stencil", "shaded", c.shaded);
        app.metrics().count("neon: capsule volumes, stencil", "lit", c.lit);
        app.metrics().count("neon: capsule volumes, stencil", "marking", c.marking);
      }
      if (std::ostream& out = app.report()) {
        glFinish();
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        out << tubes.count() << " neon tubes, " << f.mode << (deferred ? ", capsule volumes" : ", forward")
                  << ": frame took " << ms << " ms (wall clock, " << app.context().renderer() << ")";
        if (neon.counting())
          out << "; neon fragments shaded " << c.shaded << ", lit " << c.lit << ", overshading " << c.overshading()
                    << " (" << c.lit_open << " lit with the barn doors open)";
        out << '\n';
      }
      app.panel([&] {
        ImGui::Text("%d neon tubes, %d other lights", tubes.count(), lights.count());
        ImGui::Text("%s", deferred ? "capsule volumes over the G-buffer, stencil (chapters 02, 03)" : "forward pass");
        if (neon.counting())
          ImGui::Text("neon fragments shaded %llu, lit %llu: overshading %.3f", (unsigned long long)c.shaded,
                      (unsigned long long)c.lit, c.overshading());
      });
    }
  });
}
