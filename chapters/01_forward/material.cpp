#include "chapters/01_forward/material.h"

#include <glm/glm.hpp>

#include "chapters/01_forward/blinn_phong.h"

namespace lp::ch01 {

void set_surface(const ShaderProgram& program, const SceneGpu& scene, const Instance& instance, const Material& m,
                 float emissive_scale) {
  program.set("u_model", instance.model);
  program.set("u_normal_matrix", glm::mat3(glm::transpose(glm::inverse(instance.model))));
  program.set("u_base_color", m.base_color);
  program.set("u_specular", m.specular_color);
  program.set("u_exponent", exponent_from_roughness(m.roughness));
  program.set("u_emissive", m.emissive * emissive_scale);
  program.set("u_has_normal_map", int(m.normal_texture >= 0));
  program.set("u_normal_scale", m.normal_scale);
  glBindTextureUnit(0, scene.base_color_texture(m.base_color_texture));
  glBindTextureUnit(1, scene.normal_texture(m.normal_texture));
  glBindTextureUnit(2, scene.emissive_texture(m.emissive_texture));
}

}  // namespace lp::ch01
