// Chapter 09: tiled and clustered light culling. Chapter 03 drew every local light as a
// volume: a draw per light, which stops scaling long before 100 000 lights. Here compute
// shaders bin the lights into screen tiles (with each tile's depth bounds) or into a 3D grid
// of clusters (exponential depth slices), or (Z-binning) sort them by depth into bins and
// mark them in the tiles they reach, and each pixel is lit by its cell's lights alone,
// in compute or in a full-screen fragment pass. The lights, their cut and their lighting
// are chapter 03's, so every mode gives chapter 03's image; the modes are chapter 03's
// stencil volumes and the seven ways of this chapter (tiled with Harada's 2.5D depth mask
// and Z-binning among them), `--show` draws the heat maps.
#include <cmath>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

#include <imgui.h>

#include "chapters/01_forward/ground_truth.h"
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_counts.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/09_clustered/cluster_picture.h"
#include "chapters/09_clustered/clustered_forward.h"
#include "chapters/09_clustered/clustered_lights.h"
#include "common/app.h"
#include "common/target.h"

namespace {

using namespace lp;
using namespace lp::ch09;

enum Show { kResult, kHeatEvaluated, kHeatLit, kClusters, kSplit };  // --show's order

std::vector<std::string> modes() {
  std::vector<std::string> m = {"clustered"};
  for (const auto& c : kClusterModes)
    if (c != "clustered") m.push_back(c);
  m.push_back("clustered-forward");  // the scene drawn again, forward, from every cluster's list
  m.push_back("stencil");            // chapter 03's volumes, the image to equal
  return m;
}

// The heat maps draw counts: where a light's cut sphere grazes a pixel's position or a tile's
// box within float rounding, another renderer may count it one way and llvmpipe the other,
// and a count one apart is a colour several steps apart (single pixels, and whole tiles of the
// grid view); another renderer gets 2 %, the allowance of the book's other implementation-defined views,
// and the renderer that made the references keeps 0.1 %. The images (lit) are held as usual.
const CompareOptions kCounts{.threshold = 3, .max_failing_fraction = 0.02};

std::vector<Shot> references() {
  // Every mode on the street's own lights and inside a light: all chapter 03's stencil image
  // (the GL tests hold how close; here each against its own reference). The heat maps at 1000
  // lights: lights evaluated and lit per pixel, tiles against clusters, and the grid itself.
  std::vector<Shot> shots;
  for (const auto& m : modes()) shots.push_back({"street_level", m});
  shots.push_back({"street_level", "clustered-forward", {{"lights", 1000}, {"show", kHeatEvaluated}, {"heat-scale", 200}}, {}, kCounts});
  shots.push_back({"street_level", "clustered", {{"show", kSplit}}, {}, kCounts});  // the opening, the README's picture
  shots.push_back({"inside_light", "clustered"});
  shots.push_back({"inside_light", "tiled"});
  for (const std::string m : {"tiled", "clustered"})
    for (int show : {kHeatEvaluated, kHeatLit, kClusters})
      shots.push_back({"street_level", m, {{"lights", 1000}, {"show", show}, {"heat-scale", 200}}, {}, kCounts});
  shots.push_back({"street_level", "tiled-2.5d", {{"lights", 1000}, {"show", kHeatEvaluated}, {"heat-scale", 200}}, {}, kCounts});
  shots.push_back({"street_level", "clustered",
                   {{"lights", 1000}, {"clusters-x", 32}, {"clusters-y", 18}, {"slices", 8}, {"show", kHeatEvaluated}, {"heat-scale", 200}},
                   {}, kCounts});
  return shots;
}

// The exercises (the book's "Exercises"): three functions of grid.glsl, each checked on the
// image at 1000 lights (a light lost shows) and on the lights evaluated per pixel (a light kept
// everywhere shows); and the radius of the sphere they cull with, a number.
std::vector<Exercise> exercises() {
  const std::map<std::string, double> heat = {{"lights", 1000}, {"show", kHeatEvaluated}, {"heat-scale", 200}};
  const std::vector<Shot> shots = {{"street_level", "clustered", {{"lights", 1000}}},
                                   {"street_level", "clustered", heat, {}, kCounts}};
  return {{.title = "the exponential depth slice of a surface",
           .file = "slice_of.glsl",
           .define = "EXERCISE_SLICE_OF",
           .shots = shots,
           .look_at = "the street with --lights 1000: pools of light cut off at a slice's edge, and (--show "
                      "heat-evaluated) the lights each pixel evaluates"},
          {.title = "the view-space box around one cell",
           .file = "cell_box.glsl",
           .define = "EXERCISE_CELL_BOX",
           .shots = {shots[1], {"street_level", "tiled", heat, {}, kCounts}, shots[0]},
           .look_at = "the lights each pixel evaluates (--show heat-evaluated, in --mode clustered and tiled): too "
                      "many where the box is too large, and lights cut off in the image where it misses part of the cell"},
          {.title = "does a light's sphere meet a cell's box?",
           .file = "sphere_box.glsl",
           .define = "EXERCISE_SPHERE_BOX",
           .shots = shots,
           .look_at = "the lights each pixel evaluates (--show heat-evaluated), and pools of light cut off at cell "
                      "edges in the image"},
          {.title = "how far a light's cut sphere reaches (a number)",
           .file = "cut_radius.txt",
           .look_at = "chapter 03's light_radius.h [threshold]: the cut is where the light falls to one sRGB step",
           .number = NumberAnswer{.expected = [] { return double(ch03::light_radius(10.f, 0.f, ch03::cut_threshold(1.f))); },
                                  .tolerance = 0.1,
                                  .unit = "m"}}};
}

const lp::Chapter kChapter{
    .cli = {.program = "09_clustered",
            .summary = "Tiled and clustered light culling: lights binned into screen tiles or 3D clusters by compute "
                       "shaders, each pixel lit by its cell's list; chapter 03's image, towards 100 000 lights.",
            .default_scene = "assets/street/street.gltf",
            .modes = modes(),
            .knobs = {{"lights", "local lights (0: the scene's own; more adds lights like them)", 0, 0, 1000000, true},
                      choice_knob("show", "result, lights evaluated or lit per pixel, lights per cluster (the grid), "
                                          "or the image's left half beside the lights evaluated per pixel",
                                  {"result", "heat-evaluated", "heat-lit", "clusters", "split"}),
                      {"tile", "tiled and zbin: tile size in pixels", 16, 1, 512, true},
                      {"clusters-x", "clustered: tiles across (DOOM 2016: 16)", 16, 1, 1024, true},
                      {"clusters-y", "clustered: tiles down (DOOM 2016: 9)", 9, 1, 1024, true},
                      {"slices", "clustered: exponential depth slices (DOOM 2016: 24)", 24, 1, 256, true},
                      {"near-slice", "clustered: the first slice's far end in metres, the others exponential beyond it "
                                     "(0: none)", 0, 0, 100, false},
                      {"bins", "zbin: exponential depth bins", 1024, 1, 16384, true},
                      {"lanes", "zbin-staged: invocations a pixel, 1, 2 or 4 (more than 1 in tiles of at most 16 "
                                "pixels)", 4, 1, 4, true},
                      {"lanes-from", "zbin-staged: the lanes only in tiles of at least this many lights (0: every tile)",
                       1024, 0, 1000000, true},
                      {"heat-scale", "heat maps: lights per pixel or per cluster shown white", 100, 1, 1e7, false},
                      {"count", "count lights evaluated and lit (atomic counters, costs a little time)", 1, 0, 1, true}},
            // Down the street, the lit image beside the lights each pixel evaluated: the cells' lists.
            .opening = {"--view", "street_level", "--show", "split"}},
    .references = references(),
    .exercises = exercises(),
};

// The keys drawn into the picture (the window and its PNG): what a heat map's colours count,
// which slice of the grid is which, the split's halves.
void draw_keys(const Frame& f, int show, const Grid& grid) {
  ImageRGBA8 img = read_framebuffer(f.target, f.width, f.height);
  const float full = float(f.knob("heat-scale"));
  if (show == kSplit) {
    const int half = f.width / 2;
    draw_label(img, 2, 2, "image");
    draw_label(img, half + 2, 2, "lights evaluated");
    draw_heat_key(img, {.full_scale = full, .what = "lights per pixel", .stops = ch03::kHeatRamp}, half);
  } else if (show == kHeatEvaluated || show == kHeatLit) {
    draw_heat_key(img, {.full_scale = full,
                        .what = show == kHeatEvaluated ? "lights evaluated per pixel" : "lights that lit the pixel",
                        .stops = ch03::kHeatRamp});
  } else if (show == kClusters) {  // cluster_picture's layout: slices left to right, top to bottom
    const int rows = heat_key_rows(f.width), cols = int(std::ceil(std::sqrt(double(grid.slices))));
    const int w = cols * (grid.tiles_x + 1) - 1, h = ((grid.slices + cols - 1) / cols) * (grid.tiles_y + 1) - 1;
    for (int k = 0; k < grid.slices && grid.slices > 1; ++k) {  // tiles: one slice, each tile its own depth range
      const int x = (k % cols) * (grid.tiles_x + 1) * f.width / w, y = (k / cols) * (grid.tiles_y + 1) * (f.height - rows) / h;
      char range[64];
      std::snprintf(range, sizeof range, "%d: %.3g-%.3g m", k, slice_start(grid, k), slice_start(grid, k + 1));
      const int room = grid.tiles_x * f.width / w;
      draw_label(img, x, y, text_width(range, label_scale(f.width)) + 4 * label_scale(f.width) <= room ? range : std::to_string(k));
    }
    draw_heat_key(img, {.full_scale = full, .what = grid.slices > 1 ? "lights per cluster, slices near to far" : "lights per tile"});
  }
  put_picture(img, f.target);
}

}  // namespace

