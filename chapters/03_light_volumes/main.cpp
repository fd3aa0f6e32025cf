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
#include "chapters/03_light_volumes/light_counts.h"
#include "chapters/03_light_volumes/light_prepass.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/03_light_volumes/light_volumes.h"
#include "common/app.h"

namespace {

using namespace lp;
using namespace lp::ch03;

enum Show { kResult, kDiffuse, kSpecular, kVolumes, kStencilMask, kHeatShaded, kHeatLit };
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
  for (int show : {kDiffuse, kSpecular, kVolumes, kStencilMask, kHeatShaded, kHeatLit})
    shots.push_back({"overview", "stencil", {{"show", show}}});
  shots.push_back({"overview", "back-faces", {{"show", kHeatShaded}}});
  return shots;
}

const lp::Chapter kChapter{
    .cli = {.program = "03_light_volumes",
            .summary = "Light volumes: each light drawn as a sphere or cone into a light buffer; five ways to cull "
                       "its pixels, the stencil mask the tightest.",
            .default_scene = "assets/street/street.gltf",
            .modes = modes(),
            .knobs = {{"lights", "local lights (0: the scene's own; more adds lights like them)", 0, 0, 100000, true},
                      {"show", "0 result, 1 L1 diffuse light, 2 L2 specular light, 3 volumes, 4 one light's stencil mask, "
                               "5 fragments shaded per pixel, 6 fragments lit per pixel", 0, 0, 6, true},
                      {"light", "the light whose stencil mask --show 4 draws (light order)", 0, 0, 100000, true},
                      {"far", "far plane in metres (0: the camera's own); small values cut volumes", 0, 0, 10000, false},
                      {"exposure", "the exposure the light cut is relative to", 1, 0.01, 100, false},
                      {"cut", "light cut: 1 one sRGB step at black for the brightest material, 0 the sources' 1/256", 1, 0, 1, true},
                      {"count", "count fragments shaded and lit (atomic counters, costs a little time)", 1, 0, 1, true}}},
    .references = references(),
};

bool is_prepass(const std::string& mode) { return mode == "light-prepass" || mode == "light-prepass-chroma"; }

FrameCamera with_far(FrameCamera camera, double far) {
  if (far > 0) {
    camera.zfar = static_cast<float>(far);
    camera.projection = glm::perspective(camera.yfov, camera.aspect, camera.znear, camera.zfar);
  }
  return camera;
}

// The output's depth (and a clean stencil) for the pictures drawn over the image.
void copy_depth_to_output(GLuint from, const Frame& f) {
  glBlitNamedFramebuffer(from, f.target, 0, 0, f.width, f.height, 0, 0, f.width, f.height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  const GLint zero = 0;
  glClearNamedFramebufferiv(f.target, GL_STENCIL, 0, &zero);
}

void bind_output(const Frame& f) {
  glBindFramebuffer(GL_FRAMEBUFFER, f.target);
  glViewport(0, 0, f.width, f.height);
  glEnable(GL_FRAMEBUFFER_SRGB);
}

}  // namespace

