// Chapter 09's GLSL against its C++ twins (glsl_twin.h): light_pair.glsl, the shading of one
// (surface, light) pair from the records pack_cluster_lights() precomputes; grid.glsl, the cells
// lights are binned into, against cluster_grid.h, and its capsule_meets_box on the tubes' hard case.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/01_forward/blinn_phong.h"
#include "chapters/02_gbuffer/gbuffer.h"
#include "chapters/02_gbuffer/layout.h"
#include "chapters/03_light_volumes/light_instances.h"
#include "chapters/09_clustered/cluster_grid.h"
#include "chapters/09_clustered/clustered_lights.h"
#include "tests/unit/capsule_cases.h"
#include "common/gl.h"
#include "tests/unit/glsl_twin.h"

namespace lp::ch09 {
namespace {

using test::TwinCase;
using test::ulps;

TEST(GlslTwins, LightPairMatchesItsCppTwin) {
  // light_pair's diffuse term for points and spots, from the records pack_cluster_lights()
  // makes of chapter 03's packing (1 / range^2, the cone folded into an axis and an offset).
  // Its C++ statement is chapter 01's incident() and n . l, zero beyond the cut, as for
  // chapter 03's local_light (test_03_twins_gl.cpp, LocalLightsDiffuseMatchesItsCppTwin), whose
  // cases and tolerance these follow: the surface at the origin, the light at 0 to 2 cuts (cuts
  // 0.5 to 20 m, log-uniform; ranges 0 or up to 3 cuts), 48 ulp of the window absolutely and 16
  // relative (here (d^2 / range^2)^2 in place of (d / range)^4 and one division in place of
  // three: the same few roundings), n . l's 6 ulp of the radiance, either side at the cut.
  // A spot's t = (cos - cos outer) x scale is found as dot(-l, axis) + offset: the folding
  // rounds each of its terms, which reach scale, and the direction carries the octahedral
  // packing's 12 ulp: t within scale x 24 ulp absolutely, t^2 twice that, times the radiance.
  // Edge cases: a light on the surface, one at its cut along the normal, a spot pointing
  // straight at the surface and one whose cone's edge passes through it.
  const std::vector<std::string> files = {"01_forward/shaders/lighting.glsl", "02_gbuffer/shaders/gbuffer.glsl",
                                          "03_light_volumes/shaders/hooks/full_visibility.glsl",
                                          "09_clustered/shaders/light_pair.glsl"};
  const std::string helper =
      "vec4 twin_pair(vec4 a, vec4 b, vec4 c, vec4 d) { Surface s = Surface(vec3(0.0), d.xyz, vec3(1.0), vec3(1.0), "
      "16.0, vec3(0.0), false, 0.5); vec3 df = vec3(0.0), sp = vec3(0.0); uint lit = 0u; light_pair(ClusterLight(a, b), "
      "d.w > 0.5, c, 0, s, vec3(0.0, 1.0, 0.0), df, sp, lit); return vec4(df, 0.0); }";
  test::TwinRandom r(90);
  std::vector<Light> lights;
  std::vector<float> cuts;
  auto add = [&](Light l, float cut) {
    lights.push_back(l);
    cuts.push_back(cut);
  };
  const glm::vec3 up(0, 1, 0);
  add(Light{.type = LightType::Point, .intensity = 1, .position = glm::vec3(0)}, 1);
  add(Light{.type = LightType::Point, .intensity = 1, .position = glm::vec3(0, 2, 0)}, 2);
  add(Light{.type = LightType::Spot, .intensity = 1, .position = glm::vec3(0, 3, 0), .direction = -up, .inner_cone = 0.2f,
            .outer_cone = 0.4f}, 5);
  // The cone's edge through the surface: the surface seen at the outer angle from the axis.
  add(Light{.type = LightType::Spot, .intensity = 1, .position = glm::vec3(0, 3, 0),
            .direction = glm::normalize(glm::vec3(std::sin(0.4f), -std::cos(0.4f), 0)), .inner_cone = 0.2f,
            .outer_cone = 0.4f}, 5);
  while (lights.size() < 10000 + 4) {
    const float cut = r.log_uniform(0.5f, 20);
    glm::vec3 to = r.unit();
    if (glm::dot(up, to) < 0) to = -to;
    Light l{.color = {r.uniform(0, 5), r.uniform(0, 5), r.uniform(0, 5)}, .intensity = 1, .position = to * r.uniform(0, 2 * cut),
            .range = r.uniform(0, 1) < 0.3f ? 0.f : r.uniform(0.5f, 3) * cut};
    if (r.uniform(0, 1) < 0.7f) {  // a spot, pointing near the surface so that its cone decides
      l.type = LightType::Spot;
      l.direction = glm::normalize(-to + 0.6f * r.unit());
      l.outer_cone = r.uniform(0.05f, 1.5f);
      l.inner_cone = l.outer_cone * r.uniform(0, 1);
    }
    add(l, cut);
  }
  // Through the packers the shading reads: chapter 03's, then ours.
  std::vector<test::TwinCase> cases;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    ch03::LightSet set;
    const bool spot = lights[i].type == LightType::Spot;
    if (spot)
      set.cones.push_back(ch03::pack_spot(lights[i], cuts[i]));
    else
      set.points.push_back(ch03::pack_point(lights[i], cuts[i]));
    const ClusterRecords rec = pack_cluster_lights(set);
    ASSERT_EQ(rec.first_spot, spot ? 0 : 1);
    ASSERT_EQ(rec.spots.size(), spot ? 1u : 0u);
    const glm::vec3 n = i < 4 ? up : glm::normalize(glm::mix(up, r.unit(), 0.7f));
    cases.push_back({rec.lights[0].position_radius, rec.lights[0].radiance_inv_range2,
                     spot ? rec.spots[0].axis_offset : glm::vec4(0), glm::vec4(n, spot ? 1.f : 0.f)});
  }
  const std::vector<std::string> defines = ch02::gbuffer_defines(ch02::layouts()[0]);
  const auto gpu = test::run_glsl_twin({files, "twin_pair(a, b, c, d)", defines, helper}, cases);
  std::vector<glm::vec4> cpu;
  std::vector<test::TwinTolerance> tolerance;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light& l = lights[i];
    const ch01::Incident in = ch01::incident(l, glm::vec3(0));
    const float distance = glm::length(l.position);
    const float n_dot_l = glm::dot(glm::vec3(cases[i].d), in.to_light);
    const glm::vec3 diffuse = distance <= cuts[i] && n_dot_l > 0 ? in.radiance * n_dot_l : glm::vec3(0);
    cpu.push_back(glm::vec4(diffuse, 0));
    const double peak = std::max({l.color.r, l.color.g, l.color.b}) * double(l.intensity);
    const double d2 = std::max(double(distance) * distance, 1e-4);
    double cone = 0;
    if (l.type == LightType::Spot)
      cone = 2 * ulps(24) / std::max(1e-4, double(std::cos(l.inner_cone)) - double(std::cos(l.outer_cone)));
    if (std::abs(double(distance) - cuts[i]) <= ulps(8) * cuts[i])
      tolerance.push_back({peak / d2, 0});  // at the cut: lit or not
    else
      tolerance.push_back({peak * (ulps(48) + cone) / d2 + glm::length(in.radiance) * ulps(6), ulps(16)});
  }
  EXPECT_TRUE(test::twins_agree(
      gpu, cpu, 3, [&](std::size_t i) { return tolerance[i]; },
      [&](std::size_t i) {
        return "light " + test::str(cases[i].a) + " radiance, 1/range^2 " + test::str(cases[i].b) + " cone " +
               test::str(cases[i].c) + " normal, spot " + test::str(cases[i].d);
      }));
}

