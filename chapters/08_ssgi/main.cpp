// Chapter 08: screen-space diffuse interreflection (SSGI) merged with chapter 07's disk AO.
// Chapter 03's deferred frame with one stage: after every direct light, one compute pass reads
// the G-buffer and the light buffer's diffuse light in a 2D region around each pixel: a narrow
// disk gives the AO that darkens the ambient light, a wide one (5x) the light the surfaces there
// reflect toward the pixel through the disk-to-disk transfer; both are added into the light
// buffer, and chapter 03's composite shows them. `--show indirect` shows the indirect light
// alone, `--show truth` the ray-traced one-bounce light, `--show error` the difference.
// `--back-faces on` adds the source's back-face layer (its emitters seen by `--show back-faces`);
// `--guard-band N` draws the frame N pixels (or N < 1: that fraction of the height) wider on
// every side and shows the screen's part.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <sstream>

#include <imgui.h>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/08_ssgi/gi_stage.h"
#include "chapters/08_ssgi/gi_truth.h"
#include "chapters/08_ssgi/guard_band.h"
#include "common/target.h"
#include "common/app.h"
#include "common/error.h"

namespace {

using namespace lp;
using namespace lp::ch08;

enum Show { kImage, kIndirect, kAo, kTruth, kError, kBackFaces, kSplit };  // --show's order

const CliSpec kCli{
    .program = "08_ssgi",
    .summary = "Screen-space diffuse interreflection (one bounce, the disk-to-disk transfer) merged with the 2D-disk "
               "AO of chapter 07 in one pass, on the deferred frame, against ray-traced one-bounce indirect light.",
    .default_scene = "assets/cornell/cornell.gltf",
    .modes = kModeNames,  // ssgi, ssao, off
    .knobs = {{"samples", "samples of the pattern per pixel (each read in the AO disk and in the wide disk)", 32, 1,
               kMaxSamples, true},
              {"radius", "R_ao, world units: how far occluders count", 0.5, 0.01, 100, false},
              {"ratio", "R_gi / R_ao: the wide disk of the indirect light (the source: 5)", 5, 1, 20, false},
              choice_knob("pattern", "where the samples fall: the regular polar grid (bands), chapter 07's spiral, "
                                     "or the spiral randomised per pixel (then blurred)",
                          {"regular", "spiral", "randomised"}, 2),
              {"blur", "randomised pattern: the bilateral 5x5 blur (off: the raw noise)", 1, 0, 1, true},
              choice_knob("gather", "the wide disk's light: the source's disk samples (no visibility) or, beyond "
                                    "the source, slices with a visibility bitmask (Therrien et al. 2023)",
                          {"disk", "bitmask"}, 0),
              {"thickness", "--gather bitmask: the depth each sample is taken to have, world units", 0.5, 0.01, 100,
               false},
              {"bounces", "1, or 2: a second pass bounces direct + first bounce once more", 1, 1, 2, true},
              choice_knob("back-faces", "the source's fix for emitters facing away: a second G-buffer of the "
                                        "nearest back faces, lit, whose emitters the disk gather reads too",
                          {"off", "on"}, 0),
              {"guard-band", "draw the frame this much wider on every side and show the screen's part: pixels, or "
                             "below 1 a fraction of the height (0: none)",
               0, 0, kMaxGuardBand, false},
              choice_knob("show", "the lit image; the indirect light alone (albedo x L1_ind, x --exposure); the AO "
                                  "term; the ray-traced truth (the CPU traces --truth-samples rays per pixel, cached); "
                                  "|SSGI - truth| as a heat map (red: 0.2); the back-face layer's light (albedo x L1); "
                                  "the lit image's left half beside the indirect light's right half",
                          {"image", "indirect", "ao", "truth", "error", "back-faces", "split"}),
              {"exposure", "--show indirect/truth: the indirect light times this", 4, 0.1, 100, false},
              {"truth-samples", "--show truth/error: cosine-weighted rays per pixel", 256, 1, 4096, true},
              {"ambient", "the scene's ambient light times this (the AO darkens only the ambient)", 1, 0, 1000, false}},
    // The lit image beside the light its surfaces bounce (x --exposure): the bleeding is faint in
    // the lit image alone.
    .opening = {"--show", "split"}};

// [references]
// On a renderer other than the references' (a reader's GPU), the atrium's normal-mapped floor
// reads a mip level far away that OpenGL leaves to the implementation: the atrium's views get
// kMinifiedTextureAllowance (common/app.h).
const CompareOptions kOtherRenderer = kMinifiedTextureAllowance;
// The error view subtracts the CPU truth from the GPU's estimate: where two walls of the box
// meet at the same depth the depth test keeps one of them and the truth's primary ray may hit
// the other (implementation-defined, as common.raytrace's agreement test says), and the
// error there is large, along the box's corner edges; another renderer gets 1 %, the
// references' renderer keeps 0.1 %.
const CompareOptions kCornerTies{.threshold = 3, .max_failing_fraction = 0.01};

std::vector<Shot> cornell_shots() {
  return {{"front", "ssgi", {}},
          {"front", "ssgi", {{"show", kSplit}}},  // the opening, the README's picture
          {"front", "ssao", {}},
          {"front", "off", {}},
          {"front", "ssgi", {{"show", kIndirect}}},
          {"front", "ssgi", {{"show", kIndirect}, {"pattern", 0}, {"samples", 16}}},
          {"front", "ssgi", {{"show", kIndirect}, {"pattern", 1}, {"samples", 16}}},
          {"front", "ssgi", {{"show", kIndirect}, {"samples", 16}}},
          {"front", "ssgi", {{"show", kIndirect}, {"samples", 16}, {"blur", 0}}},
          {"front", "ssgi", {{"show", kIndirect}, {"bounces", 2}}},
          {"front", "ssgi", {{"show", kAo}}},
          {"front", "ssgi", {{"show", kTruth}, {"truth-samples", 64}}},
          {"front", "ssgi", {{"show", kError}, {"truth-samples", 64}}, {}, kCornerTies},
          {"front", "ssgi", {{"show", kIndirect}, {"gather", 1}}},
          {"front", "ssgi", {{"show", kBackFaces}}},
          {"front", "ssgi", {{"show", kIndirect}, {"back-faces", 1}}},
          {"front", "ssgi", {{"show", kIndirect}, {"guard-band", 0.25}}}};
}
std::vector<Shot> atrium_shots() {
  return {{"overview", "ssgi", {}, {}, kOtherRenderer}, {"overview", "ssgi", {{"show", kIndirect}}, {}, kOtherRenderer}};
}
// [/references]

// [exercises]
// The exercises (chapters/08_ssgi/exercises/), on the Cornell box as the references.
std::vector<Exercise> exercises() {
  return {{.title = "the disk-to-disk transfer",
           .file = "disk_transfer.glsl",
           .define = "EXERCISE_DISK_TRANSFER",
           .shots = {{"front", "ssgi", {{"show", kIndirect}}}, {"front", "ssgi", {}}},
           .look_at = "the indirect light (--show indirect): the red and green walls' colour bleeding onto the boxes and the floor"},
          {.title = "the sample patterns: polar grid, spiral, randomised spiral",
           .file = "pattern_point.glsl",
           .define = "EXERCISE_PATTERN_POINT",
           .shots = {{"front", "ssgi", {{"show", kIndirect}, {"pattern", 0}, {"samples", 16}}},
                     {"front", "ssgi", {{"show", kIndirect}, {"pattern", 1}, {"samples", 16}}},
                     {"front", "ssgi", {{"show", kIndirect}, {"samples", 16}, {"blur", 0}}}},
           .look_at = "the indirect light with each --pattern (regular, spiral, randomised with --blur 0): its bands or its noise"},
          {.title = "the surface a sample stands for",
           .file = "sample_area.glsl",
           .define = "EXERCISE_SAMPLE_AREA",
           .shots = {{"front", "ssgi", {{"show", kIndirect}}}, {"front", "ssgi", {{"show", kAo}}}},
           .look_at = "the indirect light and the AO (--show ao) far from the camera and on surfaces seen at a slant"}};
}
// [/exercises]

const Chapter kChapter{.cli = kCli,
                       .references = cornell_shots(),
                       .scene_references = {{"assets/atrium/atrium.gltf", atrium_shots()}},
                       .exercises = exercises()};

GiSettings settings_from(const Frame& f) {
  GiSettings s;
  s.samples = f.knob_int("samples");
  s.ao_radius = float(f.knob("radius"));
  s.gi_radius = float(f.knob("radius") * f.knob("ratio"));
  s.pattern = f.choice("pattern") == "regular" ? Pattern::Regular
            : f.choice("pattern") == "spiral"  ? Pattern::Spiral
                                               : Pattern::Randomised;
  s.blur = f.knob_int("blur") != 0;
  s.bounces = f.knob_int("bounces");
  s.gather = f.choice("gather") == "bitmask" ? Gather::Bitmask : Gather::Disk;
  s.thickness = float(f.knob("thickness"));
  s.back_faces = f.choice("back-faces") == "on";
  return s;
}

GiMode mode_from(const Frame& f) {
  return f.mode == "ssao" ? GiMode::Ssao : f.mode == "off" ? GiMode::Off : GiMode::Ssgi;
}

}  // namespace

