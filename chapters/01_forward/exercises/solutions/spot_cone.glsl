// Exercise 3 of chapter 01, solved: the same function as 01_forward/shaders/lighting.glsl.
float spot_cone(GpuLight light, vec3 to_light) {
  float t = clamp((dot(-to_light, light.direction_range.xyz) - light.spot.x) * light.spot.y, 0.0, 1.0);
  return t * t;
}
