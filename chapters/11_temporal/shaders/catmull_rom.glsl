// The history's read between texels (taa_resolve.frag), in its own file so that a test runs it
// against the 16-tap filter (test_11_twins_gl.cpp).
// [catmull-rom]
// Catmull-Rom through 4x4 texels in 9 bilinear reads of `tex` (a linear, clamped sampler): the
// middle two weights of each axis merged into one read between their texels (their sum is positive).
vec3 catmull_rom(sampler2D tex, vec2 uv) {
  vec2 size = vec2(textureSize(tex, 0));
  vec2 pos = uv * size;
  vec2 p1 = floor(pos - 0.5) + 0.5;
  vec2 f = pos - p1;
  vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
  vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
  vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
  vec2 w3 = f * f * (-0.5 + 0.5 * f);
  vec2 w12 = w1 + w2;
  vec2 t0 = (p1 - 1.0) / size, t3 = (p1 + 2.0) / size, t12 = (p1 + w2 / w12) / size;
  vec3 r = vec3(0.0);
  r += (texture(tex, vec2(t0.x, t0.y)).rgb * w0.x + texture(tex, vec2(t12.x, t0.y)).rgb * w12.x +
        texture(tex, vec2(t3.x, t0.y)).rgb * w3.x) * w0.y;
  r += (texture(tex, vec2(t0.x, t12.y)).rgb * w0.x + texture(tex, vec2(t12.x, t12.y)).rgb * w12.x +
        texture(tex, vec2(t3.x, t12.y)).rgb * w3.x) * w12.y;
  r += (texture(tex, vec2(t0.x, t3.y)).rgb * w0.x + texture(tex, vec2(t12.x, t3.y)).rgb * w12.x +
        texture(tex, vec2(t3.x, t3.y)).rgb * w3.x) * w3.y;
  return max(r, vec3(0.0));  // its negative lobes can undershoot below black
}
// [/catmull-rom]
