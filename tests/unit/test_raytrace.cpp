// The ray-traced ground truth's plumbing (common/raytrace.h) on the CPU: hits and their
// attributes, the primary rays' conventions, the self-intersection offset, analytic
// ambient occlusion and its Monte Carlo error, determinism, bad scenes and the cache.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

#include "common/error.h"
#include "common/paths.h"
#include "common/raytrace.h"
#include "tests/unit/raytrace_ao.h"

using namespace lp;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A unit square in its XZ plane, front (counter-clockwise) side +Y, uv over the square.
void add_quad_mesh(Scene& s, int material) {
  auto first_vertex = static_cast<std::uint32_t>(s.vertices.size());
  for (glm::vec2 c : {glm::vec2(0, 0), glm::vec2(0, 1), glm::vec2(1, 1), glm::vec2(1, 0)})
    s.vertices.push_back(Vertex{glm::vec3(c.x - 0.5f, 0, c.y - 0.5f), glm::vec3(0, 1, 0), c, glm::vec4(1, 0, 0, 1)});
  auto first_index = static_cast<std::uint32_t>(s.indices.size());
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) s.indices.push_back(first_vertex + i);
  s.meshes.push_back(Mesh{"quad", {Primitive{first_index, 6, material}}});
}

// Quads placed by their model matrices; instance i uses mesh i % 2 (material i % 2).
Scene quads(const std::vector<glm::mat4>& models) {
  Scene s;
  s.path = "quads (test)";
  s.materials = {Material{"first"}, Material{"second"}};
  add_quad_mesh(s, 0);
  add_quad_mesh(s, 1);
  for (std::size_t i = 0; i < models.size(); ++i)
    s.instances.push_back(Instance{"quad " + std::to_string(i), static_cast<int>(i % 2), models[i], {}});
  return s;
}

glm::mat4 floor_model(float size) { return glm::scale(glm::mat4(1), glm::vec3(size, 1, size)); }

// A wall in the plane x = d, facing -X (toward the origin), covering |y|, |z| <= half.
glm::mat4 wall_model(float d, float half) {
  glm::mat4 m = glm::translate(glm::mat4(1), glm::vec3(d, 0, 0));
  m = glm::rotate(m, glm::radians(90.f), glm::vec3(0, 0, 1));  // +Y -> -X, local x -> +Y
  return glm::scale(m, glm::vec3(2 * half, 1, 2 * half));
}

// The surface point straight below (x, 1, z), as a primary hit would give it.
SurfacePoint floor_point(const RayScene& scene, float x, float z) {
  auto hit = scene.intersect(glm::vec3(x, 1, z), glm::vec3(0, -1, 0), 0, 2);
  EXPECT_TRUE(hit.has_value());
  return surface_points({hit})[0].value();
}

// [ao-wall-derivation]
// The fraction of cosine-weighted directions from a point on a floor that hit a wall at
// distance d before length R, the wall perpendicular to the floor and unbounded (for these
// rays: taller than R and wider than 2R).
// Malley's method makes the derivation short: a cosine-weighted direction is a uniform
// point (x, z) of the unit disk lifted onto the hemisphere, and its component toward the
// wall is that point's coordinate along the wall's normal, say x. The ray meets the wall's
// plane at distance d / x, so it is occluded within R exactly when x >= a = d / R. The
// uniform disk puts mass (area)/pi on the circular segment x >= a:
//   occlusion(a) = (acos(a) - a sqrt(1 - a^2)) / pi   for 0 <= a <= 1, and 0 for a >= 1.
// (a = 0 gives 1/2: the half of the hemisphere that faces the wall.)
double wall_occlusion(double a) { return a >= 1 ? 0 : (std::acos(a) - a * std::sqrt(1 - a * a)) / kPi; }
// [/ao-wall-derivation]

double estimate(const RayScene& scene, const SurfacePoint& p, float radius, int samples, std::uint64_t seed,
                std::uint64_t stream) {
  Pcg32 rng = pixel_rng(seed, stream);
  return double(test::occluded_rays(scene, p, radius, samples, rng)) / samples;
}

}  // namespace

// --- Hits -----------------------------------------------------------------------------------

