// Chapter 01: forward Blinn-Phong. Every object is drawn once and lit by every light while
// it is drawn; the modes compare lighting per vertex and per pixel, and one pass against
// one additive pass per light. "ground-truth" shows the CPU reference the tests measure against.
#include "chapters/01_forward/forward.h"
#include "chapters/01_forward/ground_truth.h"
#include "chapters/01_forward/ground_truth_view.h"
#include "chapters/01_forward/light_buffer.h"
#include "common/app.h"

#include <imgui.h>

namespace {

using lp::ch01::ForwardMode;

std::vector<std::string> modes() {
  auto m = lp::ch01::kForwardModes;
  m.push_back("ground-truth");
  return m;
}

const lp::Chapter kChapter{
    .cli = {.program = "01_forward",
            .summary = "Forward Blinn-Phong: per-vertex vs per-pixel lighting, one pass vs one pass per light.",
            .default_scene = "assets/forward/forward.gltf",
            .modes = modes(),
            .knobs = {{"lights", "lights to use (0: the scene's own; more adds point lights)", 0, 0, 100000, true}}},
    .references = {{"overview", "per-pixel"}, {"overview", "per-vertex"}, {"overview", "unnormalized"},
                   {"overview", "multi-pass"}, {"close_16", "per-pixel"}, {"close_16", "per-vertex"},
                   {"close_16", "unnormalized"}, {"grazing", "per-pixel"}},
    // [exercises]
    .exercises = {{.title = "Blinn's half vector and the specular lobe",
                   .file = "blinn_phong.glsl",
                   .define = "EXERCISE_BLINN_PHONG",
                   .shots = {{"overview", "per-pixel"}, {"close_16", "per-pixel"}},
                   .look_at = "the highlights on the spheres (close_16 shows one large): their size and brightness"},
                  {.title = "a point light's falloff: the inverse square and the range window",
                   .file = "distance_attenuation.glsl",
                   .define = "EXERCISE_DISTANCE_ATTENUATION",
                   .shots = {{"overview", "per-pixel"}, {"grazing", "per-pixel"}},
                   .look_at = "the floor around the point lights: how fast the light falls off, and where it ends"},
                  {.title = "a spot light's cone",
                   .file = "spot_cone.glsl",
                   .define = "EXERCISE_SPOT_CONE",
                   .shots = {{"overview", "per-pixel"}, {"grazing", "per-pixel"}},
                   .look_at = "the spot's pool of light on the floor: its edge, and that nothing outside it is lit by the spot"}},
    // [/exercises]
};

}  // namespace

// [main]
int main(int argc, char** argv) {
  return lp::run_chapter(argc, argv, kChapter, [](lp::App& app) {
    lp::ch01::ForwardRenderer forward(app.scene_gpu());
    lp::ch01::GroundTruthView ground_truth(app.scene());
    std::vector<lp::Light> light_list;  // what the GPU buffer holds, for the CPU ground truth
    lp::ch01::LightBuffer lights;
    int light_count = -1;

    while (app.next_frame()) {
      const lp::Frame& f = app.frame();
      if (f.reload_shaders) forward.reload_shaders();
      if (f.knob_int("lights") != light_count) {
        light_count = f.knob_int("lights");
        light_list = lp::ch01::lights_for_count(app.scene(), light_count);
        lights.upload(light_list);
      }

      glClearColor(lp::ch01::kBackground.r, lp::ch01::kBackground.g, lp::ch01::kBackground.b, 1.f);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      if (f.mode == "ground-truth") {
        auto pass = app.metrics().pass("ground truth (CPU ray casting)");
        ground_truth.draw(f, light_list);
      } else if (lp::ch01::forward_mode(f.mode) == ForwardMode::MultiPass) {
        {
          auto pass = app.metrics().pass("base: depth, ambient, emissive");
          forward.draw_base(f.camera, lights);
        }
        auto pass = app.metrics().pass("lights: one additive pass each");
        forward.draw_additive_lights(f.camera, lights);
      } else {
        auto pass = app.metrics().pass("forward: all lights in one pass");
        forward.draw(f.camera, lp::ch01::forward_mode(f.mode), lights);
      }

      app.panel([&] { ImGui::Text("%d lights", lights.count()); });
    }
  });
}
// [/main]