// grid.glsl's capsule_meets_box on the tubes' hard case (capsule_cases.h: capsules touching a
// cluster's box by less than float rounding, 150 m from the origin), and the same capsules
// moved 3 radii plus 1 cm away from the box's face, which neither twin may bin (the grown box's
// corners reach sqrt 3 radii, the margin a fraction of a millimetre). A yes-or-no answer: the
// twins agree exactly, and the GPU bins every touching capsule, as the C++ twin does
// (ACapsuleTouchingABoxByLessThanItsRoundingIsBinned): GLSL's division may round by 2.5 ulp, which
// the margin's derivation (cluster_grid.h) allows for.
TEST(GlslTwins, CapsuleMeetsBoxMatchesItsCppTwin) {
  const FrameCamera c = test::grid_test_camera();
  const Grid grid = grid_of_counts(1920, 1080, 16, 9, 24, c.znear, c.zfar);
  const std::vector<test::CapsuleCase> touching = test::touching_capsules(c, grid, 10000);
  std::vector<test::TwinCase> cases;
  std::vector<glm::vec4> cpu;
  for (const bool away : {false, true})
    for (const test::CapsuleCase& k : touching) {
      glm::vec3 a = k.a, b = k.b;
      if (away) {  // along the face's normal, out of the box (the face's axis: the ends' nearest side)
        const glm::vec3 mid = 0.5f * (a + b), centre = 0.5f * (k.box.lo + k.box.hi), half = 0.5f * (k.box.hi - k.box.lo);
        const glm::vec3 out = (mid - centre) / half;
        int axis = 0;
        for (int j = 1; j < 3; ++j)
          if (std::abs(out[j]) > std::abs(out[axis])) axis = j;
        glm::vec3 shift(0.f);
        shift[axis] = (out[axis] > 0 ? 1.f : -1.f) * (3.f * k.radius + 0.01f);
        a += shift;
        b += shift;
      }
      cases.push_back({glm::vec4(a, k.radius), glm::vec4(b, k.eye_distance), glm::vec4(k.box.lo, 0.f), glm::vec4(k.box.hi, 0.f)});
      cpu.push_back(glm::vec4(capsule_meets_box(a, b, k.radius, k.box, k.eye_distance) ? 1.f : 0.f));
      if (!away) { EXPECT_EQ(cpu.back().x, 1.f) << "the C++ twin drops a touching capsule"; }
      if (away) { EXPECT_EQ(cpu.back().x, 0.f) << "the C++ twin bins a capsule 3 radii away"; }
    }
  const auto gpu = test::run_glsl_twin({{"09_clustered/shaders/grid.glsl"},
                                        "vec4(capsule_meets_box(a.xyz, b.xyz, a.w, Box(c.xyz, d.xyz), b.w) ? 1.0 : 0.0)"},
                                       cases);
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 1, test::TwinTolerance{0, 0}, [&](std::size_t i) {
    return "ends " + test::str(cases[i].a) + " " + test::str(cases[i].b) + " box " + test::str(cases[i].c) + " " +
           test::str(cases[i].d);
  }));
}

