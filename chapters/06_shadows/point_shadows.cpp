// Chapter 06's point lights: a cube map each (cube_math.h), drawn by ShadowStage before the
// lights; shadow_visibility.glsl's point_visibility() reads them.
#include <string>

#include "chapters/06_shadows/shadow_stage.h"
#include "common/error.h"
#include "common/scene_gpu.h"

namespace lp::ch06 {

// [point-maps]
void ShadowStage::draw_point_maps(const FrameCamera& camera, PassMetrics* metrics) {
  const Scene& scene = scene_.scene();
  point_lights_ = shadowed_point_lights(scene, settings_.all_point_lights);
  points_mapped_.assign(point_lights_.size(), false);
  point_far_.assign(point_lights_.size(), 0.f);
  if (point_lights_.empty()) return;
  const int n = settings_.cube_size;
  if (n < 1 || n > 8192) throw Error("shadow stage: cube_size must be between 1 and 8192 texels (got " + std::to_string(n) + ")");
  const int layers = int(point_lights_.size());
  if (n != point_size_ || layers != point_layers_) {
    // One layer of six faces per light; a framebuffer per face (layer-face 6 i + f).
    point_maps_ = gl::Texture(GL_TEXTURE_CUBE_MAP_ARRAY);
    glTextureStorage3D(point_maps_.id(), 1, GL_DEPTH_COMPONENT32F, n, n, 6 * layers);
    point_fbos_.clear();
    for (int i = 0; i < 6 * layers; ++i) {
      gl::Framebuffer& fbo = point_fbos_.emplace_back();
      glNamedFramebufferTextureLayer(fbo.id(), GL_DEPTH_ATTACHMENT, point_maps_.id(), 0, i);
      glNamedFramebufferDrawBuffer(fbo.id(), GL_NONE);
    }
    point_size_ = n, point_layers_ = layers;
  }
  auto pass = timed(metrics, "shadow map: cube maps of the point lights");
  // The fragment shader writes the linear distance over the far plane as the depth: one
  // comparison per texel, the same along any ray from the light, whatever the face.
  const ShaderProgram& p = programs_.get({{GL_VERTEX_SHADER, "06_shadows/shaders/point_depth.vert"},
                                          {GL_FRAGMENT_SHADER, "06_shadows/shaders/point_depth.frag"}}, {});
  depth_pass_state();
  p.use();
  const glm::mat4 view_projection = camera.projection * camera.view;
  for (std::size_t i = 0; i < point_lights_.size(); ++i) {
    const Light& l = scene.lights[std::size_t(point_lights_[i])];
    // Only what the view needs: no map for a light whose range's sphere lies off screen.
    if (l.range > 0.f && !sphere_in_view(l.position, l.range, view_projection)) continue;
    points_mapped_[i] = true;
    point_far_[i] = cube_far(l.position, l.range, scene.bounds_min, scene.bounds_max);
    p.set("u_light_position", l.position);
    p.set("u_far", point_far_[i]);
    for (int face = 0; face < 6; ++face) {
      glBindFramebuffer(GL_FRAMEBUFFER, point_fbos_[6 * i + std::size_t(face)].id());
      glViewport(0, 0, n, n);
      glClear(GL_DEPTH_BUFFER_BIT);
      p.set("u_light_view_projection", cube_face_view_projection(l.position, CubeFace(face), point_far_[i]));
      scene_.draw([&](const Instance& inst, const Material&) { p.set("u_model", inst.model); }, SceneGpu::Primitives::Opaque);
    }
  }
}
// [/point-maps]

}  // namespace lp::ch06
