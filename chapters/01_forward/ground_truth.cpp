#include "chapters/01_forward/ground_truth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "chapters/01_forward/blinn_phong.h"
#include "common/shader.h"

namespace lp::ch01 {
namespace {

struct Hit {
  float t = std::numeric_limits<float>::max();
  glm::vec3 position{0}, normal{0};
  glm::vec2 uv{0};
  const Instance* instance = nullptr;
};

std::optional<float> intersect_sphere(glm::vec3 o, glm::vec3 d, glm::vec3 c, float r) {
  glm::vec3 oc = o - c;
  float b = glm::dot(oc, d), q = glm::dot(oc, oc) - r * r;
  float disc = b * b - q;
  if (disc < 0) return std::nullopt;
  float t = -b - std::sqrt(disc);
  return t > 0 ? std::optional<float>(t) : std::nullopt;
}

void intersect(const Instance& inst, glm::vec3 o, glm::vec3 d, Hit& best) {
  if (inst.shape.kind == Shape::Sphere) {
    glm::vec3 c = glm::vec3(inst.model[3]);
    if (auto t = intersect_sphere(o, d, c, inst.shape.radius); t && *t < best.t) {
      best.t = *t;
      best.position = o + d * *t;
      best.normal = glm::normalize(best.position - c);
      best.instance = &inst;
    }
  } else if (inst.shape.kind == Shape::Rect) {
    glm::mat4 inv = glm::inverse(inst.model);
    glm::vec3 lo = glm::vec3(inv * glm::vec4(o, 1)), ld = glm::vec3(inv * glm::vec4(d, 0));
    if (std::abs(ld.y) < 1e-9f) return;
    float t = -lo.y / ld.y;
    glm::vec3 p = lo + ld * t;
    glm::vec2 half = inst.shape.size * 0.5f;
    if (t <= 0 || t >= best.t || std::abs(p.x) > half.x || std::abs(p.z) > half.y) return;
    best.t = t;
    best.position = o + d * t;
    best.normal = glm::normalize(glm::vec3(glm::transpose(inv) * glm::vec4(0, 1, 0, 0)));
    best.uv = glm::vec2(p.x / inst.shape.size.x + 0.5f, p.z / inst.shape.size.y + 0.5f);
    best.instance = &inst;
  }
}

glm::vec3 sample_srgb(const Texture& tex, glm::vec2 uv) {
  const ImageRGBA8& img = tex.image;
  int x = static_cast<int>(std::floor((uv.x - std::floor(uv.x)) * img.width)) % img.width;
  int y = static_cast<int>(std::floor((uv.y - std::floor(uv.y)) * img.height)) % img.height;
  const std::uint8_t* p = img.at(x, y);
  return glm::vec3(srgb_to_linear(p[0] / 255.f), srgb_to_linear(p[1] / 255.f), srgb_to_linear(p[2] / 255.f));
}

}  // namespace

GroundTruth render_ground_truth(const Scene& scene, const Camera& camera, int w, int h, const std::vector<Light>& lights) {
  GroundTruth gt;
  gt.radiance = ImageF::blank(w, h, 3);
  gt.instance.assign(std::size_t(w) * h, 0);
  Scene lit = scene;  // shade() reads the lights from a scene
  lit.lights = lights;
  float tan_half = std::tan(camera.yfov * 0.5f), aspect = float(w) / float(h);
  glm::vec3 eye = camera.position();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::vec3 dir_camera((2.f * (x + 0.5f) / w - 1.f) * tan_half * aspect, (1.f - 2.f * (y + 0.5f) / h) * tan_half, -1.f);
      glm::vec3 d = glm::normalize(glm::vec3(camera.world * glm::vec4(dir_camera, 0)));
      Hit hit;
      for (const auto& inst : scene.instances) intersect(inst, eye, d, hit);
      if (!hit.instance) {
        for (int k = 0; k < 3; ++k) gt.radiance.at(x, y, k) = kBackground[k];
        continue;
      }
      gt.instance[std::size_t(y) * w + x] = static_cast<int>(hit.instance - scene.instances.data()) + 1;
      const auto& prims = scene.meshes[hit.instance->mesh].primitives;
      const Material& m = scene.materials[prims.empty() ? scene.materials.size() - 1 : prims.front().material];
      glm::vec3 albedo = glm::vec3(m.base_color);
      if (m.base_color_texture >= 0) albedo *= sample_srgb(scene.textures[m.base_color_texture], hit.uv);
      SurfacePoint s{hit.position, hit.normal, -d, albedo, m.specular_color, exponent_from_roughness(m.roughness)};
      glm::vec3 c = shade(s, lit, m.emissive);
      for (int k = 0; k < 3; ++k) gt.radiance.at(x, y, k) = c[k];
    }
  return gt;
}

