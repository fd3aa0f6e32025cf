// Chapter 10: the whole frame. `--mode whole` (the default) draws every stage of the book in
// one frame (whole_frame.h), on the night street with its shop windows or, picked in the
// window's panel or with --scene, the atrium; each stage can be switched off.
// `--mode frame` is the chapter's transparency alone: chapter 03's deferred frame, then the
// glass it cannot hold (glTF alphaMode BLEND), drawn by this chapter's transparency stage over
// the finished image with a forward pass lit by the same lights: sorted back to front, or
// weighted blended order-independent transparency (WBOIT), or the exact per-pixel order
// composited on the CPU (the ground truth). `--show` draws WBOIT's two targets, or a method's
// error against the exact order. `--msaa 4` is an option of the whole frame (msaa.h: a
// multisampled G-buffer, edges marked in the stencil and lit per sample there only, a float
// resolve before the HDR chain; `--msaa-view` shows the edges or the plain mean).
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <iostream>

#include <imgui.h>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/10_frame/msaa.h"
#include "chapters/10_frame/transparency.h"
#include "chapters/10_frame/whole_frame.h"
#include "common/app.h"
#include "common/error.h"

namespace {

using namespace lp;
using namespace lp::ch10;

enum Show { kImage, kAccumulation, kRevealage, kError };  // --show's order
const std::vector<std::string> kTransparency = {"sorted", "wboit", "exact", "off"};  // --transparency's order
constexpr float kErrorFullScale = 16.f;  // --show error: 8-bit steps drawn red

const CliSpec kCli{
    .program = "10_frame",
    .summary = "The whole frame: every stage of the book (whole), each switchable. Or (frame) the glass alone, "
               "drawn after the deferred passes by a forward pass lit by the same lights: sorted back to front, "
               "weighted blended OIT, or the exact per-pixel order; --msaa 2/4/8: the whole frame with MSAA.",
    .default_scene = "assets/street_shop/street_shop.gltf",
    .modes = {"whole", "frame"},
    .knobs = {choice_knob("transparency", "the glass: sorted back to front, weighted blended OIT (McGuire & Bavoil), "
                                          "the exact per-pixel order (CPU), or none",
                          kTransparency),
              choice_knob("show", "the image; WBOIT's accumulation (its average colour) or revealage; the method's "
                                  "error against the exact order (red: 16 steps)",
                          {"image", "accumulation", "revealage", "error"}),
              // --mode whole: every stage of the book (whole_frame.h); each can be switched off.
              {"shadows", "whole: the sun's shadow map (chapter 06)", 1, 0, 1, true},
              {"sun-cascades", "whole: chapter 06's cascades for the sun, snapped (1: one map fitted to the view)",
               double(WholeFrameSettings{}.sun_cascades), 1, ch06::kMaxCascades, true},
              {"clustered", "whole: the local lights by chapter 09's clusters (off: chapter 03's stencil volumes)", 1, 0, 1, true},
              choice_knob("global", "whole: chapter 03's global pass (ambient + directional), chapter 08's add "
                                    "of the indirect light and chapter 03's composite in compute or as fragment passes: "
                                    "the same image, bit for bit; compute suits a GPU that runs fragment shaders on a "
                                    "few of its cores only",
                          {"compute", "fragment"}),
              {"ao", "whole: ambient occlusion (chapters 07, 08)", 1, 0, 1, true},
              {"indirect", "whole: one bounce of indirect light (chapter 08)", 1, 0, 1, true},
              {"neon", "whole: chapter 04's tubes", 1, 0, 1, true},
              choice_knob("tubes", "whole: the tubes' light shaded in chapter 09's clusters with the local lights, or "
                                   "chapter 04's capsule volumes through the stencil (with --clustered 0: the volumes)",
                          {"clusters", "volumes"}),
              {"sun", "whole: multiplies directional lights (chapter 05)", 1, 0, 1000},
              {"glow", "whole: multiplies emissive surfaces (chapter 05)", 8, 0, 10000},
              choice_knob("bloom", "whole: chapter 05's bloom: off, after tonemapping, or before (energy-conserving)",
                          {"off", "after", "before"}, 2),
              choice_knob("msaa", "whole: samples per pixel: 1 is the frame above; 2, 4 or 8 draw it with MSAA "
                                  "(lit per sample only on the edges, a float resolve before the HDR chain; the "
                                  "stages without MSAA yet are not run, and the plan says so)",
                          {"1", "2", "4", "8"}),
              choice_knob("msaa-view", "with --msaa 2, 4 or 8: the image, the edges marked for per-sample light (red), "
                                       "or the samples' plain mean (resolve-first: hard bright edges)",
                          {"image", "edges", "resolve-first"})}};

// The error views draw |method - exact| as a heat map whose first level (one 8-bit step,
// colour value 64) is most of what they show: half-float and 8-bit rounding of each layer
// differ by a step between renderers, so another renderer moves many pixels by that one
// level and a few by more (book/10b-transparency.md). Another renderer is held to the structure:
// differences beyond one heat level (threshold 70) on at most 1 % of the pixels; the
// renderer that made the references keeps 3 steps and 0.1 %.
const CompareOptions kOneHeatLevel{.threshold = 70, .max_failing_fraction = 0.01};

// The atrium's tiled floor is minified far into the distance: kMinifiedTextureAllowance
// (common/app.h) on another renderer, with AO and indirect light off too.
const CompareOptions kTexturedFloor = kMinifiedTextureAllowance;

// The whole frame with every stage on (the default knobs), then each stage the scene has
// switched off in turn, and its glass by WBOIT instead of sorting.
std::vector<Shot> whole_shots(const char* view, bool neon_and_glass, std::optional<CompareOptions> other = {}) {
  std::vector<Shot> shots = {{view, "whole", {}, {}, other},
                             {view, "whole", {{"shadows", 0}}, {}, other},
                             {view, "whole", {{"clustered", 0}}, {}, other},
                             {view, "whole", {{"ao", 0}, {"indirect", 0}}, {}, other},
                             {view, "whole", {{"bloom", 0}}, {}, other}};
  if (neon_and_glass) {
    shots.push_back({view, "whole", {{"neon", 0}}});
    shots.push_back({view, "whole", {{"tubes", 1}}});  // chapter 04's capsule volumes: the same image
    shots.push_back({view, "whole", {{"transparency", 1}}});
  }
  return shots;
}

std::vector<Shot> street_shots() {
  std::vector<Shot> shots = whole_shots("shops", true);
  shots.push_back({"shop_window", "whole"});
  return shots;
}

std::vector<Shot> glass_shots() {
  std::vector<Shot> shots;
  for (const char* view : {"front", "side", "crossing"})
    for (int t : {0, 1, 2}) shots.push_back({view, "frame", {{"transparency", t}}});
  shots.push_back({"front", "frame", {{"transparency", 3}}});
  shots.push_back({"front", "frame", {{"transparency", 1}, {"show", kAccumulation}}});
  shots.push_back({"front", "frame", {{"transparency", 1}, {"show", kRevealage}}});
  shots.push_back({"front", "frame", {{"transparency", 0}, {"show", kError}}, {}, kOneHeatLevel});
  shots.push_back({"front", "frame", {{"transparency", 1}, {"show", kError}}, {}, kOneHeatLevel});
  shots.push_back({"crossing", "frame", {{"transparency", 0}, {"show", kError}}, {}, kOneHeatLevel});
  return shots;
}

// [exercises]
// The exercises (chapters/10_frame/exercises/): the glass scene's panes, the street's shops.
// --transparency 1: wboit; --msaa 2: four samples; --msaa-view 1: edges, 2: resolve-first.
std::vector<Exercise> exercises() {
  return {{.title = "the depth weight of weighted blended transparency",
           .file = "wboit_weight.glsl",
           .define = "EXERCISE_WBOIT_WEIGHT",
           .shots = {{"front", "frame", {{"transparency", 1}}}, {"crossing", "frame", {{"transparency", 1}}},
                     {"front", "frame", {{"transparency", 1}, {"show", kAccumulation}}}},
           .look_at = "the glass panes where they overlap (--transparency wboit, and --show accumulation): the near pane should dominate",
           .scene = "assets/glass/glass.gltf"},
          {.title = "MSAA's edge test: which pixels are lit per sample",
           .file = "edge_test.glsl",
           .define = "EXERCISE_EDGE_TEST",
           .shots = {{"shops", "whole", {{"msaa", 2}, {"msaa-view", 1}}}, {"shop_window", "whole", {{"msaa", 2}, {"msaa-view", 1}}}},
           .look_at = "the edges marked red (--msaa 4 --msaa-view edges): silhouettes, creases and lit windows in their walls"},
          {.title = "MSAA's resolve into radiance, weighted by the tone curve",
           .file = "resolve.glsl",
           .define = "EXERCISE_RESOLVE",
           .shots = {{"shops", "whole", {{"msaa", 2}}}, {"shops", "whole", {{"msaa", 2}, {"msaa-view", 2}}}},
           .look_at = "the edges against bright lamps and windows (--msaa 4), and --msaa-view resolve-first"}};
}
// [/exercises]

const Chapter kChapter{.cli = kCli,
                       .references = street_shots(),
                       .scene_references = {{"assets/glass/glass.gltf", glass_shots()},
                                            {"assets/atrium/atrium.gltf", whole_shots("aisle", false, kTexturedFloor)}},
                       .exercises = exercises()};

// --mode whole: every chapter's stage in one deferred frame (whole_frame.cpp), and its plan.
void draw_whole(App& app, const Frame& f, WholeFrame& whole) {
  const std::string& which = f.choice("transparency");
  WholeFrameSettings s{.shadows = f.knob_int("shadows") != 0, .clustered = f.knob_int("clustered") != 0,
                       .global = ch03::global_pass_named(f.choice("global")),
                       .ao = f.knob_int("ao") != 0, .indirect = f.knob_int("indirect") != 0,
                       .neon = f.knob_int("neon") != 0,
                       .tubes = f.choice("tubes") == "volumes" ? TubeLight::Volumes : TubeLight::Clusters,
                       .sun_cascades = f.knob_int("sun-cascades"),
                       // The exact order is --mode frame's ground truth (a CPU composite): the
                       // whole frame sorts instead, and says so below.
                       .transparency = which == "off" ? Method::Off : which == "exact" ? Method::Sorted : method_named(which),
                       .sun = float(f.knob("sun")), .glow = float(f.knob("glow")),
                       .msaa = std::stoi(f.choice("msaa")),
                       .msaa_order = f.choice("msaa-view") == "resolve-first" ? ResolveOrder::ResolveFirst : ResolveOrder::TonemapFirst,
                       .msaa_edges = f.choice("msaa-view") == "edges"};
  s.hdr.bloom = static_cast<ch05::BloomMode>(f.knob_int("bloom"));
  whole.render(f.camera, {f.target, f.width, f.height}, s, f.dt, f.new_shot, &app.metrics());
  app.metrics().set_allocation("the whole frame's targets (G-buffer, light, radiance, maps, lists, HDR chains)",
                               whole.allocated_bytes());
  if (s.msaa > 1)
    if (std::ostream& out = app.report())
      out << "MSAA " << s.msaa << " samples (per sample on the marked edges, a float resolve: " << f.choice("msaa-view")
          << "); the stages without MSAA yet are not run\n";
  const char* exact_note = "the exact order is --mode frame's ground truth: the whole frame sorts the glass";
  if (which == "exact") app.report() << "note: " << exact_note << '\n';
  const std::vector<PlannedStage> plan = whole.plan(s);
  if (std::ostream& out = app.report()) {
    out << "the whole frame:\n";
    for (const PlannedStage& st : plan)
      out << "  " << (st.runs ? "runs     " : "not run  ") << st.stage << (st.runs ? "" : " (" + st.why + ")")
          << "  [reads " << st.reads << "; writes " << st.writes << "]\n";
  }
  app.panel([&] {
    // A box switches its stage (the knob of the same name); a bullet always runs or follows another knob.
    ImGui::Separator();
    ImGui::TextDisabled("the frame's stages (a box switches one)");
    static const std::map<int, std::string> kSwitch = {{kShadowMap, "shadows"}, {kNeon, "neon"}, {kAo, "ao"}, {kIndirect, "indirect"}};
    for (std::size_t i = 0; i < plan.size(); ++i)
      app.plan_line(plan[i].stage, plan[i].runs, plan[i].why, kSwitch.contains(int(i)) ? kSwitch.at(int(i)) : "");
    if (which == "exact") ImGui::TextWrapped("%s", exact_note);
  });
}

// --mode frame: the glass room's transparency study, chapter 03's frame with the glass stage,
// a method against the exact per-pixel order.
void draw_glass_study(App& app, const Frame& f, ch03::DeferredFrame& frame, TransparencyStage& glass) {
  const auto start = std::chrono::steady_clock::now();
  const ch03::FrameOutput output{f.target, f.width, f.height};
  const std::string& which = f.choice("transparency");
  const int show = f.knob_int("show");
  // [frame]
  // 3. The frame: G-buffer, lights, composite, then the glass over it.
  const bool exact_needed = which == "exact" || show == kError;
  ExactComposite exact;
  if (exact_needed) {  // the exact order over the opaque image, as the ground truth
    glass.set({.method = Method::Off});
    frame.render(f.camera, output);
    exact = glass.exact_composite(frame);
    if (exact.overflow) std::cerr << "warning: the exact composite's fragment list overflowed\n";
  }
  if (which != "exact") {
    const Method method = which == "off" ? Method::Off : method_named(which);
    TransparencySettings s{.method = method};
    if (method == Method::Wboit) s.order = DrawOrder::AsListed;  // no sorting: the point of it
    if (show == kAccumulation) s.show = TransparencyShow::Accumulation;
    if (show == kRevealage) s.show = TransparencyShow::Revealage;
    glass.set(s);
    frame.render(f.camera, output, &app.metrics());
  }
  // 4. The pictures: a method's error against the exact order.
  if (show == kError) {
    const ImageRGBA8 image = which == "exact" ? exact.image : read_framebuffer(f.target, f.width, f.height);
    ImageRGBA8 heat = diff_heatmap(image, exact.image, 1, int(kErrorFullScale));
    // The ramp's key, at the map's own scale, so the picture says what red is.
    draw_heat_key(heat, {.full_scale = kErrorFullScale,
                         .what = "|" + which + " - exact order|, 8-bit steps", .threshold = 1});
    put_picture(heat, f.target);
    if (std::ostream& out = app.report()) out << which << " against the exact order: " << compare(image, exact.image).summary() << '\n';
  } else if (which == "exact") {
    put_picture(exact.image, f.target);
  }
  // [/frame]
  app.metrics().set_allocation("G-buffer (chapter 02) + light buffer (chapter 03)", frame.allocated_bytes());
  if (which == "wboit") app.metrics().set_allocation("WBOIT accumulation RGBA16F + revealage R16F + depth", glass.allocated_bytes());
  if (std::ostream& out = app.report()) {
    glFinish();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    out << glass.blended_count() << " transparent surfaces, " << which << ": frame took " << ms << " ms (wall clock, "
        << app.context().renderer() << ")";
    if (exact_needed) out << "; exact order: " << exact.fragments << " fragments";
    out << '\n';
  }
  app.panel([&] { ImGui::Text("%zu transparent surfaces", glass.blended_count()); });
}

}  // namespace

