#include "common/raytrace.h"

#include <embree3/rtcore.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>

#include "common/error.h"
#include "common/paths.h"

namespace lp {

namespace {

// --- Building the hierarchy -------------------------------------------------------------

// One instance's triangles in world space, and what a hit on them reports.
struct InstanceGeometry {
  std::vector<float> positions;         // xyz per vertex, + 1 float: Embree reads 16 bytes at a time
  std::vector<glm::vec3> normals;       // world; zero where the vertex normal was degenerate
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices;   // 3 per triangle, into the arrays above
  std::vector<int> materials;           // per triangle
  bool mirrored = false;                // negative determinant: glTF reverses the front face

  glm::vec3 position(std::uint32_t v) const { return {positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]}; }
  std::size_t triangle_count() const { return materials.size(); }
};

std::string instance_name(const Scene& scene, std::size_t i) {
  const std::string& name = scene.instances[i].name;
  return "instance " + std::to_string(i) + (name.empty() ? "" : " '" + name + "'");
}

// The range of vertices a mesh's primitives reference, with every index checked first.
struct VertexRange {
  std::uint32_t first = 0, count = 0;
};
VertexRange checked_vertex_range(const Scene& scene, const Mesh& mesh, const std::string& where) {
  std::uint32_t lo = UINT32_MAX, hi = 0;
  for (const Primitive& p : mesh.primitives) {
    if (p.index_count % 3 != 0)
      throw Error(where + ": " + std::to_string(p.index_count) + " indices is not a whole number of triangles");
    if (std::size_t(p.first_index) + p.index_count > scene.indices.size())
      throw Error(where + ": a primitive reads indices past the end of the index array");
    if (p.material < 0 || std::size_t(p.material) >= scene.materials.size())
      throw Error(where + ": a primitive uses material " + std::to_string(p.material) + ", which does not exist");
    for (std::uint32_t k = p.first_index; k < p.first_index + p.index_count; ++k) {
      std::uint32_t v = scene.indices[k];
      if (v >= scene.vertices.size())
        throw Error(where + ": index " + std::to_string(v) + " is past the " + std::to_string(scene.vertices.size()) + " vertices");
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  return lo > hi ? VertexRange{} : VertexRange{lo, hi - lo + 1};
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
float max_abs(glm::vec3 v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }
// v normalised; `fallback` where v has no direction (a sliver triangle, opposite normals).
glm::vec3 unit_or(glm::vec3 v, glm::vec3 fallback) {
  float len = glm::length(v);
  return std::isfinite(len) && len > 0 ? v / len : fallback;
}

InstanceGeometry world_geometry(const Scene& scene, std::size_t i) {
  const Instance& inst = scene.instances[i];
  const std::string where = "ray tracer: " + scene.path.string() + ": " + instance_name(scene, i);
  if (inst.mesh < 0 || std::size_t(inst.mesh) >= scene.meshes.size())
    throw Error(where + " uses mesh " + std::to_string(inst.mesh) + ", which does not exist");
  const Mesh& mesh = scene.meshes[inst.mesh];
  VertexRange range = checked_vertex_range(scene, mesh, where);

  InstanceGeometry g;
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(inst.model)));
  g.mirrored = glm::determinant(glm::mat3(inst.model)) < 0;
  g.positions.reserve(3 * std::size_t(range.count) + 1);
  for (std::uint32_t v = 0; v < range.count; ++v) {
    const Vertex& src = scene.vertices[range.first + v];
    glm::vec3 p = glm::vec3(inst.model * glm::vec4(src.position, 1));
    if (!finite(p)) throw Error(where + ": vertex " + std::to_string(range.first + v) + " is not finite in world space");
    g.positions.insert(g.positions.end(), {p.x, p.y, p.z});
    g.normals.push_back(unit_or(normal_matrix * src.normal, glm::vec3(0)));
    g.uvs.push_back(src.uv);
  }
  g.positions.push_back(0);
  for (const Primitive& p : mesh.primitives)
    for (std::uint32_t k = p.first_index; k < p.first_index + p.index_count; k += 3) {
      for (int c = 0; c < 3; ++c) g.indices.push_back(scene.indices[k + c] - range.first);
      g.materials.push_back(p.material);
    }
  return g;
}

const char* embree_error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    default: return "unknown error";
  }
}

// Embree reports errors through a C callback, which must not throw: it records the message
// and the next check() turns it into an Error.
void record_embree_error(void* user, RTCError code, const char* message) noexcept {
  try {
    *static_cast<std::string*>(user) = std::string(embree_error_name(code)) + (message ? std::string(": ") + message : "");
  } catch (...) {
  }
}

}  // namespace