TEST(RayTrace, HitReportsWorldSpaceAttributesOfATransformedInstance) {
  // Instance 1 (mesh and material 1): tilted 30 degrees about X, stretched, moved.
  glm::mat4 model = glm::translate(glm::mat4(1), glm::vec3(10, 2, -3));
  model = glm::rotate(model, glm::radians(30.f), glm::vec3(1, 0, 0));
  model = glm::scale(model, glm::vec3(2, 1, 4));
  RayScene scene(quads({glm::translate(glm::mat4(1), glm::vec3(0, -50, 0)), model}));
  EXPECT_EQ(scene.triangle_count(), 4u);

  glm::vec3 normal = glm::normalize(glm::vec3(model * glm::vec4(0, 1, 0, 0)));
  glm::vec3 target = glm::vec3(model * glm::vec4(0.25f, 0, -0.3f, 1));  // uv (0.75, 0.2)
  glm::vec3 origin = target + 5.f * normal;
  auto hit = scene.intersect(origin, -normal, 0, 100);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t, 5, 1e-5);
  EXPECT_LT(glm::length(hit->position - target), 1e-5f);
  EXPECT_LT(glm::length(hit->geometric_normal - normal), 1e-6f);
  EXPECT_LT(glm::length(hit->shading_normal - normal), 1e-6f);
  EXPECT_NEAR(hit->uv.x, 0.75f, 1e-6);
  EXPECT_NEAR(hit->uv.y, 0.2f, 1e-6);
  EXPECT_EQ(hit->instance, 1);
  EXPECT_EQ(hit->material, 1);
  EXPECT_TRUE(hit->front_face);

  auto behind = scene.intersect(target - 5.f * normal, normal, 0, 100);  // from the back
  ASSERT_TRUE(behind.has_value());
  EXPECT_FALSE(behind->front_face);
  EXPECT_LT(glm::length(behind->geometric_normal - normal), 1e-6f) << "the normal belongs to the triangle, not the ray";
}

TEST(RayTrace, MirroredInstanceKeepsItsFrontSideAsGltfDefinesIt) {
  // A negative determinant reverses the winding (glTF 2.0, 3.7.4): the front stays +Y.
  RayScene scene(quads({glm::scale(glm::mat4(1), glm::vec3(-1, 1, 1))}));
  auto hit = scene.intersect(glm::vec3(0.1f, 1, 0.2f), glm::vec3(0, -1, 0), 0, 10);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->geometric_normal, glm::vec3(0, 1, 0));
  EXPECT_TRUE(hit->front_face);
}

TEST(RayTrace, QueriesRespectTheirInterval) {
  RayScene scene(quads({floor_model(4)}));  // the plane y = 0, 1 m below the origin used
  const glm::vec3 o(0.3f, 1, 0.1f), down(0, -1, 0);
  EXPECT_TRUE(scene.occluded(o, down, 1.001f));
  EXPECT_FALSE(scene.occluded(o, down, 0.999f));
  EXPECT_TRUE(scene.intersect(o, down, 0, 1.001f).has_value());
  EXPECT_FALSE(scene.intersect(o, down, 0, 0.999f).has_value());
  EXPECT_FALSE(scene.intersect(o, down, 1.001f, 5).has_value()) << "tmin past the plane";
  EXPECT_FALSE(scene.occluded(o, -down, 100)) << "away from the plane";
  EXPECT_FALSE(scene.occluded(glm::vec3(NAN, 1, 0), down, 5)) << "a NaN ray hits nothing (and does not crash)";
}

TEST(RayTrace, OccludedAgreesWithIntersectOnAnAssetScene) {
  Scene atrium = load_scene(from_root("assets/atrium/atrium.gltf"));
  RayScene scene(atrium);
  glm::vec3 centre = 0.5f * (atrium.bounds_min + atrium.bounds_max);
  float extent = glm::length(atrium.bounds_max - atrium.bounds_min);
  Pcg32 rng(7, 0);
  int hits = 0, disagreements = 0;
  for (int i = 0; i < 20000; ++i) {
    glm::vec3 o = centre + extent * 0.4f * glm::vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f);
    glm::vec3 d = test::cosine_direction(glm::normalize(glm::vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, 0.3f)),
                                         rng.uniform(), rng.uniform());
    float length = extent * rng.uniform();
    bool any = scene.occluded(o, d, length);
    auto closest = scene.intersect(o, d, 0, length);
    disagreements += any != closest.has_value();
    hits += any;
  }
  EXPECT_EQ(disagreements, 0);
  EXPECT_GT(hits, 1000) << "the rays must hit often enough for the comparison to mean something";
}