// grid.glsl against cluster_grid.h. The GLSL reads the grid from uniforms: a 24-slice cluster
// grid of 16 x 9 tiles over 1920 x 1080, znear 0.1 m, zfar 1000 m (DOOM 2016's), and a
// projection with a jitter (P20, P21 nonzero, as TAA's), so each term of cell_box counts.
// The integer and boolean results must be equal, except where the exact value lies within the
// two twins' rounding bounds of the boundary (a "band"): there either answer is right. u is
// float's unit roundoff 2^-24 = ulps(0.5); GLSL's + - * are correctly rounded, / is 2.5 ulp,
// log is 3 ulp (absolutely 2^-21 on [0.5, 2]), the C++ ones 0.5 ulp.
constexpr int kW = 1920, kH = 1080, kTilesX = 16, kTilesY = 9, kSlices = 24;
constexpr float kNear = 0.1f, kFar = 1000.f;

struct GridRig {
  Grid grid = grid_of_counts(kW, kH, kTilesX, kTilesY, kSlices, kNear, kFar);
  FrameCamera camera;
  GridRig() {
    camera.projection = glm::perspective(0.8f, float(kW) / float(kH), kNear, kFar);
    camera.projection[2][0] = 0.37f / float(kW);  // a jitter of a fraction of a pixel
    camera.projection[2][1] = -0.81f / float(kH);
  }
  test::GlslTwin twin(const std::string& expression, const std::string& helpers = {}) const {
    const glm::mat4 p = camera.projection;
    const Grid g = grid;
    std::vector<std::string> defines;
    if (g.has_near_slice()) defines.push_back("NEAR_SLICE 1");
    return {{"09_clustered/shaders/grid.glsl"}, expression, defines, helpers, [p, g](unsigned program) {
              glProgramUniform1f(program, glGetUniformLocation(program, "u_near_slice"), g.near_slice);
              glProgramUniform4f(program, glGetUniformLocation(program, "u_projection"), p[0][0], p[1][1], p[2][0], p[2][1]);
              glProgramUniform4i(program, glGetUniformLocation(program, "u_grid"), g.width, g.height, g.tile_w, g.tile_h);
              glProgramUniform4i(program, glGetUniformLocation(program, "u_tiles"), g.tiles_x, g.tiles_y, g.slices, 0);
              glProgramUniform2f(program, glGetUniformLocation(program, "u_depth_range"), g.znear, g.zfar);
            }};
  }
};

// The integer result agrees, or the exact t lies within `band` of the integer between them.
std::size_t count_beyond_band(const std::vector<glm::vec4>& gpu, const std::vector<int>& cpu,
                              const std::vector<double>& exact, const std::vector<double>& band,
                              const std::function<std::string(std::size_t)>& describe, std::size_t* in_band) {
  std::size_t failed = 0;
  for (std::size_t i = 0; i < cpu.size(); ++i) {
    const int g = int(gpu[i].x);
    if (g == cpu[i]) continue;
    const double boundary = std::max(g, cpu[i]);  // the integer the two results lie either side of
    if (std::abs(g - cpu[i]) == 1 && std::abs(exact[i] - boundary) <= band[i]) {
      ++*in_band;
      continue;
    }
    if (failed++ < 5) ADD_FAILURE() << "GLSL " << g << ", C++ " << cpu[i] << " (exact " << exact[i] << ", band " << band[i] << ") for " << describe(i);
  }
  return failed;
}

// slice_of, and zbin_of with its bins: t = log(d / origin) / log(zfar / origin), the index
// first + floor(t S). The exponential slices start at `origin` (znear, or the near slice) with
// slice `first` (0, or 1 after a near slice, below which both say 0: one comparison, exact).
// The GPU's t: d / origin 2.5 ulp (in the log: 2.5 ulp absolutely), log 3 ulp or 2^-21
// absolutely, log(zfar / origin) the same, the quotient 2.5 ulp: |dt| <= |t| (3 + 2.5 + 2.5 + 1)
// ulp + (2^-21 + 3 ulp) / L, and the C++ one far less (inside the GPU's allowance doubled). The
// band is S times twice that. Cases: each slice's start (every one, or 500 spread over many),
// its neighbouring floats and 1e-4 either side, the range's ends, beyond them, and log-uniform
// depths. The C++ twin is slice_of on the rig's grid (rig.grid.slices = S + first).
void expect_slice_index_matches(const GridRig& rig, const test::GlslTwin& twin, std::uint64_t seed, float origin, int first,
                                const char* name) {
  const int slices = rig.grid.slices - first;  // the exponential ones
  test::TwinRandom r(seed);
  std::vector<TwinCase> cases;
  for (int k = 0; k <= rig.grid.slices; k += std::max(1, rig.grid.slices / 500)) {
    const float d = slice_start(rig.grid, k);
    for (float e : {d, std::nextafter(d, 0.f), std::nextafter(d, 1e9f), d * (1 + 1e-4f), d * (1 - 1e-4f)}) cases.push_back({glm::vec4(e, 0, 0, 0)});
  }
  for (float e : {0.f, 1e-3f, kNear, kFar, 5000.f, -1.f}) cases.push_back({glm::vec4(e, 0, 0, 0)});
  while (cases.size() < 12000) cases.push_back({glm::vec4(r.log_uniform(0.01f, 2000.f), 0, 0, 0)});
  const auto gpu = test::run_glsl_twin(twin, cases);
  std::vector<int> cpu;
  std::vector<double> exact, band;
  const double L = std::log(double(kFar) / double(origin));
  for (const TwinCase& c : cases) {
    cpu.push_back(slice_of(rig.grid, c.a.x));
    const double t = std::log(std::max(double(c.a.x), double(origin)) / double(origin)) / L;
    exact.push_back(first > 0 && c.a.x < origin ? 0.0 : first + t * slices);
    band.push_back(2 * slices * (std::abs(t) * ulps(9) + (0x1p-21 + ulps(3)) / L));
  }
  std::size_t in_band = 0;
  EXPECT_EQ(count_beyond_band(gpu, cpu, exact, band, [&](std::size_t i) { return "d " + std::to_string(cases[i].a.x); }, &in_band), 0u);
  std::printf("%s, %d slices: %zu cases, %zu differ within the rounding band\n", name, slices, cases.size(), in_band);
}