struct RayScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::string embree_message;                // the last error Embree reported
  std::vector<InstanceGeometry> instances;   // by instance index; the BVH shares their buffers
  std::vector<bool> double_sided;            // by material index (glTF doubleSided)
  std::size_t triangles = 0;

  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void check(const std::string& what) {
    RTCError code = rtcGetDeviceError(device);
    if (code != RTC_ERROR_NONE)
      throw Error("ray tracer: " + what + ": " + (embree_message.empty() ? embree_error_name(code) : embree_message));
  }

  void attach(const InstanceGeometry& g, unsigned id) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    check("creating a triangle geometry");
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, g.positions.data(), 0,
                               3 * sizeof(float), g.normals.size());
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, g.indices.data(), 0,
                               3 * sizeof(std::uint32_t), g.triangle_count());
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(scene, geometry, id);
    rtcReleaseGeometry(geometry);  // the scene holds it now
    check("adding instance " + std::to_string(id));
  }
};

RayScene::RayScene(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.device = rtcNewDevice(nullptr);
  if (!m.device) throw Error(std::string("ray tracer: Embree cannot start: ") + embree_error_name(rtcGetDeviceError(nullptr)));
  rtcSetDeviceErrorFunction(m.device, record_embree_error, &m.embree_message);
  m.scene = rtcNewScene(m.device);
  m.check("creating the scene");
  // Robust traversal: no edge between two triangles lets a ray through (watertight), at a
  // small cost. The build quality stays the default (medium): on the book's scenes HIGH
  // changed neither the build (milliseconds) nor the rays per second (per CPU second of a
  // thread) beyond the noise of a shared machine.
  rtcSetSceneFlags(m.scene, RTC_SCENE_FLAG_ROBUST);

  m.instances.reserve(scene.instances.size());
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    m.instances.push_back(world_geometry(scene, i));
    m.triangles += m.instances.back().triangle_count();
  }
  if (m.triangles == 0) throw Error("ray tracer: " + scene.path.string() + ": the scene has no triangles to trace");
  for (const Material& material : scene.materials) m.double_sided.push_back(material.double_sided);
  for (std::size_t i = 0; i < m.instances.size(); ++i)
    if (m.instances[i].triangle_count() > 0) m.attach(m.instances[i], static_cast<unsigned>(i));
  rtcCommitScene(m.scene);
  m.check("building the hierarchy");
}

RayScene::~RayScene() = default;
RayScene::RayScene(RayScene&&) noexcept = default;
RayScene& RayScene::operator=(RayScene&&) noexcept = default;

std::size_t RayScene::triangle_count() const { return impl_->triangles; }

bool RayScene::double_sided(int material) const {
  return material >= 0 && std::size_t(material) < impl_->double_sided.size() && impl_->double_sided[std::size_t(material)];
}

namespace {

// Embree leaves rays with NaN or an empty interval undefined; they hit nothing here.
bool valid(const Ray& r) { return finite(r.origin) && finite(r.direction) && r.tmin >= 0 && r.tmin <= r.tmax; }

RTCRay embree_ray(const Ray& r) {
  RTCRay e{};
  e.org_x = r.origin.x, e.org_y = r.origin.y, e.org_z = r.origin.z;
  e.dir_x = r.direction.x, e.dir_y = r.direction.y, e.dir_z = r.direction.z;
  e.tnear = r.tmin;
  e.tfar = r.tmax;
  e.mask = UINT32_MAX;
  return e;
}

}  // namespace

bool RayScene::occluded(const Ray& r) const {
  if (!valid(r)) return false;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay e = embree_ray(r);
  rtcOccluded1(impl_->scene, &context, &e);
  return e.tfar == -std::numeric_limits<float>::infinity();  // Embree's mark for "hit"
}