TEST(RayTrace, RayTowardsATargetStopsShortOfTheSurfaceTheTargetLiesOn) {
  // A floor, a ceiling 3 m up with a "light" on it, and a blocker that can be put between.
  glm::mat4 ceiling = glm::translate(glm::mat4(1), glm::vec3(0, 3, 0)) *
                      glm::rotate(glm::mat4(1), glm::radians(180.f), glm::vec3(1, 0, 0)) * floor_model(10);
  glm::mat4 blocker = glm::translate(glm::mat4(1), glm::vec3(0, 1.5f, 0));
  RayScene open(quads({floor_model(10), ceiling}));
  RayScene blocked(quads({floor_model(10), ceiling, blocker}));
  const glm::vec3 light(0.2f, 3, 0.1f);  // exactly on the ceiling
  SurfacePoint p = floor_point(open, 0, 0);
  EXPECT_FALSE(open.occluded(p.ray_towards(light))) << "the ceiling the light is on does not hide it";
  EXPECT_TRUE(blocked.occluded(p.ray_towards(light)));
  Ray r = p.ray_towards(light);
  EXPECT_NEAR(glm::length(r.direction), 1, 1e-6);
  EXPECT_NEAR(r.tmax, glm::length(light - r.origin) - position_error(light), 1e-6);
  EXPECT_EQ(p.ray_towards(p.position).tmax, 0.f) << "a target at the point itself: an empty ray";
}

// --- Primary rays -----------------------------------------------------------------------

TEST(RayTrace, PrimaryRayGoesThroughThePixelCentreFromTheNearPlaneTopRowFirst) {
  Camera c;
  c.world = glm::inverse(glm::lookAt(glm::vec3(3, 2, 5), glm::vec3(0, 0.5f, 0), glm::vec3(0, 1, 0)));
  c.znear = 0.1f;
  c.zfar = 100;
  const int w = 37, h = 23;  // odd sizes: the centre of a pixel is not the centre of the image
  FrameCamera fc = frame_camera(c, float(w) / h);
  PrimaryRays rays(fc, w, h);
  for (int y : {0, 11, 22})
    for (int x : {0, 18, 36}) {
      Ray r = rays(x, y);
      EXPECT_NEAR(glm::length(r.direction), 1, 1e-6);
      glm::vec3 view_origin = glm::vec3(fc.view * glm::vec4(r.origin, 1));
      EXPECT_NEAR(view_origin.z, -c.znear, 1e-6) << "starts on the near plane";
      glm::vec3 view_end = glm::vec3(fc.view * glm::vec4(r.origin + r.tmax * r.direction, 1));
      EXPECT_NEAR(view_end.z, -c.zfar, 1e-3) << "ends on the far plane";
      // Project a point along the ray back: it lands on the pixel centre, OpenGL's window
      // row h - 1 - y (rows of ImageF run top to bottom, OpenGL's bottom to top).
      glm::vec4 clip = fc.view_projection() * glm::vec4(r.origin + 3.f * r.direction, 1);
      glm::vec2 window = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(w, h);
      EXPECT_NEAR(window.x, x + 0.5f, 1e-3);
      EXPECT_NEAR(window.y, (h - 1 - y) + 0.5f, 1e-3);
    }
  // Row 0 looks up: above the centre of the view.
  glm::vec3 top = glm::vec3(fc.view * glm::vec4(rays(18, 0).direction, 0));
  EXPECT_GT(top.y, 0);
}

TEST(RayTrace, SurfacePointsFromImagesTreatAZeroNormalAsSky) {
  ImageF position = ImageF::blank(2, 1, 4), normal = ImageF::blank(2, 1, 3);
  position.at(0, 0, 0) = 200;  // 200 m from the origin
  normal.at(0, 0, 1) = 2;      // not unit: normalised
  auto points = surface_points(position, normal, 0);
  ASSERT_TRUE(points[0].has_value());
  EXPECT_EQ(points[0]->normal, glm::vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(points[0]->error, 200 * kSpawnRelativeOffset);
  EXPECT_FALSE(points[1].has_value());
  EXPECT_THROW(surface_points(position, ImageF::blank(3, 1, 3)), Error);
}

// --- Ambient occlusion against analytic answers -------------------------------------------

TEST(RayTrace, UnoccludedPlaneHasZeroOcclusion) {
  // Points a camera sees on a lone plane, near the origin and 1 km from it (where a float
  // step is 61 um): not one of the rays may find the plane it leaves. Exact, no tolerance.
  for (glm::vec3 offset : {glm::vec3(0), glm::vec3(1000, 0, -1000)}) {
    RayScene scene(quads({glm::translate(glm::mat4(1), offset) * floor_model(40)}));
    Camera c;
    c.world = glm::inverse(glm::lookAt(offset + glm::vec3(0, 3, 6), offset, glm::vec3(0, 1, 0)));
    auto points = surface_points(primary_hits(scene, frame_camera(c, 16.f / 9), 64, 36));
    int seen = 0, occluded = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!points[i]) continue;
      ++seen;
      Pcg32 rng = pixel_rng(1, i);
      occluded += test::occluded_rays(scene, *points[i], 2.f, 256, rng);
    }
    EXPECT_GT(seen, 64 * 36 / 4) << "the camera must see the plane";
    EXPECT_EQ(occluded, 0) << "plane offset by " << offset.x;
  }
}

