// Exercise 3 of chapter 10, solved: the same function as 10_frame/shaders/msaa_resolve.frag.
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec3 sum = vec3(0.0);
  for (int i = 0; i < MSAA_SAMPLES; ++i) {
#if MSAA_SAMPLES > 1
    vec3 radiance = texelFetch(u_radiance, pixel, i).rgb;
#else
    vec3 radiance = texelFetch(u_radiance, pixel, 0).rgb;
#endif
    sum += u_resolve_first ? radiance : display(radiance);
  }
  vec3 mean = sum / float(MSAA_SAMPLES);
  out_color = vec4(u_resolve_first ? display(mean) : mean, 1.0);
}