std::optional<Hit> RayScene::intersect(const Ray& r) const {
  if (!valid(r)) return std::nullopt;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit e{};
  e.ray = embree_ray(r);
  e.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  e.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &e);
  if (e.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

  const InstanceGeometry& g = impl_->instances[e.hit.geomID];
  const std::uint32_t* tri = &g.indices[3 * std::size_t(e.hit.primID)];
  const float u = e.hit.u, v = e.hit.v, w = 1 - u - v;  // Embree's barycentrics: p = w p0 + u p1 + v p2
  glm::vec3 p0 = g.position(tri[0]), p1 = g.position(tri[1]), p2 = g.position(tri[2]);
  Hit h;
  h.t = e.ray.tfar;
  h.position = w * p0 + u * p1 + v * p2;
  h.geometric_normal = unit_or(glm::cross(p1 - p0, p2 - p0), -r.direction);  // counter-clockwise front
  if (g.mirrored) h.geometric_normal = -h.geometric_normal;
  h.shading_normal =
      unit_or(w * g.normals[tri[0]] + u * g.normals[tri[1]] + v * g.normals[tri[2]], h.geometric_normal);
  h.uv = w * g.uvs[tri[0]] + u * g.uvs[tri[1]] + v * g.uvs[tri[2]];
  h.material = g.materials[e.hit.primID];
  h.instance = static_cast<int>(e.hit.geomID);
  h.triangle = static_cast<int>(e.hit.primID);
  h.front_face = glm::dot(h.geometric_normal, r.direction) < 0;
  h.error = position_error(glm::vec3(std::max({max_abs(p0), max_abs(p1), max_abs(p2)})));  // the interpolation's
  return h;
}

// --- Secondary rays ---------------------------------------------------------------------

float position_error(glm::vec3 p) { return kSpawnRelativeOffset * std::max(1.f, max_abs(p)); }

glm::vec3 spawn_origin(glm::vec3 p, glm::vec3 n, glm::vec3 d, float error) {
  float offset = std::max(position_error(p), error);
  return p + (glm::dot(d, n) >= 0 ? offset : -offset) * n;
}

Ray SurfacePoint::ray(glm::vec3 direction, float length) const {
  return Ray{spawn_origin(position, normal, direction, error), direction, 0, length};
}

Ray SurfacePoint::ray_towards(glm::vec3 target, float target_error) const {
  const float stop = std::max(position_error(target), target_error);
  // A target within both offsets of the point is the point itself: nothing lies between.
  if (!(glm::length(target - position) > std::max(error, position_error(position)) + stop))
    return Ray{position, normal, 0, 0};
  glm::vec3 origin = spawn_origin(position, normal, target - position, error);
  glm::vec3 to_target = target - origin;
  float distance = glm::length(to_target);
  return Ray{origin, to_target / distance, 0, std::max(0.f, distance - stop)};
}

// --- Primary rays -------------------------------------------------------------------------

void check_image_size(int width, int height, const std::string& what) {
  constexpr int kMax = 16384;
  if (width < 1 || height < 1 || width > kMax || height > kMax)
    throw Error(what + ": " + std::to_string(width) + "x" + std::to_string(height) + " is not a size between 1x1 and " +
                std::to_string(kMax) + "x" + std::to_string(kMax));
}

PrimaryRays::PrimaryRays(const FrameCamera& camera, int width, int height)
    : inverse_view_projection_(glm::inverse(glm::dmat4(camera.projection) * glm::dmat4(camera.view))),
      width_(width),
      height_(height) {
  check_image_size(width, height, "primary rays");
}

Ray PrimaryRays::operator()(int x, int y) const {
  // Normalised device coordinates of the pixel centre; row 0 is the top (NDC y = +1 edge).
  double ndc_x = (x + 0.5) / width_ * 2 - 1;
  double ndc_y = 1 - (y + 0.5) / height_ * 2;
  glm::dvec4 near = inverse_view_projection_ * glm::dvec4(ndc_x, ndc_y, -1, 1);
  glm::dvec4 far = inverse_view_projection_ * glm::dvec4(ndc_x, ndc_y, 1, 1);
  glm::dvec3 a = glm::dvec3(near) / near.w, b = glm::dvec3(far) / far.w;
  double length = glm::length(b - a);
  return Ray{glm::vec3(a), glm::vec3((b - a) / length), 0, static_cast<float>(length)};
}

// --- Parallel images ----------------------------------------------------------------------

int available_cores() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

