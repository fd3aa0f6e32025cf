// Chapter 09's measurement: time per frame against the number of lights, 1 ... 100 000, on
// the street at 1920x1080, for chapter 03's stencil volumes, the five deferred ways of this
// chapter and clustered forward, each split into its passes (depth bounds, assign, the
// forward depth pre-pass, shade), with the lists' memory and the exact evaluated-per-lit ratio. On llvmpipe (no --size) it runs a small size and
// fewer lights so that it ends in minutes; on a GPU, the full sweep. This is the "dense"
// case: the extra lights copy the street's lamps into the same street, so the lit lights per
// pixel grow with the count.
// --density: the fair case instead (density.h): lights scaled so that every surface pixel
// sees 8, 32 or 128 lit lights on average, 1 000 to 1 000 000 lights, several views along the
// street, the median and 95th percentile over the views (09_density*.csv), with each
// method's shading as a multiple of the floor's (zbin-floor: exact per-pixel lists), the CPU's
// time per frame (cpu_ms: submission, so that a read-back that waits shows) and Z-binning's
// assignment by its timed parts (clear, sort, bins, tiles, the floor's lists).
// --grid: the same at 100 000 and 1 000 000 lights for each grid: tiled's tile size,
// clustered's tiles, slices and near slice, Z-binning's tile size and bins (09_grid*.csv).
// --subgroups: tiled and clustered with the subgroup path (shade.glsl's shared-list loop) and
// without it (the fallback), each view's light buffers compared bit for bit and the exact counts
// compared; timed side by side (09_subgroups*.csv, the path in the grid column). Exits 1 when
// the two differ anywhere.
// --lanes: zbin-staged with one lane a pixel, four in every tile, and four in the tiles that hold
// at least N lights for N from 256 to 16 384 (ClusterSettings::lanes_from), at 100 000 and
// 1 000 000 lights (09_lanes*.csv).
// --phases: zbin-staged with and without its sub-blocks at 100 000 and 1 000 000 lights, its
// phase clocks on (ClusterSettings::phase_clocks): the cycles each phase of the pass took, summed
// over its work groups and views, and each phase's share (09_phases*.csv, beside the usual rows).
//   09_clustered_sweep [--out DIR] [--size WxH] [--frames N] [--max-lights N] [--stencil-max N] [--density] [--grid]
//                      [--subgroups] [--phases] [--lanes] [--views N] [--target D]   (D: one target density alone, e.g. 32)
//                      [--min-lights N] [--modes A,B]   (the counts from N, the modes A and B and the floor alone)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <string>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_counts.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/09_clustered/clustered_forward.h"
#include "chapters/09_clustered/clustered_lights.h"
#include "chapters/09_clustered/density.h"
#include "common/context.h"
#include "common/error.h"
#include "common/measure.h"
#include "common/paths.h"
#include "common/sweep.h"
#include "common/target.h"

