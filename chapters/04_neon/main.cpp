// Chapter 04: the neon (line) light. Each fragment is lit by chapter 01's lights and by every
// neon tube of the scene, with the method the mode names: the ground truth (numerical
// integration along the tube), the thesis's approximation ("source"), our improvement of it,
// N point lights, Karis's representative point, or the exact diffuse alone.
#include "chapters/01_forward/ground_truth.h"
#include "chapters/01_forward/light_buffer.h"
#include "chapters/04_neon/neon_forward.h"
#include "chapters/04_neon/neon_scene.h"
#include "common/app.h"

#include <imgui.h>

namespace {

using lp::ch04::Method;

// The program's modes: the chapter's result first (the default), then what it is measured against.
const std::vector<std::string> kModes = {"improved", "ground-truth", "source", "points", "representative-point",
                                         "analytic-diffuse"};

const lp::Chapter kChapter{
    .cli = {.program = "04_neon",
            .summary = "Neon (line) lights: the thesis's approximation, our improvement and the common alternatives "
                       "against numerical integration along the tube.",
            .default_scene = "assets/neon/neon.gltf",
            .modes = kModes,
            .knobs = {{"samples", "ground-truth: samples along each tube", 256, 1, 65536, true},
                      {"points", "points: point lights per tube", 8, 1, 4096, true},
                      {"term", "0: the whole image, 1: the neon diffuse alone, 2: the neon specular alone", 0, 0, 2, true}}},
    .references = {{"overview", "improved"}, {"overview", "ground-truth"}, {"overview", "source"},
                   {"overview", "points"}, {"overview", "representative-point"}, {"overview", "analytic-diffuse"},
                   {"grazing", "improved"}, {"grazing", "source"}, {"grazing", "representative-point"},
                   {"close", "improved"}, {"close", "points", {{"points", 32}}}},
};

}  // namespace

int main(int argc, char** argv) {
  return lp::run_chapter(argc, argv, kChapter, [](lp::App& app) {
    lp::ch04::NeonForward forward(app.scene_gpu());
    lp::ch04::NeonTubes tubes;
    tubes.upload(lp::ch04::neon_lights(app.scene()));
    lp::ch01::LightBuffer lights;
    lights.upload(app.scene().lights);

    while (app.next_frame()) {
      const lp::Frame& f = app.frame();
      if (f.reload_shaders) forward.reload_shaders();
      lp::ch04::NeonDraw how{.method = lp::ch04::method_from_name(f.mode),
                             .samples = f.knob_int(f.mode == "points" ? "points" : "samples"),
                             .term = static_cast<lp::ch04::Term>(f.knob_int("term"))};
      glClearColor(lp::ch01::kBackground.r, lp::ch01::kBackground.g, lp::ch01::kBackground.b, 1.f);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      {
        auto pass = app.metrics().pass("forward: lights and neon tubes");
        forward.draw(f.camera, how, lights, tubes);
      }
      app.panel([&] { ImGui::Text("%d neon tubes, %d other lights", tubes.count(), lights.count()); });
    }
  });
}
