#include "chapters/09_clustered/clustered_lights.h"

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <set>

#include "common/error.h"

namespace lp::ch09 {

bool is_cluster_mode(const std::string& name) {
  return std::find(kClusterModes.begin(), kClusterModes.end(), name) != kClusterModes.end() ||
         std::find(kBenchModes.begin(), kBenchModes.end(), name) != kBenchModes.end();
}

ClusterSettings settings_for_mode(const std::string& name, ClusterSettings s) {
  if (!is_cluster_mode(name)) throw Error("unknown culling mode '" + name + "'");
  s.kind = name.rfind("tiled", 0) == 0 ? CullKind::Tiled : name.rfind("zbin", 0) == 0 ? CullKind::ZBin : CullKind::Clustered;
  s.shade = name.find("fragment") != std::string::npos ? ShadeIn::Fragment
            : name.find("staged") != std::string::npos ? ShadeIn::Staged
                                                       : ShadeIn::Compute;
  s.depth_mask = name.find("2.5d") != std::string::npos;
  s.floor = name == "zbin-floor";
  return s;
}

namespace {
// The staged shading (a work group a tile, its lights in shared memory): tiled or Z-binning's
// (not the floor's, which reads per-pixel lists), where the settings ask for it.
bool staged_shading(const ClusterSettings& s) {
  return s.shade == ShadeIn::Staged && s.kind != CullKind::Clustered && !s.floor;
}
}  // namespace

std::string mode_name(const ClusterSettings& s) {
  const bool mask = s.kind == CullKind::Tiled && s.depth_mask;
  const bool staged = staged_shading(s);
  const char* kind = s.kind == CullKind::Tiled ? "tiled" : s.kind == CullKind::ZBin ? "zbin" : "clustered";
  return std::string(kind) + (mask ? "-2.5d" : "") +
         (s.kind == CullKind::ZBin && s.floor ? "-floor" : "") + (s.shade == ShadeIn::Fragment ? "-fragment" : "") +
         (staged ? "-staged" : "");
}

std::vector<std::string> ClusteredLights::pass_names(const std::string& mode) {
  return {"local lights: " + mode + ": depth bounds", "local lights: " + mode + ": assign",
          "local lights: " + mode + ": shade"};
}

const std::vector<std::string>& ClusteredLights::zbin_assign_parts() {
  static const std::vector<std::string> parts = {"clear", "sort", "bins", "tiles", "floor lists"};
  return parts;
}

// [subgroup-support]
namespace {
std::set<std::string> gl_extensions() {
  std::set<std::string> extensions;
  GLint n = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &n);
  for (GLint i = 0; i < n; ++i) extensions.insert(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i))));
  return extensions;
}
}  // namespace

std::string subgroup_support() {
  const char* none = std::getenv("LIGHTPASS_TEST_NO_SUBGROUPS");
  if (none && std::string(none) == "1") return "";
  const std::set<std::string> extensions = gl_extensions();
  if (extensions.count("GL_KHR_shader_subgroup")) {
    GLint stages = 0, features = 0;
    glGetIntegerv(GL_SUBGROUP_SUPPORTED_STAGES_KHR, &stages);
    glGetIntegerv(GL_SUBGROUP_SUPPORTED_FEATURES_KHR, &features);
    const GLint needed = GL_SUBGROUP_FEATURE_BASIC_BIT_KHR | GL_SUBGROUP_FEATURE_VOTE_BIT_KHR | GL_SUBGROUP_FEATURE_BALLOT_BIT_KHR;
    if ((stages & GL_COMPUTE_SHADER_BIT) && (features & needed) == needed) return "KHR_shader_subgroup";
  }
  if (extensions.count("GL_ARB_shader_ballot") && extensions.count("GL_ARB_shader_group_vote")) return "ARB_shader_ballot";
  return "";
}
// [/subgroup-support]

namespace glsl {
using glm::vec4;
#include "chapters/09_clustered/shaders/cluster_light.h"  // ClusterLight, ClusterSpot, shared with GLSL
}  // namespace glsl

