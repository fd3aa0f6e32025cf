// Exercise 1 of chapter 07, solved: the same function as 07_ssao/shaders/ao_math.glsl.
float range_weight(float radius, float gap) { return smoothstep(0.0, 1.0, radius / max(abs(gap), 1e-6)); }