int main(int argc, char** argv) {
  return lp::run_chapter(argc, argv, kChapter, [](lp::App& app) {
    ch02::GeometryPass geometry(app.scene_gpu());
    LightVolumes volumes;
    LightPrePass prepass(app.scene_gpu());
    std::unique_ptr<ch02::GBuffer> gbuffer;
    std::unique_ptr<LightBuffer> light, prepass_light;
    std::vector<double> lights_key;
    const glm::vec3 background = ch01::kBackground, ambient = app.scene().ambient;
    const bool report = !app.context().is_window() && !app.options().check && !app.options().bench;

    while (app.next_frame()) {
      const lp::Frame& f = app.frame();
      const auto start = std::chrono::steady_clock::now();
      if (f.reload_shaders) {
        geometry.reload_shaders();
        volumes.reload_shaders();
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
      if (!gbuffer || gbuffer->width() != f.width || gbuffer->height() != f.height) {
        gbuffer = std::make_unique<ch02::GBuffer>(f.width, f.height);
        light = std::make_unique<LightBuffer>(f.width, f.height, ch02::depth_format(gbuffer->layout().depth));
        prepass_light = std::make_unique<LightBuffer>(f.width, f.height, LightPrePass::kDepthFormat, LightBuffer::Kind::PrePass);
        app.metrics().set_allocation("G-buffer (chapter 02)", gbuffer->bytes_per_pixel() * f.width * f.height);
        app.metrics().set_allocation("light buffer L1 + L2 RGBA16F + depth-stencil", light->bytes());
      }
      volumes.set_counting(f.knob_int("count") != 0);
      const FrameCamera camera = with_far(f.camera, f.knob("far"));
      const int show = f.knob_int("show");

      if (!is_prepass(f.mode)) {
        // [frame]
        const Strategy strategy = strategy_named(f.mode);
        {
          auto pass = app.metrics().pass("geometry: G-buffer (chapter 02)");
          geometry.draw(*gbuffer, camera);
        }
        gbuffer->bind_textures(0);
        const SurfaceView view = surface_view(*gbuffer);
        light->begin(gbuffer->framebuffer());
        const bool heat = show == kHeatShaded || show == kHeatLit;
        if (heat) {
          light->clear();
        } else {
          auto pass = app.metrics().pass("global: ambient + directional");
          volumes.draw_global(*light, view, ambient);
        }
        {
          auto pass = app.metrics().pass("local lights: " + f.mode);
          auto output = show == kHeatShaded ? LightVolumes::Output::HeatShaded
                        : show == kHeatLit  ? LightVolumes::Output::HeatLit
                                            : LightVolumes::Output::Light;
          volumes.draw_local(*light, view, strategy, output);
        }
        bind_output(f);
        {
          auto pass = app.metrics().pass("composite: albedo x L1 + L2 + emissive");
          if (heat) volumes.draw_heat(*light, kHeatFullScale);
          else if (show == kDiffuse) volumes.draw_light_target(light->diffuse(), 1.f);
          else if (show == kSpecular) volumes.draw_light_target(light->specular(), 4.f);
          else volumes.composite(*light, view, background);
        }
        if (show == kVolumes || show == kStencilMask) {
          copy_depth_to_output(gbuffer->framebuffer(), f);
          bind_output(f);
          if (show == kVolumes) volumes.draw_wireframe(view);
          else volumes.draw_stencil_mask(view, f.knob_int("light"));
        }
        // [/frame]
      } else {
        // [prepass-frame]
        {
          auto pass = app.metrics().pass("geometry 1: normal, exponent, depth");
          prepass.draw_geometry(camera, f.width, f.height);
        }
        prepass.bind_textures();
        prepass_light->begin(prepass.framebuffer());
        {
          auto pass = app.metrics().pass("global: ambient + directional");
          volumes.draw_global(*prepass_light, prepass.view(), ambient);
        }
        {
          auto pass = app.metrics().pass("local lights: stencil");
          volumes.draw_local(*prepass_light, prepass.view(), Strategy::Stencil);
        }
        bind_output(f);
        copy_depth_to_output(prepass.framebuffer(), f);
        glClearColor(background.r, background.g, background.b, 1.f);
        glClear(GL_COLOR_BUFFER_BIT);
        auto pass = app.metrics().pass("geometry 2: materials x light");
        prepass.draw_materials(*prepass_light, f.mode == "light-prepass" ? PrePassSpecular::White : PrePassSpecular::Chroma);
        // [/prepass-frame]
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
      if (report) {
        glFinish();
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        std::cout << volumes.lights().local_count() << " local lights, " << f.mode << ": frame took " << ms
                  << " ms (wall clock, " << app.context().renderer() << ")";
        if (volumes.counting())
          std::cout << "; fragments shaded " << counts.shaded << ", lit " << counts.lit << ", overshading "
                    << counts.overshading();
        const DrawStats& s = volumes.draw_stats();
        std::cout << "; " << s.draw_calls << " draw calls, " << s.lights_skipped << " lights skipped, "
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
