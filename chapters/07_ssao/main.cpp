// Chapter 07: screen-space ambient occlusion. Chapter 03's deferred frame with an AO stage:
// after the G-buffer, a compute pass turns the surfaces into the visibility A of each pixel
// (the classic algorithm, or the source's 2D-disk method with Bunnell's term), and the
// frame's ambient hook multiplies the ambient light by it; the direct lights are untouched.
// `--show ao` shows A itself. The scenes' ambient is small (0.03): the program opens with
// `--ambient 10` so that the AO shows in the lit image.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>

#include <imgui.h>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/07_ssao/ao_stage.h"
#include "chapters/07_ssao/ao_truth.h"
#include "common/app.h"
#include "common/target.h"
#include "common/error.h"

namespace {

using namespace lp;
using namespace lp::ch07;

enum Show { kImage, kAo, kRaw, kTruth, kError, kSplit };  // --show's order

const CliSpec kCli{
    .program = "07_ssao",
    .summary = "Screen-space ambient occlusion on the deferred frame: the classic algorithm (hemisphere kernel, "
               "noise, energy-minimised kernel, bilateral blur, low resolution) and the source's 2D-disk method "
               "with Bunnell's disk-to-disk term, and horizon-based AO (GTAO), against ray-traced AO.",
    .default_scene = "assets/cornell/cornell.gltf",
    .modes = kMethodNames,  // classic, disk, off
    .knobs = {{"samples", "kernel points (classic) or disk samples (disk)", 16, 1, kMaxSamples, true},
              {"radius", "R, world units: how far occluders count (the AO rays' length)", 0.5, 0.01, 100, false},
              {"noise", "rotate the kernel (classic) or turn the spiral (disk) per pixel by the 4x4 noise tile", 1, 0, 1, true},
              choice_knob("kernel", "classic: the spring-relaxed (energy-minimised) kernel or the random one",
                          {"energy", "random"}),
              {"blur", "the bilateral 4x4 blur (off: the raw AO)", 1, 0, 1, true},
              {"radii", "classic: 1 radius, or 2 (the source's second kernel at R / 5, A the product: darker in "
                        "contact, twice the depth reads)", 1, 1, 2, true},
              choice_knob("term", "disk: each sample's occlusion, the disk form factor (cosine-weighted) or Bunnell's term",
                          {"form-factor", "bunnell"}),
              choice_knob("resolution", "the AO pass at full, half or quarter resolution", {"full", "half", "quarter"}),
              choice_knob("show", "the lit image; the AO term A (white: open, black: occluded); A before the blur; "
                                  "the ray-traced truth (slow: the CPU traces --truth-samples rays per pixel, cached); "
                                  "|A - truth| as a heat map (red: 0.5); the lit image's middle beside the AO's",
                          {"image", "ao", "raw", "truth", "error", "split"}),
              {"truth-samples", "--show truth/error: cosine-weighted rays per pixel", 64, 1, 4096, true},
              {"ambient", "the scene's ambient light times this (AO darkens only the ambient)", 1, 0, 1000, false}},
    // AO darkens only the ambient light, and the scenes' own (0.03) is too faint to show it:
    // the program opens with ten times as much, the lit image beside the AO that darkens it.
    .opening = {"--ambient", "10", "--show", "split"}};

// [references]
// On a renderer other than the references' (a reader's GPU), two kinds of pixel may differ by
// more than 3 steps, and each view below that has them gets an allowance there (the renderer
// that made the references keeps 0.1 %): the atrium's normal-mapped floor, whose mip level far
// away OpenGL leaves to the implementation (the AO reads the mapped normals:
// kMinifiedTextureAllowance, common/app.h), and, with neither noise nor blur, or in the error
// view against the CPU-traced truth, a one-pixel column along a box edge where the range check
// compares depths that differ between renderers in their last bits.
const CompareOptions kOtherRenderer = kMinifiedTextureAllowance;
const CompareOptions kDepthEdge{.threshold = 3, .max_failing_fraction = 0.005};

std::vector<Shot> cornell_shots() {
  return {{"front", "classic", {{"show", kAo}}},
          {"front", "classic", {{"show", kAo}, {"noise", 0}, {"blur", 0}}, {}, kDepthEdge},
          {"front", "classic", {{"show", kAo}, {"resolution", 1}}},
          {"front", "disk", {{"show", kAo}}},
          {"front", "disk", {{"show", kAo}, {"samples", 64}}},
          {"front", "classic", {{"ambient", 10}}},
          {"front", "off", {{"ambient", 10}}},
          {"front", "gtao", {{"show", kAo}}},
          {"front", "classic", {{"show", kRaw}}},
          {"front", "disk", {{"show", kError}}, {}, kDepthEdge},
          {"front", "classic", {{"ambient", 10}, {"show", kSplit}}}};  // the opening, the README's picture
}
std::vector<Shot> atrium_shots() {
  return {{"overview", "classic", {{"show", kAo}}, {}, kOtherRenderer},
          {"overview", "disk", {{"show", kAo}}, {}, kOtherRenderer},
          {"overview", "gtao", {{"show", kAo}}, {}, kOtherRenderer},
          {"corner", "disk", {{"ambient", 10}}, {}, kOtherRenderer}};
}
// [/references]

// [exercises]
// The exercises (chapters/07_ssao/exercises/), on the Cornell box or the atrium.
std::vector<Exercise> exercises() {
  return {{.title = "the classic estimate's range check",
           .file = "range_check.glsl",
           .define = "EXERCISE_RANGE_CHECK",
           .shots = {{"front", "classic", {{"show", kAo}}}, {"front", "classic", {{"show", kRaw}}}},
           .look_at = "the AO (--show ao, --show raw before the blur) on the walls around the boxes: a dark halo where a box far in front hides the wall's kernel points"},
          {.title = "placing the classic kernel's points in view space",
           .file = "kernel_offset.glsl",
           .define = "EXERCISE_KERNEL_OFFSET",
           // The atrium's corner view: the Cornell box's camera is not turned, and there a
           // world offset added unturned (the tutorial's bug) would pass.
           .shots = {{"corner", "classic", {{"show", kAo}}, {}, kOtherRenderer}, {"aisle", "classic", {{"show", kRaw}}, {}, kOtherRenderer}},
           .look_at = "the AO (--show ao) where the columns meet the floor and the walls, in the atrium",
           .scene = "assets/atrium/atrium.gltf"},
          {.title = "the occlusion of one disk sample (its form factor)",
           .file = "disk_form_factor.glsl",
           .define = "EXERCISE_DISK_FORM_FACTOR",
           .shots = {{"front", "disk", {{"show", kAo}}}, {"front", "disk", {{"ambient", 10}}}},
           .look_at = "the AO (--mode disk --show ao) in the corners and where the boxes meet the floor"}};
}
// [/exercises]

const Chapter kChapter{.cli = kCli,
                       .references = cornell_shots(),
                       .scene_references = {{"assets/atrium/atrium.gltf", atrium_shots()}},
                       .exercises = exercises()};

AoSettings settings_from(const Frame& f) {
  AoSettings s;
  s.method = f.mode == "disk"   ? AoMethod::Disk
           : f.mode == "off"    ? AoMethod::Off
           : f.mode == "gtao"   ? AoMethod::Gtao
                                : AoMethod::Classic;
  s.samples = f.knob_int("samples");
  s.radius = float(f.knob("radius"));
  s.noise = f.knob_int("noise") != 0;
  s.energy_minimised = f.choice("kernel") == "energy";
  s.blur = f.knob_int("blur") != 0;
  s.scale = 1 << f.knob_int("resolution");
  s.bunnell_term = f.choice("term") == "bunnell";
  s.two_radii = f.knob_int("radii") == 2;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  return run_chapter(argc, argv, kChapter, [](App& app) {
    ch03::DeferredFrame frame(app.scene_gpu());
    ch03::use_lights(frame, app.scene(), app.scene().lights);
    AoStage ao;
    frame.add_stage(ao);
    std::unique_ptr<OutputTarget> split;  // --show split: the AO's half

    while (app.next_frame()) {
      const Frame& f = app.frame();
      const auto start = std::chrono::steady_clock::now();
      if (f.reload_shaders) {
        frame.reload_shaders();
        ao.reload_shaders();
      }
      // [frame]
      const glm::vec3 ambient = app.scene().ambient * float(f.knob("ambient"));
      frame.set_ambient(ambient);
      const int show = f.knob_int("show");
      ao.set(settings_from(f), show == kAo || show == kError ? AoShow::Ao : show == kRaw ? AoShow::Raw : AoShow::Image,
             ambient);
      if (show == kTruth || show == kError) {
        // the truth at this size and camera (cached on disk), and for the error the AO of
        // the frame just drawn against it
        const ImageF truth = cached_ray_traced_ao(app.scene(), f.camera, f.width, f.height,
                                                  {.radius = float(f.knob("radius")), .samples = f.knob_int("truth-samples")});
        ImageF picture = truth;
        if (show == kError) {
          frame.render(f.camera, {f.target, f.width, f.height});
          ImageF a = ImageF::blank(f.width, f.height, 1);
          if (ao.ran()) a = ao.ssao().read_full(f.width, f.height);
          else for (float& v : a.data) v = 1.f;  // no AO: A = 1
          const std::vector<float> error = ao_error_map(a, truth);
          for (std::size_t i = 0; i < error.size(); ++i) picture.data[i] = error[i];
        }
        ao.set_picture(picture, show == kError ? 0.5f : 0.f);
        ao.set(settings_from(f), AoShow::Picture, ambient);
      }
      frame.render(f.camera, {f.target, f.width, f.height}, &app.metrics());
      // [/frame]
      // The split: the AO drawn too, the middle halves of both side by side (the box is in the
      // middle), captioned.
      if (show == kSplit) {
        if (!split || split->width() != f.width || split->height() != f.height)
          split = std::make_unique<OutputTarget>(f.width, f.height);
        ao.set(settings_from(f), AoShow::Ao, ambient);
        frame.render(f.camera, {split->framebuffer(), f.width, f.height});
        const ImageRGBA8 lit = read_framebuffer(f.target, f.width, f.height);
        const ImageRGBA8 term = read_framebuffer(split->framebuffer(), f.width, f.height);
        ImageRGBA8 img = lit;
        const int half = f.width / 2, from = f.width / 4;
        for (int y = 0; y < f.height; ++y) {
          std::copy_n(lit.at(from, y), std::size_t(half) * 4, img.at(0, y));
          std::copy_n(term.at(from, y), std::size_t(f.width - half) * 4, img.at(half, y));
        }
        draw_label(img, 2, 2, "lit image");
        draw_label(img, half + 2, 2, "AO (white: open)");
        put_picture(img, f.target);
      }
      if (show == kError) {  // the heat map's key, in the picture (show_ao.frag's ramp)
        ImageRGBA8 img = read_framebuffer(f.target, f.width, f.height);
        draw_heat_key(img, {.full_scale = 0.5f, .what = "|AO - ray-traced AO|", .mixed_in_linear = true});
        put_picture(img, f.target);
      }
      app.metrics().set_allocation("G-buffer (chapter 02) + light buffer (chapter 03)", frame.allocated_bytes());
      if (std::ostream& out = app.report()) {
        glFinish();
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        const AoSettings& s = ao.settings();
        if (ao.ran())
          out << "AO " << f.mode << ", " << s.samples << " samples, radius " << s.radius << ", " << ao.ssao().width()
              << "x" << ao.ssao().height() << (s.blur ? ", blurred" : "");
        else
          out << "no AO pass (" << (s.method == AoMethod::Off ? "mode off" : "the scene's ambient light is 0") << ")";
        out << ": frame took " << ms << " ms (wall clock, " << app.context().renderer() << ")\n";
      }
      app.panel([&] {
        ImGui::Text("AO %s at %dx%d", ao.ran() ? "computed" : "not computed", ao.ssao().width(), ao.ssao().height());
        ImGui::Text("AO darkens the ambient light only (%.3f %.3f %.3f)", ambient.r, ambient.g, ambient.b);
      });
    }
  });
}