namespace {
// The GPU's records of a light and of a spot's cone (cluster_light.h).
using GpuClusterLight = glsl::ClusterLight;
using GpuClusterSpot = glsl::ClusterSpot;
// zbin.glsl's SortedRecord: a light and its cone at each sorted position (sorted_records).
constexpr std::size_t kSortedRecordBytes = sizeof(GpuClusterLight) + sizeof(GpuClusterSpot);
static_assert(sizeof(GpuClusterLight) == 32 && offsetof(GpuClusterLight, radiance_inv_range2) == 16);
static_assert(sizeof(GpuClusterSpot) == 16);
static_assert(sizeof(ClusterRecords::Light) == sizeof(GpuClusterLight) && sizeof(ClusterRecords::Spot) == sizeof(GpuClusterSpot));

struct ListState {
  std::uint32_t head, capacity, cells_over, over_lo, over_hi, needed_lo, needed_hi, max_count;
};

template <class T>
bool same(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void set4i(const ShaderProgram& p, const char* name, int a, int b, int c, int d) {
  glProgramUniform4i(p.id(), glGetUniformLocation(p.id(), name), a, b, c, d);
}

// The largest number of lights the 32-bit arithmetic of assign.comp holds (n * 64 < 2^32) and llvmpipe's loop limit allows (n / 64 / 4 < 65 535).
constexpr std::size_t kMaxLights = std::size_t(1) << 22;
constexpr GLuint kTubeBinding = 10;  // shade.glsl's Tubes buffer (CLUSTER_TUBES); 9 holds the spots' cones
constexpr GLuint kTileWordsBinding = 11;  // zbin.glsl's TileWords
constexpr GLuint kSortedBinding = 12;     // zbin.glsl's SortedRecords (ClusterSettings::sorted_records)
constexpr GLuint kClocksBinding = 13;     // zbin_staged.comp's PhaseClocks (ClusterSettings::phase_clocks)
constexpr GLuint kLaneTilesBinding = 14;  // zbin.glsl's LaneTiles (ClusterSettings::lanes_from)
}  // namespace

// [pack]
ClusterRecords pack_cluster_lights(const ch03::LightSet& set, const std::vector<ch04::NeonGpu>& tubes) {
  // 1 / range^2 (0 without a range), capped where it would overflow: 0 times it stays 0.
  auto inv_range2 = [](float range) {
    return range > 0.f ? std::min(1.f / (range * range), std::numeric_limits<float>::max()) : 0.f;
  };
  ClusterRecords r;
  r.lights.reserve(set.local_count());
  for (const auto& p : set.points)
    r.lights.push_back({p.position_radius, glm::vec4(glm::vec3(p.radiance_range), inv_range2(p.radiance_range.w))});
  r.first_spot = int(r.lights.size());
  for (const auto* spots : {&set.cones, &set.wide_spots})
    for (const auto& s : *spots) {
      r.lights.push_back({s.position_radius, glm::vec4(glm::vec3(s.radiance_range), inv_range2(s.radiance_range.w))});
      // The cone folded: (dot(-l, dir) - cos outer) * scale = dot(-l, dir * scale) - cos outer * scale.
      const glm::vec3 dir = glm::vec3(ch03::unpack(s).direction_range);
      const float cos_outer = s.direction_cone.z, scale = s.direction_cone.w;
      r.spots.push_back({glm::vec4(dir * scale, -cos_outer * scale)});
    }
  r.first_tube = int(r.lights.size());
  // [tube-records]
  // A tube's record: its capsule (the segment and the volume radius neon_light() cuts at), for
  // the assignment; the shading reads the packed tube itself by its index.
  for (std::size_t i = 0; i < tubes.size(); ++i) {
    const ch04::UnpackedNeon t = ch04::unpack_neon(tubes[i]);
    r.lights.push_back({glm::vec4(t.light.start, t.volume_radius), glm::vec4(t.light.end, float(i))});
  }
  // [/tube-records]
  return r;
}
// [/pack]

ClusteredLights::ClusteredLights(const ch03::LightVolumes& volumes, ClusterSettings settings)
    : volumes_(volumes), settings_(settings) {}

const ShaderProgram& ClusteredLights::program(GLenum stage, const std::string& file, const std::vector<std::string>& defines) {
  std::vector<ShaderStage> stages = {{stage, file}};
  if (stage == GL_FRAGMENT_SHADER) stages.insert(stages.begin(), {GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"});
  return programs_.get(stages, defines);
}

void ClusteredLights::set_tubes(const std::vector<ch04::NeonGpu>& tubes, const ch04::NeonDraw& how) {
  if (!same(tubes, tubes_)) uploaded_ = false;
  tubes_ = tubes;
  tube_how_ = how;
}

void ClusteredLights::upload_lights() {
  const ch03::LightSet& set = volumes_.lights();
  if (uploaded_ && same(set.points, points_) && same(set.cones, cones_) && same(set.wide_spots, wide_)) return;
  if (set.local_count() + tubes_.size() > kMaxLights)
    throw Error("clustered lights: " + std::to_string(set.local_count() + tubes_.size()) + " local lights and tubes, at most " +
                std::to_string(kMaxLights));
  const ClusterRecords g = pack_cluster_lights(set, tubes_);
  const std::size_t light_bytes = std::max<std::size_t>(g.lights.size() * sizeof(GpuClusterLight), 32);
  const std::size_t spot_bytes = std::max<std::size_t>(g.spots.size() * sizeof(GpuClusterSpot), 16);
  const std::size_t tube_bytes = std::max<std::size_t>(tubes_.size(), 1) * sizeof(ch04::NeonGpu);
  glNamedBufferData(lights_.id(), GLsizeiptr(light_bytes), nullptr, GL_STATIC_DRAW);
  glNamedBufferData(spots_.id(), GLsizeiptr(spot_bytes), nullptr, GL_STATIC_DRAW);
  glNamedBufferData(tube_buffer_.id(), GLsizeiptr(tube_bytes), tubes_.empty() ? nullptr : tubes_.data(), GL_STATIC_DRAW);
  if (!g.lights.empty()) glNamedBufferSubData(lights_.id(), 0, GLsizeiptr(g.lights.size() * sizeof(GpuClusterLight)), g.lights.data());
  if (!g.spots.empty()) glNamedBufferSubData(spots_.id(), 0, GLsizeiptr(g.spots.size() * sizeof(GpuClusterSpot)), g.spots.data());
  lights_bytes_ = light_bytes + spot_bytes;
  light_count_ = int(g.lights.size());
  first_spot_ = g.first_spot;
  first_tube_ = g.first_tube;
  points_ = set.points;
  cones_ = set.cones;
  wide_ = set.wide_spots;
  uploaded_ = true;
}

void ClusteredLights::set_grid_uniforms(const ShaderProgram& p, const FrameCamera& camera) const {
  p.set("u_view", camera.view);
  p.set("u_projection", glm::vec4(camera.projection[0][0], camera.projection[1][1], camera.projection[2][0],
                                  camera.projection[2][1]));
  set4i(p, "u_grid", grid_.width, grid_.height, grid_.tile_w, grid_.tile_h);
  set4i(p, "u_tiles", grid_.tiles_x, grid_.tiles_y, grid_.slices, light_count_);
  p.set("u_depth_range", glm::vec2(grid_.znear, grid_.zfar));
  glProgramUniform1f(p.id(), glGetUniformLocation(p.id(), "u_near_slice"), grid_.near_slice);  // -1 (none): ignored
  glProgramUniform1i(p.id(), glGetUniformLocation(p.id(), "u_zbins"), settings_.zbins);  // -1 (none): ignored
  glProgramUniform1i(p.id(), glGetUniformLocation(p.id(), "u_first_spot"), first_spot_);
  glProgramUniform1i(p.id(), glGetUniformLocation(p.id(), "u_first_tube"), first_tube_);
}

// [draw]
void ClusteredLights::draw(const ch03::LightBuffer& light, const ch03::SurfaceView& view,
                           ch03::LightVolumes::Output output) {
  const FrameCamera& camera = view.camera;
  const int w = light.width(), h = light.height();
  const std::vector<std::string> defines = build_lists(w, h, view);
  const std::vector<std::string> names = pass_names(name());
  // 3. Shade: each pixel adds the lights of its cell into L1 and L2.
  {
    auto pass = timed(metrics_, names[2]);
    std::vector<std::string> d = defines;
    if (counting_) {
      for (const auto& c : ch03::FragmentCounters::defines()) d.push_back(c);
      counters_.reset();
      counters_.bind();
    }
    if (output == ch03::LightVolumes::Output::HeatShaded) d.push_back("HEAT_SHADED 1");
    if (output == ch03::LightVolumes::Output::HeatLit) d.push_back("HEAT_LIT 1");
    const bool staged = staged_shading(settings_);
    if (staged) check_staged_shape();
    subgroup_path_.clear();
    if (settings_.shade != ShadeIn::Fragment) {
      for (const std::string& image : ch03::LightBuffer::image_defines()) d.push_back(image);
      if (staged) d.push_back("STAGE_TILE " + std::to_string(grid_.tile_w));
      if (staged && settings_.kind == CullKind::ZBin) {  // zbin_staged.comp's options (its lanes: dispatch_zbin_staged)
        if (settings_.sub_blocks) d.push_back("SUB_BLOCKS 1");
        if (settings_.staged_fields) d.push_back("STAGED_FIELDS 1");
        if (settings_.phase_clocks) d.push_back(phase_clocks_define());
      }
      if (!staged && settings_.kind != CullKind::ZBin) {  // a tile's or cluster's list, read once where shared
        if (!support_known_) support_ = subgroup_support();  // the context's, asked once
        support_known_ = true;
        const std::string& support = support_;
        const bool usable = support == "KHR_shader_subgroup" || (!support.empty() && settings_.subgroups == SubgroupUse::Any);
        subgroup_path_ = settings_.subgroups == SubgroupUse::Off ? "off" : usable ? support : "none (fallback)";
        if (settings_.subgroups != SubgroupUse::Off && usable) {
          d.push_back("SUBGROUP_LISTS 1");
          d.push_back(support == "KHR_shader_subgroup" ? "SUBGROUP_KHR 1" : "SUBGROUP_ARB 1");
          if (settings_.subgroup_merge) d.push_back("SUBGROUP_MERGE 1");
        }
      }
      if (staged && settings_.kind == CullKind::ZBin) {
        dispatch_zbin_staged(d, camera, &light);
      } else {
        const ShaderProgram& p = program(GL_COMPUTE_SHADER, staged ? "09_clustered/shaders/shade_staged.comp" : "09_clustered/shaders/shade.comp", d);
        set_grid_uniforms(p, camera);
        p.use();
        light.bind_images(GL_READ_WRITE);  // on the units LightBuffer::image_defines() names
        if (staged) {  // a group a tile
          glDispatchCompute(GLuint(grid_.tiles_x), GLuint(grid_.tiles_y), 1);
          glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        } else {
          light.dispatch_per_pixel();
        }
      }
    } else {
      const ShaderProgram& p = program(GL_FRAGMENT_SHADER, "09_clustered/shaders/shade.frag", d);
      set_grid_uniforms(p, camera);
      light.bind();
      glDisable(GL_DEPTH_TEST);
      glDepthMask(GL_FALSE);
      glEnable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE);
      p.use();
      full_screen_.draw();
      glDisable(GL_BLEND);
      glDepthMask(GL_TRUE);
    }
  }
  light.bind();
}
// [/draw]

// Staged: one work group per tile, so tiled or Z-binning with square tiles of at most 32
// pixels (1 024 invocations, GL's guaranteed minimum); clusters shade per pixel (shade.comp).
void ClusteredLights::check_staged_shape() const {
  if (grid_.tile_w != grid_.tile_h || grid_.tile_w > 32)
    throw Error("clustered lights: " + name() + " needs square tiles of at most 32 pixels, not " + std::to_string(grid_.tile_w) +
                " x " + std::to_string(grid_.tile_h));
  if (settings_.kind != CullKind::ZBin) return;
  const int lanes = settings_.pixel_lanes;  // zbin_staged.comp's shapes
  if (settings_.sub_blocks && grid_.tile_w % 8 != 0)
    throw Error("clustered lights: " + name() + "'s sub-blocks of 8 x 4 pixels need tiles of 8, 16, 24 or 32 pixels, not " +
                std::to_string(grid_.tile_w));
  if (lanes != 1 && lanes != 2 && lanes != 4)
    throw Error("clustered lights: " + name() + " takes 1, 2 or 4 invocations a pixel, not " + std::to_string(lanes));
  if (settings_.lanes_from < 0)
    throw Error("clustered lights: " + name() + "'s lanes_from is a count of lights, not " + std::to_string(settings_.lanes_from));
  // (Larger tiles: over 1 024 invocations, or over GL's 32 KiB of shared memory with the lanes' sums.)
  if (lanes > 1 && (settings_.sub_blocks || grid_.tile_w > 16))
    throw Error("clustered lights: " + name() + " with " + std::to_string(lanes) + " invocations a pixel needs " +
                (settings_.sub_blocks ? std::string("no sub-blocks") : "tiles of at most 16 pixels, not " + std::to_string(grid_.tile_w)) +
                " (one lane for those)");
}

void ClusteredLights::dispatch_zbin_staged(std::vector<std::string> d, const FrameCamera& camera, const ch03::LightBuffer* light) {
  if (settings_.pixel_lanes > 1 && settings_.lanes_from > 0) {  // lanes in the heavy tiles alone: a first pass lists them
    shade_heavy_then_light(d, light, camera);
    return;
  }
  if (settings_.pixel_lanes > 1) d.push_back("PIXEL_LANES " + std::to_string(settings_.pixel_lanes));  // in every tile
  const ShaderProgram& p = program(GL_COMPUTE_SHADER, "09_clustered/shaders/zbin_staged.comp", d);
  set_grid_uniforms(p, camera);
  p.use();
  if (light) light->bind_images(GL_READ_WRITE);  // on the units LightBuffer::image_defines() names
  glDispatchCompute(GLuint(grid_.tiles_x), GLuint(grid_.tiles_y), 1);  // a group a tile
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                  GL_SHADER_STORAGE_BARRIER_BIT);
}

// [lane-dispatch]
// zbin-staged with lanes only where a tile needs them (ClusterSettings::lanes_from): a group a
// tile counts the tile's lights and lists it as heavy or light (zbin_lanes.comp), then the
// heavy tiles are shaded with the lanes and the light ones with one, each dispatch as many
// groups as its list holds, read by the GPU from the counts the first pass left.
void ClusteredLights::shade_heavy_then_light(const std::vector<std::string>& defines, const ch03::LightBuffer* light,
                                             const FrameCamera& camera) {
  const std::size_t tiles = std::size_t(grid_.tiles_x) * std::size_t(grid_.tiles_y), bytes = 24 + tiles * 4;
  if (bytes != lane_tiles_bytes_) glNamedBufferData(lane_tiles_.id(), GLsizeiptr(lane_tiles_bytes_ = bytes), nullptr, GL_DYNAMIC_DRAW);
  const std::uint32_t none[6] = {0, 1, 1, 0, 1, 1};  // (x, y, z) of two dispatches of no group
  glNamedBufferSubData(lane_tiles_.id(), 0, sizeof(none), none);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLaneTilesBinding, lane_tiles_.id());
  std::vector<std::string> d = defines;
  d.push_back("LANE_TILES " + std::to_string(kLaneTilesBinding));
  const ShaderProgram& count = program(GL_COMPUTE_SHADER, "09_clustered/shaders/zbin_lanes.comp", d);
  set_grid_uniforms(count, camera);
  glProgramUniform1ui(count.id(), glGetUniformLocation(count.id(), "u_lanes_from"), GLuint(settings_.lanes_from));
  count.use();
  glDispatchCompute(GLuint(grid_.tiles_x), GLuint(grid_.tiles_y), 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);  // the lists, and the counts as dispatches
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, lane_tiles_.id());
  if (light) light->bind_images(GL_READ_WRITE);  // on the units LightBuffer::image_defines() names
  // The heavy tiles first (their groups run longest), then the light: one lane, from the back.
  for (const bool heavy : {true, false}) {
    std::vector<std::string> shade = d;
    shade.push_back(std::string("TILES_FROM_END ") + (heavy ? "0" : "1"));
    if (heavy) shade.push_back("PIXEL_LANES " + std::to_string(settings_.pixel_lanes));  // the light tiles: one lane
    const ShaderProgram& p = program(GL_COMPUTE_SHADER, "09_clustered/shaders/zbin_staged.comp", shade);
    set_grid_uniforms(p, camera);
    p.use();
    glDispatchComputeIndirect(GLintptr(heavy ? 0 : 12));
  }
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                  GL_SHADER_STORAGE_BARRIER_BIT);
}
// [/lane-dispatch]

