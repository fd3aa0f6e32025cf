#pragma once
// Chapter 09's stage: the local lights binned into screen tiles or 3D clusters by compute
// shaders, then each pixel lit by its cell's list alone. It plugs into chapter 03's frame as
// its LocalLightPass, so the G-buffer, the global lights, the composite and every later
// chapter's stage stay as they are; only how the local lights reach the light buffer changes.
//
//   ClusteredLights clustered(frame.volumes(), {.kind = CullKind::Clustered});
//   frame.set_local_lights(&clustered);
//   frame.render(camera, output, &metrics);   // depth bounds, assign, shade: three passes
//
// The lights, their cut and their lighting are chapter 03's (frame.volumes().lights(), and
// local_light.glsl): the image equals the stencil volumes' within float rounding.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/fragment_counters.h"
#include "chapters/04_neon/neon_forward.h"
#include "chapters/09_clustered/cluster_grid.h"
#include "common/gl.h"
#include "common/shader.h"

namespace lp::ch09 {

// [settings]
// ZBin: Z-binning (Drobot 2017): lights sorted by depth, a range per depth bin, a bit per
// light per tile (shaders/zbin.glsl).
enum class CullKind { Tiled, Clustered, ZBin };
enum class ShadeIn { Compute, Fragment, Staged };  // Staged: compute, the tile's lights in shared memory (tiled, zbin)
enum class SubgroupUse { Off, Native, Any };

struct ClusterSettings {
  CullKind kind = CullKind::Clustered;
  ShadeIn shade = ShadeIn::Compute;
  int tile_px = 16;          // tiled: square tiles of this many pixels
  bool depth_mask = false;   // tiled: Harada's 2.5D culling, 32 depth bins per tile (cluster_grid.h)
  glm::ivec3 clusters{16, 9, 24};  // clustered: tiles across, tiles down, depth slices (DOOM 2016's)
  float near_slice = 0.f;    // clustered: the first slice's far end, metres (0: every slice exponential; cluster_grid.h)
  int zbins = 1024;          // zbin: exponential depth bins (1 to 16 384); its tiles are tile_px
  // zbin-floor, a benchmark: Z-binning's lists turned into each pixel's exact list (the lights
  // whose cut reaches its surface) in the assignment, so that the shading pass is the per-pair
  // arithmetic alone: the floor the other modes' shading is measured against. The lists are
  // built a tile at a time by zbin_staged.comp's walk (FLOOR_LISTS), with its lanes as set below.
  bool floor = false;
  // zbin: each light's record (and a spot's cone) copied into the sorted order by the sort, so
  // that the shading reads a light at its sorted position beside its index, not through it.
  bool sorted_records = true;
  // zbin-staged: each tile cut into blocks of 8 x 4 pixels (a block to 32 invocations, an
  // NVIDIA warp) with their own depth bounds; a staged light is passed over by the pixels of
  // the blocks its sphere does not meet (zbin_staged.comp). Fewer lights evaluated, more work
  // staging each: off by default (slower on the H200).
  bool sub_blocks = false;
  // zbin-staged: the staged records held as an array per field (positions, radiances, cones: a
  // structure of arrays) instead of an array of records. The same image; measured by the sweep.
  bool staged_fields = false;
  // zbin-staged: invocations a pixel (1, 2 or 4; more than 1 in tiles of at most 16). Lane j adds
  // the lights j, j + lanes, ... of the pixel's part of each chunk, and the lanes' sums are
  // added in lane order at the end: a tile whose pixels each add thousands of lights (the far
  // end of the street) spreads them over lanes times the warps, so that the pass does not wait
  // on its heaviest tile. The same lights, the same lit pairs; the sums regrouped (float
  // addition: the same to rounding). One lane with sub_blocks or larger tiles.
  int pixel_lanes = 4;
  // zbin-staged with pixel_lanes above 1: the lanes only in the tiles whose masks hold at least
  // this many lights (the lights their pixels may stage). A first pass (zbin_lanes.comp) counts
  // each tile's and lists the tiles, heavy and light; the heavy are shaded with the lanes, the
  // light with one, by two indirect dispatches (the counts stay on the GPU). 0: every tile with
  // the lanes, one dispatch. The same lights and lit pairs either way.
  int lanes_from = 1024;
  // zbin-staged, a benchmark (09_clustered_sweep --phases): one invocation of each work group
  // reads its SM's clock (GL_ARB_shader_clock) after each phase of zbin_staged.comp and adds the
  // cycles to the phase's sum (ClusteredLights::take_phase_cycles). The same image.
  bool phase_clocks = false;
  // The index list starts this large (indices) and grows to what a frame needs, up to
  // max_indices. Growth is found a frame late, never by waiting for the GPU: a cell that does
  // not fit is shaded from every light that frame (slower, the same image) and counted, and
  // the next frame's list is large enough. grow = false keeps the list as it is.
  std::uint32_t initial_indices = 1u << 20;
  std::uint32_t max_indices = 1u << 28;  // 1 GiB of indices
  bool grow = true;
  // Clustered forward (bind_for_forward): build the list of every cluster, not only of those
  // the G-buffer's surfaces occupy, so that any fragment a forward pass draws finds its lights.
  bool all_cells = false;
  // The compute shading (shade.comp) reads a list that every invocation of a subgroup shares
  // once for the subgroup (subgroup_support()). Native: where the driver has
  // GL_KHR_shader_subgroup; Any: also through GL_ARB_shader_ballot and GL_ARB_shader_group_vote
  // (all that Mesa's llvmpipe has, and there the shared read is slower than the loop: tests and
  // the sweep ask for it); Off: the per-invocation loop everywhere (the fallback). The same
  // image either way.
  SubgroupUse subgroups = SubgroupUse::Native;
  // With the subgroup path: where a subgroup's invocations have different lists (clusters of
  // different depths), walk them together, a light at a time, each light's record read once for
  // the invocations that list it (scalarised; shade.glsl's subgroup-merge). Off: those
  // subgroups take the per-invocation loop. The same image either way.
  bool subgroup_merge = false;
};
// The eight ways of the program's --mode, beside chapter 03's: "tiled", "tiled-2.5d" (with the
// depth mask), "tiled-fragment", "tiled-staged" (the tile's lights staged in shared memory,
// tiles of at most 32 pixels), "clustered" (compute), "clustered-fragment", "zbin" (compute),
// "zbin-staged" (the lights of the tile's bins staged in shared memory: zbin_staged.comp).
inline const std::vector<std::string> kClusterModes = {"tiled",     "tiled-2.5d",         "tiled-fragment",
                                                       "tiled-staged", "clustered",       "clustered-fragment",
                                                       "zbin",      "zbin-staged"};
// Modes for measuring, not for the program's list: "zbin-floor" (settings.floor above).
inline const std::vector<std::string> kBenchModes = {"zbin-floor"};
bool is_cluster_mode(const std::string& name);  // one of kClusterModes or kBenchModes
ClusterSettings settings_for_mode(const std::string& name, ClusterSettings base = {});  // throws Error
std::string mode_name(const ClusterSettings& s);
// The subgroup operations this context's driver offers compute shaders, best first:
// "KHR_shader_subgroup" (with vote and ballot), "ARB_shader_ballot" (with ARB_shader_group_vote;
// Mesa's llvmpipe), or "" (none: the fallback). LIGHTPASS_TEST_NO_SUBGROUPS=1 says none, for tests.
std::string subgroup_support();
// [/settings]

// [stats]
// What a draw() did. The GPU's part (entries, the longest list, overflow) is read when the GPU
// has finished with it, a frame or two later, without waiting: `frame` says which draw the
// numbers are of (0: none read yet). wait_stats() waits for the last draw's (tests, reports).
struct ClusterStats {
  int cells = 0;                 // of the grid
  std::uint64_t frame = 0;       // the draw (1, 2, ...) the GPU's numbers below are of
  std::uint64_t indices = 0;     // entries in the index list (every cell's list, compacted);
                                 // zbin: bits set in the tiles' masks; zbin-floor: the exact lists' entries
  std::uint32_t max_list = 0;    // the longest cell list (zbin: 0, zbin-floor: the longest pixel list)
  std::uint32_t capacity = 0;    // the index list's size now
  int regrown = 0;               // times the list has grown
  std::uint32_t cells_over = 0;  // cells that did not fit: shaded from every light in that draw
  std::uint64_t over_entries = 0;  // the entries those cells asked for
  std::size_t bytes = 0;         // the lists' memory now: index list, cells, bounds, lights
};
// [/stats]

// Exact per-pixel counts over the frame (with counting on).
struct EvalCounts {
  std::uint64_t evaluated = 0;  // (pixel, light) pairs the shading looked at
  std::uint64_t lit = 0;        // of those, the ones where the light added anything
  std::uint64_t surface = 0;    // pixels shaded (not sky): lit / surface is the density
  std::uint64_t shared = 0;     // of those, shaded from a list their whole subgroup shared (read once)
  std::uint64_t merged = 0;     // of those, shaded by the walk over their subgroup's different lists
  double density() const { return surface ? double(lit) / double(surface) : 0.0; }
  double evaluated_per_lit() const { return lit ? double(evaluated) / double(lit) : 0.0; }
};

// The records the GPU reads (shaders/cluster_light.h), packed from chapter 03's light set in
// light order: a record per light, then a cone per spot (light first_spot + k has cone k); then
// a record per chapter 04 tube, from first_tube on (its capsule, and its index in `tubes`).
// As glm types: the header's struct is a GLSL one.
struct ClusterRecords {
  struct Light {
    glm::vec4 position_radius, radiance_inv_range2;
  };
  struct Spot {
    glm::vec4 axis_offset;
  };
  std::vector<Light> lights;
  std::vector<Spot> spots;
  int first_spot = 0, first_tube = 0;
};
ClusterRecords pack_cluster_lights(const ch03::LightSet& set, const std::vector<ch04::NeonGpu>& tubes = {});

class ClusteredLights : public ch03::LocalLightPass {
 public:
  explicit ClusteredLights(const ch03::LightVolumes& volumes, ClusterSettings settings = {});
  std::string name() const override { return mode_name(settings_); }
  void draw(const ch03::LightBuffer& light, const ch03::SurfaceView& view, ch03::LightVolumes::Output output) override;
  // Times its three passes apart: "<mode>: depth bounds", "<mode>: assign", "<mode>: shade"
  // (Z-binning: the assignment as its parts, "<mode>: assign: sort" ...).
  bool times_own_passes() const override { return true; }
  void set_metrics(PassMetrics* metrics) override { metrics_ = metrics; }
  static std::vector<std::string> pass_names(const std::string& mode);
  // Z-binning times its assignment's steps apart, each "<assign pass>: <part>": the clears,
  // the sort, the bins' ranges, the tiles' bits, and the floor's exact lists (zbin-floor).
  static const std::vector<std::string>& zbin_assign_parts();
  // Passes 1 and 2 alone (depth bounds, assign) for a w x h image seen as `view`: the lists
  // draw() shades from, and a forward pass's (ClusteredForward). Returns the shaders' defines.
  std::vector<std::string> build_lists(int w, int h, const ch03::SurfaceView& view);

