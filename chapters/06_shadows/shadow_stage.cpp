#include "chapters/06_shadows/shadow_stage.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/scene_gpu.h"

namespace lp::ch06 {

namespace glsl {
using glm::mat4, glm::vec2, glm::vec3, glm::vec4;
#include "chapters/06_shadows/shaders/shadow_block.h"  // struct ShadowParameters, shared with GLSL
}  // namespace glsl
using glsl::ShadowParameters;
static_assert(SHADOW_MAX_POISSON_TAPS == kMaxPoissonTaps);
static_assert(offsetof(ShadowParameters, view) == 112 && offsetof(ShadowParameters, extent) == 176 &&
              offsetof(ShadowParameters, poisson) == 192 && offsetof(ShadowParameters, cascade_matrix) == 704 &&
              offsetof(ShadowParameters, cascade_far) == 960 && offsetof(ShadowParameters, cascade_count) == 1024 &&
              offsetof(ShadowParameters, point_light) == 1040 && offsetof(ShadowParameters, point_count) == 1168 &&
              offsetof(ShadowParameters, spot_count) == 1180 && offsetof(ShadowParameters, spot) == 1184 &&
              sizeof(glsl::SpotTile) == 176 && offsetof(glsl::SpotTile, tile) == 160 &&
              offsetof(ShadowParameters, pcss_part) == 1184 + 176 * SHADOW_MAX_SPOTS &&
              sizeof(ShadowParameters) == 1184 + 176 * SHADOW_MAX_SPOTS + 16,
              "std140: vec4 and mat4 members on 16 bytes, the spots' records 176 bytes apart");
static_assert(SHADOW_MAX_CASCADES == kMaxCascades);
static_assert(SHADOW_MAX_POINT_LIGHTS == kMaxPointShadows);
static_assert(SHADOW_MAX_SPOTS == kMaxSpotShadows);

namespace {
// The stage's texture units, from the first the frame gave it (shadow_visibility.glsl reads
// SHADOW_UNIT + these), and its one uniform block.
enum Unit : int { kDepthUnit, kCompareUnit, kMomentsUnit, kFilterInputUnit, kVolumeUnit, kSpotUnit, kPointUnit, kCsmUnit,
                  kSunVisibilityUnit, kUnitCount };
}  // namespace

ShadowMethod method_from_name(const std::string& name) {
  auto it = std::find(kMethodNames.begin(), kMethodNames.end(), name);
  if (it == kMethodNames.end()) throw Error("unknown shadow method '" + name + "'");
  return ShadowMethod(it - kMethodNames.begin());
}

const Light& find_sun(const Scene& scene) {
  for (const Light& l : scene.lights)  // shadowed_sun()'s rule: the first one the light set keeps
    if (l.type == LightType::Directional && !light_defect(l)) return l;
  throw Error("the scene has no directional light (the sun) to cast shadows");
}

float scene_sun_scale(const Scene& scene) {
  const auto extras = nlohmann::json::parse(scene.lightpass_json, nullptr, false);
  if (extras.is_discarded() || !extras.is_object() || !extras.contains("shadows_sun_scale")) return 1.f;
  const auto& v = extras["shadows_sun_scale"];
  if (!v.is_number() || !(v.get<double>() > 0) || !(v.get<double>() <= 1000))
    throw Error(scene.path.string() + ": the scene's extras.lightpass.shadows_sun_scale must be a number above 0 and at most 1000");
  return v.get<float>();
}

bool casts_shadows(const Scene& scene, std::size_t light) {
  const Light& l = scene.lights.at(light);
  if (l.casts_shadows) return *l.casts_shadows;
  if (l.type != LightType::Directional) return false;
  for (std::size_t i = 0; i < light; ++i)  // a sun came before it (one the light set keeps)
    if (scene.lights[i].type == LightType::Directional && !light_defect(scene.lights[i])) return false;
  return true;
}

std::vector<int> shadowed_spot_lights(const Scene& scene, bool all) {
  std::vector<int> out;
  for (std::size_t i = 0; i < scene.lights.size() && out.size() < std::size_t(kMaxSpotShadows); ++i) {
    const Light& l = scene.lights[i];
    if (l.type == LightType::Spot && !light_defect(l) && (all || casts_shadows(scene, i)) && l.outer_cone <= kMaxSpotCone)
      out.push_back(int(i));
  }
  return out;
}

int shadowed_spot(const Scene& scene) {
  const std::vector<int> spots = shadowed_spot_lights(scene);
  return spots.empty() ? -1 : spots.front();
}

int shadowed_sun(const Scene& scene) {
  // The first directional light the light set keeps (it leaves out what light_defect names).
  for (std::size_t i = 0; i < scene.lights.size(); ++i)
    if (scene.lights[i].type == LightType::Directional && !light_defect(scene.lights[i]))
      return casts_shadows(scene, i) ? int(i) : -1;
  return -1;
}

int shadowed_sun_index(const Scene& scene) {
  // The sun is the first directional light the set keeps, so the set's directional light 0.
  return shadowed_sun(scene) >= 0 ? 0 : -1;
}

std::vector<int> shadowed_point_lights(const Scene& scene, bool all) {
  std::vector<int> out;
  for (std::size_t i = 0; i < scene.lights.size() && out.size() < std::size_t(kMaxPointShadows); ++i) {
    const Light& l = scene.lights[i];
    if (l.type == LightType::Point && !light_defect(l) && (all || casts_shadows(scene, i))) out.push_back(int(i));
  }
  return out;
}

std::vector<std::string> unshadowed_casters(const Scene& scene) {
  std::vector<std::string> out;
  const int sun = shadowed_sun(scene);
  const std::vector<int> points = shadowed_point_lights(scene), spots = shadowed_spot_lights(scene);
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    if (!casts_shadows(scene, i) || int(i) == sun) continue;
    if (std::find(points.begin(), points.end(), int(i)) != points.end()) continue;
    if (std::find(spots.begin(), spots.end(), int(i)) != spots.end()) continue;
    std::string why = l.type == LightType::Directional ? "only the first directional light (the sun) has a map here"
                      : l.type == LightType::Point     ? "only the first " + std::to_string(kMaxPointShadows) +
                                                          " marked point lights have cube maps here"
                      : l.outer_cone > kMaxSpotCone    ? "its cone is wider than a perspective map covers (" +
                                                          std::to_string(kMaxSpotCone) + " rad): a cube map's, an exercise"
                                                       : "only the first " + std::to_string(kMaxSpotShadows) +
                                                          " marked spot lights have a tile of the atlas here";
    out.push_back("light '" + l.name + "' is marked casts_shadows, but " + why + ": it keeps chapter 03's path (no shadow)");
  }
  return out;
}