int main(int argc, char** argv) {
  return lp::run_chapter(argc, argv, kChapter, [](lp::App& app) {
    ch03::DeferredFrame frame(app.scene_gpu());
    ClusteredLights clustered(frame.volumes());
    ClusteredForward forward(frame, app.scene_gpu());
    ClusterPicture picture;
    std::unique_ptr<OutputTarget> heat;  // --show split: the heat map's half
    double lights_key = -1;
    std::uint64_t warned_frame = 0;

    while (app.next_frame()) {
      const lp::Frame& f = app.frame();
      const auto start = std::chrono::steady_clock::now();
      if (f.reload_shaders) {
        frame.reload_shaders();
        clustered.reload_shaders();
        forward.reload_shaders();
      }
      // 1. The lights: chapter 03's set for the count asked, cut where chapter 03 cuts them.
      if (f.knob("lights") != lights_key) {
        lights_key = f.knob("lights");
        ch03::use_lights(frame, app.scene(), ch03::lights_for_count(app.scene(), f.knob_int("lights")));
      }
      // 2. The culling: chapter 03's stencil volumes, or this chapter's tiles or clusters,
      //    shaded deferred or (clustered-forward) by drawing the scene again.
      const bool ours = f.mode != "stencil", is_forward = f.mode == "clustered-forward";
      ClusteredLights& lists = is_forward ? forward.lists() : clustered;
      if (ours) {
        ClusterSettings s = settings_for_mode(is_forward ? "clustered" : f.mode);
        s.tile_px = std::max(f.knob_int("tile"), 1);
        s.clusters = {f.knob_int("clusters-x"), f.knob_int("clusters-y"), f.knob_int("slices")};
        s.near_slice = float(f.knob("near-slice"));
        s.zbins = f.knob_int("bins");
        s.pixel_lanes = f.knob_int("lanes");
        s.lanes_from = f.knob_int("lanes-from");
        if (is_forward) {
          forward.set_settings(s);
          forward.set_counting(f.knob_int("count") != 0);
          frame.set_local_lights(&forward);
        } else {
          clustered.set_settings(s);
          clustered.set_counting(f.knob_int("count") != 0);
          frame.set_local_lights(&clustered);
        }
      } else {
        frame.set_local_lights(nullptr);
        frame.set_strategy(ch03::Strategy::Stencil);
        frame.volumes().set_counting(f.knob_int("count") != 0);
      }
      // 3. The frame (chapter 03's deferred_frame.cpp): G-buffer, global light, the local
      //    lights through the pass chosen above, composite; or a heat map of the light buffer.
      const int show = f.knob_int("show");
      const ch03::FrameShow frame_show = show == kHeatEvaluated ? ch03::FrameShow::HeatShaded
                                         : show == kHeatLit     ? ch03::FrameShow::HeatLit
                                                                : ch03::FrameShow::Image;
      frame.render(f.camera, {f.target, f.width, f.height}, &app.metrics(),
                   {.show = frame_show, .heat_full_scale = float(f.knob("heat-scale"))});
      // 4. The grid itself: each cell's light count, slice by slice, over the image.
      if (show == kClusters && ours)
        picture.draw(lists.grid(), lists.cell_counts(), {f.target, f.width, f.height}, float(f.knob("heat-scale")),
                     heat_key_rows(f.width));
      // The split: the heat map drawn too, its right half over the image's.
      if (show == kSplit) {
        if (!heat || heat->width() != f.width || heat->height() != f.height)
          heat = std::make_unique<OutputTarget>(f.width, f.height);
        frame.render(f.camera, {heat->framebuffer(), f.width, f.height}, nullptr,
                     {.show = ch03::FrameShow::HeatShaded, .heat_full_scale = float(f.knob("heat-scale"))});
        glDisable(GL_FRAMEBUFFER_SRGB);  // a copy of the bytes
        glBlitNamedFramebuffer(heat->framebuffer(), f.target, f.width / 2, 0, f.width, f.height, f.width / 2, 0, f.width,
                               f.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glEnable(GL_FRAMEBUFFER_SRGB);
      }
      // 5. The keys.
      if (show != kResult && (ours || show != kClusters)) draw_keys(f, show, lists.grid());

      // What it did: lights evaluated against lit, the lists, any overflow.
      std::uint64_t evaluated = 0, lit = 0, shared = 0, surface = 0;
      if (f.knob_int("count")) {
        if (ours) {
          const EvalCounts c = lists.counts();
          evaluated = c.evaluated;
          lit = c.lit;
          shared = c.shared;
          surface = c.surface;
        } else {
          const ch03::FragmentCounts c = frame.volumes().counts();
          evaluated = c.shaded;
          lit = c.lit;
        }
      }
      if (f.knob_int("count") && ours) {  // --bench reports them with the shading pass
        const std::string shade = is_forward ? ClusteredForward::pass_names()[2] : ClusteredLights::pass_names(f.mode)[2];
        app.metrics().count(shade, "evaluated", evaluated);
        app.metrics().count(shade, "lit", lit);
      }
      // The lists' state of an earlier frame (never waited for), but the report's of this one.
      std::ostream& report = app.report();
      const ClusterStats& st = report && ours ? lists.wait_stats() : lists.stats();
      if (ours) {
        app.metrics().set_allocation("light lists (index list, cells, bounds, lights)", st.bytes);
        if (st.cells_over && st.frame != warned_frame) {
          warned_frame = st.frame;
          std::cerr << "warning: frame " << st.frame << ": " << st.cells_over << " cells did not fit the index list ("
                    << st.capacity << " entries): shaded from every light"
                    << (lists.settings().grow ? " until the list grows" : " (growth off)") << "\n";
        }
      }
      app.metrics().set_allocation("G-buffer (chapter 02) + light buffer L1 + L2 RGBA16F + depth-stencil",
                                   frame.allocated_bytes());
      if (std::ostream& out = report) {
        glFinish();
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        out << frame.volumes().lights().local_count() << " local lights, " << f.mode << ": frame took " << ms
            << " ms (wall clock, " << app.context().renderer() << ")";
        if (f.knob_int("count"))
          out << "; lights evaluated " << evaluated << ", lit " << lit << ", evaluated per lit "
              << (lit ? double(evaluated) / double(lit) : 0.0);
        if (ours)
          out << "; " << st.cells << " cells, " << st.indices << " list entries (longest " << st.max_list << "), "
              << st.bytes << " bytes of lists, regrown " << st.regrown << ", cells over " << st.cells_over
              << ", dropped 0";  // a full cell is shaded from every light: nothing is dropped
        if (ours && !lists.subgroup_path().empty()) {  // the compute shading: subgroups or the fallback
          out << "; subgroups: " << lists.subgroup_path();
          if (f.knob_int("count") && !is_forward) out << " (" << shared << " of " << surface << " pixels from a shared list)";
        }
        out << '\n';
      }
      app.panel([&] {
        const ch03::LightSet& set = frame.volumes().lights();
        ImGui::Text("%zu local lights", set.local_count());
        if (f.knob_int("count"))
          ImGui::Text("evaluated %llu, lit %llu: %.2f per lit", (unsigned long long)evaluated, (unsigned long long)lit,
                      lit ? double(evaluated) / double(lit) : 0.0);
        if (ours) {
          ImGui::Text("%d cells (%d x %d x %d), %llu entries, longest %u", st.cells, lists.grid().tiles_x,
                      lists.grid().tiles_y, lists.grid().slices, (unsigned long long)st.indices, st.max_list);
          ImGui::Text("lists: %.2f MiB, regrown %d, cells over %u (frame %llu)", double(st.bytes) / (1 << 20), st.regrown,
                      st.cells_over, (unsigned long long)st.frame);
        }
      });
    }
  });
}
