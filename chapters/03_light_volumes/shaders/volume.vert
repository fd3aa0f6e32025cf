#version 450
// Places a light's volume: the unit mesh (or a full-screen triangle) per instance, moved,
// scaled and turned by that instance's record, and hands the light on to the fragment stage.
#include "01_forward/shaders/lighting.glsl"
#include "02_gbuffer/shaders/encoding.glsl"
#include "03_light_volumes/shaders/light_instance.glsl"

layout(location = 0) in vec3 a_position;         // the unit icosphere or cone
layout(location = 4) in vec4 i_position_radius;  // per instance (attribute divisor 1)
layout(location = 5) in vec4 i_radiance_range;
layout(location = 6) in vec4 i_direction_cone;   // spots only

uniform mat4 u_view_projection;
uniform int u_shape;
uniform bool u_spot;
uniform int u_first_light;  // light order of this draw's first instance

flat out vec4 v_position_type;
flat out vec4 v_direction_range;
flat out vec4 v_radiance;
flat out vec4 v_spot;
flat out float v_cut;
flat out int v_light_index;

void main() {
  GpuLight light = u_spot ? unpack_spot(i_position_radius, i_radiance_range, i_direction_cone)
                          : unpack_point(i_position_radius, i_radiance_range);
  v_position_type = light.position_type;
  v_direction_range = light.direction_range;
  v_radiance = light.radiance;
  v_spot = light.spot;
  v_cut = i_position_radius.w;
  v_light_index = u_first_light + gl_InstanceID;
  // [place-volume]
  float r = i_position_radius.w;
  vec3 world;
  if (u_shape == SHAPE_FULL_SCREEN) {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
    return;
  } else if (u_shape == SHAPE_CONE) {
    // Apex at the light, axis along its direction, height r, base radius r tan(outer).
    float cos_outer = i_direction_cone.z;
    float base = r * sqrt(max(1.0 - cos_outer * cos_outer, 0.0)) / cos_outer;
    world = i_position_radius.xyz + basis_around(light.direction_range.xyz) * (a_position * vec3(base, base, r));
  } else {
    world = i_position_radius.xyz + a_position * r;
  }
  gl_Position = u_view_projection * vec4(world, 1.0);
  // [/place-volume]
}
