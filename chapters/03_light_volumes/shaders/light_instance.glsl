// The per-instance light records of light_instances.h, read as vertex attributes and
// unpacked into chapter 01's GpuLight, so that chapter 01's light_incident() lights with
// them. Needs 01_forward/shaders/lighting.glsl and 02_gbuffer/shaders/encoding.glsl first.

const int SHAPE_SPHERE = 0;       // the unit icosphere, scaled by the radius
const int SHAPE_CONE = 1;         // the unit cone, turned to the spot's direction
const int SHAPE_FULL_SCREEN = 2;  // one triangle over the whole viewport

// Exercise 3 (chapters/03_light_volumes/exercises/unpack_lights.glsl) stands in for these two.
#ifdef EXERCISE_UNPACK_LIGHTS
#include EXERCISE_UNPACK_LIGHTS
#else
// [unpack-glsl]
GpuLight unpack_point(vec4 position_radius, vec4 radiance_range) {
  return GpuLight(vec4(position_radius.xyz, LIGHT_POINT), vec4(0.0, 0.0, -1.0, radiance_range.w),
                  vec4(radiance_range.rgb, 0.0), vec4(0.0));
}

GpuLight unpack_spot(vec4 position_radius, vec4 radiance_range, vec4 direction_cone) {
  return GpuLight(vec4(position_radius.xyz, LIGHT_SPOT), vec4(octahedral_unfold(direction_cone.xy), radiance_range.w),
                  vec4(radiance_range.rgb, 0.0), vec4(direction_cone.zw, 0.0, 0.0));
}
// [/unpack-glsl]
#endif

// Exercise 2 (exercises/basis_around.glsl) stands in for it.
#ifdef EXERCISE_BASIS_AROUND
#include EXERCISE_BASIS_AROUND
#else
// An orthonormal basis whose third axis is the unit vector n (Duff et al. 2017).
mat3 basis_around(vec3 n) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z), b = n.x * n.y * a;
  return mat3(vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x), vec3(b, s + n.y * n.y * a, -n.y), n);
}
#endif