TEST(GlslTwins, SliceOfMatchesItsCppTwin) {
  const GridRig rig;
  expect_slice_index_matches(rig, rig.twin("float(slice_of(a.x)), 0.0, 0.0, 0.0"), 91, kNear, 0, "slice_of");
}

TEST(GlslTwins, SliceStartMatchesItsCppTwin) {
  // near (far / near)^(k / S), the depth where a cluster slice begins (assign.comp's cell boxes).
  // GLSL: far / near and k / S 2.5 ulp each, pow is exp2(y log2 x): log2 3 ulp (x = far / near
  // is beyond [0.5, 2]), the product half an ulp, so the exponent x' = y log2 x is within
  // x' 6 ulp + y 2.5 ulp / ln 2 (the quotient's error through log2), which exp2 turns into a
  // relative ln 2 times that, plus its own (3 + 2 x') ulp, and near times it half an ulp. C++:
  // the same with 0.5 ulp divisions and powf within an ulp. The ends (k <= 0, k >= S) are near
  // and far exactly on both sides. Every k from -2 to S + 2, for 24, 1024 and 16 384 slices over
  // three depth ranges (ratios 1e4, 1e4 and 2e5).
  std::size_t total = 0;
  for (const int slices : {24, 1024, 16384})
    for (const glm::vec2 range : {glm::vec2(kNear, kFar), glm::vec2(0.01f, 100.f), glm::vec2(0.5f, 1e5f)}) {
      SCOPED_TRACE(std::to_string(slices) + " slices, depths " + std::to_string(range.x) + " to " + std::to_string(range.y));
      GridRig rig;
      rig.grid = grid_of_counts(kW, kH, kTilesX, kTilesY, slices, range.x, range.y);
      std::vector<TwinCase> cases;
      for (int k = -2; k <= slices + 2; ++k) cases.push_back({glm::vec4(float(k), 0, 0, 0)});
      total += cases.size();
      const auto gpu = test::run_glsl_twin(rig.twin("slice_start(int(a.x)), 0.0, 0.0, 0.0"), cases);
      std::vector<glm::vec4> cpu;
      std::vector<double> tolerance;
      const double ln2 = std::log(2.0), log2_ratio = std::log2(double(range.y) / range.x);
      for (const TwinCase& c : cases) {
        const int k = int(c.a.x);
        const float v = slice_start(rig.grid, k);
        cpu.push_back(glm::vec4(v, 0, 0, 0));
        const double y = std::clamp(double(k) / slices, 0.0, 1.0), x = y * log2_ratio;
        const double gpu_ulps = ln2 * (6 * x + 2.5 * y / ln2) + 3 + 2 * x + 0.5, cpu_ulps = ln2 * (1.5 * x + 0.5 * y / ln2) + 1 + 0.5;
        tolerance.push_back(k <= 0 || k >= slices ? 0.0 : ulps(gpu_ulps + cpu_ulps) * v);
      }
      EXPECT_TRUE(test::twins_agree(gpu, cpu, 1, [&](std::size_t i) { return test::TwinTolerance{tolerance[i], 0}; },
                                    [&](std::size_t i) { return "k " + std::to_string(int(cases[i].a.x)); }));
    }
  EXPECT_GE(total, 10000u);
}

TEST(GlslTwins, SliceOfWithANearSliceMatchesItsCppTwin) {
  // The same with a near slice at 3 m: t = log(d / near) / log(zfar / near), slice
  // 1 + floor(t (S - 1)); the same operations, so the same band with S - 1 slices and L of
  // zfar / near.
  GridRig rig;
  rig.grid.near_slice = 3.f;
  ASSERT_TRUE(rig.grid.has_near_slice());
  expect_slice_index_matches(rig, rig.twin("float(slice_of(a.x)), 0.0, 0.0, 0.0"), 97, rig.grid.near_slice, 1,
                             "slice_of with a near slice");
}

