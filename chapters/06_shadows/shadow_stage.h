#pragma once
// Chapter 06's shadows as a stage of chapter 03's deferred frame (deferred_frame.h): before
// the lights, the sun's depth map is drawn from its fitted orthographic frustum (and, for VSM
// and ESM, pre-filtered); the frame's light shaders include the visibility hook,
// shaders/shadow_visibility.glsl, with the chosen method and the stage's slots as defines, and
// the frame binds the maps on those slots before each pass that includes it.
//
//   ch03::DeferredFrame frame(scene_gpu);   ShadowStage shadows(scene_gpu, sun);
//   frame.add_stage(shadows);
//   shadows.set({.method = ShadowMethod::Pcf, .kernel = 3});
//   frame.render(camera, output, &metrics);
#include <optional>
#include <string>

#include "chapters/02_gbuffer/deferred.h"
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/06_shadows/csm_math.h"
#include "chapters/06_shadows/cube_math.h"
#include "chapters/06_shadows/shadow_math.h"
#include "chapters/06_shadows/shadow_volumes.h"
#include "chapters/06_shadows/spot_atlas.h"
#include "common/scene.h"
#include "common/camera.h"
#include "common/shader.h"

namespace lp::ch06 {

// Volumes: no map; the sun's shadow volumes counted in the stencil (z-fail), shadow_volumes.h.
// Pcss: the sun as a disk (sun_angular_radius), PCF over the penumbra a blocker search
// estimates (shadow_math.h [pcss]). Msm: four filtered moments, the Hamburger reconstruction
// (shadow_math.h [msm]).
// CsmFourier: convolution shadow maps, the step's Fourier series of csm_terms terms, filtered
// (csm_math.h [csm]).
enum class ShadowMethod { Hard, Pcf, PcfHardware, Vsm, Esm, Volumes, Pcss, Msm, CsmFourier };
inline const std::vector<std::string> kMethodNames = {"hard", "pcf", "pcf-hardware", "vsm", "esm", "volumes", "pcss", "msm",
                                                      "csm-fourier"};
ShadowMethod method_from_name(const std::string& name);  // throws Error for an unknown one

struct ShadowSettings {
  ShadowMethod method = ShadowMethod::Pcf;
  int map_size = 1024;
  int kernel = 3;               // PCF's k x k grid; VSM's and ESM's box filter width (odd)
  int poisson_taps = 0;         // PCF: 0 for the k x k grid, or this many taps of a Poisson disk k texels
                                // across, rotated per pixel (shadow_math.h [poisson]); <= kMaxPoissonTaps.
                                // PCSS: the taps of its search and of its filter (0: kPcssDefaultTaps)
  float sun_angular_radius = kSunAngularRadius;  // PCSS: the sun's disk, radians (the soft truth's)
  // PCSS a part at a time (chapter 11 accumulates the parts over frames): its search and its
  // filter read every pcss_parts-th tap of the disk from tap pcss_part on, the disk turned
  // pcss_turn radians more. pcss_parts divides the taps.
  int pcss_parts = 1;
  int pcss_part = 0;
  float pcss_turn = 0.f;
  // The sun's visibility read from set_sun_visibility()'s texture (chapter 11's accumulation
  // computes it before the lights) instead of looked up in the hook.
  bool sun_visibility_given = false;
  float constant_bias = 0.5f;   // texels (shadow_math.h [bias])
  float slope_bias = 1.f;       // texels per unit tan(theta)
  float normal_offset = 1.f;    // texels
  float min_variance = 1e-6f;   // VSM, in window depth squared
  float p_min = 0.2f;           // VSM's light-bleeding reduction
  float c = 80.f;               // ESM's exponent (window depth in [0, 1])
  bool fit_to_view = true;      // the map's box cut to what the camera sees (else the whole scene)
  int moment_bits = 32;         // VSM, ESM: the filtered map in RG32F (32) or RG16F (16), half the bytes;
                                // MSM: RGBA32F (32) or RGBA16 through the optimised map (16)
  float msm_moment_bias = 0.f;  // MSM: the pull towards 0.5 (0: kMsmMomentBias16 or kMsmMomentBias32)
  float volume_offset = 0.01f;  // volumes: metres each volume is pushed along the light ([silhouette])
  bool count_volume_fragments = false;  // volumes: count the fragments the volumes rasterise (a second draw)
  // Cascades (shadow_math.h [cascades]): 1 is the one map fitted above; 2 to kMaxCascades maps of
  // map_size each, in a texture array (methods hard, pcf, pcf-hardware and pcss).
  int cascades = 1;
  float cascade_lambda = 0.75f;   // the split: 0 uniform, 1 logarithmic
  float cascade_distance = 0.f;   // metres of view depth the cascades cover (0: to the camera's far
                                  // plane or the scene's farthest corner, the nearer); beyond, lit
  float cascade_band = 0.1f;      // the blend band, a fraction of each cascade's depth range
  bool cascade_snap = true;       // the cascades' boxes on whole texels (no shimmer)
  // Tests: fit the cascades to this camera instead of the frame's (a map that stays where it is).
  std::optional<FrameCamera> cascade_camera;
  // Point lights (cube_math.h): the scene's marked ones get a cube map, or, with
  // all_point_lights, every point light (up to kMaxPointShadows; the atrium marks none).
  bool all_point_lights = false;
  int cube_size = 512;   // texels a face side
  int point_shown = 0;   // ShadowPicture::PointVisibility: which of point_lights()
  int csm_terms = 4;     // csm-fourier: the series' terms, 1 to kMaxCsmTerms (two channels each)
  // Spot lights (spot_atlas.h): the scene's marked ones get a tile of the one atlas, map_size
  // texels a side, or, with all_spot_lights, every spot light (up to kMaxSpotShadows).
  bool all_spot_lights = false;
  int spot_shown = 0;    // ShadowPicture::SpotVisibility: which of spot_lights()
};

// What the last frame's shadow volumes were (method Volumes).
struct VolumeStats {
  std::size_t cap_triangles = 0, side_quads = 0;
  std::uint64_t fragments = 0;  // rasterised by the volumes, every one (count_volume_fragments); else 0
};

// What composite() draws instead of the image. Penumbra (method Pcss): the filter's radius in
// metres, unclamped (0 where the search finds no blocker; blue where the sun does not reach).
// SpotVisibility: the visibility of spot light settings.spot_shown alone (blue where it does not
// reach).
// Cascades: the sun's visibility tinted by the cascade each pixel reads (red, green, blue,
// yellow; mixed in the blend bands). PointVisibility: the visibility of point light
// settings.point_shown alone (blue where it does not reach).
enum class ShadowPicture { None, Visibility, Map, Penumbra, SpotVisibility, Cascades, PointVisibility };

class ShadowStage : public ch03::FrameStage {
 public:
  // `sun`: the directional light that casts; the scene's bounds give the casters. The spot lights
  // the scene marks to cast (casts_shadows below) get a perspective map each, a tile of one atlas.
  ShadowStage(const SceneGpu& scene, const Light& sun);
  void reload_shaders();
  void set(const ShadowSettings& settings, ShadowPicture picture = ShadowPicture::None);
  const ShadowSettings& settings() const { return settings_; }
  const LightFrustum& frustum() const { return frustum_; }
  // The last frame's cascades (empty with one map) and their splits (view depths, count + 1).
  const std::vector<LightFrustum>& cascades() const { return cascades_; }
  const std::vector<float>& cascade_splits() const { return splits_; }
  // The spot lights with a tile in the atlas (indices in the scene's lights, shadowed_spot_lights)
  // and, for each, its frustum, its tile, and whether the last frame drew it: not when the
  // sphere its range reaches lies outside the view (its light reaches no pixel on screen).
  const std::vector<int>& spot_lights() const { return spot_lights_; }
  const std::vector<SpotFrustum>& spot_frustums() const { return spot_frustums_; }
  const std::vector<bool>& spots_mapped() const { return spots_mapped_; }
  AtlasTile spot_tile(int i) const { return spot_atlas_tile(i, int(spot_lights_.size()), spot_size_); }
  // The first of them, as the settings choose them (before a frame, too), its frustum and
  // whether it was drawn.
  std::optional<Light> spot() const;
  SpotFrustum spot_frustum() const { return spot_frustums_.empty() ? SpotFrustum{} : spot_frustums_.front(); }
  bool spot_mapped() const { return !spots_mapped_.empty() && spots_mapped_.front(); }
  // The point lights with a cube map (indices in the scene's lights, shadowed_point_lights) and,
  // for each, whether the last frame drew it (not when its range's sphere lies off screen).
  const std::vector<int>& point_lights() const { return point_lights_; }
  const std::vector<bool>& points_mapped() const { return points_mapped_; }
  const std::vector<float>& point_far() const { return point_far_; }
  // Bytes the method keeps per frame: the depth map, and the moments with their filter target.
  std::size_t allocated_bytes() const;
  const VolumeStats& volume_stats() const { return volume_stats_; }

