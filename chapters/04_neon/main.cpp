// Chapter 04: the neon (line) light. By default each tube is a light volume: its capsule is
// drawn over chapter 02's G-buffer through chapter 03's stencil mask, and the pixels inside
// call neon_light() with the method the mode names (the ground truth, the thesis's
// approximation "source", our improvement of it, N point lights, Karis's representative
// point, or the exact diffuse alone) into chapter 03's light buffer, where the scene's other
// lights arrive through chapter 03's own volumes. `--forward 1` lights every fragment with
// every tube in one forward pass instead: the same image, the yardstick of the tests.
#include <chrono>
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
#include "chapters/04_neon/neon_volumes.h"
#include "common/app.h"
#include "common/error.h"

namespace {

using namespace lp;
using namespace lp::ch04;

enum Show { kResult, kVolumes, kMasks, kWaste };

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
              {"term", "0: the whole image, 1: the neon diffuse alone, 2: the neon specular alone", 0, 0, 2, true},
              {"forward", "0: capsule volumes over the G-buffer (chapters 02, 03), 1: one forward pass", 0, 0, 1, true},
              {"show", "0 result, 1 the capsules as wireframes, 2 and each tube's stencil mask tinted, 3 what the "
                       "capsules shade: green lit, red not lit, blue kept dark by barn doors (deferred only)", 0, 0, 3, true},
              {"count", "count fragments shaded and lit by the tubes (atomic counters, costs a little time)", 1, 0, 1,
               true}}};

// [references]
// The reference images, per scene (a Shot names a view, not a scene): `--check` renders the
// neon room's, `--check --scene assets/street_neon/street_neon.gltf` the night street's.
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

Chapter chapter_for(int argc, char** argv) {
  std::vector<Shot> shots = room_shots();
  try {
    if (parse_cli(argc, argv, kCli).scene.find("street_neon") != std::string::npos) shots = street_shots();
  } catch (const Error&) {
    // run_chapter parses again and reports the problem.
  }
  return {.cli = kCli, .references = shots};
}

void bind_output(const Frame& f) {
  glBindFramebuffer(GL_FRAMEBUFFER, f.target);
  glViewport(0, 0, f.width, f.height);
  glEnable(GL_FRAMEBUFFER_SRGB);
}

// The output's depth from the G-buffer (and a clean stencil), for what is drawn over the image.
void copy_depth_to_output(GLuint from, const Frame& f) {
  glBlitNamedFramebuffer(from, f.target, 0, 0, f.width, f.height, 0, 0, f.width, f.height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  const GLint zero = 0;
  glClearNamedFramebufferiv(f.target, GL_STENCIL, 0, &zero);
}

}  // namespace