TEST(RayTrace, PointBesideAWallHasTheAnalyticCosineWeightedOcclusion) {
  const float radius = 1.5f;
  const int samples = 20000;
  for (double a : {0.05, 0.2, 0.5, 0.8, 0.95}) {
    RayScene scene(quads({floor_model(20 * radius), wall_model(float(a) * radius, 2 * radius)}));
    double p = wall_occlusion(a), got = estimate(scene, floor_point(scene, 0, 0), radius, samples, 3, 0);
    // The estimate is a binomial proportion: standard error sqrt(p (1 - p) / N). Four of
    // them: a correct tracer fails with probability 6e-5 (and the seed is fixed).
    double se = std::sqrt(p * (1 - p) / samples);
    EXPECT_NEAR(got, p, 4 * se) << "d / R = " << a;
  }
  // Out of reach (d > R): no ray can hit the wall, exactly.
  RayScene far(quads({floor_model(20 * radius), wall_model(1.2f * radius, 2 * radius)}));
  EXPECT_EQ(estimate(far, floor_point(far, 0, 0), radius, samples, 3, 0), 0.0);
}

TEST(RayTrace, MonteCarloErrorShrinksAsOneOverSqrtN) {
  // The RMS error over M independent estimates (4 wall distances x 100 seeds) at N and 16N
  // samples. Expected: sqrt(mean p (1 - p) / N) each, a ratio of 4. The RMS of M errors is
  // itself uncertain by a relative 1 / sqrt(2M) = 3.5%, the ratio by sqrt(2) times that
  // (5%): the bands below are three of those.
  const float radius = 1;
  const int n = 64, seeds = 100;
  const double kRmsBand = 3 * std::sqrt(1.0 / (2 * 4 * seeds)), kRatioBand = std::sqrt(2.0) * kRmsBand;
  double sum_sq[2] = {0, 0}, variance = 0;
  int m = 0;
  for (double a : {0.1, 0.3, 0.5, 0.7}) {
    RayScene scene(quads({floor_model(20 * radius), wall_model(float(a) * radius, 2 * radius)}));
    SurfacePoint p = floor_point(scene, 0, 0);
    double truth = wall_occlusion(a);
    for (int s = 0; s < seeds; ++s, ++m) {
      for (int k = 0; k < 2; ++k) {
        double e = estimate(scene, p, radius, k ? 16 * n : n, 11 + k, std::uint64_t(m)) - truth;
        sum_sq[k] += e * e;
      }
      variance += truth * (1 - truth);
    }
  }
  double rms_n = std::sqrt(sum_sq[0] / m), rms_16n = std::sqrt(sum_sq[1] / m);
  double expected_n = std::sqrt(variance / m / n), expected_16n = std::sqrt(variance / m / (16 * n));
  EXPECT_NEAR(rms_n / expected_n, 1, kRmsBand);
  EXPECT_NEAR(rms_16n / expected_16n, 1, kRmsBand);
  EXPECT_NEAR(rms_n / rms_16n / 4, 1, kRatioBand) << "RMS at N " << rms_n << ", at 16N " << rms_16n;
}

// --- Determinism ----------------------------------------------------------------------------

namespace {
// [trace-ao]
// Ambient occlusion of the surfaces a camera sees: 16 rays of length 0.5 m per pixel.
ImageF ao_image(const RayScene& scene, const Scene& s, std::uint64_t seed, int threads) {
  const int w = 64, h = 36;
  FrameCamera camera = frame_camera(s.cameras.at(0), float(w) / h);
  auto points = surface_points(primary_hits(scene, camera, w, h, threads));
  return trace_image(w, h, 1, seed, [&](int x, int y, Pcg32& rng, float* out) {
    if (const auto& p = points[std::size_t(y) * w + x])
      out[0] = float(test::occluded_rays(scene, *p, 0.5f, 16, rng)) / 16;
  }, threads);
}
// [/trace-ao]
}  // namespace

