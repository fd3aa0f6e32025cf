#pragma once
// Chapter 06's maths in C++, the twins of shaders/shadow_visibility.glsl and
// shaders/shadow_filter.frag (the unit tests hold these, the image tests the GLSL): the
// bias, the light's orthographic frustum, Chebyshev's bound for variance shadow maps with
// the P_min light-bleeding reduction, and exponential shadow maps filtered in log space.
#include <algorithm>
#include <vector>

#include <glm/glm.hpp>

namespace lp::ch06 {

// [bias]
// A receiver compared with its own depth in the map self-shadows ("acne"): the map holds one
// depth per texel, a tilted receiver's depth varies across the texel. The world-space
// distance the comparison allows, in units of the map's texel size w (world metres per
// texel): a constant part, and a slope-scaled part that grows with tan(theta) (theta between
// the normal and the light direction; half a texel across a plane at theta changes its depth
// by w/2 tan(theta)). tan is capped at kMaxSlope (grazing receivers would push it to infinity).
inline constexpr float kMaxSlope = 10.f;
float slope_scaled_bias(float constant_texels, float slope_texels, float cos_theta, float texel_world);
// Normal offset: the lookup moves off the surface along its normal by `texels` texel sizes,
// scaled by sin(theta): nothing for a receiver facing the light, most at grazing angles,
// where a depth bias alone would need to be largest.
glm::vec3 normal_offset(glm::vec3 position, glm::vec3 normal, float cos_theta, float texels, float texel_world);
// [/bias]

// [light-frustum]
// The sun's orthographic frustum: a view looking along `direction` (unit, the way the light
// shines) and a box in its space. Receivers: the scene's bounds, cut to the light-space
// bounds of the view frustum's corners when the camera is given (inverse view-projection),
// so the map's texels go to what the view can see. Casters: along the light, the whole
// scene's depth range, so a caster outside the view frustum (behind the camera, above it)
// still lands in the map in front of the receivers it shadows.
struct LightFrustum {
  glm::mat4 view{1}, projection{1};
  glm::vec3 box_min{0}, box_max{0};  // in light view space
  glm::mat4 view_projection() const { return projection * view; }
  float texel_world(int map_size) const;  // metres per texel (the larger of x, y)
  float depth_range() const { return box_max.z - box_min.z; }
};
LightFrustum fit_light_frustum(glm::vec3 direction, glm::vec3 scene_min, glm::vec3 scene_max,
                               const glm::mat4* inverse_camera_view_projection = nullptr);
// [/light-frustum]

// [cascades]
// Cascaded shadow maps for the sun: the view's depth range [near, far] cut into `count` slices,
// each with a map of its own, so that a texel near the camera covers what a pixel does there and
// one far away what a pixel does far away. The practical split scheme (Zhang et al. 2006): the
// logarithmic split, which keeps a texel's size over a pixel's the same in every slice, blended
// with the uniform one, which the log split starves far away:
//   z_i = lambda near (far / near)^(i / count) + (1 - lambda) (near + (far - near) i / count).
// Returns count + 1 view depths: z_0 = near, z_count = far.
inline constexpr int kMaxCascades = 4;
std::vector<float> cascade_splits(int count, float near, float far, float lambda);
// The smallest sphere around the slice of a symmetric perspective frustum between view depths
// n and f (`camera_world`: the camera's inverse view; yfov, aspect its projection's). Its radius
// depends on n, f, yfov and aspect only: the camera may move and turn, the sphere's size, and so
// the cascade's texel, stay the same.
struct Sphere {
  glm::vec3 centre{0};
  float radius = 0;
};
Sphere frustum_slice_sphere(const glm::mat4& camera_world, float yfov, float aspect, float n, float f);
// A cascade's orthographic frustum: the light's view as fit_light_frustum's (the scene's centre,
// the same rotation for every cascade and every frame), across it a square around the sphere,
// along it the whole scene's depth range (every caster). The square is N texels of
// 2 radius / (N - 2) metres: one spare texel a side, so that with `snap` its corner moves to a
// whole multiple of a texel (the sphere stays inside) and the texel grid stays where it was in
// the world while the camera moves: a shadow edge drawn into the same texels as the frame before.
LightFrustum fit_cascade(glm::vec3 direction, glm::vec3 scene_min, glm::vec3 scene_max, const Sphere& sphere,
                         int map_size, bool snap);
// Which cascade a point at view depth `depth` reads (the first whose far split lies beyond it;
// -1 beyond the last: lit), and the weight of the next cascade in the blend band: the last
// `band` fraction of a cascade's depth range fades into the next, so no seam shows where the
// texel's size jumps. lookup_math.glsl's choose_cascade is the twin.
struct CascadeChoice {
  int cascade = -1;
  float next_weight = 0;
};
CascadeChoice choose_cascade(float depth, const std::vector<float>& splits, float band);
// [/cascades]

// [spot-frustum]
// A spot light's perspective frustum: from its position along its direction, a square field of
// view of twice its outer cone (the cone is the circle inscribed in it), near plane 5 cm, far
// plane at the farthest corner of the scene's bounds, or its range when that is nearer. A
// perspective map's texel grows with the distance d from the light: 2 d tan(cone) / N.
// Cones up to kMaxSpotCone: wider ones need a cube map (a perspective map's texels stretch
// without bound as its field of view nears 180 degrees).
inline constexpr float kMaxSpotCone = 1.2f;  // radians, 69 degrees: a 137-degree field of view
struct SpotFrustum {
  glm::mat4 view{1}, projection{1};
  float near = 0.05f, far = 1.f, tan_cone = 1.f;
  glm::mat4 view_projection() const { return projection * view; }
  float texel_world(float distance, int map_size) const { return 2.f * distance * tan_cone / float(map_size); }
};
SpotFrustum fit_spot_frustum(glm::vec3 position, glm::vec3 direction, float outer_cone, float range, glm::vec3 scene_min,
                             glm::vec3 scene_max);
// [/spot-frustum]

// [receiver-plane]
// Receiver-plane depth bias for PCF: the receiver's window depth as a plane over the map's
// (u, v), its gradient from the normal in light view space (n_x, n_y, n_z), n_z > 0 facing the
// light: d depth / d u = (n_x / n_z) width / depth_range, likewise v with the height; n_z is
// kept >= 0.05 (slopes of at most 20:1). A tap o away compares the map with depth + g . o.
glm::vec2 receiver_plane_gradient(const LightFrustum& frustum, glm::vec3 world_normal);
// [/receiver-plane]

// [poisson]
// PCF on a rotated Poisson disk: `n` points of the unit disk no two closer than a spacing that
// starts at 0.75 sqrt(pi / n) (three quarters of the spacing of n points packed evenly) and
// shrinks by 5 % whenever 100 n darts in a row find no room, so it always ends (bounded work:
// at most 100 n darts per shrink, and the spacing reaches 0 after finitely many). The hook turns
// the disk per pixel by an angle from the pixel's position (interleaved gradient noise), so the
// pattern's regularity becomes noise instead of bands, and scales it to k texels across.
inline constexpr int kMaxPoissonTaps = 64;
std::vector<glm::vec2> poisson_disk(int n, unsigned long long seed, float* spacing = nullptr);
// [/poisson]

// [pcss]
// Percentage-closer soft shadows (Fernando 2005) for the sun as a disk of directions of angular
// radius theta (kSunAngularRadius: the soft truth's sun, shadow_truth.h; --sun-size). Depths d
// are metres along the light from the map's near plane (window depth times the box's depth).
// Seen from a receiver at d_r, the sun's disk projected back onto a plane of blockers at d_b is
// a disk of radius (d_r - d_b) tan(theta) around the lookup: the fraction of it the blockers
// leave open is the fraction of the sun the receiver sees. So:
//  1. search: the blockers that can hide any of the sun lie within (d_r - d_near) tan(theta)
//     of the lookup, d_near the map's near plane (d = 0); their mean depth is d_b;
//  2. penumbra: the filter's radius is (d_r - d_b) tan(theta), zero at contact, growing with
//     the distance from the blocker (the full penumbra across an edge is twice that);
//  3. PCF over a disk of that radius (the rotated Poisson taps of [poisson]).
// A point light of width w at distance d_b from the blocker gives Fernando's
// w (d_r - d_b) / d_b instead: the sun is that light moved to infinity with w / d_b fixed at its
// angular diameter 2 tan(theta) (point_light_penumbra tends to 2 pcss_filter_radius).
inline constexpr float kSunAngularRadius = 0.02f;  // radians (the real sun: 0.0047)
inline constexpr int kPcssDefaultTaps = 32;        // taps of the search and of the filter when --taps is 0
float pcss_search_radius(float receiver_depth, float angular_radius);                      // metres
float pcss_filter_radius(float receiver_depth, float blocker_depth, float angular_radius);  // metres, >= 0
float point_light_penumbra(float light_width, float receiver_distance, float blocker_distance);  // full width
// The whole estimate on a depth field (metres from the near plane at a lateral position in
// metres): the GLSL's steps without the bias, the map's texels or the per-pixel turn. 1 where
// the search finds no blocker; the filter radius is at least `min_radius`.
struct PcssResult {
  float visibility = 1, blocker_depth = 0, filter_radius = 0;
  int blockers = 0;
};
template <class DepthAt>
PcssResult pcss(DepthAt depth_at, glm::vec2 position, float receiver_depth, float angular_radius,
                const std::vector<glm::vec2>& disk, float min_radius) {
  PcssResult r;
  const float search = pcss_search_radius(receiver_depth, angular_radius);
  float sum = 0;
  for (const glm::vec2& t : disk) {
    const float z = depth_at(position + t * search);
    if (z < receiver_depth) sum += z, ++r.blockers;
  }
  if (r.blockers == 0) return r;
  r.blocker_depth = sum / float(r.blockers);
  r.filter_radius = std::max(pcss_filter_radius(receiver_depth, r.blocker_depth, angular_radius), min_radius);
  int lit = 0;
  for (const glm::vec2& t : disk) lit += receiver_depth <= depth_at(position + t * r.filter_radius);
  r.visibility = float(lit) / float(disk.size());
  return r;
}
// [/pcss]

// [chebyshev]
// Variance shadow maps store the moments M1 = E[z], M2 = E[z^2] of the depths z under the
// filter. For a receiver at depth d > M1, Chebyshev's one-sided inequality bounds the
// fraction of the filtered depths that lie at or beyond d (the lit fraction):
//   P(z >= d) <= p_max = s^2 / (s^2 + (d - M1)^2),   s^2 = M2 - M1^2,
// and d <= M1 is fully lit. The bound is exact for one occluder over one receiver (two
// depths); for overlapping occluders it is too high: light bleeding.
float chebyshev_upper_bound(glm::vec2 moments, float depth, float min_variance);
// [/chebyshev]

// [pmin]
// Light-bleeding reduction: every p_max below p_min is shadow, the rest stretched to [0, 1]:
// p' = clamp((p_max - p_min) / (1 - p_min), 0, 1). It cuts the bleeding's faint light and
// as much of the true penumbra.
float reduce_light_bleeding(float p_max, float p_min);
// [/pmin]

// [esm]
// Exponential shadow maps store exp(c z); filtered, E = sum w_i exp(c z_i), and the lit
// fraction is V = clamp(E exp(-c d), 0, 1), exact where every z_i >= d... or every
// z_i < d far enough. In fp32 exp(c z) overflows once c z > 88.7: with z in [0, 1], c > 88.
// Log space keeps L = log E instead and filters with log-sum-exp about the largest term:
//   L = l_max + log(sum w_i exp(l_i - l_max)),   l_i = c z_i,
// every exponent <= 0, so nothing overflows for any c; then V = clamp(exp(L - c d), 0, 1).
float esm_filter_direct(const std::vector<float>& depths, const std::vector<float>& weights, float c);  // E
float esm_filter_log(const std::vector<float>& log_values, const std::vector<float>& weights);          // L from l_i
float esm_visibility_direct(float filtered, float c, float depth);
float esm_visibility_log(float log_filtered, float c, float depth);
// [/esm]

// [msm]
// Moment shadow maps (Peters and Klein 2015) store four moments b = (z, z^2, z^3, z^4) of the
// depths under the filter. For a receiver at depth d, the Hamburger reconstruction finds the
// distribution with these moments that puts the least weight in front of d: three depths, one of
// them d itself, the other two the roots of a quadratic from the Cholesky factorisation of the
// moments' Hankel matrix; the weight of those in front of d is the shadow. Four moments pin down
// two occluders exactly, where Chebyshev's two moments let light bleed through. The moments are
// pulled a little towards (0.5, 0.5, 0.5, 0.5) first (`moment_bias`), since a Hankel matrix of
// one or two depths is singular. The lit fraction returned is 1 - shadow, in [0, 1].
float msm_hamburger(glm::vec4 moments, float depth, float moment_bias);
glm::vec4 msm_moments(float depth);  // (z, z^2, z^3, z^4)
// In 16 bits a channel (RGBA16, 64 bits a texel), the moments are stored through the paper's
// optimised affine map, which spreads them over [0, 1] so that rounding to 16 bits costs the
// reconstruction the least; filtering commutes with it (it is affine, the filter's weights sum
// to 1), so the map is filtered as stored and converted back at the lookup.
glm::vec4 msm_optimize(glm::vec4 moments);
glm::vec4 msm_unoptimize(glm::vec4 stored);
inline constexpr float kMsmMomentBias16 = 3e-5f, kMsmMomentBias32 = 3e-7f;
// [/msm]

// Does the sphere (centre, radius) reach into the view frustum of `view_projection` (OpenGL
// clip space)? Conservative: the six planes only (Gribb and Hartmann), so a sphere near a
// corner may pass that reaches nothing; a sphere that reaches the view always passes.
bool sphere_in_view(const glm::vec3& centre, float radius, const glm::mat4& view_projection);

}  // namespace lp::ch06
