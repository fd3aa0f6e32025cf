#version 450
// Copies the 1x1 top of the log-luminance mip chain into the LogAverageResult buffer, where
// the adaptation pass reads it.
#include "05_hdr/shaders/hdr_math.glsl"

layout(local_size_x = 1) in;
layout(rg32f, binding = 0) readonly uniform image2D u_top;
layout(std430, binding = LOG_AVERAGE_BINDING) writeonly buffer Result { LogAverageResult result; };
uniform float u_count_scale;  // 1: the chain counts pixels; w*h: glGenerateMipmap averaged the counts

void main() {
  vec2 t = imageLoad(u_top, ivec2(0)).rg;
  result.mean_log = t.r;
  result.count = t.g * u_count_scale;
}
