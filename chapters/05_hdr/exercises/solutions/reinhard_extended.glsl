// Exercise 1 of chapter 05, solved: the same function as 05_hdr/shaders/hdr_math.glsl.
vec3 reinhard_extended(vec3 x, float white) { return min(x * (1.0 + x / (white * white)) / (1.0 + x), vec3(1.0)); }
