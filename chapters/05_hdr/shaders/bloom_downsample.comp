#version 450
// One 2x reduction of the bloom chain: the mean of the 2x2 texels below, each weighted by
// the fraction of it that lies inside the image (alpha). Texels past the end of an odd-sized
// level count zero; the result's alpha is the covered fraction of the new, larger texel.
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba16f, binding = 0) readonly uniform image2D u_src;
layout(rgba16f, binding = 1) writeonly uniform image2D u_dst;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(u_dst)))) return;
  ivec2 src_size = imageSize(u_src);
  vec3 sum = vec3(0.0);
  float coverage = 0.0;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      ivec2 q = 2 * p + ivec2(x, y);
      if (any(greaterThanEqual(q, src_size))) continue;
      vec4 t = imageLoad(u_src, q);
      sum += t.rgb * t.a;
      coverage += t.a;
    }
  imageStore(u_dst, p, vec4(coverage > 0.0 ? sum / coverage : vec3(0.0), coverage / 4.0));
}