TEST(GlslTwins, DepthBinMatchesItsCppTwin) {
  // t = (d - lo) / (hi - lo) x 32: two subtractions (0.5 ulp each), the GPU's division 2.5 ulp,
  // x 32 exact: |dt| <= |t| 3.5 ulp on the GPU, 1.5 in C++; the band is their sum, 5 ulp of t.
  test::TwinRandom r(92);
  std::vector<TwinCase> cases;
  while (cases.size() < 12000) {
    const float lo = r.log_uniform(0.05f, 500.f), hi = lo + r.log_uniform(1e-4f, 1000.f);
    float d = r.uniform(lo - 0.1f * (hi - lo), hi + 0.1f * (hi - lo));
    if (cases.size() % 4 == 0) d = lo + (hi - lo) * float(int(r.uniform(0, 33))) / 32.f;  // on a bin's edge
    cases.push_back({glm::vec4(lo, hi, d, 0)});
  }
  cases.push_back({glm::vec4(1, 1, 1, 0)});  // an empty range: every depth in one bin
  cases.push_back({glm::vec4(1, 1, 2, 0)});
  const GridRig rig;
  const auto gpu = test::run_glsl_twin(rig.twin("float(depth_bin(a.x, a.y, a.z)), 0.0, 0.0, 0.0"), cases);
  std::vector<int> cpu;
  std::vector<double> exact, band;
  for (const TwinCase& c : cases) {
    cpu.push_back(depth_bin(c.a.x, c.a.y, c.a.z));
    const double t = (double(c.a.z) - c.a.x) / std::max(double(c.a.y) - c.a.x, 1e-30) * kDepthBins;
    exact.push_back(t);
    band.push_back(std::abs(t) * ulps(5));
  }
  std::size_t in_band = 0;
  EXPECT_EQ(count_beyond_band(gpu, cpu, exact, band, [&](std::size_t i) { return "lo, hi, d " + test::str(cases[i].a); }, &in_band), 0u);
  std::printf("depth_bin: %zu cases, %zu differ within the rounding band\n", cases.size(), in_band);
}

TEST(GlslTwins, CellBoxMatchesItsCppTwin) {
  // A corner's x = d (ndc + P20) / P00, ndc = pixel / width x 2 - 1: the GPU's two divisions
  // 2.5 ulp each, the rest 0.5 ulp an operation, each of magnitude at most d (2 + |P20|) / P00:
  // 8 ulp of that (C++: 3), and the padded depth's 1: 12 ulp of it bounds the difference; z is
  // -d times the pad, 1 ulp. The min / max over the corners cannot add to it.
  const GridRig rig;
  test::TwinRandom r(93);
  std::vector<TwinCase> cases;
  while (cases.size() < 10000) {
    const int x0 = int(r.uniform(0, kW)), y0 = int(r.uniform(0, kH));
    const int x1 = std::min(kW, x0 + 1 + int(r.uniform(0, 200))), y1 = std::min(kH, y0 + 1 + int(r.uniform(0, 200)));
    const float d0 = r.log_uniform(kNear, kFar), d1 = std::min(kFar, d0 * r.uniform(1, 2));
    cases.push_back({glm::vec4(x0, y0, x1, y1), glm::vec4(d0, d1, 0, 0)});
  }
  for (int k = 0; k < kSlices; ++k)  // the grid's own cells, corners of the image included
    for (glm::ivec2 t : {glm::ivec2(0, 0), glm::ivec2(kTilesX - 1, kTilesY - 1), glm::ivec2(7, 4)}) {
      const int tw = rig.grid.tile_w, th = rig.grid.tile_h;
      cases.push_back({glm::vec4(t.x * tw, t.y * th, std::min(kW, (t.x + 1) * tw), std::min(kH, (t.y + 1) * th)),
                       glm::vec4(slice_start(rig.grid, k), slice_start(rig.grid, k + 1), 0, 0)});
    }
  const std::string helper = "Box twin_box(vec4 a, vec4 b) { return cell_box(ivec2(a.xy), ivec2(a.zw), b.x, b.y); }";
  const auto lo = test::run_glsl_twin(rig.twin("twin_box(a, b).lo, 0.0", helper), cases);
  const auto hi = test::run_glsl_twin(rig.twin("twin_box(a, b).hi, 0.0", helper), cases);
  std::vector<glm::vec4> cpu_lo, cpu_hi;
  const glm::mat4& p = rig.camera.projection;
  for (const TwinCase& c : cases) {
    const Box b = cell_box(rig.camera, rig.grid, int(c.a.x), int(c.a.y), int(c.a.z), int(c.a.w), c.b.x, c.b.y);
    cpu_lo.push_back(glm::vec4(b.lo, 0));
    cpu_hi.push_back(glm::vec4(b.hi, 0));
  }
  const auto tolerance = [&](std::size_t i) {
    const double d = cases[i].b.y * (1 + kDepthPad);
    const double scale = d * (2 + std::max(std::abs(p[2][0]), std::abs(p[2][1]))) / std::min(p[0][0], p[1][1]);
    return test::TwinTolerance{ulps(12) * scale, 0};
  };
  const auto describe = [&](std::size_t i) { return "pixels " + test::str(cases[i].a) + " depths " + test::str(cases[i].b); };
  EXPECT_TRUE(test::twins_agree(lo, cpu_lo, 3, tolerance, describe));
  EXPECT_TRUE(test::twins_agree(hi, cpu_hi, 3, tolerance, describe));
}