int main(int argc, char** argv) {
  return run_chapter(argc, argv, chapter_for(argc, argv), [](App& app) {
    NeonForward forward(app.scene_gpu());
    NeonTubes tubes;
    tubes.upload(neon_lights(app.scene()));
    ch01::LightBuffer lights;  // the forward pass: every light of the scene
    lights.upload(app.scene().lights);
    ch02::GeometryPass geometry(app.scene_gpu());
    ch03::LightVolumes volumes;  // the scene's other lights, chapter 03's way
    volumes.set_lights(ch03::build_light_set(app.scene().lights, ch03::cut_threshold(1.f, ch03::peak_reflectance(app.scene())),
                                             volumes.shapes()));
    for (const auto& w : volumes.lights().warnings) std::cerr << "warning: " << w << '\n';
    NeonVolumes neon;
    std::unique_ptr<ch02::GBuffer> gbuffer;
    std::unique_ptr<ch03::LightBuffer> light;
    const glm::vec3 background = ch01::kBackground, ambient = app.scene().ambient;
    const bool report = !app.context().is_window() && !app.options().check && !app.options().bench;

    while (app.next_frame()) {
      const Frame& f = app.frame();
      const auto start = std::chrono::steady_clock::now();
      if (f.reload_shaders) {
        forward.reload_shaders();
        geometry.reload_shaders();
        volumes.reload_shaders();
        neon.reload_shaders();
      }
      NeonDraw how{.method = method_from_name(f.mode),
                   .samples = f.knob_int(f.mode == "points" ? "points" : "samples"),
                   .term = static_cast<Term>(f.knob_int("term"))};
      const bool deferred = f.knob_int("forward") == 0;
      const int show = f.knob_int("show");
      neon.set_counting(deferred && f.knob_int("count") != 0);

      if (!deferred) {
        glClearColor(background.r, background.g, background.b, 1.f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        auto pass = app.metrics().pass("forward: lights and neon tubes");
        forward.draw(f.camera, how, lights, tubes);
      } else {
        if (!gbuffer || gbuffer->width() != f.width || gbuffer->height() != f.height) {
          gbuffer = std::make_unique<ch02::GBuffer>(f.width, f.height);
          light = std::make_unique<ch03::LightBuffer>(f.width, f.height, ch02::depth_format(gbuffer->layout().depth));
          app.metrics().set_allocation("G-buffer (chapter 02)", gbuffer->bytes_per_pixel() * f.width * f.height);
          app.metrics().set_allocation("light buffer L1 + L2 RGBA16F + depth-stencil (chapter 03)", light->bytes());
        }
        // [frame]
        {
          auto pass = app.metrics().pass("geometry: G-buffer (chapter 02)");
          geometry.draw(*gbuffer, f.camera);
        }
        gbuffer->bind_textures(0);
        const ch03::SurfaceView view = ch03::surface_view(*gbuffer);
        light->begin(gbuffer->framebuffer());  // the G-buffer's depth, a zero stencil
        const bool whole = how.term == Term::All && show != kWaste;
        if (whole) {
          {
            auto pass = app.metrics().pass("global: ambient + directional (chapter 03)");
            volumes.draw_global(*light, view, ambient);
          }
          auto pass = app.metrics().pass("local lights: stencil (chapter 03)");
          volumes.draw_local(*light, view, ch03::Strategy::Stencil);
        } else {
          light->clear();  // the tubes alone
        }
        {
          auto pass = app.metrics().pass("neon: capsule volumes, stencil");
          neon.draw(tubes, *light, view, how, show == kWaste);
        }
        bind_output(f);
        {
          auto pass = app.metrics().pass("composite: albedo x L1 + L2 + emissive (chapter 03)");
          if (show == kWaste) volumes.draw_light_target(light->diffuse(), 1.f);
          else if (whole) volumes.composite(*light, view, background);
          else neon.draw_term(*light, view, how.term, background);
        }
        copy_depth_to_output(gbuffer->framebuffer(), f);
        bind_output(f);
        if (show == kVolumes || show == kMasks) neon.draw_pictures(tubes, view, show == kMasks);
        if (whole) {
          auto pass = app.metrics().pass("glass: the tubes themselves");
          forward.draw_glass(f.camera, tubes);
        }
        // [/frame]
      }

      const NeonCounts& c = neon.counts();
      if (neon.counting()) {
        // The neon pass's own counts beside its GL_SAMPLES_PASSED (which also counts the
        // stencil-marking draws' fragments): --bench reports them apart.
        app.metrics().count("neon: capsule volumes, stencil", "shaded", c.shaded);
        app.metrics().count("neon: capsule volumes, stencil", "lit", c.lit);
        app.metrics().count("neon: capsule volumes, stencil", "marking", c.marking);
      }
      if (report) {
        glFinish();
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        std::cout << tubes.count() << " neon tubes, " << f.mode << (deferred ? ", capsule volumes" : ", forward")
                  << ": frame took " << ms << " ms (wall clock, " << app.context().renderer() << ")";
        if (neon.counting())
          std::cout << "; neon fragments shaded " << c.shaded << ", lit " << c.lit << ", overshading " << c.overshading()
                    << " (" << c.lit_open << " lit with the barn doors open)";
        std::cout << '\n';
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
