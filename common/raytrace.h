#pragma once
// The ray-traced ground truth's plumbing (chapters 06-08 measure shadows, ambient occlusion
// and one-bounce indirect light against it): Intel Embree 3 over every instance of a scene,
// closest-hit and any-hit queries, the primary rays of the rasterised pixels, images traced
// over all cores with per-pixel random streams, and an on-disk cache of the float images.
// What a ray means for lighting (how many, in which directions, weighted how) belongs to
// the chapters; nothing here knows about light.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "common/camera.h"
#include "common/image.h"
#include "common/rng.h"
#include "common/scene.h"

namespace lp {

struct Ray {
  glm::vec3 origin{0};
  glm::vec3 direction{0, 0, -1};  // unit length: t is a distance
  float tmin = 0;
  float tmax = std::numeric_limits<float>::infinity();
};

struct Hit {
  float t = 0;                        // distance along the ray
  glm::vec3 position{0};              // world; interpolated from the triangle's world vertices
  glm::vec3 geometric_normal{0};      // world, unit; the triangle's front side (glTF winding)
  glm::vec3 shading_normal{0};        // world, unit; the interpolated vertex normal
  glm::vec2 uv{0};
  int material = 0;                   // index into Scene::materials
  int instance = 0;                   // index into Scene::instances
  int triangle = 0;                   // within the instance, primitives in order
  bool front_face = true;             // the ray came from the side geometric_normal points to
  float error = 0;                    // bound on position's rounding error (see spawn_origin)
};

// One bounding volume hierarchy over every triangle of every instance, in world space.
// Both sides of a triangle are hit (no culling; Hit::front_face tells which side).
// Queries are const and thread-safe. Throws Error (what and where) for a scene with no
// triangles, an index past the vertices, a mesh that does not exist or a non-finite vertex.
class RayScene {
 public:
  explicit RayScene(const Scene& scene);
  ~RayScene();
  RayScene(RayScene&&) noexcept;
  RayScene& operator=(RayScene&&) noexcept;
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // Whether any surface lies at a distance in [tmin, tmax] along the ray (any hit: cheaper).
  bool occluded(const Ray& ray) const;
  // The closest surface in [tmin, tmax] along the ray.
  std::optional<Hit> intersect(const Ray& ray) const;
  bool occluded(glm::vec3 origin, glm::vec3 direction, float tmax) const { return occluded(Ray{origin, direction, 0, tmax}); }
  std::optional<Hit> intersect(glm::vec3 origin, glm::vec3 direction, float tmin, float tmax) const {
    return intersect(Ray{origin, direction, tmin, tmax});
  }

  std::size_t triangle_count() const;
  // Whether scene material `material` is glTF doubleSided (false for an index out of range).
  bool double_sided(int material) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// [self-intersection]
// A secondary ray must not hit the surface it leaves. Its origin is moved off the surface
// along the normal, to the side the ray goes, by more than the position's rounding error.
// A float coordinate of magnitude m is exact to half an ulp, m * 2^-24; interpolating a
// hit from its triangle's vertices (or reconstructing it from depth) adds a few ulps of
// the largest coordinate involved. 2^-16 * max(1 m, m) is 128 to 256 ulps of that size: far
// above the rounding of a hit (so no ray starts inside its own surface), yet 15 um at 1 m
// and 1.5 mm at 100 m (so contact occlusion is kept). Positions with a larger error (D24
// depth far from the camera) pass theirs as `error`.
inline constexpr float kSpawnRelativeOffset = 0x1p-16f;
float position_error(glm::vec3 position);  // kSpawnRelativeOffset * max(1, |position|inf)
glm::vec3 spawn_origin(glm::vec3 position, glm::vec3 normal, glm::vec3 direction, float error = 0);
// [/self-intersection]

// A surface point to trace secondary rays from: a primary hit, or a G-buffer pixel.
struct SurfacePoint {
  glm::vec3 position{0};
  glm::vec3 normal{0, 1, 0};  // unit, on the side the point is seen from
  float error = 0;            // passed to spawn_origin
  // A ray of length `length` leaving the point in the unit direction.
  Ray ray(glm::vec3 direction, float length) const;
  // A ray toward `target` (a light, a point on an emitter) that stops short of it by the
  // target's own offset, so a target lying on a surface is not hidden by that surface.
  Ray ray_towards(glm::vec3 target, float target_error = 0) const;
};

// The rays of the rasterised pixels: through the centre (x + 0.5, y + 0.5) of pixel (x, y),
// with rows top to bottom like ImageF (row y is OpenGL's window row height - 1 - y). A ray
// starts on the near plane and ends on the far plane, which is what clipping keeps.
class PrimaryRays {
 public:
  PrimaryRays(const FrameCamera& camera, int width, int height);
  Ray operator()(int x, int y) const;