TEST(GlslTwins, LightDepthBitsMatchItsCppTwin) {
  // The light's 2.5D mask: bins of z - r and z + r, r = radius (1 + 1e-5) + 1e-6 + kDepthPad hi
  // (four roundings: 2 ulp of r), each end 0.5 ulp more of |z| + r; depth_bin then as above
  // (5 ulp of t). The masks must be equal, except where an end's exact t lies within its band,
  // 32 x 2.5 ulp (|z| + r) / (hi - lo) + 5 ulp of t, of a bin's edge. The mask's 32 bits come
  // back as two 16-bit halves (a float holds 24).
  test::TwinRandom r(96);
  std::vector<TwinCase> cases;
  while (cases.size() < 12000) {
    const float lo = r.log_uniform(0.05f, 500.f), hi = lo + r.log_uniform(1e-3f, 1000.f);
    const float z = r.uniform(lo - 0.5f * (hi - lo), hi + 0.5f * (hi - lo)), radius = r.log_uniform(1e-3f, 2 * (hi - lo));
    cases.push_back({glm::vec4(lo, hi, z, radius)});
  }
  const GridRig rig;
  const auto gpu = test::run_glsl_twin(rig.twin("float(light_depth_bits(a.x, a.y, a.z, a.w) & 0xFFFFu), float(light_depth_bits(a.x, a.y, a.z, a.w) >> 16u), 0.0, 0.0"), cases);
  std::size_t failed = 0, in_band = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const glm::vec4 c = cases[i].a;
    const std::uint32_t cpu = light_depth_bits(c.x, c.y, c.z, c.w);
    const std::uint32_t g = std::uint32_t(gpu[i].x) | (std::uint32_t(gpu[i].y) << 16);
    if (g == cpu) continue;
    const double rr = double(c.w) * (1 + 1e-5) + 1e-6 + kDepthPad * double(c.y);
    bool near_edge = false;
    for (double end : {double(c.z) - rr, double(c.z) + rr}) {
      const double t = (end - c.x) / (double(c.y) - c.x) * kDepthBins;
      const double band = kDepthBins * ulps(2.5) * (std::abs(double(c.z)) + rr) / (double(c.y) - c.x) + ulps(5) * std::abs(t);
      near_edge |= t > -band && t < kDepthBins + band && std::abs(t - std::round(t)) <= band;
    }
    if (near_edge) { ++in_band; continue; }
    if (failed++ < 5) ADD_FAILURE() << "GLSL " << std::hex << g << ", C++ " << cpu << std::dec << " for lo, hi, z, radius " << test::str(c);
  }
  EXPECT_EQ(failed, 0u);
  std::printf("light_depth_bits: %zu cases, %zu differ within the rounding band\n", cases.size(), in_band);
}

// Boolean twins: equal answers, or the case lies within both twins' rounding band of the
// boundary (`within_band`, evaluated only where they differ).
void booleans_agree(const char* name, const std::vector<glm::vec4>& gpu, const std::function<bool(std::size_t)>& cpu,
                    const std::function<bool(std::size_t)>& within_band, const std::function<std::string(std::size_t)>& describe) {
  std::size_t failed = 0, in_band = 0, met = 0;
  for (std::size_t i = 0; i < gpu.size(); ++i) {
    const bool c = cpu(i);
    met += c;
    if ((gpu[i].x > 0.5f) == c) continue;
    if (within_band(i)) {
      ++in_band;
      continue;
    }
    if (failed++ < 5) ADD_FAILURE() << "GLSL " << gpu[i].x << ", C++ " << c << " for " << describe(i);
  }
  EXPECT_EQ(failed, 0u);
  std::printf("%s: %zu cases (%zu met), %zu differ within the rounding band\n", name, gpu.size(), met, in_band);
}

TEST(GlslTwins, SphereMeetsBoxMatchesItsCppTwin) {
  // dot(d, d) <= r^2: the nearest point is exact (clamp), d = centre - nearest 0.5 ulp a
  // component, the dot's three products and two sums 2.5 ulp of dot(d, d) (fused or not); r is
  // radius (1 + 1e-5) + 1e-6 (1 ulp), r^2 2.5 ulp: the band is both twins' bounds, 2 (4 ulp
  // dot + 2.5 ulp r^2) of the exact values' sum. Spheres are placed at their radius from the
  // box, times 1 +- up to 1e-3, so the padding (1e-5 relative) and the band both matter.
  test::TwinRandom r(94);
  std::vector<TwinCase> cases;
  while (cases.size() < 12000) {
    const glm::vec3 lo(r.uniform(-50, 50), r.uniform(-50, 50), r.uniform(-500, -0.1f));
    const glm::vec3 hi = lo + glm::vec3(r.log_uniform(1e-3f, 50), r.log_uniform(1e-3f, 50), r.log_uniform(1e-3f, 50));
    const float radius = r.log_uniform(0.01f, 30.f);
    const glm::vec3 inside(r.uniform(lo.x, hi.x), r.uniform(lo.y, hi.y), r.uniform(lo.z, hi.z));
    glm::vec3 centre = glm::clamp(inside + r.unit() * 1000.f, lo, hi);  // a point on the box's surface
    const glm::vec3 out = r.unit();
    const float scale = cases.size() % 3 == 0 ? r.uniform(0, 3) : 1 + r.uniform(-1e-3f, 1e-3f) * (cases.size() % 3 == 1 ? 1.f : 0.01f);
    centre += out * radius * scale;
    cases.push_back({glm::vec4(centre, radius), glm::vec4(lo, 0), glm::vec4(hi, 0)});
  }
  cases.push_back({glm::vec4(0, 0, -1, 0), glm::vec4(-1, -1, -2, 0), glm::vec4(1, 1, -0.5f, 0)});  // inside, radius 0
  const GridRig rig;
  const auto gpu = test::run_glsl_twin(rig.twin("sphere_meets_box(a.xyz, a.w, Box(b.xyz, c.xyz)) ? 1.0 : 0.0, 0.0, 0.0, 0.0"), cases);
  booleans_agree(
      "sphere_meets_box", gpu,
      [&](std::size_t i) { return sphere_meets_box(glm::vec3(cases[i].a), cases[i].a.w, Box{glm::vec3(cases[i].b), glm::vec3(cases[i].c)}); },
      [&](std::size_t i) {
        const TwinCase& c = cases[i];
        const glm::dvec3 d = glm::dvec3(c.a) - glm::clamp(glm::dvec3(c.a), glm::dvec3(c.b), glm::dvec3(c.c));
        const double rr = double(c.a.w) * (1 + 1e-5) + 1e-6, dd = glm::dot(d, d);
        return std::abs(dd - rr * rr) <= 2 * (ulps(4) * dd + ulps(2.5) * rr * rr);
      },
      [&](std::size_t i) { return "sphere " + test::str(cases[i].a) + " box " + test::str(cases[i].b) + " " + test::str(cases[i].c); });
}