int main(int argc, char** argv) {
  return run_chapter(argc, argv, kChapter, [](App& app) {
    // 1. Chapter 03's deferred frame, its lights cut as chapter 03 cuts them.
    ch03::DeferredFrame frame(app.scene_gpu());
    ch03::use_lights(frame, app.scene(), app.scene().lights);
    // 2. This chapter's stage: the glass, after the composite, lit by the same lights.
    TransparencyStage glass(frame, app.scene_gpu());
    frame.add_stage(glass);
    std::unique_ptr<WholeFrame> whole;  // --mode whole: made when first asked for

    // 3. Each frame, one of two: the whole frame (with MSAA or without), or the glass study.
    while (app.next_frame()) {
      const Frame& f = app.frame();
      if (f.reload_shaders) {
        frame.reload_shaders();
        glass.reload_shaders();
        if (whole) whole->reload_shaders();
      }
      if (f.mode == "whole") {
        if (!whole) whole = std::make_unique<WholeFrame>(app.scene_gpu());
        draw_whole(app, f, *whole);
      } else {
        if (f.choice("msaa") != "1")
          throw UsageError("--msaa " + f.choice("msaa") + " is an option of the whole frame (--mode whole); the glass "
                           "study (--mode frame) draws no MSAA");
        draw_glass_study(app, f, frame, glass);
      }
    }
  });
}
