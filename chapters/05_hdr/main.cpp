// Chapter 05: HDR. The lit scene is accumulated in a float target by chapter 03's deferred
// path (G-buffer, light volumes, float light buffer), its log-average luminance sets the
// exposure (with the eye adapting over frames), bloom spreads the brightest light, and a
// tonemapping curve brings it into the display's range. The lights' volumes are cut for the
// exposure, read back from earlier frames without waiting. The modes switch the curve, show
// what an 8-bit light accumulation loses, and show the bloom's intermediate images.
#include <cmath>
#include <iostream>
#include <map>
#include <memory>

#include <imgui.h>

#include "chapters/04_neon/neon_scene.h"
#include "chapters/04_neon/neon_stage.h"
#include "chapters/05_hdr/exposure_feedback.h"
#include "chapters/05_hdr/hdr_pipeline.h"
#include "chapters/05_hdr/radiance_source.h"
#include "common/app.h"
#include "common/error.h"

namespace {

using namespace lp::ch05;

const std::vector<std::string> kModes = {"reinhard", "reinhard-extended", "aces", "clamp", "8bit", "bright-pass", "bloom-only"};

const lp::CliSpec kCli{
    .program = "05_hdr",
    .summary = "HDR: float light accumulation, log-average exposure with eye adaptation, tonemapping operators, bloom.",
    .default_scene = "assets/street/street.gltf",
    .modes = kModes,
    .knobs = {{"sun", "multiplies directional lights (the atrium's sun)", 1, 0, 1000},
              {"glow", "multiplies emissive surfaces (lamps, windows)", 8, 0, 10000},
              {"key", "exposed value of the log-average luminance (middle grey)", 0.18, 0.001, 100},
              {"adapt-floor", "darkest log-average the eye adapts to: a darker scene is shown darker "
                              "(0: the fixed key, every scene middle grey)", 0.18, 0, 1e6},
              {"white", "reinhard-extended: exposed value shown as white", 4, 0.01, 1e6},
              {"tau", "eye adaptation time constant, seconds (0: instant)", 0.5, 0, 600},
              {"adapt-start", "first frame: eye adapted to this times its average", 1, 1e-4, 1e6},
              lp::choice_knob("average", "log-average: our mip chain, a compute reduction, the naive mip chain, "
                                         "glGenerateMipmap", kAverageMethodNames),
              lp::choice_knob("bloom", "off, added after tonemapping (the source), or before (energy-conserving)",
                              {"off", "after", "before"}),
              {"bloom-level", "blur at 1/2^N of the resolution", 2, 0, 8, true},
              {"bloom-radius", "Gaussian sigma as a fraction of the image height", 0.02, 0, 0.5},
              {"bloom-threshold", "exposed luminance above which a pixel blooms", 1, 0, 1e6},
              {"bloom-strength", "how much of the bloom is added", 0.08, 0, 1}},
    // The street at night from the pavement, through the filmic curve, with bloom spread
    // before it: the README's picture.
    .opening = {"--view", "street_level", "--mode", "aces", "--bloom", "before"}};

// The reference images, per scene (a Shot names a view, not a scene): `--check` renders
// the street's, `--check --scene assets/atrium/atrium.gltf` the atrium's (kChapter below).
const std::vector<lp::Shot> kStreetShots = {
    // Each operator, 8-bit light accumulation, the fixed key's grey night (the eye adapted all
    // the way into the dark) and a night key, both bloom placements, bloom stages.
    {"street_level", "reinhard"}, {"street_level", "reinhard-extended"}, {"street_level", "aces"},
    {"street_level", "clamp"}, {"street_level", "8bit"}, {"street_level", "aces", {{"adapt-floor", 0}}},
    {"street_level", "aces", {{"key", 0.045}, {"adapt-floor", 0}}},
    {"street_level", "aces", {{"bloom", 1}}}, {"street_level", "aces", {{"bloom", 2}}},
    {"street_level", "bright-pass", {{"bloom", 1}}}, {"street_level", "bloom-only", {{"bloom", 1}}},
    // ACES at Reinhard's brightness: key 0.108 is Narkowicz's usual 0.6 pre-scale of the fit's
    // input at key 0.18 (mean 114 steps, Reinhard's 115; at the same key ACES's is 140), both
    // at the fixed key.
    {"street_level", "aces", {{"key", 0.108}, {"adapt-floor", 0}}},
};
// The atrium's tiled floor is minified far into the distance: kMinifiedTextureAllowance.
const lp::CompareOptions kTexturedFloor = lp::kMinifiedTextureAllowance;
const std::vector<lp::Shot> kAtriumShots = {
    // A strong sun: float against 8-bit, the operators, and the first frame after coming in
    // from a scene 30x brighter (the eye has not adapted yet).
    {"aisle", "reinhard", {{"sun", 25}}, {}, kTexturedFloor},
    {"aisle", "8bit", {{"sun", 25}}, {}, kTexturedFloor},
    {"aisle", "aces", {{"sun", 25}}, {}, kTexturedFloor},
    {"aisle", "reinhard-extended", {{"sun", 25}}, {}, kTexturedFloor},
    // Bloom before tonemapping where it shows: at the default threshold and strength the sunny
    // aisle blooms by 0.3 steps on average, indistinguishable from no bloom; at threshold 0.5
    // and strength 0.3 the arches glow against the sky (3.7 steps on average).
    {"aisle", "aces", {{"sun", 25}, {"bloom", 2}, {"bloom-threshold", 0.5}, {"bloom-strength", 0.3}}, {}, kTexturedFloor},
    {"aisle", "reinhard", {{"sun", 25}, {"adapt-start", 30}}, {}, kTexturedFloor},
};

// [exercises]
// The exercises (chapters/05_hdr/exercises/): each renders the street as the references do.
const std::vector<lp::Exercise> kExercises = {
    {.title = "Reinhard's extended curve, with a white point",
     .file = "reinhard_extended.glsl",
     .define = "EXERCISE_REINHARD_EXTENDED",
     .shots = {{"street_level", "reinhard-extended"}, {"street_level", "reinhard-extended", {{"white", 1.5}}}},
     .look_at = "the bright lamps and windows (white at --white) and the mid-tones (the curve's middle)"},
    {.title = "the ACES filmic curve (Narkowicz's fit)",
     .file = "aces_fit.glsl",
     .define = "EXERCISE_ACES_FIT",
     .shots = {{"street_level", "aces"}, {"street_level", "aces", {{"key", 0.045}, {"adapt-floor", 0}}}},
     .look_at = "the dark street (the curve's toe) and the lamps (its shoulder)"},
    {.title = "the bloom's bright pass",
     .file = "bright_pass.glsl",
     .define = "EXERCISE_BRIGHT_PASS",
     .shots = {{"street_level", "bright-pass", {{"bloom", 1}}}, {"street_level", "aces", {{"bloom", 1}}}},
     .look_at = "what the bright pass keeps (--mode bright-pass): only the lamps and windows, in their own colours"},
};
// [/exercises]

const lp::Chapter kChapter{.cli = kCli,
                           .references = kStreetShots,
                           .scene_references = {{"assets/atrium/atrium.gltf", kAtriumShots}},
                           .exercises = kExercises};

// The chapter's knobs as the stage's settings.
HdrSettings settings_for(const lp::Frame& f, float dt) {
  HdrSettings s;
  s.average = static_cast<AverageMethod>(f.knob_int("average"));
  s.adaptation = {.key = float(f.knob("key")), .adapt_floor = float(f.knob("adapt-floor")), .tau = float(f.knob("tau")), .dt = dt};
  s.tonemap.white = float(f.knob("white"));
  s.tonemap.op = f.mode == "reinhard-extended" ? Operator::ReinhardExtended
               : f.mode == "aces"              ? Operator::Aces
               : f.mode == "clamp"             ? Operator::Clamp
                                               : Operator::Reinhard;
  s.bloom = static_cast<BloomMode>(f.knob_int("bloom"));
  s.bloom_chain = {.level = f.knob_int("bloom-level"), .radius = float(f.knob("bloom-radius")),
                   .threshold = float(f.knob("bloom-threshold")), .limit = 64.f};
  s.bloom_strength = float(f.knob("bloom-strength"));
  if (f.mode == "bright-pass") s.view = HdrSettings::View::BrightPass;
  if (f.mode == "bloom-only") s.view = HdrSettings::View::Bloom;
  return s;
}

// The radiance target for this frame: reallocated when the size or the format changes.
// Chapter 03's composite writes every pixel and tests nothing: a depth buffer only for the
// glass of chapter 04's tubes, drawn over the image.
class RadianceTargets {
 public:
  explicit RadianceTargets(bool with_depth) : with_depth_(with_depth) {}
  RadianceTarget& get(const lp::Frame& f, lp::PassMetrics& metrics) {
    GLenum format = f.mode == "8bit" ? GL_RGBA8 : GL_RGBA16F;  // 8-bit: to see what it loses
    if (!target_ || target_->width() != f.width || target_->height() != f.height || target_->format() != format) {
      target_ = std::make_unique<RadianceTarget>(f.width, f.height, format, with_depth_);
      metrics.set_allocation(format == GL_RGBA8 ? "radiance colour RGBA8" : "radiance colour RGBA16F", target_->bytes());
    }
    return *target_;
  }