ImageF srgb_steps(const ImageRGBA8& img) {
  ImageF f = ImageF::blank(img.width, img.height, 3);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) f.at(x, y, c) = img.at(x, y)[c];
  return f;
}

std::vector<int> render_instance_ids(const SceneGpu& gpu, const FrameCamera& camera, int w, int h) {
  ShaderProgram program({{GL_VERTEX_SHADER, "01_forward/shaders/forward.vert"}, {GL_FRAGMENT_SHADER, "01_forward/shaders/instance_id.frag"}});
  gl::Texture ids = gl::make_texture_2d(GL_R32I, w, h), depth = gl::make_texture_2d(GL_DEPTH_COMPONENT32F, w, h);
  gl::Framebuffer fbo;
  glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, ids.id(), 0);
  glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  glViewport(0, 0, w, h);
  const GLint zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferiv(fbo.id(), GL_COLOR, 0, zero);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  program.use();
  program.set("u_view_projection", camera.view_projection());
  const Instance* first = gpu.scene().instances.data();
  gpu.draw([&](const Instance& inst, const Material&) {
    program.set("u_model", inst.model);
    program.set("u_normal_matrix", glm::mat3(1));
    program.set("u_instance", static_cast<int>(&inst - first));
  });
  std::vector<int> bottom_up(std::size_t(w) * h), out(std::size_t(w) * h);
  glGetTextureImage(ids.id(), 0, GL_RED_INTEGER, GL_INT, static_cast<GLsizei>(bottom_up.size() * sizeof(int)), bottom_up.data());
  for (int y = 0; y < h; ++y)
    std::copy_n(bottom_up.begin() + std::size_t(h - 1 - y) * w, w, out.begin() + std::size_t(y) * w);
  return out;
}

std::vector<std::uint8_t> sphere_mask(const Scene& scene, const GroundTruth& truth, const std::vector<int>& gpu_ids) {
  const int w = truth.radiance.width, h = truth.radiance.height;
  std::vector<std::uint8_t> mask(std::size_t(w) * h, 0);
  auto same = [&](int x, int y, int id) {
    std::size_t i = std::size_t(y) * w + x;
    return truth.instance[i] == id && gpu_ids[i] == id;
  };
  for (int y = 1; y < h - 1; ++y)
    for (int x = 1; x < w - 1; ++x) {
      int id = truth.instance[std::size_t(y) * w + x];
      if (id == 0 || scene.instances[id - 1].shape.kind != Shape::Sphere) continue;
      bool inside = true;
      for (int dy = -1; dy <= 1 && inside; ++dy)
        for (int dx = -1; dx <= 1 && inside; ++dx) inside = same(x + dx, y + dy, id);
      mask[std::size_t(y) * w + x] = inside;
    }
  return mask;
}

FloatErrorStats sphere_error(const ImageRGBA8& render, const GroundTruth& truth, const std::vector<std::uint8_t>& mask) {
  return compare_float(srgb_steps(render), srgb_steps(to_srgb8(truth.radiance)), mask);
}

}  // namespace lp::ch01
