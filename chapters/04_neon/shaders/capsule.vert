#version 450
// A tube's capsule (or cylinder) from the unit mesh of capsule.h and the packed per-instance
// matrix, as in the thesis: scale across by the radius, stretch along the axis (flattening
// the caps for a cylinder), rotate into (Ri, Rj, Rk), move to the centre. capsule_vertex()
// in capsule.cpp is the same on the CPU. The tube itself goes on to the fragment shader
// (flat): the light-volume pass lights its pixels with it.
#include "04_neon/shaders/neon.glsl"

layout(location = 0) in vec3 a_position;  // unit capsule, axis +Y
layout(location = 4) in mat4 a_packed;    // per instance: the rows of M (locations 4..7)
layout(location = 8) in vec4 a_barn_doors;
layout(location = 9) in vec4 a_extra;

uniform mat4 u_view_projection;
uniform bool u_glass;  // true: the glass tube itself (its own radius); false: the light's volume

flat out vec3 v_power;
flat out mat4 v_packed;  // the instance's NeonGpu, as it arrived
flat out vec4 v_barn_doors;
flat out vec4 v_extra;
out vec3 v_position;

void main() {
  NeonGpu g = NeonGpu(a_packed, a_barn_doors, a_extra);
  Neon t = neon_unpack(g);
  // [capsule-vertex-glsl]
  float radius = u_glass ? t.tube_radius : t.volume_radius;
  float side = a_position.y >= 0.0 ? 1.0 : -1.0;
  float cap = (a_position.y - side * 0.5) * radius * a_packed[3].w;  // 0 for a cylinder
  vec3 local = vec3(a_position.x * radius, cap + side * 0.5 * t.len, a_position.z * radius);
  vec3 rk = cross(t.door, t.axis);
  vec3 world = mat3(t.door, t.axis, rk) * local + t.centre;
  // [/capsule-vertex-glsl]
  v_power = t.power;
  v_packed = a_packed;
  v_barn_doors = a_barn_doors;
  v_extra = a_extra;
  v_position = world;
  gl_Position = u_view_projection * vec4(world, 1.0);
}