ShadowStage::ShadowStage(const SceneGpu& scene, const Light& sun)
    : scene_(scene), sun_(sun), sun_index_(shadowed_sun_index(scene.scene())) {
  glSamplerParameteri(nearest_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glSamplerParameteri(nearest_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glSamplerParameteri(compare_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glSamplerParameteri(compare_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glSamplerParameteri(compare_.id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glSamplerParameteri(compare_.id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glSamplerParameteri(linear_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glSamplerParameteri(linear_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLuint s : {nearest_.id(), compare_.id(), linear_.id()}) {
    glSamplerParameteri(s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  block_ = gl::make_buffer(nullptr, sizeof(ShadowParameters), GL_DYNAMIC_STORAGE_BIT);
  glTextureStorage3D(point_maps_.id(), 1, GL_DEPTH_COMPONENT32F, 1, 1, 6);  // until a point light casts
  glTextureStorage3D(csm_maps_.id(), 1, GL_RGBA32F, 1, 1, 1);               // until csm-fourier runs
}

void ShadowStage::depth_pass_state() {
  glDisable(GL_BLEND), glDisable(GL_STENCIL_TEST), glDisable(GL_SCISSOR_TEST), glDisable(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
}

std::optional<Light> ShadowStage::spot() const {
  const std::vector<int> spots = shadowed_spot_lights(scene_.scene(), settings_.all_spot_lights);
  if (spots.empty()) return std::nullopt;
  return scene_.scene().lights[std::size_t(spots.front())];
}

void ShadowStage::reload_shaders() {
  programs_.reload();
}

void ShadowStage::set(const ShadowSettings& settings, ShadowPicture picture) {
  settings_ = settings;
  picture_ = picture;
}

ch03::StageNeeds ShadowStage::needs() const { return {.units = kUnitCount, .blocks = 1}; }

ch03::ShaderHooks ShadowStage::shader_hooks() const {
  std::string method = "SHADOW_" + kMethodNames[int(settings_.method)];
  std::transform(method.begin(), method.end(), method.begin(), [](char c) { return c == '-' ? '_' : char(std::toupper(c)); });
  std::vector<std::string> defines = {"SHADOW_METHOD " + method, "SHADOW_UNIT " + std::to_string(slots().unit(0)),
                                      "SHADOW_BLOCK " + std::to_string(slots().block(0)),
                                      "SHADOW_SUN_INDEX " + std::to_string(sun_index_)};
  // The sun's maps as an array (only then: one map keeps the program it always had).
  if (settings_.cascades > 1) defines.push_back("SHADOW_CASCADES " + std::to_string(settings_.cascades));
  if (settings_.sun_visibility_given && settings_.method != ShadowMethod::Volumes) defines.push_back("SHADOW_SUN_VISIBILITY 1");
  return {"06_shadows/shaders/shadow_visibility.glsl", "", defines};
}

// [bind-hook]
// What shadow_visibility.glsl reads, on the stage's slots: the block, the sun's map (raw and
// through the comparison sampler), the filtered moments, the spot's map, or the volumes'
// visibility. Unused samplers still get a texture of the right kind.
void ShadowStage::bind_hook_resources() const {
  const ch03::StageSlots& at = slots();
  if (settings_.method == ShadowMethod::Volumes) {
    glBindTextureUnit(at.unit(kVolumeUnit), volume_visibility_.id());
    glBindSampler(at.unit(kVolumeUnit), nearest_.id());
    return;
  }
  glBindBufferBase(GL_UNIFORM_BUFFER, at.block(0), block_.id());
  const GLuint sun_maps = allocated_cascades_ > 1 ? cascade_depth_.id() : depth_.id();  // cascades: the array
  glBindTextureUnit(at.unit(kDepthUnit), sun_maps);
  glBindSampler(at.unit(kDepthUnit), nearest_.id());
  glBindTextureUnit(at.unit(kCompareUnit), sun_maps);
  glBindSampler(at.unit(kCompareUnit), compare_.id());
  glBindTextureUnit(at.unit(kMomentsUnit), allocated_filtered_ ? moments_.id() : depth_.id());
  glBindSampler(at.unit(kMomentsUnit), linear_.id());
  glBindTextureUnit(at.unit(kSpotUnit), spot_size_ > 0 ? spot_atlas_.id() : depth_.id());  // the spots' atlas
  glBindSampler(at.unit(kSpotUnit), nearest_.id());
  glBindTextureUnit(at.unit(kPointUnit), point_maps_.id());  // a 1-texel stand-in without point lights
  glBindSampler(at.unit(kPointUnit), nearest_.id());
  glBindTextureUnit(at.unit(kCsmUnit), csm_maps_.id());
  glBindSampler(at.unit(kCsmUnit), linear_.id());
  if (settings_.sun_visibility_given) {
    glBindTextureUnit(at.unit(kSunVisibilityUnit), sun_visibility_);
    glBindSampler(at.unit(kSunVisibilityUnit), nearest_.id());
  }
}
// [/bind-hook]

const ShaderProgram& ShadowStage::program(const std::string& vertex, const std::string& fragment,
                                          std::vector<std::string> defines) {
  return programs_.get({{GL_VERTEX_SHADER, vertex}, {GL_FRAGMENT_SHADER, fragment}}, defines);
}

void ShadowStage::allocate() {
  const int n = settings_.map_size;
  const bool msm = settings_.method == ShadowMethod::Msm;
  const bool filtered = settings_.method == ShadowMethod::Vsm || settings_.method == ShadowMethod::Esm || msm;
  if (settings_.moment_bits != 16 && settings_.moment_bits != 32)
    throw Error("shadow stage: moment_bits must be 16 or 32 (got " + std::to_string(settings_.moment_bits) + ")");
  const int bits = filtered ? settings_.moment_bits : 32;
  const int cascades = settings_.cascades;
  if (cascades < 1 || cascades > kMaxCascades)
    throw Error("shadow stage: between 1 and " + std::to_string(kMaxCascades) + " cascades (got " +
                std::to_string(cascades) + ")");
  if (cascades > 1 && settings_.method == ShadowMethod::CsmFourier)
    throw Error("shadow stage: cascades work with the methods hard, pcf, pcf-hardware and pcss, not csm-fourier "
                "(its filtered map is one layer)");
  if (cascades > 1 && filtered)
    throw Error("shadow stage: cascades work with the methods hard, pcf, pcf-hardware and pcss, not " +
                kMethodNames[int(settings_.method)] + " (its filtered map is one layer)");
  const int channels = msm ? 4 : 2;
  if (n == allocated_size_ && filtered == allocated_filtered_ && bits == allocated_bits_ &&
      cascades == allocated_cascades_ && channels == allocated_channels_)
    return;
  allocated_cascades_ = cascades;
  cascade_depth_.reset();
  cascade_fbos_.clear();
  if (cascades > 1) {
    // One depth layer per cascade, each drawn through a framebuffer of its own.
    cascade_depth_ = gl::Texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(cascade_depth_.id(), 1, GL_DEPTH_COMPONENT32F, n, n, cascades);
    for (int i = 0; i < cascades; ++i) {
      gl::Framebuffer& fbo = cascade_fbos_.emplace_back();
      glNamedFramebufferTextureLayer(fbo.id(), GL_DEPTH_ATTACHMENT, cascade_depth_.id(), 0, i);
      glNamedFramebufferDrawBuffer(fbo.id(), GL_NONE);
    }
  }
  // The one map (with cascades, a 1x1 stand-in: the visibility hook does not read it).
  const int one = cascades > 1 ? 1 : n;
  depth_ = gl::make_texture_2d(GL_DEPTH_COMPONENT32F, one, one);
  depth_fbo_ = gl::Framebuffer();
  glNamedFramebufferTexture(depth_fbo_.id(), GL_DEPTH_ATTACHMENT, depth_.id(), 0);
  glNamedFramebufferDrawBuffer(depth_fbo_.id(), GL_NONE);
  moments_.reset(), scratch_.reset();
  if (filtered) {
    // RG32F for both (ESM uses the red channel): one format, so the sizes compare; or RG16F,
    // half the bytes, whose 11-bit mantissa rounds M2 - M1^2 (shadow_math.h [fp16-moments]).
    // MSM: four moments, RGBA32F or RGBA16 (unsigned normalised: the optimised map's [0, 1]).
    const GLenum format = msm ? (bits == 16 ? GL_RGBA16 : GL_RGBA32F) : bits == 16 ? GL_RG16F : GL_RG32F;
    moments_ = gl::make_texture_2d(format, n, n);
    scratch_ = gl::make_texture_2d(format, n, n);
    moments_fbo_ = gl::Framebuffer();
    scratch_fbo_ = gl::Framebuffer();
    glNamedFramebufferTexture(moments_fbo_.id(), GL_COLOR_ATTACHMENT0, moments_.id(), 0);
    glNamedFramebufferTexture(scratch_fbo_.id(), GL_COLOR_ATTACHMENT0, scratch_.id(), 0);
  }
  allocated_size_ = n;
  allocated_filtered_ = filtered;
  allocated_bits_ = bits;
  allocated_channels_ = channels;
}

std::size_t ShadowStage::allocated_bytes() const {
  if (settings_.method == ShadowMethod::Volumes)  // the visibility bytes and the volumes' vertices
    return std::size_t(volume_width_) * std::size_t(volume_height_) + volume_buffer_bytes_;
  const std::size_t texels = std::size_t(allocated_size_) * std::size_t(allocated_size_) *
                             std::size_t(allocated_cascades_);
  const std::size_t spot = spot_lights_.empty() ? 0 : std::size_t(spot_size_) * std::size_t(spot_size_) * 4;  // the atlas
  const std::size_t points = point_lights_.empty() ? 0  // the point lights' cube maps
                             : std::size_t(point_size_) * std::size_t(point_size_) * 6 * std::size_t(point_layers_) * 4;
  const std::size_t filtered = 2 * std::size_t(allocated_channels_) * std::size_t(allocated_bits_ / 8);  // map + scratch
  const std::size_t csm = settings_.method == ShadowMethod::CsmFourier  // the basis and its scratch, RGBA32F layers
                              ? 2 * std::size_t(csm_size_) * std::size_t(csm_size_) * std::size_t(csm_layers_) * 16 : 0;
  return texels * (4 + (allocated_filtered_ ? filtered : 0)) + spot + points + csm;
}

// [shadow-stage]
void ShadowStage::before_lights(ch03::DeferredFrame& frame, PassMetrics* metrics) {
  if (settings_.method == ShadowMethod::Volumes) return draw_volumes(frame, metrics);
  allocate();
  const int n = settings_.map_size;
  const glm::mat4 inverse_view_projection = glm::inverse(frame.camera().projection * frame.camera().view);
  const Scene& scene = scene_.scene();
  frustum_ = fit_light_frustum(sun_.direction, scene.bounds_min, scene.bounds_max,
                               settings_.fit_to_view ? &inverse_view_projection : nullptr);
  if (settings_.cascades > 1) fit_cascades(settings_.cascade_camera ? *settings_.cascade_camera : frame.camera());
  else cascades_.clear(), splits_.clear();
  if (!cascades_.empty()) draw_cascades(metrics);
  else {
    // 1. Depth from the light: every opaque triangle, both sides (no culling), depth only (glass,
    //    alphaMode BLEND, casts no shadow: a map of depths cannot hold what it lets through).
    auto pass = timed(metrics, "shadow map: depth from the sun");
    const ShaderProgram& p = program("06_shadows/shaders/shadow_depth.vert", "06_shadows/shaders/shadow_depth.frag", {});
    glBindFramebuffer(GL_FRAMEBUFFER, depth_fbo_.id());
    glViewport(0, 0, n, n);
    depth_pass_state();
    glClear(GL_DEPTH_BUFFER_BIT);
    p.use();
    p.set("u_light_view_projection", frustum_.view_projection());
    scene_.draw([&](const Instance& inst, const Material&) { p.set("u_model", inst.model); }, SceneGpu::Primitives::Opaque);
  }
  // 1b. The spot lights' perspective maps, a tile each of one atlas (spot_atlas.cpp).
  draw_spot_atlas(frame.camera(), metrics);
  // 1c. The point lights' cube maps (point_shadows.cpp).
  draw_point_maps(frame.camera(), metrics);
  // 2'. Convolution shadow maps: the basis of the step's series, filtered (csm_stage.cpp).
  if (settings_.method == ShadowMethod::CsmFourier)
    filter_csm(metrics, slots().unit(kFilterInputUnit), slots().unit(kCsmUnit));
  if (allocated_filtered_) {
    // 2. VSM / ESM: what the method filters, pre-filtered by a separable box.
    auto pass = timed(metrics, "shadow map: pre-filter");
    std::vector<std::string> defines = {settings_.method == ShadowMethod::Vsm   ? "SHADOW_VSM 1"
                                        : settings_.method == ShadowMethod::Msm ? "SHADOW_MSM 1"
                                                                                : "SHADOW_ESM 1"};
    if (settings_.method == ShadowMethod::Msm && allocated_bits_ == 16) defines.push_back("MSM_OPTIMIZED 1");
    const ShaderProgram& p = program("02_gbuffer/shaders/fullscreen.vert", "06_shadows/shaders/shadow_filter.frag", defines);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    p.use();
    p.set("u_radius", settings_.kernel / 2);
    p.set("u_c", settings_.c);
    const GLuint input = slots().unit(kFilterInputUnit);
    glUniform1i(p.location("u_input"), int(input));
    glBindSampler(input, 0);
    for (int step = 0; step < 2; ++step) {
      glBindFramebuffer(GL_FRAMEBUFFER, step == 0 ? scratch_fbo_.id() : moments_fbo_.id());
      glViewport(0, 0, n, n);
      glBindTextureUnit(input, step == 0 ? depth_.id() : scratch_.id());
      p.set("u_from_depth", step == 0 ? 1 : 0);
      glProgramUniform2i(p.id(), p.location("u_step"), step == 0 ? 1 : 0, step == 0 ? 0 : 1);
      full_screen_.draw();
    }
  }
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  // 3. What the visibility hook reads.
  if (settings_.poisson_taps < 0 || settings_.poisson_taps > kMaxPoissonTaps)
    throw Error("shadow stage: poisson_taps must be between 0 and " + std::to_string(kMaxPoissonTaps));
  const bool pcss = settings_.method == ShadowMethod::Pcss;
  const int taps = pcss && settings_.poisson_taps == 0 ? kPcssDefaultTaps : settings_.poisson_taps;
  if (pcss && !(settings_.sun_angular_radius >= 0.f && settings_.sun_angular_radius < 1.f))
    throw Error("shadow stage: sun_angular_radius must be in [0, 1) radians (got " +
                std::to_string(settings_.sun_angular_radius) + ")");
  if (pcss && (settings_.pcss_parts < 1 || taps % settings_.pcss_parts != 0 || settings_.pcss_part < 0 ||
               settings_.pcss_part >= settings_.pcss_parts))
    throw Error("shadow stage: PCSS's part " + std::to_string(settings_.pcss_part) + " of " +
                std::to_string(settings_.pcss_parts) + " parts: the parts must divide its " + std::to_string(taps) +
                " taps, and the part be one of them");
  if (taps != poisson_taps_) {
    poisson_ = taps > 0 ? poisson_disk(taps, 0x504fu) : std::vector<glm::vec2>{};
    poisson_taps_ = taps;
  }
  ShadowParameters block{};
  block.matrix = frustum_.view_projection();
  block.texel_metres = frustum_.texel_world(n);
  block.depth_range = frustum_.depth_range();
  block.map_size = float(n);
  block.pcf_radius = float(settings_.kernel / 2);
  block.constant_bias = settings_.constant_bias;
  block.slope_bias = settings_.slope_bias;
  block.normal_offset = settings_.normal_offset;
  block.min_variance = settings_.min_variance;
  block.esm_c = settings_.c;
  block.vsm_p_min = settings_.p_min;
  block.poisson_taps = float(poisson_taps_);
  block.msm_moment_bias = settings_.msm_moment_bias > 0.f ? settings_.msm_moment_bias
                          : allocated_bits_ == 16        ? kMsmMomentBias16
                                                         : kMsmMomentBias32;
  block.msm_optimized = settings_.method == ShadowMethod::Msm && allocated_bits_ == 16 ? 1.f : 0.f;
  block.view = frustum_.view;
  block.extent = glm::vec2(frustum_.box_max - frustum_.box_min);
  block.tan_sun_radius = std::tan(settings_.sun_angular_radius);
  block.pcss_part = pcss ? float(settings_.pcss_part) : 0.f;
  block.pcss_parts = pcss ? float(settings_.pcss_parts) : 1.f;
  block.pcss_turn = pcss ? settings_.pcss_turn : 0.f;
  for (std::size_t i = 0; i < poisson_.size(); ++i) {
    glm::vec4& slot = block.poisson[i / 2];
    slot[int(i % 2) * 2] = poisson_[i].x;
    slot[int(i % 2) * 2 + 1] = poisson_[i].y;
  }
  block.spot_count = float(spot_lights_.size());
  for (std::size_t i = 0; i < spot_lights_.size(); ++i) {
    const SpotFrustum& f = spot_frustums_[i];
    const AtlasTile tile = spot_tile(int(i));
    glsl::SpotTile& t = block.spot[i];
    t.matrix = f.view_projection();
    t.view = f.view;
    t.position = glm::vec4(scene.lights[std::size_t(spot_lights_[i])].position, spots_mapped_[i] ? 1.f : 0.f);
    t.frustum = glm::vec4(f.near, f.far, f.tan_cone, float(tile.size));
    t.tile = glm::vec4(tile.corner, tile.side, 0.f);
  }
  block.cascade_count = float(cascades_.size());
  block.cascade_band = settings_.cascade_band;
  block.camera_depth = cascade_depth_plane_;
  block.cascade_near = splits_.empty() ? 0.f : splits_.front();
  block.point_count = float(point_lights_.size());
  block.point_map_size = float(point_size_);
  block.csm_terms = float(settings_.csm_terms);
  for (std::size_t i = 0; i < point_lights_.size(); ++i)
    block.point_light[i] = glm::vec4(scene.lights[std::size_t(point_lights_[i])].position, points_mapped_[i] ? point_far_[i] : 0.f);
  for (std::size_t i = 0; i < cascades_.size(); ++i) {
    block.cascade_matrix[i] = cascades_[i].view_projection();
    block.cascade_far[int(i)] = splits_[i + 1];
    block.cascade_texel[int(i)] = cascades_[i].texel_world(n);
    block.cascade_extent[int(i)] = cascades_[i].box_max.x - cascades_[i].box_min.x;
  }
  glNamedBufferSubData(block_.id(), 0, sizeof(block), &block);
}
// [/shadow-stage]

// [cascades-stage]
// The cascades for this camera: the splits of its depth range, a sphere around each slice, the
// sphere's square in the light's view, on whole texels.
void ShadowStage::fit_cascades(const FrameCamera& camera) {
  const Scene& scene = scene_.scene();
  const glm::mat4 camera_world = glm::inverse(camera.view);
  float far = settings_.cascade_distance;
  if (!(far >= 0.f)) throw Error("shadow stage: cascade_distance must be 0 or more metres");
  if (far == 0.f) {
    // To the camera's far plane, or to the scene's farthest corner in view depth, the nearer.
    float corner = 0.f;
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 c(i & 1 ? scene.bounds_max.x : scene.bounds_min.x, i & 2 ? scene.bounds_max.y : scene.bounds_min.y,
                        i & 4 ? scene.bounds_max.z : scene.bounds_min.z);
      corner = std::max(corner, -(camera.view * glm::vec4(c, 1.f)).z);
    }
    far = std::min(camera.zfar, corner);
  }
  far = std::max(far, 2.f * camera.znear);
  splits_ = ch06::cascade_splits(settings_.cascades, camera.znear, far, settings_.cascade_lambda);
  cascades_.clear();
  for (int i = 0; i < settings_.cascades; ++i) {
    const Sphere sphere = frustum_slice_sphere(camera_world, camera.yfov, camera.aspect, splits_[std::size_t(i)],
                                               splits_[std::size_t(i) + 1]);
    cascades_.push_back(fit_cascade(sun_.direction, scene.bounds_min, scene.bounds_max, sphere, settings_.map_size,
                                    settings_.cascade_snap));
  }
  // A world point's view depth, -z in the camera's view space: minus the view matrix's third row.
  cascade_depth_plane_ = -glm::vec4(camera.view[0][2], camera.view[1][2], camera.view[2][2], camera.view[3][2]);
}

void ShadowStage::draw_cascades(PassMetrics* metrics) {
  // 1. Depth from the light, once per cascade into its layer (every opaque triangle each time).
  auto pass = timed(metrics, "shadow map: depth from the sun");
  const int n = settings_.map_size;
  const ShaderProgram& p = program("06_shadows/shaders/shadow_depth.vert", "06_shadows/shaders/shadow_depth.frag", {});
  depth_pass_state();
  p.use();
  for (std::size_t i = 0; i < cascades_.size(); ++i) {
    glBindFramebuffer(GL_FRAMEBUFFER, cascade_fbos_[i].id());
    glViewport(0, 0, n, n);
    glClear(GL_DEPTH_BUFFER_BIT);
    p.set("u_light_view_projection", cascades_[i].view_projection());
    scene_.draw([&](const Instance& inst, const Material&) { p.set("u_model", inst.model); }, SceneGpu::Primitives::Opaque);
  }
  frustum_ = cascades_.front();  // what frustum() reports: the nearest cascade
}
// [/cascades-stage]

// [volumes-stage]
void ShadowStage::draw_volumes(ch03::DeferredFrame& frame, PassMetrics* metrics) {
  const ch02::GBuffer& g = frame.gbuffer();
  const Scene& scene = scene_.scene();
  if (adjacency_.empty())
    for (const Mesh& m : scene.meshes) adjacency_.push_back(build_adjacency(scene, m));
  {
    // 1. The volumes on the CPU: every instance's casting triangles and net edges.
    auto pass = timed(metrics, "shadow volumes: silhouettes and extrusion (CPU)");
    volume_vertices_.clear();
    volume_stats_ = {};
    for (const Instance& inst : scene.instances) {
      if (inst.mesh < 0) continue;
      const VolumeCounts c = append_sun_volume(adjacency_[std::size_t(inst.mesh)], inst.model, sun_.direction,
                                               settings_.volume_offset, volume_vertices_);
      volume_stats_.cap_triangles += c.cap_triangles;
      volume_stats_.side_quads += c.side_quads;
    }
    const std::size_t bytes = volume_vertices_.size() * sizeof(glm::vec4);
    if (bytes > volume_buffer_bytes_ || volume_buffer_bytes_ == 0) {
      volume_buffer_bytes_ = std::max<std::size_t>(bytes, 1024);
      volume_buffer_ = gl::make_buffer(nullptr, volume_buffer_bytes_, GL_DYNAMIC_STORAGE_BIT);
      glVertexArrayVertexBuffer(volume_vao_.id(), 0, volume_buffer_.id(), 0, sizeof(glm::vec4));
      glEnableVertexArrayAttrib(volume_vao_.id(), 0);
      glVertexArrayAttribFormat(volume_vao_.id(), 0, 4, GL_FLOAT, GL_FALSE, 0);
      glVertexArrayAttribBinding(volume_vao_.id(), 0, 0);
    }
    if (bytes) glNamedBufferSubData(volume_buffer_.id(), 0, GLsizeiptr(bytes), volume_vertices_.data());
  }
  // The visibility target beside the G-buffer's depth-stencil (whose stencil the geometry
  // pass cleared to 0, and which this pass leaves at 0).
  if (volume_width_ != g.width() || volume_height_ != g.height() || volume_depth_stencil_ != g.depth_stencil()) {
    volume_visibility_ = gl::make_texture_2d(GL_R8, g.width(), g.height());
    volume_fbo_ = gl::Framebuffer();
    glNamedFramebufferTexture(volume_fbo_.id(), GL_COLOR_ATTACHMENT0, volume_visibility_.id(), 0);
    glNamedFramebufferTexture(volume_fbo_.id(), GL_DEPTH_STENCIL_ATTACHMENT, g.depth_stencil(), 0);
    volume_width_ = g.width(), volume_height_ = g.height(), volume_depth_stencil_ = g.depth_stencil();
  }
  const ShaderProgram& p = program("06_shadows/shaders/shadow_volume.vert", "06_shadows/shaders/shadow_depth.frag", {});
  const auto count = GLsizei(volume_vertices_.size());
  glBindFramebuffer(GL_FRAMEBUFFER, volume_fbo_.id());
  glViewport(0, 0, volume_width_, volume_height_);
  glDisable(GL_BLEND), glDisable(GL_SCISSOR_TEST), glDisable(GL_CULL_FACE);
  const GLfloat lit[] = {1, 1, 1, 1};
  glClearNamedFramebufferfv(volume_fbo_.id(), GL_COLOR, 0, lit);
  p.use();
  p.set("u_view_projection", g.camera().view_projection());
  glBindVertexArray(volume_vao_.id());
  {
    // 2. The z-fail count (Carmack's reverse) against the G-buffer's depth: where a volume's
    // face lies behind the visible surface, +1 for a back face, -1 for a front face. What is
    // left is the number of volumes the surface lies in: every face behind it is counted, so
    // the count is right wherever the camera is, inside a volume too. Depth clamp instead of
    // clipping at the near and far planes: the w = 0 corners lie beyond any far plane, and a
    // cap cut off by the near plane would open the volume.
    auto pass = timed(metrics, "shadow volumes: z-fail stencil count");
    g.begin_depth_convention();
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_DEPTH_CLAMP);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0xff);
    glStencilFunc(GL_ALWAYS, 0, 0xff);
    glStencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
    glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
    glDrawArrays(GL_TRIANGLES, 0, count);
    glDisable(GL_DEPTH_CLAMP);
    ch02::GBuffer::restore_default_depth_convention();
  }
  {
    // 3. The visibility term: 0 where the count is not 0 (in shadow; modulo 256: a pixel in
    // exactly 256 volumes reads lit), 1 elsewhere. Then the stencil back to 0.
    auto pass = timed(metrics, "shadow volumes: visibility from the stencil");
    const ShaderProgram& fill = program("02_gbuffer/shaders/fullscreen.vert", "06_shadows/shaders/shadow_volume_fill.frag", {});
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    glStencilFunc(GL_NOTEQUAL, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    fill.use();
    full_screen_.draw();
    glDisable(GL_STENCIL_TEST);
    const GLint zero = 0;
    glClearNamedFramebufferiv(volume_fbo_.id(), GL_STENCIL, 0, &zero);
  }
  if (settings_.count_volume_fragments) {
    // The fill rate, counted exactly: the same triangles again with no depth or stencil test
    // and nothing written, inside a GL_SAMPLES_PASSED query: every fragment they rasterise.
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnable(GL_DEPTH_CLAMP);
    p.use();
    glBindVertexArray(volume_vao_.id());
    glBeginQuery(GL_SAMPLES_PASSED, fragments_query_.id());
    glDrawArrays(GL_TRIANGLES, 0, count);
    glEndQuery(GL_SAMPLES_PASSED);
    GLuint64 samples = 0;
    glGetQueryObjectui64v(fragments_query_.id(), GL_QUERY_RESULT, &samples);
    volume_stats_.fragments = samples;
    glDisable(GL_DEPTH_CLAMP);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }
  glBindVertexArray(0);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
}
// [/volumes-stage]

bool ShadowStage::composite(ch03::DeferredFrame& frame, PassMetrics* metrics) {
  if (picture_ == ShadowPicture::None) return false;
  if (picture_ == ShadowPicture::Penumbra && settings_.method != ShadowMethod::Pcss)
    throw Error("shadow stage: the penumbra picture is PCSS's (method pcss), not " + kMethodNames[int(settings_.method)] + "'s");
  auto pass = timed(metrics, picture_ == ShadowPicture::Map ? "composite: the sun's depth map"
                                                                  : "composite: the sun's visibility alone");
  std::vector<std::string> defines = frame.view().defines;
  for (const auto& d : frame.view().hooks.glsl_defines()) defines.push_back(d);
  if (picture_ == ShadowPicture::Map) defines.push_back("SHOW_MAP 1");
  if (picture_ == ShadowPicture::Penumbra) defines.push_back("SHOW_PENUMBRA 1");
  if (picture_ == ShadowPicture::Cascades) {
    if (settings_.method == ShadowMethod::Volumes)
      throw Error("shadow stage: the cascades picture needs a map method, not volumes");
    defines.push_back("SHOW_CASCADES 1");
  }
  if (picture_ == ShadowPicture::PointVisibility) {
    if (settings_.point_shown < 0 || std::size_t(settings_.point_shown) >= point_lights_.size() ||
        settings_.method == ShadowMethod::Volumes)
      throw Error("shadow stage: the point light's visibility needs point light " + std::to_string(settings_.point_shown) +
                  " of the " + std::to_string(point_lights_.size()) + " with a cube map, and a map method");
    defines.push_back("SHOW_POINT 1");
  }
  if (picture_ == ShadowPicture::SpotVisibility) {
    if (settings_.spot_shown < 0 || std::size_t(settings_.spot_shown) >= spot_lights_.size() ||
        settings_.method == ShadowMethod::Volumes)
      throw Error("shadow stage: the spot light's visibility needs spot light " + std::to_string(settings_.spot_shown) +
                  " of the " + std::to_string(spot_lights_.size()) + " with a tile of the atlas, and a map method");
    defines.push_back("SHOW_SPOT 1");
  }
  const ShaderProgram& p = program("02_gbuffer/shaders/fullscreen.vert", "06_shadows/shaders/show_visibility.frag", defines);
  frame.bind_hooks();
  glDisable(GL_DEPTH_TEST), glDisable(GL_BLEND), glDisable(GL_CULL_FACE), glDisable(GL_STENCIL_TEST);
  p.use();
  p.set("u_sun_direction", glm::normalize(sun_.direction));
  p.set("u_output_size", glm::vec2(frame.output().width, frame.output().height));
  if (picture_ == ShadowPicture::SpotVisibility) {
    const Light& l = scene_.scene().lights[std::size_t(spot_lights_[std::size_t(settings_.spot_shown)])];
    p.set("u_spot_position", l.position);
    p.set("u_spot_direction", glm::normalize(l.direction));
    p.set("u_spot_cos_cone", std::cos(l.outer_cone));
  }
  if (picture_ == ShadowPicture::PointVisibility) {
    const Light& l = scene_.scene().lights[std::size_t(point_lights_[std::size_t(settings_.point_shown)])];
    p.set("u_point_position", l.position);
    p.set("u_point_range", l.range);
  }
  full_screen_.draw();
  glEnable(GL_DEPTH_TEST);
  return true;
}

}  // namespace lp::ch06
