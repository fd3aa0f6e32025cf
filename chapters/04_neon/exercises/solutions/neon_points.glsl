// Exercise 1 of chapter 04, solved: the same function as 04_neon/shaders/neon.glsl.
vec2 neon_points(NeonSurface s, Neon t, int count) {
  // count chapter-01 point lights along the tube, sharing its intensity.
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  for (int i = 0; i < count; ++i) {
    GpuLight point;
    point.position_type = vec4(mix(t.start, t.end, (float(i) + 0.5) / float(count)), LIGHT_POINT);
    point.direction_range = vec4(0.0, 0.0, -1.0, 0.0);
    point.radiance = vec4(vec3(1.0 / float(count)), 0.0);
    point.spot = vec4(0.0);
    vec3 to_light, radiance;
    light_incident(point, s.position, to_light, radiance);
    blinn_phong(s.normal, s.to_eye, to_light, radiance, s.exponent, diffuse, specular);
  }
  return vec2(diffuse.x, specular.x);
}