  // With ShadowSettings::sun_visibility_given, the sun's visibility computed elsewhere, one R32F
  // texel a pixel of the output (chapter 11's accumulation), set before the lights: the hook
  // reads it for the G-buffer's surface at the pixel (SHADOW_SUN_VISIBILITY; a forward pass's
  // surface in front of it, the glass, still looks up the map).
  void set_sun_visibility(GLuint texture) { sun_visibility_ = texture; }
  const Light& sun() const { return sun_; }

  ch03::StageNeeds needs() const override;
  ch03::ShaderHooks shader_hooks() const override;
  void bind_hook_resources() const override;
  void before_lights(ch03::DeferredFrame& frame, PassMetrics* metrics) override;
  bool composite(ch03::DeferredFrame& frame, PassMetrics* metrics) override;

 private:
  void allocate();
  void draw_volumes(ch03::DeferredFrame& frame, PassMetrics* metrics);
  void fit_cascades(const FrameCamera& camera);
  void draw_cascades(PassMetrics* metrics);
  void draw_point_maps(const FrameCamera& camera, PassMetrics* metrics);  // point_shadows.cpp
  void draw_spot_atlas(const FrameCamera& camera, PassMetrics* metrics);  // spot_atlas.cpp
  // Every depth-from-a-light pass's state, set before its draws: depth only, both faces.
  static void depth_pass_state();
  const ShaderProgram& program(const std::string& vertex, const std::string& fragment, std::vector<std::string> defines);
  const SceneGpu& scene_;
  Light sun_;
  int sun_index_;  // shadowed_sun_index(): the directional light the hook shadows
  GLuint sun_visibility_ = 0;
  ShadowSettings settings_;
  ShadowPicture picture_ = ShadowPicture::None;
  LightFrustum frustum_;
  // Spot lights: one depth atlas, a tile per light, drawn through one framebuffer.
  std::vector<int> spot_lights_;
  std::vector<bool> spots_mapped_;
  std::vector<SpotFrustum> spot_frustums_;
  gl::Texture spot_atlas_{GL_TEXTURE_2D};
  gl::Framebuffer spot_fbo_;
  int spot_size_ = 0;
  int allocated_size_ = 0;
  bool allocated_filtered_ = false;
  int allocated_channels_ = 2;  // of the filtered map: 2 (VSM, ESM) or 4 (MSM)
  int allocated_bits_ = 32;
  int poisson_taps_ = 0;
  std::vector<glm::vec2> poisson_;
  std::vector<LightFrustum> cascades_;
  std::vector<float> splits_;
  int allocated_cascades_ = 1;
  glm::vec4 cascade_depth_plane_{0};
  gl::Texture cascade_depth_{GL_TEXTURE_2D_ARRAY};
  std::vector<gl::Framebuffer> cascade_fbos_;
  // Point lights: one cube map array, a layer of six faces per light, each face its framebuffer.
  std::vector<int> point_lights_;
  std::vector<bool> points_mapped_;
  std::vector<float> point_far_;
  gl::Texture point_maps_{GL_TEXTURE_CUBE_MAP_ARRAY};
  std::vector<gl::Framebuffer> point_fbos_;
  int point_size_ = 0, point_layers_ = 0;
  // Convolution shadow maps: the filtered basis, four values a layer (csm_math.h), and the
  // horizontal pass's output; one framebuffer each with a colour attachment per layer.
  gl::Texture csm_maps_{GL_TEXTURE_2D_ARRAY}, csm_scratch_{GL_TEXTURE_2D_ARRAY};
  gl::Framebuffer csm_fbo_, csm_scratch_fbo_;
  int csm_size_ = 0, csm_layers_ = 0;
  void filter_csm(PassMetrics* metrics, GLuint depth_unit, GLuint input_unit);  // csm_stage.cpp
  gl::Texture depth_{GL_TEXTURE_2D}, moments_{GL_TEXTURE_2D}, scratch_{GL_TEXTURE_2D};
  gl::Framebuffer depth_fbo_, moments_fbo_, scratch_fbo_;
  gl::Sampler nearest_, compare_, linear_;
  gl::Buffer block_;
  ProgramCache programs_;
  ch02::FullScreenPass full_screen_;
  // Shadow volumes: each mesh's edge table (built on first use), the volumes' vertices, and
  // the visibility they leave, one byte per pixel, beside the G-buffer's depth-stencil.
  std::vector<MeshAdjacency> adjacency_;
  std::vector<glm::vec4> volume_vertices_;
  gl::Buffer volume_buffer_;
  std::size_t volume_buffer_bytes_ = 0;
  gl::VertexArray volume_vao_;
  gl::Texture volume_visibility_{GL_TEXTURE_2D};
  gl::Framebuffer volume_fbo_;
  int volume_width_ = 0, volume_height_ = 0;
  GLuint volume_depth_stencil_ = 0;
  gl::Query fragments_query_{GL_SAMPLES_PASSED};
  VolumeStats volume_stats_;
};

// The sun: the first directional light the light set keeps (light_defect(), as shadowed_sun()),
// or an Error naming the scene's lights.
const Light& find_sun(const Scene& scene);

// The factor the scene asks this chapter to apply to its directional lights, so that their
// shadows read plainly (the scene's extras {"lightpass": {"shadows_sun_scale": 4}}: the
// atrium's weak sun beside its point lights); 1 where it asks nothing, so any other scene's
// sun, and the default rig, are shown as they are. An Error names the file for a bad value.
float scene_sun_scale(const Scene& scene);

// [casts-shadows]
// Which lights cast shadows in this chapter. A light marked in the scene (the light node's
// extras {"lightpass": {"casts_shadows": true | false}}, Light::casts_shadows; the format is in
// book/appendix-scenes.md) does as it says; an unmarked one casts if it is the sun (the first
// directional light) and not otherwise. The sun gets its orthographic map, the first
// kMaxSpotShadows marked spot lights (of at most kMaxSpotCone) a perspective one each in a tile of
// one atlas (spot_atlas.h), the first kMaxPointShadows marked point
// lights a cube map each (cube_math.h; looked up hard with the method hard, with PCF on the k x k
// grid with every other map method; with volumes they cast nothing). A
// light that does not cast keeps chapter 03's path: visibility 1, no map, no pass.
bool casts_shadows(const Scene& scene, std::size_t light);
// The lights marked to cast that this chapter cannot shadow (the sun's map, kMaxSpotShadows spot
// lights' tiles and kMaxPointShadows point lights' cube maps: another directional light, a
// seventeenth spot light or one wider than kMaxSpotCone, a ninth point light), each named with
// why: for the program to say so.
std::vector<std::string> unshadowed_casters(const Scene& scene);
// The spot lights that get a tile of the atlas: the first kMaxSpotShadows spot lights the light
// set keeps that are marked to cast (or every one of them, with `all`) with a cone of at most
// kMaxSpotCone; their indices. shadowed_spot: the first of the marked ones, or -1.
std::vector<int> shadowed_spot_lights(const Scene& scene, bool all = false);
int shadowed_spot(const Scene& scene);
// The sun that gets a map: the first directional light, if it casts; its index, or -1.
int shadowed_sun(const Scene& scene);
// That sun's index among the directional lights chapter 03's light set keeps (light_defect()
// leaves some out): the `index` the visibility hook shadows (SHADOW_SUN_INDEX); -1 if none.
int shadowed_sun_index(const Scene& scene);
// The point lights that get a cube map: the first kMaxPointShadows point lights the light set
// keeps that are marked to cast (or every one of them, with `all`); their indices.
std::vector<int> shadowed_point_lights(const Scene& scene, bool all = false);
// [/casts-shadows]

}  // namespace lp::ch06