void parallel_rows(int height, int threads, const std::function<void(int)>& row) {
  if (threads < 0) throw Error("parallel_rows: " + std::to_string(threads) + " threads");
  if (threads == 0) threads = available_cores();
  threads = std::min(threads, std::max(height, 1));
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first_error;
  std::mutex error_mutex;
  auto work = [&] {
    for (int y; !failed && (y = next++) < height;) {
      try {
        row(y);
      } catch (...) {
        std::lock_guard lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  if (first_error) std::rethrow_exception(first_error);
}

ImageF trace_image(int width, int height, int channels, std::uint64_t seed, const PixelFunction& pixel, int threads) {
  check_image_size(width, height, "trace_image");
  if (channels < 1 || channels > 4) throw Error("trace_image: " + std::to_string(channels) + " channels (1 to 4)");
  ImageF image = ImageF::blank(width, height, channels);
  parallel_rows(height, threads, [&](int y) {
    for (int x = 0; x < width; ++x) {
      std::size_t i = std::size_t(y) * width + x;
      Pcg32 rng = pixel_rng(seed, i);
      pixel(x, y, rng, &image.data[i * channels]);
    }
  });
  return image;
}

// [visible-hit]
// What the rasteriser shows along a primary ray: it culls the back faces of single-sided
// materials (SceneGpu::draw), so a ray that meets one goes on past it. Each step starts
// beyond the hit by more than its rounding (spawn_origin's bound along the ray); a ray that
// passes more back faces than kMaxBackFaces (a pathological stack of them) sees nothing.
std::optional<Hit> visible_hit(const RayScene& scene, Ray ray) {
  constexpr int kMaxBackFaces = 64;
  for (int i = 0; i <= kMaxBackFaces; ++i) {
    std::optional<Hit> h = scene.intersect(ray);
    if (!h || h->front_face || scene.double_sided(h->material)) return h;
    ray.tmin = h->t + std::max(4.f * h->error, h->t * 0x1p-20f);
  }
  return std::nullopt;
}
// [/visible-hit]

std::vector<std::optional<Hit>> primary_hits(const RayScene& scene, const FrameCamera& camera, int width, int height,
                                             int threads) {
  PrimaryRays rays(camera, width, height);
  std::vector<std::optional<Hit>> hits(std::size_t(width) * height);
  parallel_rows(height, threads, [&](int y) {
    for (int x = 0; x < width; ++x) hits[std::size_t(y) * width + x] = visible_hit(scene, rays(x, y));
  });
  return hits;
}

std::vector<std::optional<SurfacePoint>> surface_points(const std::vector<std::optional<Hit>>& hits) {
  std::vector<std::optional<SurfacePoint>> points(hits.size());
  for (std::size_t i = 0; i < hits.size(); ++i)
    if (const auto& h = hits[i])
      points[i] = SurfacePoint{h->position, h->front_face ? h->geometric_normal : -h->geometric_normal, h->error};
  return points;
}

std::vector<std::optional<SurfacePoint>> surface_points(const ImageF& position, const ImageF& normal, float error) {
  return surface_points(position, normal, [error](int, int, glm::vec3) { return error; });
}

std::vector<std::optional<SurfacePoint>> surface_points(const ImageF& position, const ImageF& normal,
                                                        const PositionError& error) {
  if (position.width != normal.width || position.height != normal.height || position.channels < 3 || normal.channels < 3)
    throw Error("surface_points: the position and normal images must be the same size with at least 3 channels");
  std::vector<std::optional<SurfacePoint>> points(std::size_t(position.width) * position.height);
  for (int y = 0; y < position.height; ++y)
    for (int x = 0; x < position.width; ++x) {
      glm::vec3 p(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2));
      glm::vec3 n(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
      float len = glm::length(n);
      if (len > 0 && std::isfinite(len) && finite(p))
        points[std::size_t(y) * position.width + x] = SurfacePoint{p, n / len, std::max(error(x, y, p), position_error(p))};
    }
  return points;
}

// --- The truth cache ----------------------------------------------------------------------

namespace {

class Fnv1a {
 public:
  void bytes(const void* data, std::size_t n) {
    auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h_ = (h_ ^ p[i]) * 0x100000001b3ull;
  }
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes(&v, sizeof v);
  }
  template <class T>
  void array(const std::vector<T>& v) {
    value(v.size());
    bytes(v.data(), v.size() * sizeof(T));
  }
  void text(const std::string& s) { array(std::vector<char>(s.begin(), s.end())); }
  std::uint64_t get() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ull;
};

std::string hex64(std::uint64_t v) {
  char s[17];
  std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(v));
  return s;
}

// Exact: a camera that moved by one ulp is another key.
std::string matrix_text(const glm::mat4& m) {
  std::string s;
  char buf[32];
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      std::snprintf(buf, sizeof buf, " %a", static_cast<double>(m[c][r]));
      s += buf;
    }
  return s;
}

std::optional<std::string> read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Written under a name of its own, then renamed: a reader never sees half a file, even
// with tests running in parallel.
void write_atomically(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path tmp = path;
  tmp += ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  write(tmp);
  std::filesystem::rename(tmp, path);
}

}  // namespace