namespace {
using namespace lp;

struct Settings {
  std::string out = (source_root() / "book" / "figures").string();
  int width = 1920, height = 1080;
  bool size_given = false;
  int frames = 20;
  int max_lights = 0;  // 0: the case's own (dense 100 000, density 1 000 000)
  int stencil_max = 100000;  // the stencil volumes cost a draw per light: where to stop them
  std::string view = "street_level";
  bool density = false;
  bool grid = false;
  bool subgroups = false;
  bool phases = false;
  bool lanes = false;
  // The sweeps that run the density sweep's loop over their own methods, two counts a density.
  bool density_variant() const { return grid || subgroups || phases || lanes; }
  int views = kViewsUnset;  // 6, the grid sweep 3
  int target = 0;           // one target density alone (0: every one)
  int min_lights = 0;       // light counts below this are skipped (their density is not fitted)
  std::string modes_arg;    // --modes a,b: those modes' methods alone (and the floor, which every ratio needs),
  std::vector<std::string> modes;  // the modes it names (main() checks each)
  static constexpr int kViewsUnset = -1000000;
};

// A pass's mean time, or the sum of its parts' ("<name>: <part>": Z-binning's assignment);
// 0 when neither was drawn.
double pass_ms(const Measurement& t, const std::string& name) {
  double ms = 0;
  for (const PassMeasurement& p : t.passes)
    if (p.name == name || p.name.rfind(name + ": ", 0) == 0) ms += p.mean_ms;
  return ms;
}

// [density-sweep]
// The fair case. For each target density and light count: the street's lights_for_count(n)
// scaled (density.h) until the lit pairs per surface pixel over the views are the target,
// then each method timed on each view; a row per view and a summary per (density, n, method).
// A method and its grid: the mode, its settings and the grid's name in the CSV.
struct Method {
  std::string mode, grid;
  ch09::ClusterSettings settings;
};

std::vector<Method> density_methods(const ch09::ClusterSettings& base) {
  std::vector<Method> m;
  // The floor first: every other method's shading is stated as a multiple of its.
  for (const std::string mode : {"zbin-floor", "tiled", "tiled-2.5d", "tiled-staged", "clustered", "zbin", "zbin-staged"})
    m.push_back({mode, "default", ch09::settings_for_mode(mode, base)});
  Method indexed{"zbin", "records by index", ch09::settings_for_mode("zbin", base)};
  indexed.settings.sorted_records = false;  // each light's record read through the sorted order's index
  m.push_back(indexed);
  Method blocks{"zbin-staged", "sub-blocks", ch09::settings_for_mode("zbin-staged", base)};
  blocks.settings.sub_blocks = true;  // a bit per 8 x 4 block of the tile for each staged light
  blocks.settings.pixel_lanes = 1;
  m.push_back(blocks);
  Method fields{"zbin-staged", "fields", ch09::settings_for_mode("zbin-staged", base)};
  fields.settings.staged_fields = true;  // the staged records as a structure of arrays
  m.push_back(fields);
  for (const int lanes : {1, 2, 4}) {  // invocations a pixel in every tile (default: 4 in the heavy tiles)
    Method laned{"zbin-staged", "lanes " + std::to_string(lanes), ch09::settings_for_mode("zbin-staged", base)};
    laned.settings.pixel_lanes = lanes;
    laned.settings.lanes_from = 0;
    m.push_back(laned);
  }
  return m;
}

// zbin-staged's lanes: one lane, four in every tile, and four in the tiles of at least N lights
// (ClusterSettings::lanes_from) for N from 256 to 16 384.
std::vector<Method> lane_methods(const ch09::ClusterSettings& base) {
  std::vector<Method> m = {{"zbin-floor", "default", ch09::settings_for_mode("zbin-floor", base)}};
  for (const int from : {-1, 0, 256, 512, 1024, 2048, 4096, 8192, 16384}) {
    Method z{"zbin-staged", from < 0 ? "lanes 1" : from == 0 ? "lanes 4" : "lanes 4 from " + std::to_string(from),
             ch09::settings_for_mode("zbin-staged", base)};
    z.settings.pixel_lanes = from < 0 ? 1 : 4;
    z.settings.lanes_from = std::max(from, 0);
    m.push_back(z);
  }
  return m;
}

// [grid-methods]
std::vector<Method> grid_methods(const ch09::ClusterSettings& base) {
  std::vector<Method> m = {{"zbin-floor", "default", ch09::settings_for_mode("zbin-floor", base)}};
  for (const int tile : {8, 16, 32}) {
    Method t{"tiled", "tile " + std::to_string(tile), ch09::settings_for_mode("tiled", base)};
    t.settings.tile_px = tile;
    m.push_back(t);
  }
  for (const glm::ivec3 c : {glm::ivec3(16, 9, 24), glm::ivec3(16, 9, 96), glm::ivec3(60, 34, 24), glm::ivec3(60, 34, 96)}) {
    Method k{"clustered", std::to_string(c.x) + "x" + std::to_string(c.y) + "x" + std::to_string(c.z),
             ch09::settings_for_mode("clustered", base)};
    k.settings.clusters = c;
    m.push_back(k);
  }
  // The near slice (cluster_grid.h): DOOM's tiles, 24 and 96 slices, slice 0 ending 2, 5 or 10 m out.
  for (const int slices : {24, 96})
    for (const int near : {2, 5, 10}) {
      Method k{"clustered", "16x9x" + std::to_string(slices) + " near " + std::to_string(near),
               ch09::settings_for_mode("clustered", base)};
      k.settings.clusters = {16, 9, slices};
      k.settings.near_slice = float(near);
      m.push_back(k);
    }
  // (8-pixel tiles' masks for a million lights at 1080p exceed their bound: warned, not timed.)
  for (const int tile : {8, 16, 32, 64})
    for (const int bins : {256, 1024, 4096}) {
      Method z{"zbin", "tile " + std::to_string(tile) + " bins " + std::to_string(bins), ch09::settings_for_mode("zbin", base)};
      z.settings.tile_px = tile;
      z.settings.zbins = bins;
      m.push_back(z);
    }
  for (const int tile : {8, 16, 32})  // staged: a work group a tile, so at most 32 pixels
    for (const bool blocks : {false, true}) {
      Method z{"zbin-staged", "tile " + std::to_string(tile) + " bins 1024" + (blocks ? " sub-blocks" : ""),
               ch09::settings_for_mode("zbin-staged", base)};
      z.settings.tile_px = tile;
      z.settings.sub_blocks = blocks;
      z.settings.pixel_lanes = 1;  // the grid varies, one lane throughout (32-pixel tiles take no more)
      m.push_back(z);
    }
  for (const int bins : {256, 4096}) {  // and its bins, at 16-pixel tiles
    Method z{"zbin-staged", "tile 16 bins " + std::to_string(bins), ch09::settings_for_mode("zbin-staged", base)};
    z.settings.tile_px = 16;
    z.settings.zbins = bins;
    z.settings.pixel_lanes = 1;
    m.push_back(z);
  }
  return m;
}
// [/grid-methods]

// zbin-staged timed phase by phase (one lane a pixel), without and with the sub-blocks.
std::vector<Method> phase_methods(const ch09::ClusterSettings& base) {
  std::vector<Method> m;
  for (const bool blocks : {false, true}) {
    Method z{"zbin-staged", blocks ? "sub-blocks phase clocks" : "phase clocks", ch09::settings_for_mode("zbin-staged", base)};
    z.settings.sub_blocks = blocks;
    z.settings.pixel_lanes = 1;  // a pixel's work in one invocation, as the blocks take it
    z.settings.phase_clocks = true;
    m.push_back(z);
  }
  return m;
}

// The compute shading with and without the subgroup path, for the two ways whose lists a
// subgroup may share (a tile's, a cluster's).
std::vector<Method> subgroup_methods(const ch09::ClusterSettings& base) {
  std::vector<Method> m;
  for (const std::string mode : {"tiled", "clustered"}) {
    Method fallback{mode, "fallback", ch09::settings_for_mode(mode, base)};
    fallback.settings.subgroups = ch09::SubgroupUse::Off;
    m.push_back(fallback);
    Method shared{mode, "subgroups", ch09::settings_for_mode(mode, base)};
    shared.settings.subgroups = ch09::SubgroupUse::Any;  // ARB's ballot too, where that is all there is
    m.push_back(shared);
    if (mode == "clustered") {  // a cluster's subgroups may hold different lists: walked together
      Method merged{mode, "subgroups+merge", shared.settings};
      merged.settings.subgroup_merge = true;
      m.push_back(merged);
    }
  }
  return m;
}

// The frame's light buffers (L1, L2) as stored, half floats, for comparing bit for bit.
std::vector<std::uint16_t> light_buffers(const ch03::DeferredFrame& frame, int w, int h) {
  std::vector<std::uint16_t> v(std::size_t(w) * std::size_t(h) * 8);
  const GLsizei half = GLsizei(v.size() * sizeof(std::uint16_t) / 2);
  glGetTextureImage(frame.light().diffuse(), 0, GL_RGBA, GL_HALF_FLOAT, half, v.data());
  glGetTextureImage(frame.light().specular(), 0, GL_RGBA, GL_HALF_FLOAT, half, v.data() + v.size() / 2);
  return v;
}

void density_sweep(const Settings& s, Context& context, const Scene& scene, ch03::DeferredFrame& frame, OutputTarget& target) {
  const auto began = std::chrono::steady_clock::now();
  const bool software = context.is_software();
  const std::vector<Camera> views = ch09::views_along(scene.camera(s.view), s.views, 12.f);
  std::vector<int> counts = {1000, 10000, 100000, 1000000};
  if (s.density_variant()) counts = software ? std::vector<int>{1000} : std::vector<int>{100000, 1000000};
  std::vector<double> densities = {8, 32, 128};
  if (software) densities = {8, 32};
  if (s.subgroups) densities = {32};
  if (s.target > 0) densities = {double(s.target)};
  const float threshold = ch03::cut_threshold(1.f, ch03::peak_reflectance(scene));
  // One target alone writes its own files (09_grid_d32...), so that runs of each density add up.
  const std::string label = software ? "_llvmpipe" : "";
  const std::string name = std::string(s.subgroups ? "09_subgroups" : s.grid ? "09_grid" : s.phases ? "09_phases"
                                       : s.lanes ? "09_lanes" : "09_density") +
                           (s.target > 0 ? "_d" + std::to_string(s.target) : "");
  const std::string rows_file = s.out + "/" + name + label + ".csv", summary_file = s.out + "/" + name + "_summary" + label + ".csv";
  std::ofstream rows(rows_file), summary(summary_file);
  const std::string phases_file = s.out + "/" + name + "_cycles" + label + ".csv";
  std::ofstream phases;
  // cpu_ms: the CPU's time per frame (submission; a read-back that waits shows here), and
  // Z-binning's assignment by its parts (0 for the other methods; the summary's are medians).
  std::string parts_header;
  for (const std::string& part : ch09::ClusteredLights::zbin_assign_parts())
    parts_header += "assign_" + std::string(part == "floor lists" ? "floor" : part) + "_ms,";
  const std::string header = std::string("# ") + (software ? "llvmpipe CPU time: " : "GPU time: ") + context.renderer() + ", " +
                             std::to_string(s.width) + "x" + std::to_string(s.height) + ", street, " + std::to_string(views.size()) +
                             " views along it from " + s.view + ", lights scaled to a density (chapters/09_clustered/density.h)\n";
  rows << header << "target_density,lights,view,method,grid,range_scale,surface_pixels,lit,density,evaluated,evaluated_per_lit,"
       << "depth_bounds_ms,assign_ms,shade_ms,local_ms,list_bytes,list_entries,cells_over,cpu_ms,"
       << parts_header << csv_measure_columns() << "\n";
  summary << header << "target_density,lights,method,grid,range_scale,density,lit,evaluated_per_lit,local_median_ms,local_p95_ms,"
          << "assign_median_ms,assign_p95_ms,shade_median_ms,shade_p95_ms,shade_per_floor,list_bytes_max,views,cpu_median_ms,"
          << parts_header << csv_measure_columns() << "\n";
  if (s.phases) {
    phases.open(phases_file);
    phases << header << "target_density,lights,method,grid,phase,cycles,share," << csv_measure_columns() << "\n";
  }
  // A cell that overflows is shaded from every light for a frame, very slow with a million
  // lights: on a GPU the lists start at 2^26 entries (256 MiB), so they rarely grow.
  ch09::ClusterSettings base_settings;
  if (!software) base_settings.initial_indices = 1u << 26;
  std::vector<Method> methods = s.subgroups ? subgroup_methods(base_settings)
                               : s.grid    ? grid_methods(base_settings)
                               : s.phases  ? phase_methods(base_settings)
                               : s.lanes   ? lane_methods(base_settings)
                                           : density_methods(base_settings);
  if (!s.modes.empty()) {
    std::erase_if(methods, [&](const Method& m) { return m.mode != "zbin-floor" && std::ranges::find(s.modes, m.mode) == s.modes.end(); });
    if (methods.size() < 2) throw UsageError("--modes " + s.modes_arg + ": names no method of this sweep but the floor");
  }
  // --subgroups: each mode's fallback buffers per view, which its subgroup path must equal.
  std::map<std::string, std::vector<std::uint16_t>> fallback_buffers;  // by "mode|view"
  std::map<std::string, ch09::EvalCounts> fallback_counts;
  std::vector<std::string> differences;
  std::vector<std::unique_ptr<ch09::ClusteredLights>> passes;
  for (const Method& m : methods) passes.push_back(std::make_unique<ch09::ClusteredLights>(frame.volumes(), m.settings));
  // The density's fit counts lit pairs, exact in every mode (the tests hold each mode to chapter
  // 3's); zbin-staged's, whose memory is a bit per light per tile: a fit's wide try (thousands of
  // lit lights a pixel at a million lights) would overflow a cell list's bound and be shaded
  // from every light.
  ch09::ClusteredLights fit_pass(frame.volumes(), ch09::settings_for_mode("zbin-staged", base_settings));
  auto render = [&](const Camera& view, ch09::ClusteredLights& pass, PassMetrics* m) {
    frame.set_local_lights(&pass);
    frame.render(frame_camera(view, float(s.width) / float(s.height)), {target.framebuffer(), s.width, s.height}, m);
  };
  // A frame whose lists did not fit is shaded from every light: draw until they fit (the
  // list grows a frame after it overflowed), so that counts and times are of fitting lists.
  auto settle = [&](const Camera& view, ch09::ClusteredLights& pass) {
    for (int k = 0; k < 4; ++k) {
      render(view, pass, nullptr);
      if (pass.wait_stats().cells_over == 0) return true;
    }
    std::cerr << "warning: the lists still overflow after 4 frames (" << pass.stats().capacity << " entries)\n";
    return false;
  };
  auto counted = [&](const Camera& view, ch09::ClusteredLights& pass) {
    settle(view, pass);
    pass.set_counting(true);
    render(view, pass, nullptr);
    pass.set_counting(false);
    return pass.counts();
  };
  for (const double target_density : densities) {
    float start = 1.f;
    int previous = 0;
    for (const int n : counts) {
      if (n > s.max_lights) break;
      if (previous) start *= std::cbrt(float(previous) / float(n));  // the same density: volume per light x previous / n
      previous = n;
      if (n < s.min_lights) continue;
      const std::vector<Light> base = ch03::lights_for_count(scene, n);
      auto use = [&](float scale) {
        frame.volumes().set_lights(ch03::build_light_set(ch09::scaled_lights(base, scale), threshold, frame.volumes().shapes()));
      };
      const ch09::DensityFit fit = ch09::fit_density(target_density, start, [&](float scale) {
        use(scale);
        std::uint64_t lit = 0, surface = 0;
        for (const Camera& v : views) {
          const ch09::EvalCounts c = counted(v, fit_pass);
          lit += c.lit;
          surface += c.surface;
        }
        const double d = surface ? double(lit) / double(surface) : 0.0;
        std::cout << "  " << n << " lights, scale " << scale << ": " << d << " lit lights per surface pixel" << std::endl;
        return d;
      });
      start = fit.scale;
      use(fit.scale);
      if (!fit.met) std::cerr << "warning: " << n << " lights: density " << fit.density << " not " << target_density << "\n";
      double floor_shade = 0;  // the floor's median shading time at this density and count
      fallback_buffers.clear();
      fallback_counts.clear();
      for (std::size_t mi = 0; mi < methods.size(); ++mi) {
        const std::string& method = methods[mi].mode;
        std::string grid = methods[mi].grid;
        ch09::ClusteredLights& pass = *passes[mi];
        std::vector<double> local, assign, shade, cpu;
        std::vector<std::vector<double>> assign_parts(ch09::ClusteredLights::zbin_assign_parts().size());
        std::uint64_t lit = 0, surface = 0, evaluated = 0;
        std::vector<std::uint64_t> cycles(ch09::ClusteredLights::phase_names().size(), 0);  // --phases: over the views
        std::size_t bytes = 0;
        int frames = 0;
        for (const Camera& view : views) {
          ch09::EvalCounts c;
          try {
            c = counted(view, pass);
          } catch (const Error& e) {  // a grid too large for its bounds (Z-binning's masks at a million lights)
            std::cerr << "warning: " << method << " (" << grid << ") at " << n << " lights: " << e.what() << "; not timed\n";
            break;
          }
          if (pass.wait_stats().cells_over) {  // lists past max_indices: every light everywhere, no time worth taking
            std::cerr << "warning: " << method << " at " << n << " lights: lists over " << pass.stats().capacity
                      << " entries; not timed\n";
            continue;
          }
          PassMetrics metrics;
          MeasureOptions options{.frames = s.frames};
          options.warmup = {.block_frames = 2, .block_seconds = 0.05, .min_seconds = 0.1, .tolerance = 0.03, .max_seconds = 2};
          if (methods[mi].settings.phase_clocks) pass.take_phase_cycles();  // the measured frames' cycles alone
          const Measurement t = measure(metrics, [&] { render(view, pass, &metrics); }, options);
          if (methods[mi].settings.phase_clocks) {
            const std::vector<std::uint64_t> taken = pass.take_phase_cycles();
            for (std::size_t k = 0; k < cycles.size(); ++k) cycles[k] += taken[k];
          }
          if (s.subgroups) {  // the path taken, and the last timed frame's buffers against the fallback's
            grid = methods[mi].grid == "fallback" ? "fallback" : methods[mi].grid + " " + pass.subgroup_path();
            std::vector<std::uint16_t> buffers = light_buffers(frame, s.width, s.height);
            const std::string key = method + "|" + view.name;
            if (methods[mi].grid == "fallback") {
              fallback_buffers[key] = std::move(buffers);
              fallback_counts[key] = c;
            } else {
              const bool have = fallback_buffers.count(key) > 0;
              std::size_t differ = 0;
              if (have)
                for (std::size_t k = 0; k < buffers.size(); ++k) differ += buffers[k] != fallback_buffers[key][k];
              const ch09::EvalCounts& f = have ? fallback_counts[key] : c;
              const bool same = have && differ == 0 && f.lit == c.lit && f.evaluated == c.evaluated && f.surface == c.surface;
              std::cout << "  " << method << ", " << view.name << ": " << grid << " against the fallback: "
                        << (same ? "identical" : "DIFFERENT") << " (" << differ << " half floats differ, lit " << c.lit
                        << " / " << f.lit << ", evaluated " << c.evaluated << " / " << f.evaluated << "; " << c.shared
                        << " of " << c.surface << " pixels from a shared list, " << c.merged << " by the merged walk)" << std::endl;
              if (!same) differences.push_back(method + " at " + std::to_string(n) + " lights, " + view.name);
            }
          }
          const auto names = ch09::ClusteredLights::pass_names(method);
          const double parts[3] = {pass_ms(t, names[0]), pass_ms(t, names[1]), pass_ms(t, names[2])};
          std::string parts_values;
          for (std::size_t k = 0; k < assign_parts.size(); ++k) {
            assign_parts[k].push_back(pass_ms(t, names[1] + ": " + ch09::ClusteredLights::zbin_assign_parts()[k]));
            parts_values += std::to_string(assign_parts[k].back()) + ",";
          }
          cpu.push_back(t.cpu_ms);
          const ch09::ClusterStats& st = pass.wait_stats();
          local.push_back(parts[0] + parts[1] + parts[2]);
          assign.push_back(parts[1]);
          shade.push_back(parts[2]);
          lit += c.lit;
          surface += c.surface;
          evaluated += c.evaluated;
          bytes = std::max(bytes, st.bytes);
          frames = t.frames;
          rows << target_density << ',' << n << ',' << view.name << ',' << method << ',' << grid << ',' << fit.scale << ','
               << c.surface << ','
               << c.lit << ',' << c.density() << ',' << c.evaluated << ',' << c.evaluated_per_lit() << ',' << parts[0] << ','
               << parts[1] << ',' << parts[2] << ',' << local.back() << ',' << st.bytes << ',' << st.indices << ','
               << st.cells_over << ',' << t.cpu_ms << ',' << parts_values
               << csv_measure_values(context.renderer(), s.width, s.height, t.frames) << std::endl;
        }
        if (local.empty()) continue;  // not timed (warned above)
        const double shade_median = ch09::quantile(shade, 0.5);
        if (method == "zbin-floor") floor_shade = shade_median;
        const double per_floor = floor_shade > 0 ? shade_median / floor_shade : 0.0;  // 0: no floor measured
        summary << target_density << ',' << n << ',' << method << ',' << grid << ',' << fit.scale << ','
                << (surface ? double(lit) / double(surface) : 0.0) << ',' << lit << ','
                << (lit ? double(evaluated) / double(lit) : 0.0) << ',' << ch09::quantile(local, 0.5) << ','
                << ch09::quantile(local, 0.95) << ',' << ch09::quantile(assign, 0.5) << ',' << ch09::quantile(assign, 0.95)
                << ',' << shade_median << ',' << ch09::quantile(shade, 0.95) << ',' << per_floor << ',' << bytes << ','
                << views.size() << ',' << ch09::quantile(cpu, 0.5) << ',';
        for (const std::vector<double>& p : assign_parts) summary << ch09::quantile(p, 0.5) << ',';
        summary << csv_measure_values(context.renderer(), s.width, s.height, frames) << std::endl;
        if (methods[mi].settings.phase_clocks) {
          std::uint64_t all = 0;
          for (const std::uint64_t c : cycles) all += c;
          for (std::size_t k = 0; k < cycles.size(); ++k)
            phases << target_density << ',' << n << ',' << method << ',' << grid << ','
                   << ch09::ClusteredLights::phase_names()[k] << ',' << cycles[k] << ','
                   << (all ? double(cycles[k]) / double(all) : 0.0) << ','
                   << csv_measure_values(context.renderer(), s.width, s.height, frames) << std::endl;
        }
        std::cout << target_density << " per pixel, " << n << " lights, " << method << " (" << grid << "): local lights "
                  << ch09::quantile(local, 0.5) << " ms median, " << ch09::quantile(local, 0.95) << " p95; evaluated per lit "
                  << (lit ? double(evaluated) / double(lit) : 0.0) << "; shading " << per_floor << " x the floor's" << std::endl;
      }
    }
  }
  frame.set_local_lights(nullptr);
  std::cout << "took " << std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count() << " s\n";
  std::cout << "wrote " << rows_file << " and " << summary_file << (s.phases ? " and " + phases_file : "") << '\n';
  if (!differences.empty()) {
    std::string where;
    for (const std::string& d : differences) where += (where.empty() ? "" : "; ") + d;
    throw Error("the subgroup path differs from the fallback: " + where);
  }
}
// [/density-sweep]
}  // namespace