// zbin.glsl against cluster_grid.h: Z-binning's bins and a light's screen rectangle. The GLSL
// reads grid.glsl's uniforms (the rig's camera, and here zbin's own grid: 16-pixel tiles, the
// last row cut short) and u_zbins.
test::GlslTwin zbin_twin(const GridRig& rig, int bins, const std::string& expression) {
  test::GlslTwin t = rig.twin(expression);
  t.files.push_back("09_clustered/shaders/zbin.glsl");
  t.uniforms = [set = t.uniforms, bins](unsigned program) {
    set(program);
    glProgramUniform1i(program, glGetUniformLocation(program, "u_zbins"), bins);
  };
  return t;
}

TEST(GlslTwins, ZbinOfMatchesItsCppTwin) {
  // zbin_of is slice_of with u_zbins slices: its C++ twin is slice_of on a grid of that many
  // (what ZBinRangesAndTileBitsHoldExactlyTheLightsThatReach takes it for), with slice_of's band.
  // Bins: 1 (everything in bin 0), 24 (a slice's worth), the program's 1024, the most, 16 384.
  for (const int bins : {1, 24, 1024, 16384}) {
    GridRig rig;
    rig.grid = grid_of_tiles(kW, kH, 16, bins, kNear, kFar);
    expect_slice_index_matches(rig, zbin_twin(rig, bins, "float(zbin_of(a.x)), 0.0, 0.0, 0.0"), 97 + std::uint64_t(bins), kNear, 0, "zbin_of");
  }
}

