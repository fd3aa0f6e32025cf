// How the G-buffer packs normals and exponents, in GLSL: the same maths as encoding.h (the
// C++ copy the unit tests hold to its error bounds). The geometry pass encodes, gbuffer.glsl
// decodes. Stored values are what a normalised channel holds: code / (2^bits - 1).

// [signed-codes-glsl]
// [-1, 1] on codes 0 .. 2^bits - 2, the middle code meaning exactly 0.
float gb_code_scale(int bits) { return float((1 << (bits - 1)) - 1); }
float gb_code_top(int bits) { return float((1 << bits) - 1); }
// [/signed-codes-glsl]

vec2 gb_sign_not_zero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

// [octahedral-glsl]
// Exercises 1 and 2 (chapters/02_gbuffer/exercises/) stand in for these two with --exercise.
#ifdef EXERCISE_OCTAHEDRAL_FOLD
#include EXERCISE_OCTAHEDRAL_FOLD
#else
vec2 octahedral_fold(vec3 n) {
  vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
  if (n.z < 0.0) p = (1.0 - abs(p.yx)) * gb_sign_not_zero(p);
  return p;
}
#endif

#ifdef EXERCISE_OCTAHEDRAL_UNFOLD
#include EXERCISE_OCTAHEDRAL_UNFOLD
#else
vec3 octahedral_unfold(vec2 p) {
  vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
  float t = max(-n.z, 0.0);
  n.x += n.x >= 0.0 ? -t : t;
  n.y += n.y >= 0.0 ? -t : t;
  return normalize(n);
}
#endif

vec3 decode_octahedral_codes(vec2 codes, int bits) {
  float m = gb_code_scale(bits);
  return octahedral_unfold(clamp((codes - m) / m, -1.0, 1.0));
}

// Unit normal -> the two stored values, keeping the best of the four codes around the point.
vec2 encode_octahedral(vec3 n, int bits) {
  float m = gb_code_scale(bits);
  vec2 c = clamp(octahedral_fold(n) * m + m, 0.0, 2.0 * m);
  vec2 lo = floor(c);
  vec2 best = lo;
  float best_distance = 1e30;
  for (int i = 0; i < 4; ++i) {
    vec2 k = min(lo + vec2(i & 1, i >> 1), vec2(2.0 * m));
    vec3 e = decode_octahedral_codes(k, bits) - n;  // squared chord: a cosine near 1 is too coarse
    float distance = dot(e, e);
    if (distance < best_distance) { best_distance = distance; best = k; }
  }
  return best / gb_code_top(bits);
}

vec3 decode_octahedral(vec2 stored, int bits) {
  return decode_octahedral_codes(round(stored * gb_code_top(bits)), bits);
}
// [/octahedral-glsl]

// The source's normal: components from [-1, 1] to [0, 1]; the channel rounds.
vec3 encode_xyz(vec3 n) { return n * 0.5 + 0.5; }
vec3 decode_xyz(vec3 stored) { return normalize(stored * 2.0 - 1.0); }

// [exponent-glsl]
// Blinn-Phong exponent 1..8192 on an 8-bit log2 scale (steps 3.6 % apart).
const float GB_MAX_LOG2_EXPONENT = 13.0;
float encode_exponent(float n) { return round(clamp(log2(max(n, 1.0)) / GB_MAX_LOG2_EXPONENT, 0.0, 1.0) * 255.0) / 255.0; }
float decode_exponent(float stored) { return exp2(round(stored * 255.0) / 255.0 * GB_MAX_LOG2_EXPONENT); }
// [/exponent-glsl]
