#version 450
// One direction of the separable Gaussian: weights exp(-i^2 / (2 sigma^2)) for
// |i| <= radius = ceil(3 sigma), divided by their sum so the blur neither adds nor removes
// light; taps past the edge read the edge texel.
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba16f, binding = 0) readonly uniform image2D u_src;
layout(rgba16f, binding = 1) writeonly uniform image2D u_dst;
uniform float u_sigma;
uniform int u_radius;
uniform bool u_horizontal;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(u_src);
  if (any(greaterThanEqual(p, size))) return;
  // [gaussian]
  ivec2 dir = u_horizontal ? ivec2(1, 0) : ivec2(0, 1);
  vec3 sum = vec3(0.0);
  float total = 0.0;
  for (int i = -u_radius; i <= u_radius; ++i) {
    float w = exp(-float(i * i) / (2.0 * u_sigma * u_sigma));
    sum += w * imageLoad(u_src, clamp(p + i * dir, ivec2(0), size - 1)).rgb;
    total += w;
  }
  // [/gaussian]
  imageStore(u_dst, p, vec4(sum / total, imageLoad(u_src, p).a));
}