ClusteredLights::LaneTiles ClusteredLights::lane_tiles() const {
  LaneTiles t;
  if (lane_tiles_bytes_ < 24) return t;
  std::vector<std::uint32_t> v(lane_tiles_bytes_ / 4);
  glGetNamedBufferSubData(lane_tiles_.id(), 0, GLsizeiptr(lane_tiles_bytes_), v.data());
  const std::size_t tiles = v.size() - 6, heavy = std::min<std::size_t>(v[0], tiles), light = std::min<std::size_t>(v[3], tiles - heavy);
  t.heavy.assign(v.begin() + 6, v.begin() + 6 + std::ptrdiff_t(heavy));
  t.light.assign(v.end() - std::ptrdiff_t(light), v.end());
  std::sort(t.heavy.begin(), t.heavy.end());
  std::sort(t.light.begin(), t.light.end());
  return t;
}

const std::vector<std::string>& ClusteredLights::phase_names() {
  static const std::vector<std::string> names = {"setup", "span", "stage", "reach", "shade", "output"};  // zbin_staged.comp's
  return names;
}

std::string ClusteredLights::phase_clocks_define() {
  if (!clocks_ready_) {
    if (!gl_extensions().count("GL_ARB_shader_clock"))
      throw Error("clustered lights: the phase clocks need GL_ARB_shader_clock, which this driver does not offer");
    const std::vector<std::uint32_t> zero(2 * phase_names().size(), 0u);  // a 64-bit sum a phase, as two words
    glNamedBufferData(clocks_.id(), GLsizeiptr(zero.size() * 4), zero.data(), GL_DYNAMIC_READ);
    clocks_ready_ = true;
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kClocksBinding, clocks_.id());
  return "PHASE_CLOCKS " + std::to_string(kClocksBinding);
}

