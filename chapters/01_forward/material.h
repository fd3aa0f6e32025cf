#pragma once
// The surface a draw shades, as chapter 01's lighting model reads it: one function sets the
// per-draw uniforms and textures for every pass that draws the scene's materials (chapter 01's
// forward pass, chapter 02's geometry pass, chapter 03's light pre-pass, chapter 04's neon
// forward pass, later chapters' shadow passes), so they cannot drift apart.
#include "common/scene.h"
#include "common/scene_gpu.h"
#include "common/shader.h"

namespace lp::ch01 {

// [set-surface]
// Texture units of a material, the same in every such shader:
//   layout(binding = 0) uniform sampler2D u_base_color_texture;
//   layout(binding = 1) uniform sampler2D u_normal_texture;
//   layout(binding = 2) uniform sampler2D u_emissive_texture;
// Uniforms: u_model, u_normal_matrix (the instance), u_base_color, u_specular, u_exponent
// (from the roughness, blinn_phong.h), u_emissive, u_has_normal_map, u_normal_scale. A
// program that declares only some of them gets those (OpenGL ignores location -1).
// `emissive_scale` multiplies the material's emitted colour (chapter 05's glow knob).
void set_surface(const ShaderProgram& program, const SceneGpu& scene, const Instance& instance, const Material& material,
                 float emissive_scale = 1.f);
// [/set-surface]

}  // namespace lp::ch01
