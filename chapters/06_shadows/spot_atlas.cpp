#include "chapters/06_shadows/spot_atlas.h"

#include <cmath>
#include <string>

#include "chapters/06_shadows/shadow_stage.h"
#include "common/error.h"
#include "common/scene_gpu.h"

namespace lp::ch06 {

// [spot-atlas-cpp]
AtlasTile spot_atlas_tile(int index, int count, int atlas_size) {
  if (count < 1 || count > kMaxSpotShadows || index < 0 || index >= count)
    throw Error("spot atlas: tile " + std::to_string(index) + " of " + std::to_string(count) + " (1 to " +
                std::to_string(kMaxSpotShadows) + " tiles)");
  int g = 1;
  while (g * g < count) ++g;
  if (atlas_size < g || atlas_size > 16384)
    throw Error("spot atlas: " + std::to_string(atlas_size) + " texels cannot hold a " + std::to_string(g) + " x " +
                std::to_string(g) + " grid of tiles");
  AtlasTile t;
  t.size = atlas_size / g;
  t.x = (index % g) * t.size;
  t.y = (index / g) * t.size;
  t.corner = glm::vec2(float(t.x), float(t.y)) / float(atlas_size);
  t.side = float(t.size) / float(atlas_size);
  return t;
}

glm::vec2 spot_atlas_uv(const AtlasTile& tile, glm::vec2 uv) {
  const float half_texel = 0.5f / float(tile.size);
  return tile.corner + glm::clamp(uv, glm::vec2(half_texel), glm::vec2(1.f - half_texel)) * tile.side;
}
// [/spot-atlas-cpp]

// [spot-atlas-stage]
void ShadowStage::draw_spot_atlas(const FrameCamera& camera, PassMetrics* metrics) {
  const Scene& scene = scene_.scene();
  spot_lights_ = shadowed_spot_lights(scene, settings_.all_spot_lights);
  const std::size_t count = spot_lights_.size();
  spots_mapped_.assign(count, false);
  spot_frustums_.assign(count, SpotFrustum{});
  if (count == 0) return;
  const int n = settings_.map_size;
  if (n != spot_size_) {
    spot_atlas_ = gl::make_texture_2d(GL_DEPTH_COMPONENT32F, n, n);
    spot_fbo_ = gl::Framebuffer();
    glNamedFramebufferTexture(spot_fbo_.id(), GL_DEPTH_ATTACHMENT, spot_atlas_.id(), 0);
    glNamedFramebufferDrawBuffer(spot_fbo_.id(), GL_NONE);
    spot_size_ = n;
  }
  // Only what the view needs: no tile is drawn for a spot whose reach lies off screen (an
  // unbounded spot, range 0, always has one).
  const glm::mat4 view_projection = camera.projection * camera.view;
  bool any = false;
  for (std::size_t i = 0; i < count; ++i) {
    const Light& l = scene.lights[std::size_t(spot_lights_[i])];
    spots_mapped_[i] = !(l.range > 0.f) || sphere_in_view(l.position, l.range, view_projection);
    spot_frustums_[i] = fit_spot_frustum(l.position, l.direction, l.outer_cone, l.range, scene.bounds_min, scene.bounds_max);
    any = any || spots_mapped_[i];
  }
  if (!any) return;
  auto pass = timed(metrics, "shadow map: the spot lights' atlas");
  const ShaderProgram& p = program("06_shadows/shaders/shadow_depth.vert", "06_shadows/shaders/shadow_depth.frag", {});
  glBindFramebuffer(GL_FRAMEBUFFER, spot_fbo_.id());
  depth_pass_state();
  glClear(GL_DEPTH_BUFFER_BIT);  // every tile to the far plane (no scissor: the whole atlas)
  p.use();
  for (std::size_t i = 0; i < count; ++i) {
    if (!spots_mapped_[i]) continue;
    // The same depth pass as the sun's, from the spot's frustum, into its tile: the viewport
    // maps the frustum's clip space onto the tile's texels alone.
    const AtlasTile tile = spot_tile(int(i));
    glViewport(tile.x, tile.y, tile.size, tile.size);
    p.set("u_light_view_projection", spot_frustums_[i].view_projection());
    scene_.draw([&](const Instance& inst, const Material&) { p.set("u_model", inst.model); }, SceneGpu::Primitives::Opaque);
  }
}
// [/spot-atlas-stage]

}  // namespace lp::ch06