 private:
  bool with_depth_;
  std::unique_ptr<RadianceTarget> target_;
};

}  // namespace

int main(int argc, char** argv) {
  return lp::run_chapter(argc, argv, kChapter, [](lp::App& app) {
    DeferredRadiance source(app.scene_gpu());  // the program's scene, as uploaded
    // Chapter 04's tubes, where the scene has any (the night street with its signs), as a
    // stage of the same deferred frame.
    lp::ch04::NeonTubes tubes;
    tubes.upload(lp::ch04::neon_lights(app.scene()));
    lp::ch04::NeonStage neon(source.scene_gpu(), tubes);
    if (tubes.count() > 0) source.frame().add_stage(neon);
    RadianceTargets targets(tubes.count() > 0);
    HdrPipeline hdr;
    ExposureFeedback feedback;
    double adapted_from = -1;  // --adapt-start of the eye's last reset
    ExposureEstimate cut;

    while (app.next_frame()) {
      const lp::Frame& f = app.frame();
      if (f.reload_shaders) {
        source.reload_shaders();
        neon.reload_shaders();
        hdr.reload_shaders();
      }
      // [frame]
      // Each new image (and a new --adapt-start) starts with a fresh eye.
      const float start_scale = float(f.knob("adapt-start"));
      if (f.new_shot || start_scale != adapted_from) {
        hdr.reset_adaptation(start_scale);
        feedback.reset();
        adapted_from = start_scale;
      }
      const HdrSettings settings = settings_for(f, f.dt);
      auto draw = [&](lp::PassMetrics* metrics) {
        // 1. The lights' volumes end where a light gives less than one output step after the
        //    largest exposure this frame can get: read back from an earlier frame, never waiting.
        cut = feedback.begin_frame(settings.adaptation, settings.delta, start_scale);
        source.set_cut_exposure(cut.exposure * output_slope(settings.tonemap.op, settings.tonemap.white));

        // 2. The lit scene as radiance in a float target, by chapter 03's deferred frame:
        //    G-buffer, light volumes (and chapter 04's tubes) into the float light buffer,
        //    composite into our target.
        source.set_scales(float(f.knob("sun")), float(f.knob("glow")));
        RadianceTarget& radiance = targets.get(f, app.metrics());
        source.render(f.camera, radiance, metrics);

        // 3. The HDR stage: log-average, eye adaptation, bloom, tonemapping into the sRGB8 output.
        hdr.process(radiance.texture(), f.width, f.height, settings, f.target, metrics);
        feedback.end_frame(hdr.adaptation().state_buffer());
      };
      // [/frame]
      // A still image (headless) would be cut with no reading (a new shot resets the readings):
      // it is drawn once unmeasured first, whose exposure, read once the GPU finished, cuts the
      // lights of the picture; the eye is reset in between, so the picture is still the first
      // frame of a new view.
      if (app.options().headless && f.new_shot) {
        draw(nullptr);
        glFinish();
        hdr.reset_adaptation(start_scale);
      }
      draw(&app.metrics());
      app.metrics().set_allocation("G-buffer (chapter 02) + light buffer (chapter 03)", source.allocated_bytes());
      app.metrics().set_allocation("hdr: log-average chain + bloom chain", hdr.allocated_bytes());

      app.panel([&] {
        if (const ExposureState* e = feedback.latest()) {  // read back late: the panel does not wait either
          ImGui::Text("log-average %.4g, adapted %.4g (%d frames ago)", e->target, e->adapted, feedback.latest_age());
          ImGui::Text("exposure %.4g (%.0f pixels averaged)", e->exposure, e->count);
          if (const float floor = settings.adaptation.adapt_floor; e->adapted < floor)
            ImGui::Text("darker than the adaptation floor %.3g: shown %.1f stops under the key", floor,
                        std::log2(floor / e->adapted));
        }
        if (cut.age < 0) ImGui::Text("lights cut for exposure %.4g (no reading yet: the stage's limit)", source.cut_exposure());
        else ImGui::Text("lights cut for exposure %.4g (read %d frames ago: %.4g)", source.cut_exposure(), cut.age, cut.read);
        if (ImGui::Button("re-adapt from 30x brighter")) {
          hdr.reset_adaptation(30.f);
          feedback.reset();
        }
      });
    }
    if (std::ostream& out = app.report()) {
      ExposureState e = hdr.adaptation().read();
      out << "log-average luminance " << e.target << " (" << e.count << " pixels), adapted " << e.adapted
                << ", exposure " << e.exposure << '\n';
      out << "lights cut for exposure " << source.cut_exposure() << " (an exposure of at most " << cut.exposure;
      if (cut.age < 0) out << ", the stage's limit: no reading yet)\n";
      else out << " from the one read " << cut.age << " frames before, " << cut.read << ")\n";
    }
  });
}