 private:
  glm::dmat4 inverse_view_projection_;
  int width_, height_;
};

// Width and height between 1 and 16384: Error otherwise (names `what`).
void check_image_size(int width, int height, const std::string& what);

// The cores this process may run on (its CPU affinity, as nproc counts them).
int available_cores();

// Calls row(y) for y in [0, height) on `threads` threads (0: available_cores()). Rows are handed
// out one at a time, so uneven rows balance; the first exception is rethrown after all join.
void parallel_rows(int height, int threads, const std::function<void(int y)>& row);

// An image whose pixel (x, y) is written by pixel(x, y, rng, out): `out` holds `channels`
// zeros, `rng` is the pixel's own stream pixel_rng(seed, y * width + x). The image is the
// same bits for any thread count.
using PixelFunction = std::function<void(int x, int y, Pcg32& rng, float* out)>;
ImageF trace_image(int width, int height, int channels, std::uint64_t seed, const PixelFunction& pixel, int threads = 0);

// The closest surface the rasteriser would show along a camera ray: back faces of
// single-sided materials are passed (the rasteriser culls them), doubleSided ones are hit.
std::optional<Hit> visible_hit(const RayScene& scene, Ray ray);
// Every pixel's visible_hit, top row first; nullopt where the ray leaves the scene.
std::vector<std::optional<Hit>> primary_hits(const RayScene& scene, const FrameCamera& camera, int width, int height,
                                             int threads = 0);
// The points the primary hits see, normals turned toward the camera; nullopt for the sky.
std::vector<std::optional<SurfacePoint>> surface_points(const std::vector<std::optional<Hit>>& hits);
// The points of float images of world positions and unit normals (the G-buffer's, read
// back): a zero normal is the sky, as the G-buffer writes it. `error` as in spawn_origin:
// one bound for every pixel, or error(x, y, position) per pixel (e.g. chapter 02's bound
// for a position reconstructed from depth, which grows with the distance).
using PositionError = std::function<float(int x, int y, glm::vec3 position)>;
std::vector<std::optional<SurfacePoint>> surface_points(const ImageF& position, const ImageF& normal,
                                                        const PositionError& error);
std::vector<std::optional<SurfacePoint>> surface_points(const ImageF& position, const ImageF& normal, float error = 0);

// --- The cache of ground-truth images ------------------------------------------------------
// [truth-cache]
// A truth is recomputed only when something it depends on changes: the key holds the
// geometry, materials and lights actually loaded (hashed), the camera's matrices, the size
// and the estimator's own settings (method, samples, radius, seed: the caller's string).
// kTruthCacheVersion is in the key too: bump it when this file changes what a ray returns.
inline constexpr int kTruthCacheVersion = 2;  // 2: primary hits pass single-sided back faces

struct TruthKey {
  std::string text;  // every line of the key; the file name is its hash, the text is checked
  int width = 0, height = 0;
};
TruthKey truth_key(const Scene& scene, const FrameCamera& camera, int width, int height, const std::string& settings);

// 64-bit FNV-1a of what a ray tracer or a lighting estimator reads from the scene.
std::uint64_t scene_fingerprint(const Scene& scene);

// Where truths are kept: $LIGHTPASS_TRUTH_CACHE, else out/truth-cache under the source root
// (git-ignored).
std::filesystem::path truth_cache_dir();

// The image stored under `key`, or compute()'s, stored (1 or 3 channels, PFM, exact floats).
// A missing, unreadable or mismatched entry is recomputed, never trusted.
ImageF cached_image(const TruthKey& key, const std::function<ImageF()>& compute,
                    const std::filesystem::path& dir = truth_cache_dir());
// [/truth-cache]

}  // namespace lp