int main(int argc, char** argv) {
  Settings s;
  return run_sweep(argc, argv, "09_clustered_sweep", [&](SweepArgs& args) {
    args.text("--out", s.out).size("--size", s.width, s.height, &s.size_given).integer("--frames", s.frames)
        .integer("--max-lights", s.max_lights).integer("--stencil-max", s.stencil_max).text("--view", s.view)
        .flag("--density", s.density).flag("--grid", s.grid).flag("--subgroups", s.subgroups).flag("--phases", s.phases).flag("--lanes", s.lanes).integer("--views", s.views)
        .integer("--target", s.target).integer("--min-lights", s.min_lights).text("--modes", s.modes_arg);
  }, [&] {
    std::filesystem::create_directories(s.out);
    if (s.views == Settings::kViewsUnset) s.views = s.density_variant() ? 3 : 6;
    if (s.views < 1 || s.views > 64) throw Error("--views: 1 to 64, not " + std::to_string(s.views));
    if (int(s.grid) + int(s.subgroups) + int(s.phases) + int(s.lanes) > 1)
      throw UsageError("--grid, --subgroups, --phases and --lanes: one at a time");
    for (std::size_t at = 0; !s.modes_arg.empty() && at <= s.modes_arg.size();) {  // each of --modes a,b is a mode
      const std::size_t end = std::min(s.modes_arg.find(',', at), s.modes_arg.size());
      s.modes.push_back(s.modes_arg.substr(at, end - at));
      if (!ch09::is_cluster_mode(s.modes.back())) throw UsageError("--modes: '" + s.modes.back() + "' is no mode of chapter 9");
      at = end + 1;
    }
    if (s.density_variant()) s.density = true;  // the density sweep over grids, the two paths or the phases
    if (s.density) {  // many configurations: fewer frames each
      s.frames = std::min(s.frames, 10);
    }
    if (s.max_lights <= 0) s.max_lights = s.density ? 1000000 : 100000;
    auto context = Context::create({.headless = true, .width = s.width, .height = s.height});
    const bool software = context->is_software();
    if (software && !s.size_given && s.density) {  // a CPU: a small image, up to 10 000 lights, three views
      s.width = 160;
      s.height = 90;
      s.frames = std::min(s.frames, 2);
      s.max_lights = std::min(s.max_lights, 10000);
      s.views = std::min(s.views, s.density_variant() ? 2 : 3);
    } else if (software && !s.size_given) {  // a CPU: small, few lights, few frames
      s.width = 320;
      s.height = 180;
      s.frames = std::min(s.frames, 3);
      s.max_lights = std::min(s.max_lights, 1000);  // 10 000 take 25 s a frame here
      s.stencil_max = std::min(s.stencil_max, 1000);
    }
    Scene scene = load_scene(from_root("assets/street/street.gltf"));
    SceneGpu gpu(scene);
    ch03::DeferredFrame frame(gpu);
    OutputTarget target(s.width, s.height);
    if (s.density) return density_sweep(s, *context, scene, frame, target);
    const FrameCamera camera = frame_camera(scene.camera(s.view), float(s.width) / float(s.height));
    const std::string timer = (software ? "llvmpipe CPU time: " : "GPU time: ") + context->renderer();
    // On a GPU 09_lights.csv (the lead names it after the GPU: 09_lights_h200.csv), on llvmpipe 09_lights_llvmpipe.csv.
    const std::string file = s.out + (software ? "/09_lights_llvmpipe.csv" : "/09_lights.csv");
    std::ofstream csv(file);
    csv << "# " << timer << ", " << s.width << "x" << s.height << ", street, view " << s.view << "\n"
        << "lights,method,total_ms,local_ms,depth_bounds_ms,assign_ms,prepass_ms,shade_ms,list_bytes,list_entries,regrown,"
        << "cells_over,evaluated,lit,evaluated_per_lit,cpu_ms," << csv_measure_columns() << "\n";
    const float threshold = ch03::cut_threshold(1.f, ch03::peak_reflectance(scene));
    for (int n : {1, 10, 100, 1000, 10000, 100000}) {
      if (n > s.max_lights) break;
      frame.volumes().set_lights(ch03::build_light_set(ch03::lights_for_count(scene, n), threshold, frame.volumes().shapes()));
      auto draw = [&](PassMetrics& m) { frame.render(camera, {target.framebuffer(), s.width, s.height}, &m); };
      std::vector<std::string> methods = {"stencil"};
      for (const auto& m : ch09::kClusterModes) methods.push_back(m);
      methods.push_back("clustered-forward");  // the scene drawn again, lit from every cluster's list
      for (const std::string& method : methods) {
        if (method == "stencil" && n > s.stencil_max) continue;
        const bool forward = method == "clustered-forward";
        ch09::ClusteredForward forward_pass(frame, gpu);
        ch09::ClusteredLights deferred_pass(frame.volumes(), ch09::settings_for_mode(
                                                method == "stencil" || forward ? "clustered" : method));
        ch09::ClusteredLights& pass = forward ? forward_pass.lists() : deferred_pass;
        frame.set_local_lights(method == "stencil" ? nullptr : forward ? static_cast<ch03::LocalLightPass*>(&forward_pass) : &pass);
        frame.set_strategy(ch03::Strategy::Stencil);
        // Lists that fit first (they grow a frame after they overflow; a full cell is shaded
        // from every light meanwhile), then one counted frame for the exact counts, then the
        // timed frames without counting.
        if (method != "stencil")
          for (int k = 0; k < 4; ++k) {
            frame.render(camera, {target.framebuffer(), s.width, s.height}, nullptr);
            if (pass.wait_stats().cells_over == 0) break;
          }
        std::uint64_t evaluated = 0, lit = 0;
        frame.volumes().set_counting(method == "stencil");
        pass.set_counting(method != "stencil" && !forward);
        forward_pass.set_counting(forward);
        {
          PassMetrics m;
          measure(m, [&] { draw(m); }, {.frames = 1, .skip_warmup = true});
        }
        if (method == "stencil") {
          const ch03::FragmentCounts c = frame.volumes().counts();
          evaluated = c.shaded;
          lit = c.lit;
        } else {
          const ch09::EvalCounts c = pass.counts();
          evaluated = c.evaluated;
          lit = c.lit;
        }
        frame.volumes().set_counting(false);
        pass.set_counting(false);
        forward_pass.set_counting(false);
        PassMetrics metrics;
        // The stencil volumes at 10 000 lights and more take most of a second a frame or more:
        // a few frames, one-frame warm-up blocks (a pass that long
        // needs no clock ramp), so that the sweep stays within minutes.
        MeasureOptions options{.frames = s.frames};
        if (method == "stencil" && n >= 10000) {
          options.frames = std::min(s.frames, 3);
          options.warmup = {.block_frames = 1, .block_seconds = 0, .min_seconds = 0, .tolerance = 0.03, .max_seconds = 1};
        }
        const Measurement t = measure(metrics, [&] { draw(metrics); }, options);
        double parts[4] = {0, 0, 0, 0}, local = 0;  // depth bounds, assign, pre-pass, shade
        if (method == "stencil") {
          local = t.pass("local lights: stencil").mean_ms;
        } else if (forward) {
          const auto names = ch09::ClusteredForward::pass_names();  // assign, depth pre-pass, shade
          for (int k = 0; k < 3; ++k) local += parts[k + 1] = t.pass(names[k]).mean_ms;
        } else {
          const auto names = ch09::ClusteredLights::pass_names(method);
          for (int k = 0; k < 3; ++k) local += parts[k == 2 ? 3 : k] = pass_ms(t, names[k]);
        }
        const bool ours = method != "stencil";
        const ch09::ClusterStats& st = ours ? pass.wait_stats() : pass.stats();
        csv << n << ',' << method << ',' << t.total_ms() << ',' << local << ',' << parts[0] << ',' << parts[1] << ','
            << parts[2] << ',' << parts[3] << ',' << (ours ? st.bytes : 0) << ',' << (ours ? st.indices : 0) << ',' << (ours ? st.regrown : 0)
            << ',' << (ours ? st.cells_over : 0) << ',' << evaluated << ',' << lit << ','
            << (lit ? double(evaluated) / double(lit) : 0.0) << ',' << t.cpu_ms << ','
            << csv_measure_values(context->renderer(), s.width, s.height, t.frames)
            << std::endl;  // a row at a time: a long GPU run cut short keeps what it measured
        std::cout << n << " lights, " << method << ": " << t.total_ms() << " ms (local lights " << local << "), evaluated "
                  << evaluated << ", lit " << lit << (ours && st.cells_over ? ", CELLS OVER " + std::to_string(st.cells_over) : "")
                  << std::endl;
        frame.set_local_lights(nullptr);
      }
    }
    std::cout << "wrote " << file << '\n';
  });
}