std::uint64_t scene_fingerprint(const Scene& s) {
  Fnv1a h;
  static_assert(sizeof(Vertex) == 12 * sizeof(float), "Vertex is hashed as raw floats");
  h.array(s.vertices);
  h.array(s.indices);
  for (const Mesh& m : s.meshes)
    for (const Primitive& p : m.primitives) h.value(p);
  for (const Instance& i : s.instances) h.value(i.mesh), h.value(i.model), h.value(i.shape);
  for (const Material& m : s.materials) {
    h.value(m.base_color), h.value(m.base_color_texture), h.value(m.emissive), h.value(m.specular_color);
    h.value(m.specular_factor), h.value(m.has_specular_extension), h.value(m.roughness);
    h.value(m.normal_texture), h.value(m.normal_scale);
  }
  for (const Texture& t : s.textures) h.value(t.image.width), h.value(t.image.height), h.value(t.srgb), h.array(t.image.pixels);
  for (const Light& l : s.lights) {
    h.value(l.type), h.value(l.color), h.value(l.intensity), h.value(l.position), h.value(l.direction);
    h.value(l.range), h.value(l.inner_cone), h.value(l.outer_cone);
  }
  for (const NodeExtras& e : s.node_extras) h.value(e.world), h.text(e.lightpass_json);  // e.g. chapter 04's neon
  h.value(s.ambient);
  return h.get();
}

TruthKey truth_key(const Scene& scene, const FrameCamera& camera, int width, int height, const std::string& settings) {
  check_image_size(width, height, "truth_key");
  std::string text = "lightpass truth cache v" + std::to_string(kTruthCacheVersion) + "\n";
  // The content decides, not where the file lies (the GPU machine has the tree elsewhere).
  text += "scene " + scene.path.filename().string() + " " + hex64(scene_fingerprint(scene)) + "\n";
  text += "view" + matrix_text(camera.view) + "\nprojection" + matrix_text(camera.projection) + "\n";
  text += "size " + std::to_string(width) + "x" + std::to_string(height) + "\n";
  text += "settings " + settings + "\n";
  return TruthKey{text, width, height};
}

std::filesystem::path truth_cache_dir() {
  if (const char* dir = std::getenv("LIGHTPASS_TRUTH_CACHE"); dir && *dir) return dir;
  return from_root("out/truth-cache");
}

namespace {

std::optional<ImageF> read_entry(const std::filesystem::path& base, const TruthKey& key) {
  std::filesystem::path key_file = base, image_file = base;
  key_file += ".key";
  image_file += ".pfm";
  if (read_file(key_file) != key.text) return std::nullopt;  // absent, or another key with this hash
  try {
    ImageF image = load_pfm(image_file);
    if (image.width == key.width && image.height == key.height) return image;
  } catch (const Error&) {  // truncated or corrupt: recompute
  }
  return std::nullopt;
}

void write_entry(const std::filesystem::path& base, const TruthKey& key, const ImageF& image) {
  std::filesystem::path key_file = base, image_file = base;
  key_file += ".key";
  image_file += ".pfm";
  std::filesystem::create_directories(base.parent_path());
  std::filesystem::remove(key_file);  // an entry is valid only once both files are whole
  write_atomically(image_file, [&](const std::filesystem::path& p) { save_pfm(p, image); });
  write_atomically(key_file, [&](const std::filesystem::path& p) {
    std::ofstream out(p, std::ios::binary);
    out << key.text;
    if (!out.flush()) throw Error("cannot write " + p.string());
  });
}

}  // namespace

ImageF cached_image(const TruthKey& key, const std::function<ImageF()>& compute, const std::filesystem::path& dir) {
  Fnv1a h;
  h.text(key.text);
  const std::filesystem::path base = dir / hex64(h.get());
  if (auto image = read_entry(base, key)) return *image;
  ImageF image = compute();
  if (image.width != key.width || image.height != key.height)
    throw Error("truth cache: the computed image is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                " but its key says " + std::to_string(key.width) + "x" + std::to_string(key.height));
  if (image.channels != 1 && image.channels != 3)
    throw Error("truth cache: PFM keeps 1 or 3 channels, not " + std::to_string(image.channels));
  try {
    write_entry(base, key, image);
  } catch (const std::exception& e) {  // a read-only tree still gets its truth, just not kept
    std::cerr << "warning: truth cache: cannot store " << base.string() << ": " << e.what() << "\n";
  }
  return image;
}

}  // namespace lp
