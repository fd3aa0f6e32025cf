// Exercise 3 of chapter 10, solved: the same function as 10_frame/shaders/msaa_resolve_radiance.frag.
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec3 sum = vec3(0.0);
  float weights = 0.0;
  for (int i = 0; i < MSAA_SAMPLES; ++i) {
    vec3 radiance = sample_radiance(pixel, i);
    float w = u_resolve_first ? 1.0 : tone_weight(radiance);
    sum += w * radiance;
    weights += w;
  }
  out_color = vec4(sum / weights, 1.0);
}