  // [tubes-api]
  // Chapter 04's tubes binned with the lights, as their capsules (cluster_grid.h's
  // capsule_meets_box), after them in light order, and shaded in the same pass by chapter 04's
  // neon_light() with `how`'s method: the light chapter 04's capsule volumes add, without the
  // volumes. None (the default): the lights alone. Tiled and clustered (Z-binning refuses them).
  void set_tubes(const std::vector<ch04::NeonGpu>& tubes, const ch04::NeonDraw& how = {});
  int tube_count() const { return int(tubes_.size()); }
  // [/tubes-api]
  // The path the last draw's compute shading took: subgroup_support()'s name, "none (fallback)"
  // where the driver has none, "off" (settings.subgroups false), or "" (the fragment or staged
  // shading, Z-binning, whose lists are per pixel, or no draw yet).
  const std::string& subgroup_path() const { return subgroup_path_; }
  // With settings().phase_clocks: the cycles of each phase of zbin_staged.comp (phase_names())
  // summed over its work groups since the last call, then zeroed. It waits for the GPU: a
  // benchmark's read-back, never a frame's.
  static const std::vector<std::string>& phase_names();
  std::vector<std::uint64_t> take_phase_cycles();
  // With lanes_from: the last draw's tiles (y * tiles_x + x) that were shaded with the lanes
  // (heavy) and with one (light), each sorted, for the tests. Waits for the GPU.
  struct LaneTiles {
    std::vector<std::uint32_t> heavy, light;
  };
  LaneTiles lane_tiles() const;
  const ClusterSettings& settings() const { return settings_; }
  void set_settings(const ClusterSettings& s) { settings_ = s; }
  void set_counting(bool on) { counting_ = on; }
  const ClusterStats& stats() const { return stats_; }  // never waits: the GPU's part is late
  const ClusterStats& wait_stats();                     // waits for the last draw's
  EvalCounts counts() const;  // of the last draw (waits for the GPU)
  const Grid& grid() const { return grid_; }
  // Every cell's light count in the last draw (cell_index order: x fastest, then y, then slice).
  std::vector<std::uint32_t> cell_counts() const;
  // Every cell's list as stored: (offset, count) per cell and the index list, for the tests.
  // zbin: each tile's (0, bits set); zbin-floor: each pixel's exact list (row by row).
  std::vector<glm::uvec2> cell_lists() const;
  std::vector<std::uint32_t> index_list();  // waits for the last draw
  // Z-binning's lists as stored, for the tests: the sorted order (order[p] is a light), each
  // bin's range of sorted positions (x > y: none), each tile's words of bits (words per tile),
  // and which of those words have bits ((words + 31) / 32 words per tile: bit w % 32 of the
  // tile's word w / 32 for its word w).
  struct ZBinLists {
    std::vector<std::uint32_t> order;
    std::vector<glm::uvec2> ranges;
    std::vector<std::uint32_t> masks, touched;
    std::size_t words = 0;
    // With sorted_records: the light and cone at each sorted position (xyzw of each: position
    // and radius, radiance and 1 / range^2, the cone).
    std::vector<glm::vec4> records;
  };
  ZBinLists zbin_lists() const;
  void reload_shaders() { programs_.clear(); }

