#version 450
// The bloom's bright pass: the exposed radiance above the threshold (hdr_math.glsl:
// bright_pass), averaged over each texel's footprint of u_footprint x u_footprint pixels.
// Alpha is the fraction of the footprint inside the image (less than 1 only in the last
// row and column when the size is odd).
#include "05_hdr/shaders/hdr_math.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D u_radiance;
layout(rgba16f, binding = 0) writeonly uniform image2D u_out;
layout(std430, binding = EXPOSURE_BINDING) readonly buffer State { ExposureState state; };
uniform int u_footprint;
uniform float u_threshold, u_limit;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(u_out)))) return;
  ivec2 size = textureSize(u_radiance, 0);
  vec3 sum = vec3(0.0);
  float count = 0.0;
  for (int y = 0; y < u_footprint; ++y)
    for (int x = 0; x < u_footprint; ++x) {
      ivec2 q = p * u_footprint + ivec2(x, y);
      if (any(greaterThanEqual(q, size))) continue;
      bool valid;
      vec3 c = sanitize(texelFetch(u_radiance, q, 0).rgb, valid);
      sum += bright_pass(c * state.exposure, u_threshold, u_limit);
      count += 1.0;
    }
  imageStore(u_out, p, vec4(sum / count, count / float(u_footprint * u_footprint)));
}