int main(int argc, char** argv) {
  return run_chapter(argc, argv, kChapter, [](App& app) {
    // 1. The frame: chapter 03's deferred frame with the scene's lights, cut at one output step.
    ch03::DeferredFrame frame(app.scene_gpu());
    ch03::use_lights(frame, app.scene(), app.scene().lights);
    // 2. The stage: its ambient hook leaves the ambient out of the global pass; after the direct
    //    lights it computes AO + indirect light in one pass and adds A x ambient + L1_ind.
    GiStage gi(app.scene_gpu());
    frame.add_stage(gi);
    // 3. The guard band, when asked for: the frame drawn wider into its own target, cropped.
    std::unique_ptr<OutputTarget> wide;
    std::unique_ptr<OutputTarget> split;  // --show split: the indirect light's half

    while (app.next_frame()) {
      const Frame& f = app.frame();
      const auto start = std::chrono::steady_clock::now();
      if (f.reload_shaders) {
        frame.reload_shaders();
        gi.reload_shaders();
      }
      // [frame]
      const glm::vec3 ambient = app.scene().ambient * float(f.knob("ambient"));
      frame.set_ambient(ambient);
      const int show = f.knob_int("show");
      const float exposure = float(f.knob("exposure"));
      const GiSettings settings = settings_from(f);
      const GuardBand band{guard_band_pixels(f.knob("guard-band"), f.height)};
      gi.set_guard_band(band.pixels);
      auto render = [&](PassMetrics* metrics, GLuint target) {
        if (band.pixels == 0) return frame.render(f.camera, {target, f.width, f.height}, metrics);
        if (!wide || wide->width() != band.width(f.width) || wide->height() != band.height(f.height)) {
          // the wide frame obeys --size's own limit (16384) and this GL's texture size
          GLint gl_most = 0;
          glGetIntegerv(GL_MAX_TEXTURE_SIZE, &gl_most);
          const int most = std::min(16384, int(gl_most));
          if (band.width(f.width) > most || band.height(f.height) > most)
            throw Error("--guard-band " + std::to_string(band.pixels) + " px makes the frame " +
                        std::to_string(band.width(f.width)) + "x" + std::to_string(band.height(f.height)) +
                        ", larger than the " + std::to_string(most) + " pixels a side a frame may have here");
          wide = std::make_unique<OutputTarget>(band.width(f.width), band.height(f.height));
        }
        frame.render(band.widen(f.camera, f.width, f.height), {wide->framebuffer(), wide->width(), wide->height()},
                     metrics);
        band.crop(wide->framebuffer(), target, f.width, f.height);
      };
      gi.set(mode_from(f), settings,
             show == kIndirect ? GiShow::Indirect : show == kAo ? GiShow::Ao : show == kBackFaces ? GiShow::BackFaces
                                                                                               : GiShow::Image,
             ambient, exposure);
      if (show == kTruth || show == kError) {
        // 3. The truth at this size and camera (cached on disk), and for the error the SSGI of
        //    the frame just drawn against it
        GiTruthSettings ts{.samples = f.knob_int("truth-samples"), .bounces = settings.bounces};
        const ImageF truth = cached_ray_traced_indirect(app.scene(), frame.volumes().lights(), f.camera, f.width,
                                                        f.height, ts);
        if (show == kTruth) {
          ImageF picture = truth;
          for (float& v : picture.data) v = std::max(v, 0.f);
          gi.set_picture(picture);
          gi.set(mode_from(f), settings, GiShow::Picture, ambient, exposure);
        } else {
          render(nullptr, f.target);
          ImageF estimate = ImageF::blank(f.width, f.height, 4);
          if (gi.ran() && gi.settings().indirect) estimate = band.crop(gi.ssgi().read());
          gi.set_picture(gi_error_map(estimate, truth), 0.2f);
          gi.set(mode_from(f), settings, GiShow::Heat, ambient, exposure);
        }
      }
      // 4. G-buffer, direct lights, the SSGI pass added (the back-face layer drawn and lit first
      //    when asked for), the composite (or the picture), the screen's part of a guard band
      render(&app.metrics(), f.target);
      // [/frame]
      // The split: the indirect light drawn too, the middle halves of both side by side (the
      // box is in the middle); the captions and keys drawn into the picture.
      if (show == kSplit || show == kError) {
        ImageRGBA8 img = read_framebuffer(f.target, f.width, f.height);
        if (show == kSplit) {
          if (!split || split->width() != f.width || split->height() != f.height)
            split = std::make_unique<OutputTarget>(f.width, f.height);
          gi.set(mode_from(f), settings, GiShow::Indirect, ambient, exposure);
          render(nullptr, split->framebuffer());
          const ImageRGBA8 lit = img, indirect = read_framebuffer(split->framebuffer(), f.width, f.height);
          const int half = f.width / 2, from = f.width / 4;
          for (int y = 0; y < f.height; ++y) {
            std::copy_n(lit.at(from, y), std::size_t(half) * 4, img.at(0, y));
            std::copy_n(indirect.at(from, y), std::size_t(f.width - half) * 4, img.at(half, y));
          }
          draw_label(img, 2, 2, "lit image");
          std::ostringstream what;
          what << "indirect light x " << exposure;
          draw_label(img, f.width / 2 + 2, 2, what.str());
        } else {
          draw_heat_key(img, {.full_scale = 0.2f, .what = "|indirect light - ray-traced truth|", .mixed_in_linear = true});  // show_gi.frag's ramp
        }
        put_picture(img, f.target);
      }
      app.metrics().set_allocation("G-buffer (chapter 02) + light buffer (chapter 03)", frame.allocated_bytes());
      if (gi.drew_back_faces())
        app.metrics().set_allocation("back-face layer: G-buffer + light buffer", gi.back_faces().allocated_bytes());
      if (std::ostream& out = app.report()) {
        glFinish();
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        const GiSettings& s = gi.settings();
        if (gi.ran())
          out << "SSGI " << f.mode << ", " << Ssgi::used_samples(s.pattern, s.samples) << " samples, "
              << kPatternNames[int(s.pattern)] << ", radii " << s.ao_radius << " / " << s.gi_radius << ", "
              << s.bounces << (s.bounces == 1 ? " bounce" : " bounces")
              << (s.gather == Gather::Bitmask ? ", bitmask gather" : "")
              << (s.back_faces && s.indirect ? s.gather == Gather::Disk ? ", back-face layer" : ", no back-face layer (the bitmask gather reads the front layer only)" : "");
        else
          out << "no SSGI pass (mode off)";
        if (band.pixels > 0) out << ", guard band " << band.pixels << " px (frame " << band.width(f.width) << "x" << band.height(f.height) << ")";
        out << ": frame took " << ms << " ms (wall clock, " << app.context().renderer() << ")\n";
      }
      app.panel([&] {
        ImGui::Text("%s", gi.ran() ? "AO + indirect computed after the direct lights" : "no pass: constant ambient");
        ImGui::Text("ambient %.3f %.3f %.3f, darkened by the AO", ambient.r, ambient.g, ambient.b);
      });
    }
  });
}