TEST(RayTrace, SameSeedGivesTheSameBitsForAnyThreadCountAndAnotherSeedDiffers) {
  Scene s = load_scene(from_root("assets/cornell/cornell.gltf"));
  RayScene scene(s);
  ImageF one = ao_image(scene, s, 42, 1);
  for (int threads : {2, 3, 8}) {
    ImageF many = ao_image(scene, s, 42, threads);
    ASSERT_EQ(many.data.size(), one.data.size());
    EXPECT_EQ(std::memcmp(many.data.data(), one.data.data(), one.data.size() * sizeof(float)), 0) << threads << " threads";
  }
  ImageF other = ao_image(scene, s, 43, 2);
  std::size_t differ = 0, occluded = 0;
  for (std::size_t i = 0; i < one.data.size(); ++i) {
    differ += one.data[i] != other.data[i];
    occluded += one.data[i] > 0 && one.data[i] < 1;
  }
  ASSERT_GT(occluded, one.data.size() / 10) << "the Cornell box's corners must be partly occluded";
  EXPECT_GT(differ, occluded / 4) << "another seed, other samples";
}

TEST(RayTrace, RebuildingTheHierarchyGivesTheSameBits) {
  // Embree builds in parallel (TBB); the hierarchy, and so which of two surfaces at equal
  // distance a ray reports, must not depend on how the build was scheduled.
  Scene s = load_scene(from_root("assets/atrium/atrium.gltf"));
  RayScene first(s);
  ImageF reference = ao_image(first, s, 9, 2);
  std::size_t occluded = 0;
  for (float v : reference.data) occluded += v > 0;
  ASSERT_GT(occluded, reference.data.size() / 50) << "some pixels must see occluders";
  for (int build = 0; build < 3; ++build) {
    RayScene again(s);
    ImageF rebuilt = ao_image(again, s, 9, 2);
    EXPECT_EQ(std::memcmp(rebuilt.data.data(), reference.data.data(), reference.data.size() * sizeof(float)), 0);
  }
}

TEST(RayTrace, ParallelRowsRethrowsAWorkersException) {
  EXPECT_THROW(parallel_rows(100, 4, [](int y) { if (y == 57) throw Error("row 57"); }), Error);
  EXPECT_THROW(trace_image(0, 10, 1, 0, [](int, int, Pcg32&, float*) {}), Error);
}

// --- Bad scenes ---------------------------------------------------------------------------