  // [forward-api]
  // Clustered forward: a forward fragment shader that includes
  // 09_clustered/shaders/clustered_forward.glsl, compiled with forward_defines(view), lights
  // its fragments from the lists the last draw() built (clustered, with all_cells on: throws
  // Error otherwise). bind_for_forward() binds them and sets the program's grid uniforms for
  // the camera that draw() had; with `counting`, counts() then reads the forward pass's counts.
  std::vector<std::string> forward_defines(const ch03::SurfaceView& view, bool counting = false) const;
  void bind_for_forward(const ShaderProgram& program, const FrameCamera& camera, bool counting = false);
  // [/forward-api]

 private:
  void upload_lights();
  void assign(const std::vector<std::string>& defines, const FrameCamera& camera);
  void assign_zbin(const std::vector<std::string>& defines, const FrameCamera& camera);
  void fence_state();
  void grow_if_an_earlier_draw_overflowed();
  void read_finished_states(bool wait_for_last);
  void set_grid_uniforms(const ShaderProgram& p, const FrameCamera& camera) const;
  const ShaderProgram& program(GLenum stage, const std::string& file, const std::vector<std::string>& defines);

  const ch03::LightVolumes& volumes_;
  ClusterSettings settings_;
  PassMetrics* metrics_ = nullptr;
  bool counting_ = false;
  Grid grid_;
  ClusterStats stats_;
  // What was uploaded, to see when chapter 03's light set changes.
  std::vector<ch03::PointInstance> points_;
  std::vector<ch03::SpotInstance> cones_, wide_;
  std::vector<ch04::NeonGpu> tubes_;  // set_tubes(): uploaded with the lights
  ch04::NeonDraw tube_how_;
  gl::Buffer tube_buffer_;
  bool uploaded_ = false;
  int light_count_ = 0, first_spot_ = 0, first_tube_ = 0;
  gl::Buffer lights_, spots_, cells_, bounds_, indices_, state_;
  std::size_t lights_bytes_ = 0, cells_bytes_ = 0, bounds_bytes_ = 0;
  // Z-binning's: the sorted order, each bin's range, each tile's bits and which of its words
  // have bits (the last frame's, cleared word by word), the sort's scratch.
  gl::Buffer order_, zbins_, masks_, touched_, sort_, sorted_;
  std::size_t order_bytes_ = 0, zbins_bytes_ = 0, masks_bytes_ = 0, touched_bytes_ = 0, sort_bytes_ = 0, sorted_bytes_ = 0;
  glm::uvec2 mask_layout_{0, 0};  // (tiles, words a tile) the masks hold now; (0, 0): not cleared yet
  std::uint32_t capacity_ = 0;
  // Each draw's list state, copied when its assignment ends and read once the GPU has passed
  // the fence: a few draws may be in flight, the oldest slot is reused.
  struct Fence {
    GLsync sync = nullptr;
    Fence() = default;
    Fence(const Fence&) = delete;
    Fence& operator=(const Fence&) = delete;
    ~Fence() { reset(); }
    void reset() {
      if (sync) glDeleteSync(sync);
      sync = nullptr;
    }
  };
  struct PendingState {
    gl::Buffer copy;
    Fence fence;
    std::uint64_t frame = 0;
  };
  std::array<PendingState, 4> pending_;
  std::uint64_t frame_ = 0;
  ch03::FragmentCounters counters_{5};
  std::string subgroup_path_, support_;
  std::string phase_clocks_define();  // checks for GL_ARB_shader_clock, binds the sums
  gl::Buffer clocks_;
  gl::Buffer lane_tiles_;  // zbin_lanes.comp's two dispatches and lists of tiles (lanes_from)
  std::size_t lane_tiles_bytes_ = 0;
  void shade_heavy_then_light(const std::vector<std::string>& defines, const ch03::LightBuffer* light, const FrameCamera& camera);
  // zbin_staged.comp, a group a tile (its lanes as the settings say; `defines` name its STAGE_TILE):
  // the shading into `light`, or with FLOOR_LISTS in `defines` (light null) the floor's exact lists.
  void dispatch_zbin_staged(std::vector<std::string> defines, const FrameCamera& camera, const ch03::LightBuffer* light);
  void check_staged_shape() const;  // throws where zbin_staged.comp cannot take the tiles and lanes asked for
  bool clocks_ready_ = false;
  bool support_known_ = false;
  ch02::FullScreenPass full_screen_;
  ProgramCache programs_;
};

}  // namespace lp::ch09
