#version 450
// One level of the log-luminance mip chain: level k from level k - 1, whose size is
// floor(size / 2) as for any mip level. Each texel holds (mean log, pixels counted); a
// texel's footprint is its 2x2 block of the level below and, when the level below has an
// odd size, the last row and column fold the leftover row / column into theirs (3 wide).
// Weighting by the counts keeps the result an exact mean of every pixel. With NAIVE the
// leftover is simply dropped, as a plain 2x2 box filter does.
layout(local_size_x = 8, local_size_y = 8) in;
layout(rg32f, binding = 0) readonly uniform image2D u_src;
layout(rg32f, binding = 1) writeonly uniform image2D u_dst;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 dst_size = imageSize(u_dst), src_size = imageSize(u_src);
  if (any(greaterThanEqual(p, dst_size))) return;
  // [fold-last-row]
  ivec2 first = 2 * p;
  ivec2 last = min(2 * p + 1, src_size - 1);
#ifndef NAIVE
  // The last texel of a row (column) also takes the leftover texel of an odd-sized level.
  if (p.x == dst_size.x - 1) last.x = src_size.x - 1;
  if (p.y == dst_size.y - 1) last.y = src_size.y - 1;
#endif
  float weighted = 0.0, count = 0.0;
  for (int y = first.y; y <= last.y; ++y)
    for (int x = first.x; x <= last.x; ++x) {
      vec2 t = imageLoad(u_src, ivec2(x, y)).rg;  // (mean log, pixels)
      weighted += t.r * t.g;
      count += t.g;
    }
  imageStore(u_dst, p, vec4(count > 0.0 ? weighted / count : 0.0, count, 0.0, 0.0));
  // [/fold-last-row]
}
