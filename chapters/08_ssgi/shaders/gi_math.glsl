// Chapter 08's sampling pattern and disk transfer in GLSL, in a file of their own so that a test
// runs them against their C++ twins in gi_math.h (tests/unit/test_08_twins_gl.cpp); ssgi.comp
// includes it.

const float PI = 3.14159265358979;

uint wang_hash(uint h) {
  h = (h ^ 61u) ^ (h >> 16);
  h *= 9u;
  h ^= h >> 4;
  h *= 0x27d4eb2du;
  h ^= h >> 15;
  return h;
}

// The randomised pattern's two numbers in [0, 1) for a pixel (gi_math.h's pixel_jitter).
vec2 pixel_jitter(ivec2 pixel) {
  uint a = wang_hash(uint(pixel.x) * 1973u + uint(pixel.y) * 9277u + 26699u), b = wang_hash(a);
  return vec2(float(a >> 8), float(b >> 8)) / 16777216.0;
}

// [pattern-glsl]
// pattern: 0 regular (rings x spokes), 1 spiral, 2 randomised (by the pixel's jitter)
vec2 pattern_point(int pattern, int i, int samples, int rings, int spokes, vec2 jitter) {
  if (pattern == 0) {
    int ring = i / spokes, spoke = i % spokes;
    float a = 2.0 * PI * float(spoke) / float(spokes);
    return sqrt((float(ring) + 0.5) / float(rings)) * vec2(cos(a), sin(a));
  }
  float offset = pattern == 2 ? jitter.y : 0.5;
  float a = 2.39996323 * float(i) + (pattern == 2 ? 2.0 * PI * jitter.x : 0.0);
  return sqrt((float(i) + offset) / float(samples)) * vec2(cos(a), sin(a));
}
// [/pattern-glsl]

// Exercise 1 of chapter 08 (chapters/08_ssgi/exercises/) stands in for the transfer.
#ifdef EXERCISE_DISK_TRANSFER
#include EXERCISE_DISK_TRANSFER
#else
// [transfer-glsl]
float disk_transfer(vec3 p, vec3 np, vec3 e, vec3 ne, float area) {
  vec3 v = e - p;
  float r2 = dot(v, v);
  if (r2 <= 0.0 || area <= 0.0) return 0.0;
  v *= inversesqrt(r2);
  return area * max(-dot(ne, v), 0.0) * max(dot(np, v), 0.0) / (PI * r2 + area);
}
// [/transfer-glsl]
#endif