// A light's screen rectangle (zbin.glsl's sphere_tiles against cluster_grid.h's). Each end is
// floor(e) of e = px / tile, px = ((q P - O) 0.5 + 0.5) W -+ 1, q = (c.x -+ r) / d over the two
// depths d0 (the box's near side, or half the near plane) and d1; the tiles are integers, equal
// unless the exact e lies within both twins' rounding band of the integer between them. Per
// side, u = 2^-24 and a division's allowance v (GLSL 5 u, C++ u): r = radius (1 + 1e-5) + 1e-6
// rounds twice (2 u r); d1 and d0 once more (dd = u (|c.z| + r) + 2 u r; d0 not at all where
// it is half the near plane, constant); the numerator u |c.x -+ r| + 2 u r; each q = num / d
// within dnum / d + |q| (dd / d + v), the min / max no further than the larger; q P - O:
// P dq + u |q P| + u (|q P| + |O|); the pixel: W / 2 of that plus u W (|ndc| / 2 + 1 / 2)
// + 2 u (|px| + 1); e: dpx / T + v |e|. The band is the two sides' sum (at most 0.3 tiles, for
// spheres around the camera cut at half the near plane: r's rounding over d0 = 5 cm). Whether the rectangle is empty (d1 < d0) is decided within 2 (u (|c.z| + r) + 2 u r) of
// d1 = d0: there either answer is right. Cases: spheres in front of the camera, in and out of
// the view, large and small; ones cut by or behind the near plane, on the camera; spheres
// grazing a tile's edge (their rectangle's exact end on an integer).
TEST(GlslTwins, SphereTilesMatchesItsCppTwin) {
  GridRig rig;
  rig.grid = grid_of_tiles(kW, kH, 16, 1024, kNear, kFar);
  const Grid& g = rig.grid;
  const glm::mat4& p = rig.camera.projection;
  test::TwinRandom r(98);
  std::vector<TwinCase> cases;
  const float tan_x = 1.f / p[0][0], tan_y = 1.f / p[1][1];
  while (cases.size() < 12000) {
    const int kind = int(cases.size() % 6);
    const float depth = kind == 0 ? r.uniform(-2.f, 0.2f) : r.log_uniform(0.05f, 1500.f);
    const float spread = kind == 1 ? 3.f : 1.2f;
    glm::vec3 c(r.uniform(-spread, spread) * tan_x * std::max(depth, 0.1f), r.uniform(-spread, spread) * tan_y * std::max(depth, 0.1f), -depth);
    float radius = r.log_uniform(0.01f, 50.f);
    if (kind == 2) radius = std::max(0.001f, depth - 0.5f * kNear + r.uniform(-1e-3f, 1e-3f));  // d0 at half the near plane
    if (kind == 3) radius = depth + r.uniform(-0.1f, 0.1f);  // the near plane's cut
    if (kind >= 4) {  // x's low end (4) or y's high end (5) exactly on a tile's edge, before c rounds to float
      const int axis = kind - 4, sign = kind == 4 ? -1 : 1;
      const double rr = double(radius) * double(1.f + 1e-5f) + double(1e-6f);
      const double d0 = std::max(double(depth) - rr, 0.5 * double(kNear)), d1 = double(depth) + rr;
      const int tiles = axis == 0 ? g.tiles_x : g.tiles_y, size = axis == 0 ? g.width : g.height, tile = axis == 0 ? g.tile_w : g.tile_h;
      const double edge = double(1 + int(r.uniform(0, float(tiles - 1)))) * tile - sign;  // the pixel before the margin
      const double ndc = 2 * edge / size - 1, q = (ndc + p[2][axis]) / p[axis][axis];
      // lo = min over d of (c - r) / d: at d1 when c - r > 0; hi = max of (c + r) / d: at d0 when c + r > 0.
      const double num = q * (sign < 0 ? (q > 0 ? d1 : d0) : (q > 0 ? d0 : d1));
      c[axis] = float(num - sign * rr);
    }
    cases.push_back({glm::vec4(c, radius)});
  }
  cases.push_back({glm::vec4(0, 0, 0, 0)});          // on the camera, radius 0
  cases.push_back({glm::vec4(0, 0, 0, 1)});          // around the camera
  cases.push_back({glm::vec4(0, 0, 5, 1)});          // wholly behind it
  cases.push_back({glm::vec4(0, 0, -1000, 2000)});   // the whole screen
  const auto gpu = test::run_glsl_twin(zbin_twin(rig, 1024, "vec4(sphere_tiles(a.xyz, a.w))"), cases);
  const double P[2] = {p[0][0], p[1][1]}, O[2] = {p[2][0], p[2][1]}, W[2] = {double(g.width), double(g.height)};
  const double T[2] = {double(g.tile_w), double(g.tile_h)}, u = 0x1p-24;
  std::size_t failed = 0, in_band = 0, empty = 0, either = 0, grazing = 0;
  double widest = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const glm::vec4 c = cases[i].a;
    const TileRect cpu = sphere_tiles(rig.camera, g, glm::vec3(c), c.w);
    const glm::ivec4 want(cpu.lo, cpu.hi), got(gpu[i]);
    const double rr = double(c.w) * double(1.f + 1e-5f) + double(1e-6f), dr = 2 * u * rr;
    const double d0 = std::max(-double(c.z) - rr, 0.5 * double(kNear)), d1 = -double(c.z) + rr;
    const double dd = u * (std::abs(double(c.z)) + rr) + dr;
    empty += cpu.lo.x > cpu.hi.x;
    if (std::abs(d1 - d0) <= 2 * dd) {  // empty or not: within the rounding of d0 and d1
      either += got != want;
      continue;
    }
    bool ok = got == want || d1 >= d0, near_edge = false;
    for (int e = 0; e < 4 && d1 >= d0; ++e) {
      const int axis = e % 2, sign = e < 2 ? -1 : 1;  // lo (x, y) then hi (x, y)
      const double num = double(c[axis]) + sign * rr, q = sign < 0 ? std::min(num / d0, num / d1) : std::max(num / d0, num / d1);
      const double ndc = q * P[axis] - O[axis], px = (ndc * 0.5 + 0.5) * W[axis] + sign, exact = px / T[axis];
      near_edge |= std::abs(exact - std::round(exact)) < 1e-3;
      // d0 is exact where half the near plane is taken (its max more than dd from the box's side).
      const double dd0 = -double(c.z) - rr < 0.5 * double(kNear) - dd ? 0.0 : dd;
      const double qmax = std::max(std::abs(num / d0), std::abs(num / d1)), dnum = u * std::abs(num) + dr;
      double band = 0;
      for (double v : {5 * u, u}) {
        const double dq = std::max(dnum / d0 + std::abs(num / d0) * (dd0 / d0 + v), dnum / d1 + std::abs(num / d1) * (dd / d1 + v));
        const double dndc = P[axis] * dq + u * qmax * P[axis] + u * (qmax * P[axis] + std::abs(O[axis]));
        const double dpx = W[axis] / 2 * dndc + u * W[axis] * (std::abs(ndc) / 2 + 0.5) + 2 * u * (std::abs(px) + 1);
        band += dpx / T[axis] + v * std::abs(exact);
      }
      if (std::abs(exact) < 2 * (axis == 0 ? g.tiles_x : g.tiles_y)) widest = std::max(widest, band);  // (on the screen or near it)
      if (got[e] == want[e]) continue;
      const double boundary = std::max(got[e], want[e]);
      ok = ok && std::abs(got[e] - want[e]) == 1 && std::abs(exact - boundary) <= band;
    }
    grazing += near_edge;
    if (got == want) continue;
    if (ok) {
      ++in_band;
      continue;
    }
    if (failed++ < 5)
      ADD_FAILURE() << "GLSL tiles " << got.x << "," << got.y << " .. " << got.z << "," << got.w << ", C++ " << want.x << ","
                    << want.y << " .. " << want.z << "," << want.w << " for the sphere " << test::str(c);
  }
  EXPECT_EQ(failed, 0u);
  EXPECT_GT(empty, 100u) << "cases wholly nearer than the near plane";
  EXPECT_GT(grazing, 2000u) << "cases with an end within 1e-3 tiles of a tile's edge";
  std::printf("sphere_tiles: %zu cases (%zu empty, %zu with an end within 1e-3 tiles of an edge), %zu differ within the "
              "rounding band (at most %.2g tiles wide near the screen), %zu at the emptiness's\n",
              cases.size(), empty, grazing, in_band, widest, either);
}

}  // namespace
}  // namespace lp::ch09