namespace {
std::string error_of(const Scene& s) {
  try {
    RayScene scene(s);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST(RayTrace, SceneWithoutTrianglesIsAnError) {
  Scene empty;
  empty.path = "empty.gltf";
  EXPECT_EQ(error_of(empty), "ray tracer: empty.gltf: the scene has no triangles to trace");
  Scene no_indices = quads({glm::mat4(1)});
  no_indices.meshes[0].primitives[0].index_count = 0;
  EXPECT_EQ(error_of(no_indices), "ray tracer: quads (test): the scene has no triangles to trace");
}

TEST(RayTrace, MalformedSceneIsAnErrorThatSaysWhatAndWhere) {
  Scene bad_index = quads({glm::mat4(1)});
  bad_index.indices[4] = 99;
  EXPECT_EQ(error_of(bad_index), "ray tracer: quads (test): instance 0 'quad 0': index 99 is past the 8 vertices");
  Scene bad_mesh = quads({glm::mat4(1)});
  bad_mesh.instances[0].mesh = 7;
  EXPECT_EQ(error_of(bad_mesh), "ray tracer: quads (test): instance 0 'quad 0' uses mesh 7, which does not exist");
  Scene past_end = quads({glm::mat4(1)});
  past_end.meshes[0].primitives[0].first_index = 0xfffffff0u;
  EXPECT_NE(error_of(past_end).find("reads indices past the end"), std::string::npos);
  Scene not_finite = quads({glm::mat4(1)});
  not_finite.vertices[2].position.y = NAN;
  EXPECT_EQ(error_of(not_finite), "ray tracer: quads (test): instance 0 'quad 0': vertex 2 is not finite in world space");
  Scene bad_material = quads({glm::mat4(1)});
  bad_material.meshes[0].primitives[0].material = 5;
  EXPECT_NE(error_of(bad_material).find("uses material 5, which does not exist"), std::string::npos);
  // A file that is not glTF never reaches the ray tracer: the loader says so.
  EXPECT_THROW(load_scene(from_root("tests/data/malformed.gltf")), Error);
}

// --- The cache ----------------------------------------------------------------------------

namespace {
struct TempDir {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("lightpass_truth_test_" + std::to_string(::getpid()));
  TempDir() { std::filesystem::remove_all(path); }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};
}  // namespace

TEST(RayTrace, CacheComputesOncePerKey) {
  TempDir dir;
  Scene s = quads({glm::mat4(1)});
  FrameCamera camera = frame_camera(Camera{}, 2.f);
  int calls = 0;
  auto compute = [&] {
    ++calls;
    ImageF img = ImageF::blank(4, 2, 1);
    for (std::size_t i = 0; i < img.data.size(); ++i) img.data[i] = 0.1f * float(i) + float(calls);
    return img;
  };
  TruthKey key = truth_key(s, camera, 4, 2, "ao samples=512 radius=1");
  ImageF first = cached_image(key, compute, dir.path);
  ImageF second = cached_image(key, compute, dir.path);
  EXPECT_EQ(calls, 1) << "the same key is read back, not recomputed";
  EXPECT_EQ(second.data, first.data) << "bit for bit";

  cached_image(truth_key(s, camera, 4, 2, "ao samples=256 radius=1"), compute, dir.path);
  EXPECT_EQ(calls, 2) << "other settings";
  FrameCamera moved = camera;
  moved.view[3][0] = std::nextafter(moved.view[3][0], 1.f);
  cached_image(truth_key(s, moved, 4, 2, "ao samples=512 radius=1"), compute, dir.path);
  EXPECT_EQ(calls, 3) << "a camera one ulp away";
  Scene edited = s;
  edited.vertices[1].position.y += 0.001f;
  cached_image(truth_key(edited, camera, 4, 2, "ao samples=512 radius=1"), compute, dir.path);
  EXPECT_EQ(calls, 4) << "another scene";
  cached_image(key, compute, dir.path);
  EXPECT_EQ(calls, 4) << "the first entry is still there";
  Scene lit = s, neon = s, moved_file = s;
  lit.lights.push_back(Light{});
  neon.node_extras.push_back(NodeExtras{"sign", glm::mat4(1), R"({"neon":[]})"});
  moved_file.path = "/elsewhere/" + s.path.filename().string();
  EXPECT_NE(truth_key(lit, camera, 4, 2, "ao").text, truth_key(s, camera, 4, 2, "ao").text) << "a light";
  EXPECT_NE(truth_key(neon, camera, 4, 2, "ao").text, truth_key(s, camera, 4, 2, "ao").text) << "a node's extras";
  EXPECT_EQ(truth_key(moved_file, camera, 4, 2, "ao").text, truth_key(s, camera, 4, 2, "ao").text)
      << "the same content in another folder (the GPU machine's copy of the tree)";
  EXPECT_NE(key.text.find("v" + std::to_string(kTruthCacheVersion) + "\n"), std::string::npos) << key.text;
}

TEST(RayTrace, CacheNeverTrustsABrokenEntry) {
  TempDir dir;
  Scene s = quads({glm::mat4(1)});
  TruthKey key = truth_key(s, frame_camera(Camera{}, 2.f), 4, 2, "x");
  int calls = 0;
  auto compute = [&] {
    ++calls;
    return ImageF::blank(4, 2, 3);
  };
  cached_image(key, compute, dir.path);
  for (const auto& entry : std::filesystem::directory_iterator(dir.path))
    if (entry.path().extension() == ".pfm") std::ofstream(entry.path(), std::ios::trunc) << "PF\n4 2\n-1\n";  // no pixels
  cached_image(key, compute, dir.path);
  EXPECT_EQ(calls, 2) << "a truncated image is recomputed";
  cached_image(key, compute, dir.path);
  EXPECT_EQ(calls, 2) << "and stored again";

  EXPECT_THROW(cached_image(truth_key(s, frame_camera(Camera{}, 2.f), 5, 2, "x"), compute, dir.path), Error)
      << "an image of another size than its key";
  EXPECT_THROW(cached_image(key, [] { return ImageF::blank(4, 2, 2); }, dir.path / "other"), Error)
      << "PFM cannot keep two channels";
}