std::vector<std::uint64_t> ClusteredLights::take_phase_cycles() {
  std::vector<std::uint64_t> cycles(phase_names().size(), 0);
  if (!clocks_ready_) return cycles;
  std::vector<std::uint32_t> words(2 * cycles.size());
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(clocks_.id(), 0, GLsizeiptr(words.size() * 4), words.data());
  for (std::size_t k = 0; k < cycles.size(); ++k) cycles[k] = (std::uint64_t(words[2 * k + 1]) << 32) | words[2 * k];
  std::fill(words.begin(), words.end(), 0u);
  glNamedBufferSubData(clocks_.id(), 0, GLsizeiptr(words.size() * 4), words.data());
  return cycles;
}

// [build-lists]
std::vector<std::string> ClusteredLights::build_lists(int w, int h, const ch03::SurfaceView& view) {
  const FrameCamera& camera = view.camera;
  const bool clustered = settings_.kind == CullKind::Clustered, zbin = settings_.kind == CullKind::ZBin;
  grid_ = clustered ? grid_of_counts(w, h, settings_.clusters.x, settings_.clusters.y, settings_.clusters.z,
                                     camera.znear, camera.zfar)
                    : grid_of_tiles(w, h, settings_.tile_px, 1, camera.znear, camera.zfar);
  if (clustered) grid_.near_slice = settings_.near_slice;
  // Bounded work and memory for any knob values: at most 2^22 cells (32 MiB of cell records).
  if (std::uint64_t(grid_.tiles_x) * std::uint64_t(grid_.tiles_y) * std::uint64_t(grid_.slices) > (1u << 22))
    throw Error("clustered lights: a grid of " + std::to_string(grid_.tiles_x) + " x " + std::to_string(grid_.tiles_y) +
                " x " + std::to_string(grid_.slices) + " cells is more than 4 194 304; use larger tiles or fewer slices");
  upload_lights();
  stats_.cells = grid_.cells();

  std::vector<std::string> defines = view.defines;
  for (const auto& d : view.hooks.glsl_defines()) defines.push_back(d);
  if (clustered) defines.push_back("CLUSTERED 1");
  if (clustered && grid_.has_near_slice()) defines.push_back("NEAR_SLICE 1");
  if (clustered && settings_.all_cells) defines.push_back("ALL_CELLS 1");
  if (!tubes_.empty()) {  // the tubes' buffer and how neon_light() lights them (shade.glsl)
    if (zbin) throw Error("clustered lights: Z-binning bins spheres, not chapter 04's tubes; use tiled or clustered");
    defines.push_back("CLUSTER_TUBES " + std::to_string(kTubeBinding));
    defines.push_back("TUBE_METHOD " + std::to_string(static_cast<int>(tube_how_.method)));
    defines.push_back("TUBE_SAMPLES " + std::to_string(tube_how_.samples));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTubeBinding, tube_buffer_.id());
  }
  const bool floor = zbin && settings_.floor;
  if (zbin) defines.push_back("ZBIN 1");
  if (zbin && settings_.sorted_records) defines.push_back("SORTED_RECORDS " + std::to_string(kSortedBinding));
  if (floor) defines.push_back("FLOOR 1");
  const bool mask = settings_.kind == CullKind::Tiled && settings_.depth_mask;
  if (mask) defines.push_back("DEPTH_MASK 1");

  // The cells and the bounds: one (offset, count) per cell; tiled: (min, max) per tile and
  // with the depth mask its 32 bins, clustered: an occupied flag per cell.
  // (The floor: one (offset, count) per pixel instead.)
  const std::size_t cells_bytes = (floor ? std::size_t(w) * std::size_t(h) : std::size_t(grid_.cells())) * 8;
  const std::size_t bounds_bytes = std::size_t(grid_.cells()) * 4 * (clustered ? 1 : mask ? 3 : 2);
  if (cells_bytes != cells_bytes_) glNamedBufferData(cells_.id(), GLsizeiptr(cells_bytes_ = cells_bytes), nullptr, GL_DYNAMIC_DRAW);
  if (bounds_bytes != bounds_bytes_) glNamedBufferData(bounds_.id(), GLsizeiptr(bounds_bytes_ = bounds_bytes), nullptr, GL_DYNAMIC_DRAW);
  if (capacity_ == 0) {
    capacity_ = std::max<std::uint32_t>(settings_.initial_indices, 1);
    glNamedBufferData(indices_.id(), GLsizeiptr(capacity_) * 4, nullptr, GL_DYNAMIC_DRAW);
    glNamedBufferData(state_.id(), sizeof(ListState), nullptr, GL_DYNAMIC_COPY);
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, lights_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, spots_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, cells_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, bounds_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, indices_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, state_.id());
  const std::vector<std::string> names = pass_names(name());

  // 1. Depth bounds: what depths each tile's surfaces span (tiled), which clusters hold any
  //    (clustered; not needed when every cell gets its list).
  if (!(clustered && settings_.all_cells)) {
    auto pass = timed(metrics_, names[0]);
    const std::uint32_t zero = 0;
    glClearNamedBufferData(bounds_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    const ShaderProgram& p = program(GL_COMPUTE_SHADER, "09_clustered/shaders/depth_bounds.comp", defines);
    set_grid_uniforms(p, camera);
    p.use();
    glDispatchCompute(GLuint(grid_.tiles_x), GLuint(grid_.tiles_y), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  // 2. Assign: each cell's lights into the index list (grown first if an earlier draw's did not fit).
  //    Z-binning times its steps apart instead ("<mode>: assign: sort" ...: zbin_assign_parts).
  if (zbin) {
    assign_zbin(defines, camera);
  } else {
    auto pass = timed(metrics_, names[1]);
    assign(defines, camera);
  }
  return defines;
}
// [/build-lists]

void ClusteredLights::assign(const std::vector<std::string>& defines, const FrameCamera& camera) {
  // [overflow]
  // No read-back in the frame: what earlier draws needed is read once the GPU is done with
  // them. If one overflowed, the list grows now, before this draw's assignment; the draw that
  // overflowed shaded its full cells from every light (assign.comp), so nothing was lost.
  grow_if_an_earlier_draw_overflowed();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, indices_.id());
  const ShaderProgram& p = program(GL_COMPUTE_SHADER, "09_clustered/shaders/assign.comp", defines);
  set_grid_uniforms(p, camera);
  const ListState start{0, capacity_, 0, 0, 0, 0, 0, 0};
  glNamedBufferSubData(state_.id(), 0, sizeof(start), &start);
  p.use();
  glDispatchCompute(GLuint(grid_.tiles_x), GLuint(grid_.tiles_y), GLuint(grid_.slices));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  fence_state();
  // [/overflow]
}

void ClusteredLights::grow_if_an_earlier_draw_overflowed() {
  read_finished_states(false);
  if (stats_.frame > 0 && stats_.cells_over > 0 && settings_.grow && capacity_ < settings_.max_indices &&
      stats_.indices > capacity_) {
    capacity_ = std::uint32_t(std::min<std::uint64_t>(stats_.indices + stats_.indices / 4, settings_.max_indices));
    glNamedBufferData(indices_.id(), GLsizeiptr(capacity_) * 4, nullptr, GL_DYNAMIC_DRAW);
    ++stats_.regrown;
  }
}

void ClusteredLights::fence_state() {
  // This draw's state, copied on the GPU and fenced: read by a later draw, or wait_stats().
  PendingState* slot = &pending_[0];
  for (PendingState& q : pending_)
    if (q.frame < slot->frame) slot = &q;  // a free slot (frame 0) or the oldest
  if (slot->frame == 0) glNamedBufferData(slot->copy.id(), sizeof(ListState), nullptr, GL_STREAM_READ);
  glCopyNamedBufferSubData(state_.id(), slot->copy.id(), 0, 0, sizeof(ListState));
  slot->fence.reset();
  slot->fence.sync = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  slot->frame = ++frame_;
  stats_.capacity = capacity_;
  stats_.bytes = std::size_t(capacity_) * 4 + cells_bytes_ + bounds_bytes_ + lights_bytes_;
}

// [assign-zbin]
void ClusteredLights::assign_zbin(const std::vector<std::string>& defines, const FrameCamera& camera) {
  if (settings_.zbins < 1 || settings_.zbins > 16384)
    throw Error("clustered lights: Z-binning needs 1 to 16 384 depth bins, not " + std::to_string(settings_.zbins));
  // Bounded memory: a bit per light per tile, at most 1 GiB (1 000 000 lights over 16-pixel tiles at 1080p fit).
  const std::uint64_t words = (std::uint64_t(light_count_) + 31) / 32;
  const std::uint64_t mask_bytes = std::max<std::uint64_t>(std::uint64_t(grid_.tiles_x) * std::uint64_t(grid_.tiles_y) * words * 4, 4);
  if (mask_bytes > (std::uint64_t(1) << 30))
    throw Error("clustered lights: Z-binning's tile masks, " + std::to_string(grid_.tiles_x * grid_.tiles_y) + " tiles x " +
                std::to_string(light_count_) + " lights, take more than 1 GiB; use larger tiles (--tile)");
  constexpr std::size_t kSortKeys = 16384;  // zbin.comp's
  auto size = [](gl::Buffer& b, std::size_t& have, std::size_t want) {
    if (want != have) glNamedBufferData(b.id(), GLsizeiptr(have = want), nullptr, GL_DYNAMIC_DRAW);
  };
  // A word of tile_words per 32 words of a tile's mask (zbin.glsl): which words have bits.
  const std::uint64_t tiles = std::uint64_t(grid_.tiles_x) * std::uint64_t(grid_.tiles_y);
  const std::uint64_t word_words = (words + 31) / 32;
  size(order_, order_bytes_, std::max<std::size_t>(std::size_t(light_count_) * 4, 4));
  size(zbins_, zbins_bytes_, std::size_t(settings_.zbins) * 8);
  size(masks_, masks_bytes_, std::size_t(mask_bytes));
  size(touched_, touched_bytes_, std::size_t(std::max<std::uint64_t>(tiles * word_words * 4, 4)));
  size(sort_, sort_bytes_, (kSortKeys + std::size_t(light_count_)) * 4);
  if (settings_.sorted_records) {  // a light and a cone at each sorted position (zbin.glsl)
    size(sorted_, sorted_bytes_, std::max<std::size_t>(std::size_t(light_count_), 1) * kSortedRecordBytes);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSortedBinding, sorted_.id());
  }
  // Each step timed apart, so that a sweep can say where the assignment's time goes: the
  // clears, the sort, the bins' ranges, the tiles' bits.
  const std::string part = pass_names(name())[1] + ": ";
  const bool floor = settings_.floor;
  grow_if_an_earlier_draw_overflowed();  // the floor's lists are the index list; others: the late stats read
  const GLuint groups = GLuint((light_count_ + 255) / 256);
  auto dispatch = [&](int step, GLuint n) {
    std::vector<std::string> d = defines;
    d.push_back("STEP " + std::to_string(step));
    const ShaderProgram& p = program(GL_COMPUTE_SHADER, "09_clustered/shaders/zbin.comp", d);
    set_grid_uniforms(p, camera);
    p.use();
    glDispatchCompute(n, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  };
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTileWordsBinding, touched_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, order_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, zbins_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, masks_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, sort_.id());
  // [zbin-clear-words]
  {
    // The masks are tiles x lights bits, a gigabyte at a million lights over 16-pixel tiles,
    // but a frame sets bits in few of their words. So they are cleared whole only when their
    // layout changes (tiles or lights); otherwise only the words the last frame set, which
    // tile_words names (zbin.comp's step 0).
    auto pass = timed(metrics_, part + "clear");
    const std::uint32_t zero = 0, empty_range[2] = {0xFFFFFFFFu, 0u};
    glClearNamedBufferSubData(sort_.id(), GL_R32UI, 0, GLsizeiptr(kSortKeys * 4), GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glClearNamedBufferData(zbins_.id(), GL_RG32UI, GL_RG_INTEGER, GL_UNSIGNED_INT, empty_range);
    const glm::uvec2 layout{std::uint32_t(tiles), std::uint32_t(words)};
    if (layout != mask_layout_) {
      glClearNamedBufferData(masks_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
      glClearNamedBufferData(touched_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
      mask_layout_ = layout;
    } else {
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the last frame's shading has read them
      dispatch(0, GLuint(std::clamp<std::uint64_t>((tiles * word_words + 255) / 256, 1, 65535)));
    }
    const ListState start{0, floor ? capacity_ : 0, 0, 0, 0, 0, 0, 0};
    glNamedBufferSubData(state_.id(), 0, sizeof(start), &start);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }
  // [/zbin-clear-words]
  // Keys, scan, scatter (the sort), bins, tiles: one invocation per light except the scan's
  // one group and the wide lights' step, whose groups stride over the lights step 5 passed on
  // (their count is on the GPU; a group with none ends at once).
  constexpr GLuint kWideGroups = 1024;
  auto steps = [&](const std::string& what, int first, int last) {
    if (light_count_ == 0) return;
    auto pass = timed(metrics_, part + what);
    for (int step = first; step <= last; ++step) {
      if (step == 5) {  // the wide lights' count, in the sort's scratch (zbin.comp's ZWide)
        const std::uint32_t zero = 0;
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glClearNamedBufferSubData(sort_.id(), GL_R32UI, 0, 4, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
      }
      dispatch(step, step == 2 ? 1 : step == 6 ? kWideGroups : groups);
    }
  };
  steps("sort", 1, 3);
  steps("bins", 4, 4);
  steps("tiles", 5, 6);
  if (floor) {  // each pixel's exact list, into the index list (bound where the sort's scratch was)
    check_staged_shape();  // built a tile at a time, with zbin-staged's walk and lanes
    auto floor_pass = timed(metrics_, part + "floor lists");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, indices_.id());
    std::vector<std::string> d = defines;
    d.push_back("FLOOR_LISTS 1");
    d.push_back("STAGE_TILE " + std::to_string(grid_.tile_w));
    dispatch_zbin_staged(d, camera, nullptr);
  }
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  fence_state();
  stats_.bytes = order_bytes_ + zbins_bytes_ + masks_bytes_ + touched_bytes_ + sort_bytes_ + bounds_bytes_ + lights_bytes_ +
                 (settings_.sorted_records ? sorted_bytes_ : 0) +
                 (floor ? std::size_t(capacity_) * 4 + cells_bytes_ : 0);
}
// [/assign-zbin]

void ClusteredLights::read_finished_states(bool wait_for_last) {
  for (PendingState& q : pending_) {
    if (!q.fence.sync) continue;
    const bool last = q.frame == frame_;
    GLenum r = glClientWaitSync(q.fence.sync, GL_SYNC_FLUSH_COMMANDS_BIT, 0);
    while (wait_for_last && last && r == GL_TIMEOUT_EXPIRED)
      r = glClientWaitSync(q.fence.sync, GL_SYNC_FLUSH_COMMANDS_BIT, 1000000000ull);
    if (r == GL_TIMEOUT_EXPIRED) continue;
    if (r == GL_WAIT_FAILED) throw Error("clustered lights: waiting for the lists' state failed");
    q.fence.reset();
    if (q.frame <= stats_.frame) continue;  // a newer draw's state was read already
    ListState s{};
    glGetNamedBufferSubData(q.copy.id(), 0, sizeof(s), &s);
    stats_.frame = q.frame;
    stats_.indices = s.needed_lo + (std::uint64_t(s.needed_hi) << 32);
    stats_.max_list = s.max_count;
    stats_.cells_over = s.cells_over;
    stats_.over_entries = s.over_lo + (std::uint64_t(s.over_hi) << 32);
  }
}

const ClusterStats& ClusteredLights::wait_stats() {
  read_finished_states(true);
  return stats_;
}

std::vector<std::string> ClusteredLights::forward_defines(const ch03::SurfaceView& view, bool counting) const {
  std::vector<std::string> d = view.defines;
  for (const auto& h : view.hooks.glsl_defines()) d.push_back(h);
  d.push_back("CLUSTERED 1");
  Grid g;  // as build_lists() makes it for this camera: whether it has a near slice
  g.slices = settings_.clusters.z;
  g.znear = view.camera.znear;
  g.zfar = view.camera.zfar;
  g.near_slice = settings_.near_slice;
  if (g.has_near_slice()) d.push_back("NEAR_SLICE 1");
  if (counting)
    for (const auto& c : ch03::FragmentCounters::defines()) d.push_back(c);
  return d;
}

void ClusteredLights::bind_for_forward(const ShaderProgram& program, const FrameCamera& camera, bool counting) {
  if (settings_.kind != CullKind::Clustered || !settings_.all_cells || grid_.cells() == 0)
    throw Error("clustered forward: needs the lists of a clustered draw() with all_cells on (" + name() +
                (settings_.all_cells ? "" : ", all_cells off") + ")");
  program.use();
  set_grid_uniforms(program, camera);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, lights_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, spots_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, cells_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, indices_.id());
  if (counting) {
    glMemoryBarrier(GL_ALL_BARRIER_BITS);  // a previous pass's counting done before the reset
    counters_.reset();
    counters_.bind();
  }
}

EvalCounts ClusteredLights::counts() const {
  const std::vector<std::uint64_t> c = counters_.read();
  return {c[0], c[1], c[2], c[3], c[4]};
}

std::vector<glm::uvec2> ClusteredLights::cell_lists() const {
  if (settings_.kind == CullKind::ZBin && !settings_.floor) {  // each tile's bits: (0, how many)
    std::vector<std::uint32_t> m(masks_bytes_ / 4);
    if (!m.empty()) glGetNamedBufferSubData(masks_.id(), 0, GLsizeiptr(masks_bytes_), m.data());
    const std::size_t words = (std::size_t(light_count_) + 31) / 32;
    std::vector<glm::uvec2> v(std::size_t(grid_.cells()), glm::uvec2(0));
    for (std::size_t t = 0; t < v.size() && words; ++t)
      for (std::size_t k = 0; k < words && t * words + k < m.size(); ++k) v[t].y += std::uint32_t(std::popcount(m[t * words + k]));
    return v;
  }
  std::vector<glm::uvec2> v(cells_bytes_ / 8);  // a cell's, or (the floor) a pixel's
  if (!v.empty()) glGetNamedBufferSubData(cells_.id(), 0, GLsizeiptr(v.size() * 8), v.data());
  return v;
}

ClusteredLights::ZBinLists ClusteredLights::zbin_lists() const {
  ZBinLists z;
  if (settings_.kind != CullKind::ZBin) return z;
  auto read = [](const gl::Buffer& b, std::size_t bytes, auto& v) {
    v.resize(bytes / sizeof(v[0]));
    if (!v.empty()) glGetNamedBufferSubData(b.id(), 0, GLsizeiptr(v.size() * sizeof(v[0])), v.data());
  };
  read(order_, std::size_t(light_count_) * 4, z.order);
  read(zbins_, zbins_bytes_, z.ranges);
  read(masks_, masks_bytes_, z.masks);
  read(touched_, touched_bytes_, z.touched);
  z.words = (std::size_t(light_count_) + 31) / 32;
  if (settings_.sorted_records) read(sorted_, std::size_t(light_count_) * kSortedRecordBytes, z.records);
  return z;
}

std::vector<std::uint32_t> ClusteredLights::cell_counts() const {
  std::vector<std::uint32_t> n;
  for (const glm::uvec2& c : cell_lists()) n.push_back(c.y);
  return n;
}

std::vector<std::uint32_t> ClusteredLights::index_list() {
  wait_stats();  // the last draw's entry count (a read-back for tests: it waits anyway)
  std::vector<std::uint32_t> v(std::size_t(std::min<std::uint64_t>(stats_.indices, capacity_)));
  if (!v.empty()) glGetNamedBufferSubData(indices_.id(), 0, GLsizeiptr(v.size() * 4), v.data());
  return v;
}

}  // namespace lp::ch09
