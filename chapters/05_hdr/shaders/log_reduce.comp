#version 450
// The log-average as a parallel reduction (beyond the source). STAGE 1: each workgroup of
// 16x16 threads sums log(delta + L) over a 32x32 tile (2x2 pixels per thread) in shared
// memory and writes one partial sum and count. STAGE 2: one workgroup sums the partials
// and writes the mean. Same policy as the mip chain: NaN pixels are not counted.
#include "05_hdr/shaders/hdr_math.glsl"

layout(std430, binding = PARTIALS_BINDING) buffer Partials { Partial partials[]; };
layout(std430, binding = LOG_AVERAGE_BINDING) writeonly buffer Result { LogAverageResult result; };

#if STAGE == 1
layout(local_size_x = 16, local_size_y = 16) in;
#else
layout(local_size_x = 256) in;
#endif
shared float s_sum[256];
shared uint s_count[256];

layout(binding = 0) uniform sampler2D u_radiance;
uniform float u_delta;
uniform int u_partial_count;

// [tree-reduction]
// Halves the active threads each step: 256 -> 128 -> ... -> 1; thread 0 ends with the sum.
void reduce_shared(uint i) {
  for (uint stride = 128u; stride > 0u; stride >>= 1u) {
    barrier();
    if (i < stride) {
      s_sum[i] += s_sum[i + stride];
      s_count[i] += s_count[i + stride];
    }
  }
  barrier();
}
// [/tree-reduction]

void main() {
  uint i = gl_LocalInvocationIndex;
  float sum = 0.0;
  uint count = 0u;
#if STAGE == 1
  ivec2 size = textureSize(u_radiance, 0);
  ivec2 base = 2 * ivec2(gl_GlobalInvocationID.xy);
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      ivec2 p = base + ivec2(dx, dy);
      if (any(greaterThanEqual(p, size))) continue;
      bool valid;
      vec3 s = sanitize(texelFetch(u_radiance, p, 0).rgb, valid);
      if (!valid) continue;
      sum += log_luminance(s, u_delta);
      count += 1u;
    }
#else
  for (int k = int(i); k < u_partial_count; k += 256) {
    sum += partials[k].sum_log;
    count += partials[k].count;
  }
#endif
  s_sum[i] = sum;
  s_count[i] = count;
  reduce_shared(i);
  if (i != 0u) return;
#if STAGE == 1
  partials[gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x] = Partial(s_sum[0], s_count[0]);
#else
  result.mean_log = s_count[0] > 0u ? s_sum[0] / float(s_count[0]) : 0.0;
  result.count = float(s_count[0]);
#endif
}
