// Chapter 09's GLSL against its C++ twin (glsl_twin.h): light_pair.glsl, the shading of one
// (surface, light) pair from the records pack_cluster_lights() precomputes, and grid.glsl's
// capsule_meets_box, the tubes' binning.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "chapters/01_forward/blinn_phong.h"
#include "chapters/02_gbuffer/gbuffer.h"
#include "chapters/02_gbuffer/layout.h"
#include "chapters/03_light_volumes/light_instances.h"
#include "chapters/09_clustered/clustered_lights.h"
#include "tests/unit/capsule_cases.h"
#include "tests/unit/glsl_twin.h"

namespace lp::ch09 {
namespace {

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
      if (!away) EXPECT_EQ(cpu.back().x, 1.f) << "the C++ twin drops a touching capsule";
      if (away) EXPECT_EQ(cpu.back().x, 0.f) << "the C++ twin bins a capsule 3 radii away";
    }
  const auto gpu = test::run_glsl_twin({{"09_clustered/shaders/grid.glsl"},
                                        "vec4(capsule_meets_box(a.xyz, b.xyz, a.w, Box(c.xyz, d.xyz), b.w) ? 1.0 : 0.0)"},
                                       cases);
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 1, test::TwinTolerance{0, 0}, [&](std::size_t i) {
    return "ends " + test::str(cases[i].a) + " " + test::str(cases[i].b) + " box " + test::str(cases[i].c) + " " +
           test::str(cases[i].d);
  }));
}

}  // namespace
}  // namespace lp::ch09
